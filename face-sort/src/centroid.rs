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
    scratch: Vec<(f64, u32)>,
}

/// From this many drawn pieces on, the depths are radix sorted.
const RADIX_MIN: usize = 1024;

/// Sorts `keys` by depth (`f64::total_cmp`): a comparison sort for few keys, else a radix sort
/// (8 bits a pass from the lowest; passes whose digit every key shares are skipped, which a
/// model's depths, close in sign and exponent, make most of the high ones). The radix sort
/// pays off from `RADIX_MIN` keys on; below it, it is no faster than the comparison sort
/// (measurements in docs/bench.md).
fn sort_by_depth(keys: &mut Vec<(f64, u32)>, scratch: &mut Vec<(f64, u32)>) {
    if keys.len() < RADIX_MIN {
        keys.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        return;
    }
    // An integer with `total_cmp`'s order.
    let bits = |x: f64| {
        let b = x.to_bits();
        if b >> 63 == 1 { !b } else { b | (1 << 63) }
    };
    let mut counts = [[0u32; 256]; 8];
    for k in keys.iter() {
        let b = bits(k.0);
        for (pass, c) in counts.iter_mut().enumerate() {
            c[((b >> (8 * pass)) & 255) as usize] += 1;
        }
    }
    scratch.clear();
    scratch.resize(keys.len(), (0.0, 0));
    let n = keys.len() as u32;
    for (pass, c) in counts.iter_mut().enumerate() {
        if c.contains(&n) {
            continue;
        }
        let mut start = 0;
        for count in c.iter_mut() {
            (*count, start) = (start, start + *count);
        }
        for k in keys.iter() {
            let digit = &mut c[((bits(k.0) >> (8 * pass)) & 255) as usize];
            scratch[*digit as usize] = *k;
            *digit += 1;
        }
        std::mem::swap(keys, scratch);
    }
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
            scratch: Vec::new(),
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
        sort_by_depth(&mut self.keys, &mut self.scratch);
        out.begin(&self.pieces);
        for &(_, i) in &self.keys {
            out.push(i, self.pieces.face(i as usize));
        }
    }

    fn stats(&self) -> SorterStats {
        SorterStats {
            polygons: self.pieces.len(),
            cached_bytes: self.centroids.capacity() * size_of::<DVec3>()
                + (self.keys.capacity() + self.scratch.capacity()) * size_of::<(f64, u32)>(),
            ..SorterStats::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_radix_sort_orders_as_total_cmp() {
        let mut rng = crate::generate::Rng::new(7);
        for n in [RADIX_MIN, 3000] {
            let mut keys: Vec<(f64, u32)> = (0..n as u32)
                .map(|i| {
                    let r = rng.next_u64();
                    // Depths near one another, both signs, zeros of both signs, and ties.
                    let d = match r % 7 {
                        0 => 0.0,
                        1 => -0.0,
                        2 => -((r >> 8) as f64) * 1e-9,
                        3 => 0.5,
                        _ => ((r >> 11) as f64) * 1e-12 - 3.0,
                    };
                    (d, i)
                })
                .collect();
            let mut want = keys.clone();
            want.sort_by(|a, b| a.0.total_cmp(&b.0));
            sort_by_depth(&mut keys, &mut Vec::new());
            let depths = |v: &[(f64, u32)]| v.iter().map(|k| k.0.to_bits()).collect::<Vec<_>>();
            assert_eq!(depths(&keys), depths(&want));
        }
    }
}
