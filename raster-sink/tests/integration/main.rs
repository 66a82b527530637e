//! Integration tests of raster-sink (one binary, modules per area).

mod common;
mod cracks;
mod seams;
mod truth;
