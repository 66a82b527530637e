//! Integration tests of sprite-compose (one binary, modules by area).

#[path = "../support/mod.rs"]
mod support;

mod bake;
mod bake_player;
mod painter;
