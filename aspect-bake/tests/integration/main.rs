//! Integration tests of aspect-bake (one binary, modules by area; `budget` is its own binary:
//! it installs a peak-memory global allocator).

#[path = "../common/mod.rs"]
mod common;

mod bake;
mod two_axes;
