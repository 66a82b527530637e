//! The baseline: sort drawn pieces by the view depth of their centroid.

use std::sync::Arc;

use glam::DVec3;

use crate::{DrawList, FaceSorter, Geometry, PolygonSet, SorterStats, View};

/// Sorts pieces by view-space centroid depth, farthest first. What most tools ship; fast and
/// visibly wrong on ordinary models. The baseline of every benchmark.
#[derive(Debug)]
pub struct Centroid {
    pieces: Arc<PolygonSet>,
    centroids: Vec<DVec3>,
    keys: Vec<(f64, u32)>,
}

impl Centroid {
    /// A centroid sorter over a geometry's pieces.
    #[must_use]
    pub fn new(geometry: &Geometry) -> Self {
        let pieces = Arc::clone(geometry.pieces());
        let centroids = (0..pieces.len())
            .map(|i| {
                let c = pieces.corners(i);
                c.iter().copied().sum::<DVec3>() / c.len() as f64
            })
            .collect();
        Centroid {
            pieces,
            centroids,
            keys: Vec::new(),
        }
    }
}

impl FaceSorter for Centroid {
    fn name(&self) -> &'static str {
        "centroid"
    }

    fn sort(&mut self, view: &View, out: &mut DrawList) {
        let cull = view.cull_test();
        let depth_axis = view.rotation().row(2);
        self.keys.clear();
        for (i, plane) in self.pieces.planes().iter().enumerate() {
            if cull.is_drawn(plane, self.pieces.corners(i)[0]) {
                self.keys
                    .push((depth_axis.dot(self.centroids[i]), i as u32));
            }
        }
        self.keys.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        out.begin(&self.pieces);
        for &(_, i) in &self.keys {
            out.push(i, self.pieces.face(i as usize));
        }
    }

    fn stats(&self) -> SorterStats {
        SorterStats {
            polygons: self.pieces.len(),
            cached_bytes: self.centroids.capacity() * size_of::<DVec3>()
                + self.keys.capacity() * size_of::<(f64, u32)>(),
            ..SorterStats::default()
        }
    }
}
