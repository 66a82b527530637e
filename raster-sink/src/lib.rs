//! Reference raster for painter draw lists.
//!
//! TODO: crate docs.

mod error;
mod fill;
mod ids;
mod project;
pub mod tolerance;
mod truth;

pub use error::RasterError;
pub use fill::{for_each_pixel_near_segment, for_each_span};
pub use ids::{IdImage, MAX_ID_FACE, id_to_rgb, render_ids, render_ids_into};
pub use truth::{PixelError, Truth, pixel_error, truth};

pub use face_sort;
pub use tiny_skia;

/// Largest image side the colour raster accepts (after supersampling).
pub const MAX_IMAGE_SIDE: u32 = 16384;
/// Largest pixel count the colour raster accepts (after supersampling).
pub const MAX_IMAGE_PIXELS: u64 = 1 << 28;
