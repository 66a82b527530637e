//! Integration tests of raster-sink (one binary, modules per area).

mod common;
mod cracks;
mod golden;
mod grid;
mod materials;
mod scenes;
mod seams;
mod sink_culls;
mod steps;
mod truth;
