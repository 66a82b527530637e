//! Reference raster for painter draw lists.
//!
//! TODO: crate docs.

mod colour;
mod error;
mod fill;
mod grid;
mod ids;
mod project;
mod seams;
mod style;
pub mod tolerance;
mod truth;

pub use colour::{
    Light, MAX_SUPERSAMPLE, MAX_TEXTURE_SUBDIVISION, Override, RasterOptions, Step, default_steps,
    new_pixmap, render_colour, run_steps, save_png,
};
pub use error::RasterError;
pub use fill::{for_each_pixel_near_segment, for_each_span};
pub use grid::GroundGrid;
pub use ids::{IdImage, MAX_ID_FACE, id_to_rgb, render_ids, render_ids_into};
pub use style::{
    Brush, GOLDEN_ANGLE_DEG, PALETTE_SATURATION, PALETTE_VALUE, Style, TextureBrush, UvMap,
    golden_angle_colour,
};
pub use truth::{PixelError, Truth, pixel_error, truth};

pub use face_sort;
pub use tiny_skia;

/// Largest image side the colour raster accepts (after supersampling).
pub const MAX_IMAGE_SIDE: u32 = 16384;
/// Largest pixel count the colour raster accepts (after supersampling).
pub const MAX_IMAGE_PIXELS: u64 = 1 << 28;
