//! The z-buffer truth and the pixel error of a painter order (CONVENTIONS.md).

use face_sort::glam::{DVec2, DVec3};
use face_sort::{Geometry, PixelRays, Plane, Projection, View};

use crate::fill::{for_each_pixel_near_segment, for_each_span};
use crate::ids::IdImage;
use crate::project::Projector;
use crate::tolerance::{DEPTH_GAP, EDGE_MARGIN_PX};

/// What a depth buffer shows, per pixel centre, and where that answer is unambiguous.
///
/// # Guarantees
/// `ids` and `unambiguous` have `width · height` entries; an unambiguous pixel is covered
/// (`ids != 0`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Truth {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major nearest face per pixel centre: 0 = background, else face index + 1.
    pub ids: Vec<u32>,
    /// Row-major: covered, at least [`EDGE_MARGIN_PX`] from every projected edge of every
    /// drawn piece, and the nearest two depths differ by more than [`DEPTH_GAP`]` · L`.
    pub unambiguous: Vec<bool>,
}

impl Truth {
    /// The truth's IDs as an [`IdImage`] (e.g. to save as PNG).
    #[must_use]
    pub fn to_id_image(&self) -> IdImage {
        IdImage {
            width: self.width,
            height: self.height,
            ids: self.ids.clone(),
        }
    }

    /// Number of unambiguous pixels.
    #[must_use]
    pub fn unambiguous_count(&self) -> usize {
        self.unambiguous.iter().filter(|&&u| u).count()
    }
}

/// The view-space normal and offset of a centred-model-space plane.
#[inline]
pub(crate) fn view_plane(view: &View, plane: &Plane) -> (DVec3, f64) {
    view.plane_to_view(plane.normal(), plane.offset())
}

/// Computes the truth of `geometry` under `view`: per pixel centre, among the pieces the view
/// draws (its cull mode), the one whose plane the pixel's ray meets nearest; ties go to the
/// lower face index. Depths are computed per pixel in f64 and clamped to the piece's own
/// depth range (which only matters for near edge-on pieces).
///
/// Cost: one pixel-centre fill per piece plus a band of ±[`EDGE_MARGIN_PX`] around every
/// projected edge; memory about 21 bytes per pixel while it runs.
#[must_use]
pub fn truth(view: &View, geometry: &Geometry) -> Truth {
    let (width, height) = (view.width(), view.height());
    let n_pixels = width as usize * height as usize;
    let mut best = vec![f64::NEG_INFINITY; n_pixels];
    let mut second = vec![f64::NEG_INFINITY; n_pixels];
    let mut ids = vec![0u32; n_pixels];
    let near_edge = for_each_fragment(view, geometry, |face, k, depth| {
        let (z, face_id) = (depth(DVec2::ZERO), face.wrapping_add(1));
        if z > best[k] || (z == best[k] && face_id < ids[k]) {
            second[k] = best[k];
            best[k] = z;
            ids[k] = face_id;
        } else if z > second[k] {
            second[k] = z;
        }
    });
    let gap = DEPTH_GAP * view.diagonal();
    let unambiguous = (0..n_pixels)
        .map(|k| ids[k] != 0 && !near_edge[k] && best[k] - second[k] > gap)
        .collect();
    Truth {
        width,
        height,
        ids,
        unambiguous,
    }
}

/// Every piece of `geometry` the view draws (its cull mode), filled at pixel centres:
/// `fragment(face, pixel, depth)` for each covered pixel centre (row-major index), where
/// `depth(offset)` is the piece's view-space depth (toward the viewer) on the ray through
/// the centre moved by `offset` pixels, clamped to the piece's own depth range. Returns, per
/// pixel, whether it lies within [`EDGE_MARGIN_PX`] of a drawn piece's projected edge. The
/// one rasterisation of the truths ([`truth`], [`composite_truth`](crate::composite_truth)).
pub(crate) fn for_each_fragment(
    view: &View,
    geometry: &Geometry,
    mut fragment: impl FnMut(u32, usize, &dyn Fn(DVec2) -> f64),
) -> Vec<bool> {
    let (width, height) = (view.width(), view.height());
    let stride = width as usize;
    let mut near_edge = vec![false; stride * height as usize];
    let caster = PixelRays::new(view);
    let cull = view.cull_test();
    let pieces = geometry.pieces();
    let mut projector = Projector::default();
    let near_z = match view.projection() {
        Projection::Orthographic => f64::INFINITY,
        Projection::Perspective { distance } => {
            (1.0 - face_sort::tolerance::NEAR_W) * distance / view.scale()
        }
    };
    for i in 0..pieces.len() {
        let corners = pieces.corners(i);
        let plane = pieces.plane(i);
        if !cull.is_drawn(plane, corners[0]) || !projector.project(view, corners) {
            continue;
        }
        let face = pieces.face(i);
        let (n, offset) = view_plane(view, plane);
        let (mut z_lo, mut z_hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for &c in corners {
            let z = view.to_view(c).z;
            z_lo = z_lo.min(z);
            z_hi = z_hi.max(z);
        }
        z_hi = z_hi.min(near_z);
        let points = &projector.points;
        for_each_span(points, width, height, |y, x0, x1| {
            for x in x0..x1 {
                let centre = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
                let depth = |moved: DVec2| {
                    let z = caster.depth(centre + moved, n, offset);
                    if z.is_nan() {
                        z_hi
                    } else {
                        z.clamp(z_lo, z_hi)
                    }
                };
                fragment(face, y as usize * stride + x as usize, &depth);
            }
        });
        let m = points.len();
        for e in 0..m {
            for_each_pixel_near_segment(
                points[e],
                points[(e + 1) % m],
                EDGE_MARGIN_PX,
                width,
                height,
                |x, y| near_edge[y as usize * stride + x as usize] = true,
            );
        }
    }
    near_edge
}

/// The pixel error of a painter's ID image against the truth (CONVENTIONS.md).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelError {
    /// Unambiguous (hence covered) pixels of the truth.
    pub pixels: usize,
    /// Unambiguous pixels whose painter ID differs from the truth.
    pub wrong: usize,
    /// `wrong / pixels`, 0 when `pixels == 0`.
    pub error: f64,
}

/// Compares a painter's ID image with the truth over the truth's unambiguous pixels.
/// A painter image of another size counts its missing pixels as background.
#[must_use]
pub fn pixel_error(painter: &IdImage, truth: &Truth) -> PixelError {
    let (mut pixels, mut wrong) = (0usize, 0usize);
    let same_size = painter.width == truth.width && painter.height == truth.height;
    for (k, (&unambiguous, &id)) in truth.unambiguous.iter().zip(&truth.ids).enumerate() {
        if !unambiguous {
            continue;
        }
        pixels += 1;
        let painted = if same_size {
            painter.ids.get(k).copied().unwrap_or(0)
        } else {
            let w = truth.width.max(1) as usize;
            painter.get((k % w) as u32, (k / w) as u32).unwrap_or(0)
        };
        if painted != id {
            wrong += 1;
        }
    }
    PixelError {
        pixels,
        wrong,
        error: if pixels == 0 {
            0.0
        } else {
            wrong as f64 / pixels as f64
        },
    }
}
