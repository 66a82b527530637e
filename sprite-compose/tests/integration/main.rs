//! Integration tests of sprite-compose (one binary, modules by area).

#[path = "../support/mod.rs"]
mod support;

mod painter;
mod writers;
mod browser;
