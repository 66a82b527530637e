//! Integration tests of obj-quads (one binary, modules by area; `budget` is its own binary:
//! it installs a peak-memory global allocator).

mod embedded_textures;
mod errors;
mod fuzz;
mod hostile;
mod models;
