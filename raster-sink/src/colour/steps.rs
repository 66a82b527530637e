//! The render steps (clear, draw, resolve), the entry points that run them, the canvas
//! size check, the supersampling resolve and PNG output.

use std::path::Path;

use face_sort::{DrawItem, DrawList, View};
use tiny_skia::Pixmap;

use super::options::{MAX_SUPERSAMPLE, MAX_TEXTURE_SUBDIVISION, Override, RasterOptions};
use super::painter::{DrawContext, Painter};
use crate::style::Style;
use crate::{MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, RasterError};

/// One step of a render: a small ordered list a caller may change (see [`default_steps`]).
#[derive(Clone, Copy)]
pub enum Step<'a> {
    /// Fill the canvas with a colour (sRGB, straight alpha).
    Clear([u8; 4]),
    /// Draw the list's items in order, those the filter keeps, with an optional override.
    Draw {
        /// Keeps an item when it returns true; `None` keeps all.
        filter: Option<&'a dyn Fn(DrawItem) -> bool>,
        /// Replaces the style's brushes.
        brush: Override,
    },
    /// Box-filter the supersampled canvas down to the output size (no-op without
    /// supersampling). Later draw steps draw at the output size.
    Resolve,
}

impl std::fmt::Debug for Step<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Step::Clear(c) => f.debug_tuple("Clear").field(c).finish(),
            Step::Draw { filter, brush } => f
                .debug_struct("Draw")
                .field("filter", &filter.is_some())
                .field("brush", brush)
                .finish(),
            Step::Resolve => f.write_str("Resolve"),
        }
    }
}

/// The steps [`render_colour`] runs: clear to the background, draw everything with the
/// options' override brush, resolve.
#[must_use]
pub fn default_steps(options: &RasterOptions) -> [Step<'static>; 3] {
    [
        Step::Clear(options.background),
        Step::Draw {
            filter: None,
            brush: options.brush_override,
        },
        Step::Resolve,
    ]
}

/// Renders a draw list in colour: [`default_steps`] through [`run_steps`].
pub fn render_colour(
    view: &View,
    list: &DrawList,
    style: &Style,
    options: &RasterOptions,
) -> Result<Pixmap, RasterError> {
    run_steps(view, list, style, options, &default_steps(options))
}

/// Checks an image size against [`MAX_IMAGE_SIDE`] and [`MAX_IMAGE_PIXELS`] and creates the
/// pixmap (tiny-skia aborts the process on huge sizes, so this check comes first).
pub fn new_pixmap(width: u64, height: u64) -> Result<Pixmap, RasterError> {
    let error = || RasterError::ImageSize {
        width,
        height,
        max_side: MAX_IMAGE_SIDE,
        max_pixels: MAX_IMAGE_PIXELS,
    };
    if width == 0
        || height == 0
        || width > u64::from(MAX_IMAGE_SIDE)
        || height > u64::from(MAX_IMAGE_SIDE)
        || width * height > MAX_IMAGE_PIXELS
    {
        return Err(error());
    }
    Pixmap::new(width as u32, height as u32).ok_or_else(error)
}

/// Runs render steps on a fresh canvas of the view's size times the supersampling factor
/// and returns the canvas (resolved or not, as the steps left it).
pub fn run_steps(
    view: &View,
    list: &DrawList,
    style: &Style,
    options: &RasterOptions,
    steps: &[Step<'_>],
) -> Result<Pixmap, RasterError> {
    let factor = options.supersample;
    if !(1..=MAX_SUPERSAMPLE).contains(&factor) {
        return Err(RasterError::InvalidOption {
            option: "supersample",
            message: format!("{factor} is not in 1..={MAX_SUPERSAMPLE}"),
        });
    }
    if !(1..=MAX_TEXTURE_SUBDIVISION).contains(&options.texture_subdivision) {
        return Err(RasterError::InvalidOption {
            option: "texture_subdivision",
            message: format!(
                "{} is not in 1..={MAX_TEXTURE_SUBDIVISION}",
                options.texture_subdivision
            ),
        });
    }
    if !(options.seam_outset.is_finite() && (0.0..=4.0).contains(&options.seam_outset)) {
        return Err(RasterError::InvalidOption {
            option: "seam_outset",
            message: format!("{} is not in 0..=4 pixels", options.seam_outset),
        });
    }
    let mut canvas = new_pixmap(
        u64::from(view.width()) * u64::from(factor),
        u64::from(view.height()) * u64::from(factor),
    )?;
    let mut current = factor;
    let mut painter = Painter::default();
    for step in steps {
        match *step {
            Step::Clear(colour) => {
                let [r, g, b, a] = colour;
                canvas.fill(tiny_skia::Color::from_rgba8(r, g, b, a));
            }
            Step::Draw { filter, brush } => {
                let context = DrawContext {
                    view,
                    list,
                    style,
                    options,
                    factor: current,
                };
                painter.draw(&mut canvas, context, filter, brush)?;
            }
            Step::Resolve => {
                if current > 1 {
                    canvas = resolve(&canvas, current)?;
                    current = 1;
                }
            }
        }
    }
    Ok(canvas)
}

/// Box-filters a pixmap down by an integer factor.
fn resolve(canvas: &Pixmap, factor: u32) -> Result<Pixmap, RasterError> {
    let (w, h) = (canvas.width() / factor, canvas.height() / factor);
    let mut out = new_pixmap(u64::from(w), u64::from(h))?;
    let src = canvas.data();
    let stride = canvas.width() as usize * 4;
    let k = factor as usize;
    let n = (k * k) as u32;
    let dst = out.data_mut();
    for y in 0..h as usize {
        for x in 0..w as usize {
            let mut sum = [0u32; 4];
            for sy in 0..k {
                let row = (y * k + sy) * stride + x * k * 4;
                for sx in 0..k {
                    for c in 0..4 {
                        sum[c] += u32::from(src[row + sx * 4 + c]);
                    }
                }
            }
            let o = (y * w as usize + x) * 4;
            for c in 0..4 {
                dst[o + c] = ((sum[c] + n / 2) / n) as u8;
            }
        }
    }
    Ok(out)
}

/// Writes a pixmap as an 8-bit RGBA PNG (un-premultiplied).
pub fn save_png(pixmap: &Pixmap, path: impl AsRef<Path>) -> Result<(), RasterError> {
    let path = path.as_ref();
    let data = pixmap.encode_png().map_err(|e| RasterError::Png {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    std::fs::write(path, data).map_err(|source| RasterError::Io {
        path: path.to_path_buf(),
        source,
    })
}
