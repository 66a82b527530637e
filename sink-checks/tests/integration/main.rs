//! Both sinks against one truth (one binary, modules by area): vector-sink's files read back
//! by their real consumers (resvg, Chromium, poppler) and sprite-compose's visible lines,
//! judged by raster-sink's references, which share none of the code under test.

mod browser;
mod hidden;
mod materials;
mod overlay;
mod pdf;
mod plot;
mod spin;
mod spin_culled;
mod support;
mod textures;
mod turn_page;
mod writers;
