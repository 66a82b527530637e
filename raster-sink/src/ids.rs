//! ID images per CONVENTIONS.md: exact pixel-centre fill, painter order, 24-bit face IDs.

use std::io::BufWriter;
use std::path::Path;

use face_sort::colours::id_value_to_rgb;
use face_sort::{DrawList, View};

use crate::RasterError;
use crate::fill::for_each_span;
use crate::project::Projector;

/// Largest face index an ID image can hold (24 bits, minus the background value 0).
pub const MAX_ID_FACE: u32 = (1 << 24) - 2;

/// A face-ID image: `ids[y · width + x]` is 0 for background, else face index + 1.
///
/// # Guarantees
/// `ids.len() == width · height` when built by this crate; [`IdImage::new`] checks it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IdImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major IDs, 0 = background, else face index + 1.
    pub ids: Vec<u32>,
}

impl IdImage {
    /// An all-background image.
    #[must_use]
    pub fn blank(width: u32, height: u32) -> Self {
        IdImage {
            width,
            height,
            ids: vec![0; width as usize * height as usize],
        }
    }

    /// An image from row-major IDs; errors when the length is not `width · height`.
    pub fn new(width: u32, height: u32, ids: Vec<u32>) -> Result<Self, RasterError> {
        if ids.len() != width as usize * height as usize {
            return Err(RasterError::BufferSize {
                width,
                height,
                len: ids.len(),
            });
        }
        Ok(IdImage { width, height, ids })
    }

    /// The ID at `(x, y)` (0 = background); `None` outside the image.
    #[must_use]
    pub fn get(&self, x: u32, y: u32) -> Option<u32> {
        if x < self.width && y < self.height {
            self.ids
                .get(y as usize * self.width as usize + x as usize)
                .copied()
        } else {
            None
        }
    }

    /// 8-bit RGB bytes (no alpha), R the high byte of the 24-bit value, B the low byte.
    /// Values above 24 bits keep their low 24 bits.
    #[must_use]
    pub fn to_rgb_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.ids.len() * 3);
        for &id in &self.ids {
            out.extend_from_slice(&id_value_to_rgb(id));
        }
        out
    }

    /// Writes an 8-bit RGB PNG (no alpha) per CONVENTIONS.md.
    pub fn save_png(&self, path: impl AsRef<Path>) -> Result<(), RasterError> {
        let path = path.as_ref();
        let io = |source| RasterError::Io {
            path: path.to_path_buf(),
            source,
        };
        let png_error = |e: png::EncodingError| RasterError::Png {
            path: path.to_path_buf(),
            message: e.to_string(),
        };
        let file = std::fs::File::create(path).map_err(io)?;
        let mut encoder = png::Encoder::new(BufWriter::new(file), self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(png_error)?;
        writer
            .write_image_data(&self.to_rgb_bytes())
            .map_err(png_error)?;
        writer.finish().map_err(png_error)
    }

    /// Reads an ID PNG written by [`save_png`](Self::save_png) (8-bit RGB or RGBA; alpha is ignored).
    pub fn load_png(path: impl AsRef<Path>) -> Result<Self, RasterError> {
        let path = path.as_ref();
        let png_error = |message: String| RasterError::Png {
            path: path.to_path_buf(),
            message,
        };
        let file = std::fs::File::open(path).map_err(|source| RasterError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let decoder = png::Decoder::new(std::io::BufReader::new(file));
        let mut reader = decoder.read_info().map_err(|e| png_error(e.to_string()))?;
        let size = reader
            .output_buffer_size()
            .ok_or_else(|| png_error("image too large".into()))?;
        let mut buf = vec![0; size];
        let info = reader
            .next_frame(&mut buf)
            .map_err(|e| png_error(e.to_string()))?;
        let channels = match (info.color_type, info.bit_depth) {
            (png::ColorType::Rgb, png::BitDepth::Eight) => 3,
            (png::ColorType::Rgba, png::BitDepth::Eight) => 4,
            (c, d) => return Err(png_error(format!("expected 8-bit RGB, found {c:?} {d:?}"))),
        };
        let ids = buf[..info.buffer_size()]
            .chunks_exact(info.line_size)
            .flat_map(|line| line.chunks_exact(channels))
            .map(|px| (u32::from(px[0]) << 16) | (u32::from(px[1]) << 8) | u32::from(px[2]))
            .collect();
        IdImage::new(info.width, info.height, ids)
    }
}

/// Renders the ID image of a draw list: every item filled at pixel centres (f64, top-left
/// rule, see [`for_each_span`]) in paint order, later items overwriting earlier ones.
///
/// Each polygon is projected through `view` (near-plane clipped); polygons whose projection
/// has zero area draw nothing. Face indices above [`MAX_ID_FACE`] wrap in the PNG encoding.
#[must_use]
pub fn render_ids(view: &View, list: &DrawList) -> IdImage {
    let mut image = IdImage::blank(view.width(), view.height());
    render_ids_into(view, list, &mut image);
    image
}

/// [`render_ids`] into an existing image (resized and cleared), reusing its buffer.
pub fn render_ids_into(view: &View, list: &DrawList, image: &mut IdImage) {
    let (width, height) = (view.width(), view.height());
    image.width = width;
    image.height = height;
    image.ids.clear();
    image.ids.resize(width as usize * height as usize, 0);
    let mut projector = Projector::default();
    let stride = width as usize;
    let test = view.cull_test();
    for &item in list.items() {
        if !list.paints(item, &test) || !projector.project(view, list.corners(item)) {
            continue;
        }
        let id = item.face.wrapping_add(1);
        let ids = &mut image.ids;
        for_each_span(&projector.points, width, height, |y, x0, x1| {
            let row = y as usize * stride;
            ids[row + x0 as usize..row + x1 as usize].fill(id);
        });
    }
}
