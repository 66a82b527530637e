//! The per-pixel compositing reference for translucent faces: what a renderer that sorts
//! every pixel's fragments (an A-buffer) shows, to judge a painter's order of translucent
//! faces, which only an exact order gets right.

use face_sort::glam::DVec2;
use face_sort::{Geometry, View};
use tiny_skia::{Paint, Pixmap, Rect, Transform};

use crate::tolerance::{DEPTH_GAP, EDGE_MARGIN_PX};
use crate::truth::for_each_fragment;

/// The composited colour of every pixel centre, and where it is unambiguous.
#[derive(Clone, Debug, PartialEq)]
pub struct CompositeTruth {
    /// Every fragment at each pixel centre blended far to near over the background, by
    /// tiny-skia (source-over, no anti-aliasing): the same arithmetic as
    /// [`render_colour`](crate::render_colour)'s solid fills, so an exact order matches it.
    pub image: Pixmap,
    /// Row-major: at least [`EDGE_MARGIN_PX`] from every projected edge of every drawn piece,
    /// and no two fragments change places within [`EDGE_MARGIN_PX`] of the centre (their
    /// depths over that square, sampled at its corners and the centre, stay more than
    /// [`DEPTH_GAP`]` · L` apart): pixels by an interpenetration line, where a rasteriser's
    /// fill rule decides, are not judged.
    pub unambiguous: Vec<bool>,
}

impl CompositeTruth {
    /// How many unambiguous pixels of `image` (the same size) differ from the reference by
    /// more than 2/255 in a channel (the anti-aliasing-free raster of a draw list should
    /// match exactly; 2 absorbs rounding of other canvases).
    #[must_use]
    pub fn wrong_pixels(&self, image: &Pixmap) -> usize {
        image
            .pixels()
            .iter()
            .zip(self.image.pixels())
            .zip(&self.unambiguous)
            .filter(|&((got, want), &judged)| {
                let (got, want) = (got.demultiply(), want.demultiply());
                judged
                    && [
                        (got.red(), want.red()),
                        (got.green(), want.green()),
                        (got.blue(), want.blue()),
                    ]
                    .iter()
                    .any(|(g, w)| g.abs_diff(*w) > 2)
            })
            .count()
    }
}

/// Composites, per pixel centre, every piece of `geometry` the view draws, far to near,
/// each in `colour(face)` (straight sRGB RGBA), over `background`.
///
/// Cost: one fill per piece and one 1 × 1 blend per fragment; memory about 24 bytes per
/// fragment. Errors when the view's size is not a valid canvas.
pub fn composite_truth(
    view: &View,
    geometry: &Geometry,
    colour: impl Fn(u32) -> [u8; 4],
    background: [u8; 4],
) -> Result<CompositeTruth, crate::RasterError> {
    let (width, height) = (view.width(), view.height());
    // (pixel, depth toward the viewer at the centre, face, lowest and highest depth over
    // the pixel's ±EDGE_MARGIN_PX square)
    let mut fragments: Vec<(u32, f64, u32, f64, f64)> = Vec::new();
    let m = EDGE_MARGIN_PX;
    let near_edge = for_each_fragment(view, geometry, |face, pixel, depth| {
        let z = depth(DVec2::ZERO);
        let (mut lo, mut hi) = (z, z);
        for moved in [
            DVec2::new(-m, -m),
            DVec2::new(m, -m),
            DVec2::new(-m, m),
            DVec2::new(m, m),
        ] {
            let d = depth(moved);
            lo = lo.min(d);
            hi = hi.max(d);
        }
        fragments.push((pixel as u32, z, face, lo, hi));
    });
    // Far to near per pixel: depth grows toward the viewer.
    fragments.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let gap = DEPTH_GAP * view.diagonal();
    let mut image = crate::new_pixmap(u64::from(width), u64::from(height))?;
    let [r, g, b, a] = background;
    image.fill(tiny_skia::Color::from_rgba8(r, g, b, a));
    let mut unambiguous: Vec<bool> = near_edge.iter().map(|&e| !e).collect();
    let mut paint = Paint {
        anti_alias: false,
        ..Paint::default()
    };
    for (k, &(pixel, _, face, lo, _)) in fragments.iter().enumerate() {
        // Sorted by centre depth: the nearer one's lowest depth must clear the farther
        // one's highest over the whole square.
        if k > 0 && fragments[k - 1].0 == pixel && lo - fragments[k - 1].4 <= gap {
            unambiguous[pixel as usize] = false;
        }
        let [r, g, b, a] = colour(face);
        paint.set_color_rgba8(r, g, b, a);
        let (x, y) = (pixel % width, pixel / width);
        if let Some(rect) = Rect::from_xywh(x as f32, y as f32, 1.0, 1.0) {
            image.fill_rect(rect, &paint, Transform::identity(), None);
        }
    }
    Ok(CompositeTruth { image, unambiguous })
}
