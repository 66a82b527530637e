//! Projection of draw-list polygons and pieces to pixel coordinates.

use face_sort::glam::DVec2;
use face_sort::{ProjectionScratch, View, glam::DVec3};

use crate::tolerance::DEGENERATE_PROJECTED_AREA;

/// Reusable buffers for projecting polygons.
#[derive(Debug, Default)]
pub(crate) struct Projector {
    pub(crate) points: Vec<DVec2>,
    scratch: ProjectionScratch,
}

impl Projector {
    /// Projects (near-clipped) into `self.points`; returns false (and leaves `points` empty)
    /// when nothing with area is left.
    pub(crate) fn project(&mut self, view: &View, corners: &[DVec3]) -> bool {
        view.project_polygon(corners, &mut self.points, &mut self.scratch);
        if self.points.len() < 3 || !self.points.iter().all(|p| p.is_finite()) {
            self.points.clear();
            return false;
        }
        if is_degenerate(&self.points) {
            self.points.clear();
            return false;
        }
        true
    }
}

/// Whether a projected polygon has zero area per [`DEGENERATE_PROJECTED_AREA`].
pub(crate) fn is_degenerate(points: &[DVec2]) -> bool {
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for &p in points {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    let d2 = (hi - lo).length_squared();
    let area2 = face_sort::signed_area_2d(points).abs() * 2.0;
    area2.is_nan() || area2 <= DEGENERATE_PROJECTED_AREA * d2
}
