//! The seed's pairwise rule as a graph built once in model space, ordered per view by Kahn's
//! algorithm over the drawn subset. Cheap per frame, not exact.

use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::sync::Arc;
use std::time::Instant;

use glam::DVec3;

use crate::plane::Side;
use crate::tolerance::PLANE_SIDE;
use crate::{DrawList, FaceSorter, Geometry, PolygonSet, SorterStats, View};

/// Meshes up to this many pieces test every pair; larger ones only pairs within reach.
const ALL_PAIRS_LIMIT: usize = 512;
/// On large meshes, pairs are considered when their bounding spheres come within this many
/// median piece diameters of each other.
const REACH_IN_DIAMETERS: f64 = 2.0;

/// Pairwise "behind" graph + Kahn's algorithm per view; cycles and unrelated pairs fall back to
/// centroid depth order.
///
/// The graph holds a pair `(x, y)` when every corner of `x` is on or behind `y`'s plane and one
/// strictly behind. Per view, `x` goes before `y` when the viewer is in front of `y`'s plane,
/// after it otherwise. Meshes of more than 512 pieces only relate pieces within two median
/// piece diameters of each other (a spatial grid), so the build stays near-linear: an
/// approximation on top of an approximation, measured by the bench like everything else.
#[derive(Debug)]
pub struct Topological {
    pieces: Arc<PolygonSet>,
    centroids: Vec<DVec3>,
    /// For piece `u`: `after[u]` = pieces `y` such that `u` is behind `y`'s plane.
    after_start: Vec<u32>,
    after: Vec<u32>,
    /// For piece `u`: `behind[u]` = pieces `x` behind `u`'s plane.
    behind_start: Vec<u32>,
    behind: Vec<u32>,
    build_ms: f64,
    // Per-frame buffers.
    drawn: Vec<bool>,
    facing: Vec<bool>,
    in_degree: Vec<u32>,
    emitted: Vec<bool>,
    depth: Vec<f64>,
    by_depth: Vec<u32>,
    ready: BinaryHeap<Ready>,
    fallbacks: usize,
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Ready {
    depth: f64,
    piece: u32,
}
impl Eq for Ready {}
impl PartialOrd for Ready {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Ready {
    fn cmp(&self, other: &Self) -> Ordering {
        // Max-heap: the farthest (smallest depth) first.
        other
            .depth
            .total_cmp(&self.depth)
            .then_with(|| other.piece.cmp(&self.piece))
    }
}

impl Topological {
    /// Builds the pair graph over a geometry's pieces.
    #[must_use]
    pub fn new(geometry: &Geometry) -> Self {
        let start = Instant::now();
        let pieces = Arc::clone(geometry.pieces());
        let n = pieces.len();
        let tolerance = PLANE_SIDE * geometry.bounds().diagonal();
        let centroids: Vec<DVec3> = (0..n)
            .map(|i| {
                let c = pieces.corners(i);
                c.iter().copied().sum::<DVec3>() / c.len() as f64
            })
            .collect();
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        let mut relate = |a: usize, b: usize| {
            if pieces
                .plane(b)
                .side_of_polygon(pieces.corners(a), tolerance)
                == Side::Back
            {
                pairs.push((a as u32, b as u32));
            }
            if pieces
                .plane(a)
                .side_of_polygon(pieces.corners(b), tolerance)
                == Side::Back
            {
                pairs.push((b as u32, a as u32));
            }
        };
        if n <= ALL_PAIRS_LIMIT {
            for a in 0..n {
                for b in a + 1..n {
                    relate(a, b);
                }
            }
        } else {
            for_each_near_pair(&pieces, &centroids, &mut relate);
        }
        let (after_start, after) = csr(n, pairs.iter().map(|&(x, y)| (x, y)));
        let (behind_start, behind) = csr(n, pairs.iter().map(|&(x, y)| (y, x)));
        Topological {
            centroids,
            after_start,
            after,
            behind_start,
            behind,
            build_ms: start.elapsed().as_secs_f64() * 1e3,
            drawn: vec![false; n],
            facing: vec![false; n],
            in_degree: vec![0; n],
            emitted: vec![false; n],
            depth: vec![0.0; n],
            by_depth: Vec::with_capacity(n),
            ready: BinaryHeap::with_capacity(n),
            fallbacks: 0,
            pieces,
        }
    }

    /// Number of pair relations in the graph.
    #[must_use]
    pub fn edge_count(&self) -> usize {
        self.after.len()
    }

    /// One predecessor of `v` was drawn: `v` is ready when it has none left.
    #[inline]
    fn release(&mut self, v: usize) {
        if self.drawn[v] && !self.emitted[v] {
            self.in_degree[v] = self.in_degree[v].saturating_sub(1);
            if self.in_degree[v] == 0 {
                self.ready.push(Ready {
                    depth: self.depth[v],
                    piece: v as u32,
                });
            }
        }
    }
}

/// Compressed adjacency lists from (from, to) pairs.
fn csr(n: usize, edges: impl Iterator<Item = (u32, u32)> + Clone) -> (Vec<u32>, Vec<u32>) {
    let mut start = vec![0u32; n + 1];
    for (from, _) in edges.clone() {
        start[from as usize + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut list = vec![0u32; start[n] as usize];
    for (from, to) in edges {
        list[fill[from as usize] as usize] = to;
        fill[from as usize] += 1;
    }
    (start, list)
}

/// Calls `f(a, b)` for pairs of pieces whose bounding spheres come within reach (a uniform grid
/// of cells two reaches wide).
fn for_each_near_pair(pieces: &PolygonSet, centroids: &[DVec3], f: &mut impl FnMut(usize, usize)) {
    let n = pieces.len();
    let radii: Vec<f64> = (0..n)
        .map(|i| {
            pieces
                .corners(i)
                .iter()
                .map(|c| c.distance(centroids[i]))
                .fold(0.0, f64::max)
        })
        .collect();
    let mut sorted = radii.clone();
    sorted.sort_unstable_by(f64::total_cmp);
    let median = sorted[n / 2].max(1e-300);
    let cell = 2.0 * median * (1.0 + REACH_IN_DIAMETERS);
    let key = |p: DVec3| {
        let c = (p / cell).floor();
        (c.x as i64, c.y as i64, c.z as i64)
    };
    let mut cells: std::collections::HashMap<(i64, i64, i64), Vec<u32>> = Default::default();
    for (i, &c) in centroids.iter().enumerate() {
        cells.entry(key(c)).or_default().push(i as u32);
    }
    let reach = 2.0 * median * REACH_IN_DIAMETERS;
    for (&(x, y, z), members) in &cells {
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(others) = cells.get(&(x + dx, y + dy, z + dz)) else {
                        continue;
                    };
                    for &a in members {
                        for &b in others {
                            if a >= b {
                                continue;
                            }
                            let (a, b) = (a as usize, b as usize);
                            if centroids[a].distance(centroids[b]) <= radii[a] + radii[b] + reach {
                                f(a, b);
                            }
                        }
                    }
                }
            }
        }
    }
}

impl FaceSorter for Topological {
    fn name(&self) -> &'static str {
        "topological"
    }

    fn sort(&mut self, view: &View, out: &mut DrawList) {
        let cull = view.cull_test();
        let depth_axis = view.rotation().row(2);
        let n = self.pieces.len();
        self.by_depth.clear();
        self.ready.clear();
        self.fallbacks = 0;
        for i in 0..n {
            let plane = self.pieces.plane(i);
            self.drawn[i] = cull.is_drawn(plane, self.pieces.corners(i)[0]);
            self.facing[i] = cull.viewer.facing(plane) >= 0.0;
            self.in_degree[i] = 0;
            self.emitted[i] = false;
            self.depth[i] = depth_axis.dot(self.centroids[i]);
            if self.drawn[i] {
                self.by_depth.push(i as u32);
            }
        }
        for u in 0..n {
            if !self.drawn[u] {
                continue;
            }
            let mut count = |v: usize| {
                if self.drawn[v] {
                    self.in_degree[v] += 1;
                }
            };
            for &y in &self.after[self.after_start[u] as usize..self.after_start[u + 1] as usize] {
                if self.facing[y as usize] {
                    count(y as usize);
                }
            }
            if !self.facing[u] {
                for &x in
                    &self.behind[self.behind_start[u] as usize..self.behind_start[u + 1] as usize]
                {
                    count(x as usize);
                }
            }
        }
        let depth = &self.depth;
        self.by_depth
            .sort_unstable_by(|&a, &b| depth[a as usize].total_cmp(&depth[b as usize]));
        for &i in &self.by_depth {
            if self.in_degree[i as usize] == 0 {
                self.ready.push(Ready {
                    depth: self.depth[i as usize],
                    piece: i,
                });
            }
        }
        out.begin(&self.pieces);
        let mut cursor = 0;
        let mut emitted = 0;
        let total = self.by_depth.len();
        while emitted < total {
            let u = match self.ready.pop() {
                Some(r) if !self.emitted[r.piece as usize] => r.piece as usize,
                Some(_) => continue,
                None => {
                    // A cycle: break it with the farthest piece not yet drawn.
                    while self.emitted[self.by_depth[cursor] as usize] {
                        cursor += 1;
                    }
                    self.fallbacks += 1;
                    self.by_depth[cursor] as usize
                }
            };
            self.emitted[u] = true;
            emitted += 1;
            out.push(u as u32, self.pieces.face(u));
            let (a0, a1) = (
                self.after_start[u] as usize,
                self.after_start[u + 1] as usize,
            );
            for k in a0..a1 {
                let y = self.after[k] as usize;
                if self.facing[y] {
                    self.release(y);
                }
            }
            if !self.facing[u] {
                let (b0, b1) = (
                    self.behind_start[u] as usize,
                    self.behind_start[u + 1] as usize,
                );
                for k in b0..b1 {
                    self.release(self.behind[k] as usize);
                }
            }
        }
    }

    fn stats(&self) -> SorterStats {
        SorterStats {
            build_ms: self.build_ms,
            polygons: self.pieces.len(),
            cached_bytes: (self.after.capacity()
                + self.after_start.capacity()
                + self.behind.capacity()
                + self.behind_start.capacity())
                * 4
                + self.centroids.capacity() * size_of::<DVec3>(),
            depth: 0,
            fallbacks: self.fallbacks,
        }
    }
}
