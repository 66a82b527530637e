//! Integration tests of face-sort (one binary, modules by area; `alloc` is its own binary:
//! it installs a counting global allocator).

#[path = "../common/mod.rs"]
mod common;

mod book;
mod bsp_budget;
mod bsp_depth;
mod bsp_frustum;
mod conversions;
mod fuzz_cases;
mod models;
mod oracle;
mod plan;
mod presorted;
mod properties;
mod scene;
mod small;
mod stress;
