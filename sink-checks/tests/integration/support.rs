//! The workspace's `test-support` under the names these tests use.

#![allow(unused_imports, reason = "each test module uses part of it")]

pub use test_support::models::boxes;
pub use test_support::{Rng, geometry, load_polygon_mesh as load_obj};
