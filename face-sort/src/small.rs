//! The optional per-frame skip of pieces too small to matter (off unless called).

use glam::DVec2;

use crate::{DrawList, ProjectionScratch, View, signed_area_2d};

/// Drops draw items whose projection covers less than a given area in the image: a
/// trade of exactness for time in the sinks (fewer items to raster, write or send), for
/// callers who accept it. Every pixel a dropped item covered shows what lies behind it
/// instead; raster-sink's pixel error measures the cost (the bench's small-piece curve).
#[derive(Debug, Default)]
pub struct SmallPieceFilter {
    scratch: ProjectionScratch,
    points: Vec<DVec2>,
    keep: Vec<bool>,
}

impl SmallPieceFilter {
    /// A filter (its buffers grow to the largest list seen, then stay).
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Removes from `list`, keeping the order of the rest, every item whose projection
    /// (clipped at the near plane) covers less than `min_area_px2` square pixels; returns
    /// how many it removed. `min_area_px2 <= 0` removes nothing. No allocation once the
    /// buffers have grown.
    pub fn apply(&mut self, view: &View, list: &mut DrawList, min_area_px2: f64) -> usize {
        if min_area_px2 <= 0.0 {
            return 0;
        }
        self.keep.clear();
        for &item in list.items() {
            view.project_polygon(list.corners(item), &mut self.points, &mut self.scratch);
            let area = signed_area_2d(&self.points).abs();
            self.keep.push(area >= min_area_px2);
        }
        let before = list.len();
        let mut k = 0;
        let keep = &self.keep;
        list.items_mut().retain(|_| {
            k += 1;
            keep[k - 1]
        });
        before - list.len()
    }
}
