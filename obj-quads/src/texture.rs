//! Texture images (PNG, JPEG) decoded to RGBA8 with limits.
//!
//! The image's width and height are read from its header (PNG `IHDR`, JPEG
//! frame header) and checked against
//! [`LoadOptions::max_texture_side`](crate::LoadOptions::max_texture_side) and
//! [`LoadOptions::max_texture_pixels`](crate::LoadOptions::max_texture_pixels)
//! before anything is decoded, and the file size against
//! [`LoadOptions::max_texture_file_bytes`](crate::LoadOptions::max_texture_file_bytes)
//! before it is read, so a small file that declares a huge image costs a few
//! bytes of reading, not gigabytes of memory. Decoding then allocates at most
//! 8 bytes per accepted pixel (a PNG's decoded frame of up to 4 bytes a pixel
//! and its RGBA8 copy; JPEG decodes straight to RGBA8) plus the decoders'
//! bounded working buffers.

use std::io::Cursor;
use std::panic::catch_unwind;
use std::path::Path;

use crate::{LoadError, LoadOptions};

/// A decoded texture: 8-bit RGBA, straight (not premultiplied) alpha, rows
/// from top to bottom.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub struct Texture {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width · height · 4` bytes, RGBA per pixel, row by row.
    pub rgba: Vec<u8>,
}

/// An image format recognised by its signature.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum TextureFormat {
    /// PNG (`\x89PNG\r\n\x1a\n`).
    Png,
    /// JPEG (`FF D8`).
    Jpeg,
}

/// What an image's header declares, read without decoding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub struct TextureHeader {
    /// The format.
    pub format: TextureFormat,
    /// Declared width in pixels.
    pub width: u32,
    /// Declared height in pixels.
    pub height: u32,
}

const PNG_SIGNATURE: &[u8; 8] = b"\x89PNG\r\n\x1a\n";

/// Reads the format and declared size of a PNG or JPEG image from its first
/// bytes, without decoding. The cost is bounded by the header's length (PNG: 24
/// bytes; JPEG: the segments before the frame header).
///
/// ```
/// use obj_quads::{TextureFormat, texture_header};
/// let mut png = b"\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR".to_vec();
/// png.extend(30_000u32.to_be_bytes()); // width
/// png.extend(30_000u32.to_be_bytes()); // height
/// let header = texture_header(&png, "bomb.png")?;
/// assert_eq!((header.format, header.width, header.height), (TextureFormat::Png, 30_000, 30_000));
/// # Ok::<(), obj_quads::LoadError>(())
/// ```
pub fn texture_header(bytes: &[u8], file: &str) -> Result<TextureHeader, LoadError> {
    let bad = |detail: &str| LoadError::Texture {
        file: file.to_owned(),
        detail: detail.to_owned(),
    };
    if bytes.starts_with(PNG_SIGNATURE) {
        let ihdr = bytes
            .get(8..24)
            .ok_or_else(|| bad("PNG too short for its IHDR chunk"))?;
        if &ihdr[4..8] != b"IHDR" {
            return Err(bad("PNG does not start with an IHDR chunk"));
        }
        let be = |b: &[u8]| u32::from_be_bytes([b[0], b[1], b[2], b[3]]);
        let (width, height) = (be(&ihdr[8..12]), be(&ihdr[12..16]));
        if width == 0 || height == 0 {
            return Err(bad("PNG declares a zero width or height"));
        }
        return Ok(TextureHeader {
            format: TextureFormat::Png,
            width,
            height,
        });
    }
    if bytes.starts_with(&[0xFF, 0xD8]) {
        let (width, height) = jpeg_size(bytes).map_err(bad)?;
        return Ok(TextureHeader {
            format: TextureFormat::Jpeg,
            width,
            height,
        });
    }
    Err(bad("not a PNG or JPEG image"))
}

/// Walks JPEG marker segments to the first frame header (SOFn) and returns
/// its width and height.
fn jpeg_size(bytes: &[u8]) -> Result<(u32, u32), &'static str> {
    let mut i = 2;
    loop {
        // Markers may be preceded by any number of 0xFF fill bytes.
        while bytes.get(i) == Some(&0xFF) && bytes.get(i + 1) == Some(&0xFF) {
            i += 1;
        }
        let (Some(&0xFF), Some(&marker)) = (bytes.get(i), bytes.get(i + 1)) else {
            return Err("JPEG ends or breaks before its frame header");
        };
        i += 2;
        match marker {
            // Stand-alone markers: no length.
            0x01 | 0xD0..=0xD7 => continue,
            0xD8..=0xDA => return Err("JPEG has no frame header before its scan"),
            _ => {}
        }
        let len = match bytes.get(i..i + 2) {
            Some(l) => usize::from(u16::from_be_bytes([l[0], l[1]])),
            None => return Err("JPEG segment length missing"),
        };
        if len < 2 {
            return Err("JPEG segment length below 2");
        }
        let is_sof = matches!(marker, 0xC0..=0xCF) && !matches!(marker, 0xC4 | 0xC8 | 0xCC);
        if is_sof {
            let seg = bytes
                .get(i + 2..i + 7)
                .ok_or("JPEG frame header too short")?;
            let height = u32::from(u16::from_be_bytes([seg[1], seg[2]]));
            let width = u32::from(u16::from_be_bytes([seg[3], seg[4]]));
            if width == 0 || height == 0 {
                return Err("JPEG declares a zero width or height (DNL height is not supported)");
            }
            return Ok((width, height));
        }
        i += len;
    }
}

/// Checks a header against the texture limits of `options`.
fn check_limits(
    header: &TextureHeader,
    file: &str,
    options: &LoadOptions,
) -> Result<(), LoadError> {
    let too_large = |what: &'static str, actual: u64, limit: u64| LoadError::TooLarge {
        file: file.to_owned(),
        what,
        actual,
        limit,
    };
    let side = u64::from(options.max_texture_side);
    if header.width > options.max_texture_side {
        return Err(too_large(
            "texture width in pixels",
            header.width.into(),
            side,
        ));
    }
    if header.height > options.max_texture_side {
        return Err(too_large(
            "texture height in pixels",
            header.height.into(),
            side,
        ));
    }
    let pixels = u64::from(header.width) * u64::from(header.height);
    if pixels > options.max_texture_pixels {
        return Err(too_large(
            "texture pixel count (width × height)",
            pixels,
            options.max_texture_pixels,
        ));
    }
    Ok(())
}

/// Reads and decodes a PNG or JPEG texture file within the texture limits of
/// `options`: file size before reading, declared width, height and pixel
/// count before decoding.
///
/// This reads `path` as given; the path confinement of a model's textures
/// happens when the model is loaded ([`Material::texture`](crate::Material::texture)
/// holds only paths that passed it).
pub fn load_texture(path: impl AsRef<Path>, options: &LoadOptions) -> Result<Texture, LoadError> {
    let path = path.as_ref();
    let file = path.display().to_string();
    let bytes = crate::read_file_capped(path, &file, options.max_texture_file_bytes)?;
    decode_texture(&bytes, &file, options)
}

/// Decodes PNG or JPEG bytes within the texture limits of `options` (see
/// [`load_texture`]); `file` names the image in errors.
///
/// ```
/// use obj_quads::{LoadError, LoadOptions, decode_texture};
/// // A PNG header declaring 30000 × 30000 pixels, and no image data.
/// let mut bomb = b"\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR".to_vec();
/// bomb.extend(30_000u32.to_be_bytes());
/// bomb.extend(30_000u32.to_be_bytes());
/// bomb.extend([8, 6, 0, 0, 0, 0, 0, 0, 0]);
/// let e = decode_texture(&bomb, "bomb.png", &LoadOptions::DEFAULT).unwrap_err();
/// assert!(matches!(e, LoadError::TooLarge { .. }), "{e}");
/// ```
pub fn decode_texture(
    bytes: &[u8],
    file: &str,
    options: &LoadOptions,
) -> Result<Texture, LoadError> {
    if bytes.len() as u64 > options.max_texture_file_bytes {
        return Err(LoadError::TooLarge {
            file: file.to_owned(),
            what: "texture size in bytes",
            actual: bytes.len() as u64,
            limit: options.max_texture_file_bytes,
        });
    }
    let header = texture_header(bytes, file)?;
    check_limits(&header, file, options)?;
    // The decoders are dependencies: a panic they still have on some input
    // becomes a typed error here (found by `cargo xtask fuzz --loaders`).
    let decoded = catch_unwind(|| match header.format {
        TextureFormat::Png => decode_png(bytes, file),
        TextureFormat::Jpeg => decode_jpeg(bytes, file, options),
    });
    let texture = decoded.unwrap_or_else(|_| {
        Err(LoadError::Texture {
            file: file.to_owned(),
            detail: format!("the {:?} decoder panicked on this input", header.format),
        })
    })?;
    if (texture.width, texture.height) != (header.width, header.height) {
        return Err(LoadError::Texture {
            file: file.to_owned(),
            detail: format!(
                "decoded {}×{} but the header declares {}×{}",
                texture.width, texture.height, header.width, header.height
            ),
        });
    }
    Ok(texture)
}

/// Finds palette chunks that png 0.18's palette expansion indexes out of
/// bounds (it panics on them): a `PLTE` whose length is not a multiple of 3 or
/// exceeds 256 entries, or a `tRNS` with more entries than the `PLTE`. Walks
/// the chunks up to the first `IDAT`, bounded by the input's length.
fn png_palette_problem(bytes: &[u8]) -> Option<String> {
    let mut at = PNG_SIGNATURE.len();
    let mut palette_entries = None;
    while let Some(header) = bytes.get(at..at + 8) {
        let len = u32::from_be_bytes([header[0], header[1], header[2], header[3]]) as usize;
        let kind = &header[4..8];
        match kind {
            b"PLTE" => {
                if !len.is_multiple_of(3) || len > 3 * 256 {
                    return Some(format!(
                        "PLTE chunk of {len} bytes (3 per entry, at most 256 entries)"
                    ));
                }
                palette_entries = Some(len / 3);
            }
            b"tRNS" => {
                if let Some(entries) = palette_entries
                    && len > entries
                {
                    return Some(format!(
                        "tRNS chunk of {len} entries for a palette of {entries}"
                    ));
                }
            }
            b"IDAT" => return None,
            _ => {}
        }
        at = at.checked_add(12)?.checked_add(len)?;
    }
    None
}

fn decode_png(bytes: &[u8], file: &str) -> Result<Texture, LoadError> {
    let err = |e: png::DecodingError| LoadError::Texture {
        file: file.to_owned(),
        detail: format!("PNG: {e}"),
    };
    if let Some(problem) = png_palette_problem(bytes) {
        return Err(LoadError::Texture {
            file: file.to_owned(),
            detail: format!("PNG: {problem}"),
        });
    }
    // The header was checked: the decoder may allocate the 16-bit RGBA frame
    // (8 bytes per pixel) and its row buffers, no more.
    let mut decoder = png::Decoder::new(Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = decoder.read_info().map_err(err)?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| LoadError::Texture {
            file: file.to_owned(),
            detail: "PNG frame size overflows".into(),
        })?;
    let mut buffer = vec![0u8; size];
    let info = reader.next_frame(&mut buffer).map_err(err)?;
    buffer.truncate(info.buffer_size());
    let (width, height) = (info.width, info.height);
    let pixels = width as usize * height as usize;
    let rgba = match info.color_type {
        png::ColorType::Rgba => buffer,
        png::ColorType::Rgb => buffer
            .chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect(),
        png::ColorType::GrayscaleAlpha => buffer
            .chunks_exact(2)
            .flat_map(|p| [p[0], p[0], p[0], p[1]])
            .collect(),
        png::ColorType::Grayscale => buffer.iter().flat_map(|&g| [g, g, g, 255]).collect(),
        png::ColorType::Indexed => {
            return Err(LoadError::Texture {
                file: file.to_owned(),
                detail: "PNG palette was not expanded".into(),
            });
        }
    };
    if rgba.len() != pixels * 4 {
        return Err(LoadError::Texture {
            file: file.to_owned(),
            detail: format!(
                "PNG frame has {} bytes, expected {}",
                rgba.len(),
                pixels * 4
            ),
        });
    }
    Ok(Texture {
        width,
        height,
        rgba,
    })
}

fn decode_jpeg(bytes: &[u8], file: &str, options: &LoadOptions) -> Result<Texture, LoadError> {
    use zune_jpeg::zune_core::bytestream::ZCursor;
    use zune_jpeg::zune_core::colorspace::ColorSpace;
    use zune_jpeg::zune_core::options::DecoderOptions;
    let side = options.max_texture_side as usize;
    let decoder_options = DecoderOptions::default()
        .jpeg_set_out_colorspace(ColorSpace::RGBA)
        .set_max_width(side)
        .set_max_height(side);
    let mut decoder =
        zune_jpeg::JpegDecoder::new_with_options(ZCursor::new(bytes), decoder_options);
    let err = |detail: String| LoadError::Texture {
        file: file.to_owned(),
        detail: format!("JPEG: {detail}"),
    };
    let rgba = decoder.decode().map_err(|e| err(format!("{e:?}")))?;
    let info = decoder
        .info()
        .ok_or_else(|| err("no image information after decoding".into()))?;
    let (width, height) = (u32::from(info.width), u32::from(info.height));
    if rgba.len() != width as usize * height as usize * 4 {
        return Err(err(format!(
            "decoded {} bytes for {width}×{height} RGBA",
            rgba.len()
        )));
    }
    Ok(Texture {
        width,
        height,
        rgba,
    })
}
