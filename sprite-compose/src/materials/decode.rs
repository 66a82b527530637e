//! Decoding textures through obj-quads (feature `obj-quads`), within its texture limits, and
//! tinting them as glTF's factors and alpha modes say.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::image::Image;

/// A texture that could not be loaded.
#[derive(Debug, thiserror::Error)]
#[error("{source}")]
pub struct TextureError {
    /// The file (or, for a texture held in the model file, its name).
    pub path: PathBuf,
    /// What the texture loader said (boxed: it is large).
    #[source]
    pub source: Box<obj_quads::LoadError>,
}

impl Image {
    /// This image with every texel multiplied by `factor` (linear RGBA, as glTF's
    /// `baseColorFactor`: sRGB texels to linear, times the factor, back to sRGB) and its
    /// alpha then taken as `alpha` says.
    #[must_use]
    pub fn tinted(&self, factor: [f32; 4], alpha: obj_quads::AlphaMode) -> Image {
        let to_linear = |c: u8| {
            let c = f32::from(c) / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        let to_srgb = |l: f32| {
            let l = l.clamp(0.0, 1.0);
            let c = if l <= 0.003_130_8 {
                l * 12.92
            } else {
                1.055 * l.powf(1.0 / 2.4) - 0.055
            };
            (c * 255.0).round() as u8
        };
        let scale = |v: u8, f: f32| {
            if f == 1.0 {
                v // no round trip through linear light
            } else {
                to_srgb(to_linear(v) * f)
            }
        };
        let mut rgba = self.rgba.clone();
        for p in rgba.chunks_exact_mut(4) {
            let a = alpha_byte(
                (f32::from(p[3]) * factor[3].clamp(0.0, 1.0)).round() as u8,
                alpha,
            );
            p[0] = scale(p[0], factor[0]);
            p[1] = scale(p[1], factor[1]);
            p[2] = scale(p[2], factor[2]);
            p[3] = a;
        }
        Image {
            width: self.width,
            height: self.height,
            rgba,
            name: format!("{} (tinted)", self.name),
            file: None,
            encoded: None,
        }
    }
}

/// Loads a PNG or JPEG texture within the texture limits of `limits`: file size before
/// reading, width, height and pixel count from the image header before decoding
/// (`obj_quads::load_texture`), so a small file declaring a huge image fails fast instead
/// of allocating it.
pub fn load_image(path: &Path, limits: &obj_quads::LoadOptions) -> Result<Image, TextureError> {
    let error = |source| TextureError {
        path: path.to_path_buf(),
        source: Box::new(source),
    };
    let texture = obj_quads::load_texture(path, limits).map_err(error)?;
    // The bytes for embedding, read under the same cap (the file passed it just now).
    let mut bytes = Vec::new();
    let read = std::fs::File::open(path).and_then(|f| {
        f.take(limits.max_texture_file_bytes)
            .read_to_end(&mut bytes)
    });
    Ok(Image {
        width: texture.width,
        height: texture.height,
        rgba: texture.rgba,
        name: path.display().to_string(),
        file: Some(path.to_path_buf()),
        encoded: read.is_ok().then(|| Arc::from(bytes)),
    })
}

/// Decodes a texture held in a model file within `limits`.
pub fn decode_image(
    name: &str,
    bytes: &[u8],
    limits: &obj_quads::LoadOptions,
) -> Result<Image, TextureError> {
    let texture =
        obj_quads::decode_texture(bytes, name, limits).map_err(|source| TextureError {
            path: PathBuf::from(name),
            source: Box::new(source),
        })?;
    Ok(Image {
        width: texture.width,
        height: texture.height,
        rgba: texture.rgba,
        name: name.to_owned(),
        file: None,
        encoded: Some(Arc::from(bytes)),
    })
}

/// Where a face's texture comes from.
#[derive(Clone, Copy)]
pub(super) enum TextureSource<'a> {
    File(&'a Path),
    /// Name for messages, encoded bytes.
    Embedded(&'a str, &'a [u8]),
}

/// A decoded texture's cache key: its file, or its bytes' address and length.
#[derive(Clone, PartialEq, Eq, Hash)]
pub(super) enum TextureKey {
    File(PathBuf),
    Embedded(usize, usize),
}

impl TextureSource<'_> {
    pub(super) fn key(&self) -> TextureKey {
        match *self {
            TextureSource::File(path) => TextureKey::File(path.to_path_buf()),
            TextureSource::Embedded(_, bytes) => {
                TextureKey::Embedded(bytes.as_ptr() as usize, bytes.len())
            }
        }
    }

    /// Decodes it within the default texture limits.
    pub(super) fn decode(&self) -> Result<Image, TextureError> {
        match *self {
            TextureSource::File(path) => load_image(path, &obj_quads::LoadOptions::DEFAULT),
            TextureSource::Embedded(name, bytes) => {
                decode_image(name, bytes, &obj_quads::LoadOptions::DEFAULT)
            }
        }
    }
}

/// An alpha mode as a hashable cache key.
pub(super) type AlphaKey = (u8, u32);

pub(super) fn alpha_key(mode: obj_quads::AlphaMode) -> AlphaKey {
    match mode {
        obj_quads::AlphaMode::Opaque => (0, 0),
        obj_quads::AlphaMode::Mask { cutoff } => (2, cutoff.to_bits()),
        _ => (1, 0),
    }
}

/// An alpha byte under an alpha mode: as is (blend), 255 (opaque), or 255 / 0 at the
/// cutoff (mask).
pub(super) fn alpha_byte(alpha: u8, mode: obj_quads::AlphaMode) -> u8 {
    match mode {
        obj_quads::AlphaMode::Opaque => 255,
        obj_quads::AlphaMode::Mask { cutoff } => {
            if f32::from(alpha) / 255.0 >= cutoff {
                255
            } else {
                0
            }
        }
        _ => alpha,
    }
}
