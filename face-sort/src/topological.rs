//! The seed's pairwise rule as a graph built once in model space, ordered per view by Kahn's
//! algorithm over the drawn subset. Cheap per frame, not exact.

use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::sync::Arc;
use web_time::Instant;

use glam::DVec3;

use crate::plane::Side;
use crate::tolerance::{PLANE_SIDE, SAME_CORNER, UNDERFLOW_ABS};
use crate::{DrawList, FaceSorter, Geometry, PolygonSet, SorterStats, View};

/// Tag bit on an adjacency entry: the relation holds both ways with the same side (each
/// behind the other's plane, or each in front): two such pieces that both face the viewer
/// cannot hide one another, and their two edges would only make a cycle.
const MUTUAL: u32 = 1 << 31;
/// Tag bit on an adjacency entry: the piece lies in front of the other's plane (else behind).
const FRONT: u32 = 1 << 30;
/// Tag bit on an adjacency entry: the two pieces share an edge. Two pieces sharing an edge
/// that both face the viewer lie on either side of it on screen: they never overlap.
const ADJACENT: u32 = 1 << 29;
/// The piece index in an adjacency entry.
const INDEX: u32 = ADJACENT - 1;

/// Meshes up to this many pieces test every pair; larger ones only pairs within reach.
const ALL_PAIRS_LIMIT: usize = 512;
/// On large meshes, pairs are considered when their bounding spheres come within this many
/// median piece diameters of each other.
const REACH_IN_DIAMETERS: f64 = 2.0;

/// Pairwise plane-side graph + Kahn's algorithm per view; cycles and unrelated pairs fall back
/// to centroid depth order.
///
/// The graph holds a relation `(x, y, side)` when every corner of `x` is on one side of `y`'s
/// plane (or on it) and one strictly on that side — the seed's "behind" rule, and its mirror
/// "in front". Per view, `x` goes after `y` when the viewer is on `x`'s side of `y`'s plane
/// (only `x` can hide `y` then), before it otherwise. Relations are skipped in a view when they
/// cannot matter: both pieces face the viewer and either share an edge or each lies on the same
/// side of the other's plane, or their screen circles are apart.
///
/// The relations are only *safe* directions, not *required* ones: between pieces that do not
/// overlap on screen they still constrain, and on curved meshes they form cycles through
/// non-overlapping pieces (hundreds per frame on spot), each broken by drawing the farthest
/// remaining piece. So this sorter is measured, not promised: it beats the centroid order on
/// boxy scenes (the cornell box) and loses to it on curved ones. Meshes of more than 512 pieces only relate pieces within two median
/// piece diameters of each other (a spatial grid), so the build stays near-linear: an
/// approximation on top of an approximation, measured by the bench like everything else.
#[derive(Debug)]
pub struct Topological {
    pieces: Arc<PolygonSet>,
    centroids: Vec<DVec3>,
    /// Bounding-sphere radius of each piece about its centroid.
    radii: Vec<f64>,
    /// For piece `u`: the pieces `y` whose plane `u` lies on one side of (entries tagged).
    sides_of_start: Vec<u32>,
    sides_of: Vec<u32>,
    /// For piece `u`: the pieces `x` lying on one side of `u`'s plane (entries tagged).
    sided_by_start: Vec<u32>,
    sided_by: Vec<u32>,
    build_ms: f64,
    // Per-frame buffers.
    drawn: Vec<bool>,
    facing: Vec<bool>,
    in_degree: Vec<u32>,
    emitted: Vec<bool>,
    depth: Vec<f64>,
    by_depth: Vec<u32>,
    ready: BinaryHeap<Ready>,
    released: Vec<u32>,
    /// Per frame: each piece's bounding circle on screen (view units) as `(x, y, radius)`.
    screen: Vec<DVec3>,
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
        let radii: Vec<f64> = (0..n)
            .map(|i| {
                pieces
                    .corners(i)
                    .iter()
                    .map(|c| c.distance(centroids[i]))
                    .fold(0.0, f64::max)
            })
            .collect();
        let same_corner_sq = (SAME_CORNER * geometry.bounds().diagonal()).powi(2);
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        let mut relate = |a: usize, b: usize| {
            let tag = |side: Side| match side {
                Side::Back => Some(0),
                Side::Front => Some(FRONT),
                _ => None,
            };
            let a_side = tag(pieces
                .plane(b)
                .side_of_polygon(pieces.corners(a), tolerance));
            let b_side = tag(pieces
                .plane(a)
                .side_of_polygon(pieces.corners(b), tolerance));
            let mutual = if a_side.is_some() && a_side == b_side {
                MUTUAL
            } else {
                0
            };
            let (corners_a, corners_b) = (pieces.corners(a), pieces.corners(b));
            let shared = corners_a
                .iter()
                .filter(|p| {
                    corners_b
                        .iter()
                        .any(|q| p.distance_squared(*q) <= same_corner_sq)
                })
                .count();
            let adjacent = if shared >= 2 { ADJACENT } else { 0 };
            if let Some(side) = a_side {
                pairs.push((a as u32, b as u32 | side | mutual | adjacent));
            }
            if let Some(side) = b_side {
                pairs.push((b as u32, a as u32 | side | mutual | adjacent));
            }
        };
        if n > INDEX as usize {
            // Beyond 2^29 pieces the tagged entries cannot hold an index: depth order only.
        } else if n <= ALL_PAIRS_LIMIT {
            for a in 0..n {
                for b in a + 1..n {
                    relate(a, b);
                }
            }
        } else {
            for_each_near_pair(&centroids, &radii, &mut relate);
        }
        let (sides_of_start, sides_of) = csr(n, pairs.iter().map(|&(x, y)| (x, y)));
        let (sided_by_start, sided_by) =
            csr(n, pairs.iter().map(|&(x, y)| (y & INDEX, x | (y & !INDEX))));
        Topological {
            centroids,
            radii,
            screen: vec![DVec3::ZERO; n],
            sides_of_start,
            sides_of,
            sided_by_start,
            sided_by,
            build_ms: start.elapsed().as_secs_f64() * 1e3,
            drawn: vec![false; n],
            facing: vec![false; n],
            in_degree: vec![0; n],
            emitted: vec![false; n],
            depth: vec![0.0; n],
            by_depth: Vec::with_capacity(n),
            ready: BinaryHeap::with_capacity(n),
            released: Vec::new(),
            fallbacks: 0,
            pieces,
        }
    }

    /// Number of pair relations in the graph.
    #[must_use]
    pub fn edge_count(&self) -> usize {
        self.sides_of.len()
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

/// Calls `f` for every piece that must be drawn after `u` in this frame (`facing[i]`: the
/// viewer is in front of piece `i`'s plane). Relations between pieces whose screen circles are
/// apart are skipped: they constrain nothing in this view and would only make cycles.
fn for_each_successor(
    u: usize,
    facing: &[bool],
    screen: &[DVec3],
    (sides_of_start, sides_of): (&[u32], &[u32]),
    (sided_by_start, sided_by): (&[u32], &[u32]),
    mut f: impl FnMut(usize),
) {
    // `u` lies on one side of `y`'s plane: `u` goes before `y` unless the viewer is on `u`'s side.
    for &entry in &sides_of[sides_of_start[u] as usize..sides_of_start[u + 1] as usize] {
        let y = (entry & INDEX) as usize;
        let front = entry & FRONT != 0;
        let skip =
            (entry & (MUTUAL | ADJACENT) != 0 && facing[u] && facing[y]) || apart(screen, u, y);
        if !skip && facing[y] != front {
            f(y);
        }
    }
    // `x` lies on one side of `u`'s plane: `x` goes after `u` when the viewer is on `x`'s side.
    for &entry in &sided_by[sided_by_start[u] as usize..sided_by_start[u + 1] as usize] {
        let x = (entry & INDEX) as usize;
        let front = entry & FRONT != 0;
        let skip =
            (entry & (MUTUAL | ADJACENT) != 0 && facing[u] && facing[x]) || apart(screen, u, x);
        if !skip && facing[u] == front {
            f(x);
        }
    }
}

#[inline]
fn apart(screen: &[DVec3], a: usize, b: usize) -> bool {
    let (p, q) = (screen[a], screen[b]);
    let d = p.truncate() - q.truncate();
    d.length_squared() > (p.z + q.z) * (p.z + q.z)
}

/// A conservative screen circle (view units, `(x, y, radius)`) of a sphere in centred model space.
fn screen_circle(view: &View, centre: DVec3, radius: f64) -> DVec3 {
    let v = view.to_view(centre);
    if view.eye_in_view().is_none() {
        return DVec3::new(v.x, v.y, radius);
    }
    // w of the sphere's centre and of its point nearest the eye.
    let w = view.w_of_view_point(v);
    let w_near = view.w_of_view_point(v + DVec3::Z * radius);
    if w_near <= crate::tolerance::NEAR_W {
        return DVec3::new(v.x, v.y, f64::INFINITY);
    }
    let xy = v.truncate() / w;
    let spread = v.truncate().length() * (1.0 / w_near - 1.0 / w).abs();
    DVec3::new(xy.x, xy.y, radius / w_near + spread)
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
fn for_each_near_pair(centroids: &[DVec3], radii: &[f64], f: &mut impl FnMut(usize, usize)) {
    let n = centroids.len();
    let mut sorted = radii.to_vec();
    sorted.sort_unstable_by(f64::total_cmp);
    let median = sorted[n / 2].max(UNDERFLOW_ABS);
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
            self.screen[i] = screen_circle(view, self.centroids[i], self.radii[i]);
            if self.drawn[i] {
                self.by_depth.push(i as u32);
            }
        }
        for u in 0..n {
            if !self.drawn[u] {
                continue;
            }
            let (in_degree, drawn) = (&mut self.in_degree, &self.drawn);
            for_each_successor(
                u,
                &self.facing,
                &self.screen,
                (&self.sides_of_start, &self.sides_of),
                (&self.sided_by_start, &self.sided_by),
                |v| {
                    if drawn[v] {
                        in_degree[v] += 1;
                    }
                },
            );
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
            let mut released = std::mem::take(&mut self.released);
            released.clear();
            for_each_successor(
                u,
                &self.facing,
                &self.screen,
                (&self.sides_of_start, &self.sides_of),
                (&self.sided_by_start, &self.sided_by),
                |v| released.push(v as u32),
            );
            for &v in &released {
                self.release(v as usize);
            }
            self.released = released;
        }
    }

    fn stats(&self) -> SorterStats {
        SorterStats {
            build_ms: self.build_ms,
            polygons: self.pieces.len(),
            cached_bytes: (self.sides_of.capacity()
                + self.sides_of_start.capacity()
                + self.sided_by.capacity()
                + self.sided_by_start.capacity())
                * 4
                + self.centroids.capacity() * size_of::<DVec3>(),
            fallbacks: self.fallbacks,
            ..SorterStats::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn sphere(rings: u32, segments: u32) -> crate::PolygonMesh {
        let mut positions = vec![DVec3::Y, -DVec3::Y];
        for r in 1..rings {
            let phi = std::f64::consts::PI * f64::from(r) / f64::from(rings);
            for s in 0..segments {
                let theta = std::f64::consts::TAU * f64::from(s) / f64::from(segments);
                positions.push(DVec3::new(
                    phi.sin() * theta.cos(),
                    phi.cos(),
                    -phi.sin() * theta.sin(),
                ));
            }
        }
        let at = |r: u32, s: u32| 2 + (r - 1) * segments + s % segments;
        let mut faces: Vec<Vec<u32>> = Vec::new();
        for s in 0..segments {
            faces.push(vec![0, at(1, s + 1), at(1, s)]);
            faces.push(vec![1, at(rings - 1, s), at(rings - 1, s + 1)]);
            for r in 1..rings - 1 {
                faces.push(vec![at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r + 1, s)]);
            }
        }
        crate::PolygonMesh::new(positions, faces).unwrap()
    }

    #[test]
    fn a_convex_mesh_has_no_cycle() {
        let geometry = Geometry::new(&sphere(12, 24)).unwrap();
        let mut sorter = Topological::new(&geometry);
        let mut list = DrawList::new();
        let view = View::fit(&geometry.bounds(), 256, 256).with_yaw_pitch_roll(30.0, 20.0, 0.0);
        sorter.sort(&view, &mut list);
        assert!(list.len() > 100);
        assert_eq!(sorter.stats().fallbacks, 0);
    }
}
