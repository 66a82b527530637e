//! The colour raster on tiny-skia, one concern per module: [`options`] (what the caller
//! sets), [`steps`] (the ordered render steps and the entry points), the draw step's
//! [`painter`], [`texture`] mapping, [`shading`] and [`blend`] (fills and compositing).

mod blend;
mod options;
mod painter;
mod shading;
mod steps;
mod texture;

pub use blend::polygon_path;
pub use options::{MAX_SUPERSAMPLE, MAX_TEXTURE_SUBDIVISION, Override, RasterOptions};
pub use shading::{Light, shade_colour};
pub use steps::{Step, default_steps, new_pixmap, render_colour, run_steps, save_png};
