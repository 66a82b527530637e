//! The crate's one error type.

use std::path::PathBuf;

/// Everything that can go wrong while rendering or writing images.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RasterError {
    /// The requested image (after supersampling) is larger than the crate allows
    /// ([`MAX_IMAGE_SIDE`](crate::MAX_IMAGE_SIDE) per side, [`MAX_IMAGE_PIXELS`](crate::MAX_IMAGE_PIXELS)
    /// in all) or empty.
    #[error(
        "image size {width}×{height} is not allowed (each side 1..={max_side}, at most {max_pixels} pixels)"
    )]
    ImageSize {
        /// Requested width in pixels.
        width: u64,
        /// Requested height in pixels.
        height: u64,
        /// Largest side allowed.
        max_side: u32,
        /// Largest pixel count allowed.
        max_pixels: u64,
    },
    /// Creating, writing or reading a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// PNG encoding or decoding failed.
    #[error("{path}: PNG error: {message}")]
    Png {
        /// The file.
        path: PathBuf,
        /// What the PNG codec said.
        message: String,
    },
    /// A texture could not be read or decoded, or breaks a texture limit
    /// (`obj_quads::LoadOptions`: side, pixel count, file size, checked before decoding).
    #[error("{source}")]
    Texture {
        /// The file.
        path: PathBuf,
        /// What the texture loader said (boxed: it is large).
        #[source]
        source: Box<obj_quads::LoadError>,
    },
    /// An image buffer does not have `width × height` entries.
    #[error("image buffer has {len} entries, expected {width}×{height}")]
    BufferSize {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
        /// Entries found.
        len: usize,
    },
    /// An option is out of its range.
    #[error("option `{option}` is out of range: {message}")]
    InvalidOption {
        /// The option's name.
        option: &'static str,
        /// Why.
        message: String,
    },
}

impl From<sprite_compose::TextureError> for RasterError {
    fn from(e: sprite_compose::TextureError) -> Self {
        RasterError::Texture {
            path: e.path,
            source: e.source,
        }
    }
}
