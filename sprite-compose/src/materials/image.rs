//! Decoded textures: straight-alpha RGBA with the bytes they came from, for embedding.

use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A decoded texture: straight-alpha sRGB RGBA8, row by row from the top-left, with the
/// encoded bytes (PNG or JPEG) it was decoded from when it is unchanged, so that a writer
/// embeds the original file rather than a re-encoding.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub(super) width: u32,
    pub(super) height: u32,
    pub(super) rgba: Vec<u8>,
    pub(super) name: String,
    pub(super) file: Option<PathBuf>,
    pub(super) encoded: Option<Arc<[u8]>>,
}

impl Image {
    /// An image from straight-alpha RGBA8 pixels (`width · height · 4` bytes), with a name
    /// for messages; `None` when the length does not match.
    #[must_use]
    pub fn from_rgba(
        width: u32,
        height: u32,
        rgba: Vec<u8>,
        name: impl Into<String>,
    ) -> Option<Self> {
        (rgba.len() as u64 == u64::from(width) * u64::from(height) * 4).then(|| Image {
            width,
            height,
            rgba,
            name: name.into(),
            file: None,
            encoded: None,
        })
    }

    /// Width in pixels.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }
    /// Height in pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }
    /// The pixels: straight-alpha RGBA8, row by row from the top-left.
    #[must_use]
    pub fn rgba(&self) -> &[u8] {
        &self.rgba
    }
    /// A name for messages: the file's path, or the name a model file gives an embedded
    /// image.
    #[must_use]
    pub fn name(&self) -> &str {
        &self.name
    }
    /// The file it was loaded from, when it came from a file and is unchanged (not
    /// tinted).
    #[must_use]
    pub fn file(&self) -> Option<&Path> {
        self.file.as_deref()
    }

    /// The encoded file it was decoded from (PNG or JPEG) with its MIME type, when it is
    /// unchanged (not tinted or tiled): a writer embeds these bytes rather than a
    /// re-encoding.
    #[must_use]
    pub fn original(&self) -> Option<(&[u8], &'static str)> {
        self.encoded.as_deref().map(|bytes| {
            let mime = if bytes.starts_with(&[0xff, 0xd8]) {
                "image/jpeg"
            } else {
                "image/png"
            };
            (bytes, mime)
        })
    }

    /// The mean straight-alpha colour, opaque.
    #[must_use]
    pub fn mean_colour(&self) -> [u8; 4] {
        let mut sum = [0u64; 3];
        for p in self.rgba.chunks_exact(4) {
            for k in 0..3 {
                sum[k] += u64::from(p[k]);
            }
        }
        let n = (self.rgba.len() / 4).max(1) as u64;
        [
            (sum[0] / n) as u8,
            (sum[1] / n) as u8,
            (sum[2] / n) as u8,
            255,
        ]
    }
}
