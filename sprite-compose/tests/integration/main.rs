//! Integration tests of sprite-compose (one binary, modules by area).

#[path = "../support/mod.rs"]
mod support;

mod bake;
mod bake_player;
mod browser;
mod hidden;
mod overlay;
mod painter;
mod pdf;
mod plot;
mod spin;
mod spin_culled;
mod textures;
mod turn_page;
mod writers;
