//! Seam-free anti-aliasing: find the edges shared by two drawn polygons and push the fill
//! out across them by a fraction of a pixel. raster-sink's PNG and the HTML writer's colour
//! pages both use it, so that their pictures agree along every shared edge.
//!
//! Anti-aliased neighbours *conflate*: a pixel half covered by each of two adjacent polygons
//! ends up 75 % colour and 25 % background after both are composited, a hairline of
//! background along every internal edge. Outsetting each polygon by about half a pixel along
//! its shared edges makes every pixel on such an edge fully covered by at least one of the two
//! (the later one, painted on top, is the one that shows, and along a shared edge both lie
//! at the same depth). Silhouette edges are left where they are, so the outline stays exact.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use glam::DVec2;

use crate::tolerance::{SEAM_PARALLEL_NORMALS, SEAM_SHARED_EDGE_PX};

/// Polygons drawn in one frame, in paint order: screen points (pixels) stored flat, so that
/// a frame reuses the storage of the last.
#[derive(Debug, Default)]
pub struct ScreenPolygons {
    points: Vec<DVec2>,
    /// `starts[i]..starts[i + 1]` are polygon `i`'s points; edge `k` runs from point `k` to the
    /// next point of the same polygon (cyclic).
    starts: Vec<usize>,
}

impl ScreenPolygons {
    /// Forgets every polygon (keeping the storage).
    pub fn clear(&mut self) {
        self.points.clear();
        self.starts.clear();
        self.starts.push(0);
    }

    /// Appends a polygon (its corners in order, either orientation).
    pub fn push(&mut self, points: &[DVec2]) {
        if self.starts.is_empty() {
            self.starts.push(0);
        }
        self.points.extend_from_slice(points);
        self.starts.push(self.points.len());
    }

    /// How many polygons there are.
    #[must_use]
    pub fn len(&self) -> usize {
        self.starts.len().saturating_sub(1)
    }

    /// Whether there are none.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Polygon `i`'s corners. Panics when `i >= len()`.
    #[must_use]
    pub fn polygon(&self, i: usize) -> &[DVec2] {
        &self.points[self.edges(i)]
    }

    /// The indices of polygon `i`'s edges among all polygons' edges (edge `k` runs from
    /// corner `k` to the next corner of the same polygon), as [`SharedEdges::flags`] takes
    /// them. Panics when `i >= len()`.
    #[must_use]
    pub fn edges(&self, i: usize) -> std::ops::Range<usize> {
        self.starts[i]..self.starts[i + 1]
    }
    fn edge(&self, polygon: usize, k: usize) -> (DVec2, DVec2) {
        let (s, e) = (self.starts[polygon], self.starts[polygon + 1]);
        let next = if k + 1 == e { s } else { k + 1 };
        (self.points[k], self.points[next])
    }
}

/// A tiny multiplicative hasher for integer keys (FxHash's mixing).
#[derive(Default)]
struct FxHasher(u64);

impl Hasher for FxHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    fn write_u64(&mut self, i: u64) {
        self.0 = (self.0.rotate_left(5) ^ i).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
    fn write_i64(&mut self, i: i64) {
        self.write_u64(i as u64);
    }
}

type EdgeKey = [i64; 4];

/// Which edges of a set of [`ScreenPolygons`] another polygon shares; reusable between
/// frames.
#[derive(Default)]
pub struct SharedEdges {
    /// Per point index (= edge index): whether that edge is shared.
    shared: Vec<bool>,
    counts: HashMap<EdgeKey, u32, BuildHasherDefault<FxHasher>>,
    loose: Vec<(f64, f64, usize, usize)>,
}

impl std::fmt::Debug for SharedEdges {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SharedEdges").finish_non_exhaustive()
    }
}

const QUANTUM: f64 = 256.0;

fn key(a: DVec2, b: DVec2) -> EdgeKey {
    let q = |p: DVec2| {
        (
            (p.x * QUANTUM).round() as i64,
            (p.y * QUANTUM).round() as i64,
        )
    };
    let (qa, qb) = (q(a), q(b));
    let (lo, hi) = if qa <= qb { (qa, qb) } else { (qb, qa) };
    [lo.0, lo.1, hi.0, hi.1]
}

impl SharedEdges {
    /// Whether each of the edges `edges` (a range from [`ScreenPolygons::edges`]) is shared,
    /// as of the last [`compute`](Self::compute). Panics when the range is out of bounds.
    #[must_use]
    pub fn flags(&self, edges: std::ops::Range<usize>) -> &[bool] {
        &self.shared[edges]
    }

    /// Marks every edge of `polygons` that another polygon shares: same endpoints (within
    /// [`SEAM_SHARED_EDGE_PX`]), or collinear with a positive overlap (T-junctions, e.g. where a
    /// sorter split one face but not its neighbour).
    pub fn compute(&mut self, polygons: &ScreenPolygons) {
        let n_edges = polygons.points.len();
        self.shared.clear();
        self.shared.resize(n_edges, false);
        self.counts.clear();
        for i in 0..polygons.len() {
            for k in polygons.starts[i]..polygons.starts[i + 1] {
                let (a, b) = polygons.edge(i, k);
                *self.counts.entry(key(a, b)).or_insert(0) += 1;
            }
        }
        self.loose.clear();
        for i in 0..polygons.len() {
            for k in polygons.starts[i]..polygons.starts[i + 1] {
                let (a, b) = polygons.edge(i, k);
                if self.counts.get(&key(a, b)).copied().unwrap_or(0) >= 2 {
                    self.shared[k] = true;
                } else {
                    self.loose.push((a.x.min(b.x), a.x.max(b.x), i, k));
                }
            }
        }
        // Unmatched edges: collinear overlaps, found by a sweep over x.
        self.loose.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        let eps = SEAM_SHARED_EDGE_PX;
        for s in 0..self.loose.len() {
            let (_, max_x, pi, ki) = self.loose[s];
            let (a0, a1) = polygons.edge(pi, ki);
            for t in s + 1..self.loose.len() {
                let (min_x2, _, pj, kj) = self.loose[t];
                if min_x2 > max_x + eps {
                    break;
                }
                if pi == pj {
                    continue;
                }
                let (b0, b1) = polygons.edge(pj, kj);
                if collinear_overlap(a0, a1, b0, b1, eps) {
                    self.shared[ki] = true;
                    self.shared[kj] = true;
                }
            }
        }
    }
}

/// Whether segments `a` and `b` lie on one line (within `eps`) and overlap by more than `eps`.
fn collinear_overlap(a0: DVec2, a1: DVec2, b0: DVec2, b1: DVec2, eps: f64) -> bool {
    let d = a1 - a0;
    let len = d.length();
    if len <= eps || (b1 - b0).length() <= eps {
        return false;
    }
    let u = d / len;
    let off = |p: DVec2| u.perp_dot(p - a0).abs();
    if off(b0) > eps || off(b1) > eps {
        return false;
    }
    let (t0, t1) = (u.dot(b0 - a0), u.dot(b1 - a0));
    let (lo, hi) = (t0.min(t1).max(0.0), t0.max(t1).min(len));
    hi - lo > eps
}

/// Largest miter, in multiples of the outset, before a corner is bevelled instead.
const MITER_LIMIT: f64 = 3.0;

/// Writes `points` outset by `outset` pixels along the edges whose flag is set (edge `k`
/// runs from point `k` to `k + 1`) into `out`. Corners are mitred (bevelled beyond
/// three times the outset); edges without the flag stay on their line. With `outset <= 0` or no
/// flag set, `out` is `points`.
pub fn outset_polygon(points: &[DVec2], shared: &[bool], outset: f64, out: &mut Vec<DVec2>) {
    out.clear();
    let n = points.len();
    if outset <= 0.0 || !shared.iter().any(|&s| s) {
        out.extend_from_slice(points);
        return;
    }
    let orientation = face_sort::signed_area_2d(points).signum();
    let normal = |k: usize| {
        let d = points[(k + 1) % n] - points[k];
        let len = d.length();
        if len > 0.0 {
            DVec2::new(d.y, -d.x) / len * orientation
        } else {
            DVec2::ZERO
        }
    };
    for i in 0..n {
        let prev = (i + n - 1) % n;
        let v = points[i];
        let (o1, o2) = (
            if shared[prev] { outset } else { 0.0 },
            if shared[i] { outset } else { 0.0 },
        );
        if o1 == 0.0 && o2 == 0.0 {
            out.push(v);
            continue;
        }
        let (n1, n2) = (normal(prev), normal(i));
        let det = n1.perp_dot(n2);
        let miter = if det.abs() > SEAM_PARALLEL_NORMALS {
            Some(DVec2::new(o1 * n2.y - o2 * n1.y, n1.x * o2 - n2.x * o1) / det)
        } else if n1.dot(n2) > 0.0 && o1 == o2 {
            Some(n1 * o1)
        } else {
            None
        };
        match miter {
            Some(m) if m.length() <= MITER_LIMIT * outset => out.push(v + m),
            _ => {
                out.push(v + n1 * o1);
                if o2 != o1 || n1 != n2 {
                    out.push(v + n2 * o2);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_squares_share_one_edge_and_outset_moves_only_it() {
        let mut polys = ScreenPolygons::default();
        polys.clear();
        let a = [
            DVec2::new(0.0, 0.0),
            DVec2::new(10.0, 0.0),
            DVec2::new(10.0, 10.0),
            DVec2::new(0.0, 10.0),
        ];
        let b = [
            DVec2::new(10.0, 0.0),
            DVec2::new(20.0, 0.0),
            DVec2::new(20.0, 10.0),
            DVec2::new(10.0, 10.0),
        ];
        // A T-junction neighbour below `a`, sharing half of its bottom edge.
        let c = [
            DVec2::new(0.0, 10.0),
            DVec2::new(5.0, 10.0),
            DVec2::new(5.0, 20.0),
            DVec2::new(0.0, 20.0),
        ];
        polys.push(&a);
        polys.push(&b);
        polys.push(&c);
        let mut shared = SharedEdges::default();
        shared.compute(&polys);
        assert_eq!(shared.flags(0..4), &[false, true, true, false]);
        assert_eq!(shared.flags(4..8), &[false, false, false, true]);
        assert_eq!(shared.flags(8..12), &[true, false, false, false]);
        let mut out = Vec::new();
        outset_polygon(&a, shared.flags(0..4), 0.5, &mut out);
        assert_eq!(
            out,
            [
                DVec2::new(0.0, 0.0),
                DVec2::new(10.5, 0.0),
                DVec2::new(10.5, 10.5),
                DVec2::new(0.0, 10.5)
            ]
        );
    }
}
