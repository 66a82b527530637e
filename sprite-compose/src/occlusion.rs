//! Exact occlusion of lines by drawn pieces, shared by plotter edges and by lines and points
//! among faces: the drawn pieces bucketed in a screen grid, and a line's covered parameter
//! intervals in closed form (see [`plot`](crate::plot_edges)'s module docs for why they are
//! exact).

use face_sort::tolerance::NEAR_W;
use std::collections::HashMap;

use face_sort::{Geometry, Plane, PolygonMesh, ProjectionScratch, View};
use glam::{DVec2, DVec3};

use crate::tolerance::{PLOT_BEHIND, PLOT_INSIDE_PX, PLOT_MIN_LENGTH_PX};

/// A drawn piece as an occluder: its projection, plane and face.
pub(crate) struct Occluder {
    pub(crate) face: u32,
    /// Corners in centred model space.
    pub(crate) corners_3d: Vec<DVec3>,
    /// Projected corners (pixels), counter-clockwise in the picture's y-down frame or not:
    /// `orientation` says which.
    pub(crate) corners: Vec<DVec2>,
    pub(crate) orientation: f64,
    pub(crate) min: DVec2,
    pub(crate) max: DVec2,
    pub(crate) plane: Plane,
    /// +1 when the viewer is on the side the normal points to, −1 otherwise.
    pub(crate) viewer_side: f64,
}

/// The drawn pieces, bucketed in a screen grid.
pub(crate) struct Occluders {
    pub(crate) pieces: Vec<Occluder>,
    /// Per mesh face: it has a piece drawn in this view.
    pub(crate) drawn_faces: Vec<bool>,
    /// Per mesh face: it has any piece (faces without area have none).
    pub(crate) has_pieces: Vec<bool>,
    pub(crate) origin: DVec2,
    pub(crate) cell: f64,
    pub(crate) cols: usize,
    pub(crate) rows: usize,
    pub(crate) cells: Vec<Vec<u32>>,
}

impl Occluders {
    pub(crate) fn new(geometry: &Geometry, view: &View, include: &impl Fn(u32) -> bool) -> Self {
        let set = geometry.pieces();
        let cull = view.cull_test();
        let viewer = view.viewer();
        let mut drawn_faces = vec![false; geometry.face_count()];
        let mut has_pieces = vec![false; geometry.face_count()];
        let mut pieces = Vec::new();
        let mut scratch = ProjectionScratch::default();
        let mut projected = Vec::new();
        for i in 0..set.len() {
            let face = set.face(i);
            if !include(face) {
                continue;
            }
            has_pieces[face as usize] = true;
            let plane = set.plane(i);
            let corners = set.corners(i);
            if !cull.is_drawn(plane, corners[0]) {
                continue;
            }
            drawn_faces[face as usize] = true;
            let facing = viewer.facing(plane);
            view.project_polygon(corners, &mut projected, &mut scratch);
            if projected.len() < 3 || facing == 0.0 {
                continue;
            }
            let area: f64 = (0..projected.len())
                .map(|k| projected[k].perp_dot(projected[(k + 1) % projected.len()]))
                .sum();
            if area == 0.0 {
                continue;
            }
            let (min, max) = projected
                .iter()
                .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), &p| {
                    (lo.min(p), hi.max(p))
                });
            pieces.push(Occluder {
                face,
                corners_3d: corners.to_vec(),
                corners: projected.clone(),
                orientation: area.signum(),
                min,
                max,
                plane: *plane,
                viewer_side: facing.signum(),
            });
        }
        // A grid of about one piece per cell over the pieces' extent.
        let (lo, hi) = pieces
            .iter()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.min), hi.max(p.max))
            });
        let extent = (hi - lo).max(DVec2::splat(1.0));
        let side = (pieces.len() as f64).sqrt().ceil().clamp(1.0, 1024.0);
        let cell = extent.max_element() / side;
        let (cols, rows) = (
            ((extent.x / cell).ceil() as usize).max(1),
            ((extent.y / cell).ceil() as usize).max(1),
        );
        let origin = if pieces.is_empty() { DVec2::ZERO } else { lo };
        let mut grid = Occluders {
            pieces: Vec::new(),
            drawn_faces,
            has_pieces,
            origin,
            cell,
            cols,
            rows,
            cells: vec![Vec::new(); cols * rows],
        };
        for (k, p) in pieces.iter().enumerate() {
            let (c0, r0, c1, r1) = grid.cell_range(p.min, p.max);
            for r in r0..=r1 {
                for c in c0..=c1 {
                    grid.cells[r * cols + c].push(k as u32);
                }
            }
        }
        grid.pieces = pieces;
        grid
    }

    /// The grid cells a pixel box touches, clamped to the grid.
    pub(crate) fn cell_range(&self, min: DVec2, max: DVec2) -> (usize, usize, usize, usize) {
        let index = |v: f64, n: usize| ((v / self.cell).floor().max(0.0) as usize).min(n - 1);
        let (a, b) = (min - self.origin, max - self.origin);
        (
            index(a.x, self.cols),
            index(a.y, self.rows),
            index(b.x, self.cols),
            index(b.y, self.rows),
        )
    }

    /// The pieces whose box overlaps the segment's (each once; `stamp` marks them with
    /// `tag`).
    pub(crate) fn candidates(
        &self,
        segment: &Segment,
        tag: u32,
        stamp: &mut [u32],
        out: &mut Vec<u32>,
    ) {
        out.clear();
        let (min, max) = segment.pixel_box();
        if self.pieces.is_empty() {
            return;
        }
        let (c0, r0, c1, r1) = self.cell_range(min, max);
        for r in r0..=r1 {
            for c in c0..=c1 {
                for &k in &self.cells[r * self.cols + c] {
                    let p = &self.pieces[k as usize];
                    if stamp[k as usize] != tag
                        && p.min.x <= max.x
                        && p.max.x >= min.x
                        && p.min.y <= max.y
                        && p.max.y >= min.y
                    {
                        stamp[k as usize] = tag;
                        out.push(k);
                    }
                }
            }
        }
    }
}

/// An edge in front of the near plane: its ends in centred model space, the parameter range
/// kept, and its homogeneous screen coordinates at `t = 0` and `t = 1`.
pub(crate) struct Segment {
    pub(crate) ends: [DVec3; 2],
    pub(crate) range: [f64; 2],
    /// `(x·w, y·w, w)` of the pixel position at `t = 0` and `t = 1` (linear in `t`).
    pub(crate) screen: [DVec3; 2],
}

impl Segment {
    /// `None` when the whole edge lies behind the near plane.
    pub(crate) fn new(view: &View, ends: [DVec3; 2]) -> Option<Self> {
        let screen = ends.map(|p| view.homogeneous_pixel(p));
        // Keep w(t) ≥ NEAR_W.
        let (w0, w1) = (screen[0].z, screen[1].z);
        let mut range = [0.0, 1.0];
        if w0 < NEAR_W && w1 < NEAR_W {
            return None;
        }
        if w0 < NEAR_W || w1 < NEAR_W {
            let t = (NEAR_W - w0) / (w1 - w0);
            if w0 < NEAR_W {
                range[0] = t;
            } else {
                range[1] = t;
            }
        }
        Some(Segment {
            ends,
            range,
            screen,
        })
    }

    pub(crate) fn at_pixel(&self, t: f64) -> DVec2 {
        let h = self.screen[0].lerp(self.screen[1], t);
        DVec2::new(h.x / h.z, h.y / h.z)
    }

    pub(crate) fn pixel_box(&self) -> (DVec2, DVec2) {
        let (a, b) = (self.at_pixel(self.range[0]), self.at_pixel(self.range[1]));
        (a.min(b), a.max(b))
    }

    /// The interval of `t` (within the kept range) where `piece` covers the edge: inside
    /// its projection by more than [`PLOT_INSIDE_PX`] and behind its plane by more than
    /// [`PLOT_BEHIND`] times `length` (the model's diagonal). `None` when empty.
    pub(crate) fn covered_by(&self, piece: &Occluder, length: f64) -> Option<[f64; 2]> {
        let [mut lo, mut hi] = self.range;
        // Keeps the t where f0 + t·(f1 − f0) > 0.
        let mut keep = |f0: f64, f1: f64| -> bool {
            let slope = f1 - f0;
            if slope == 0.0 {
                return f0 > 0.0;
            }
            let root = -f0 / slope;
            if slope > 0.0 {
                lo = lo.max(root);
            } else {
                hi = hi.min(root);
            }
            lo < hi
        };
        let n = piece.corners.len();
        for k in 0..n {
            let (q, r) = (piece.corners[k], piece.corners[(k + 1) % n]);
            let e = r - q;
            let margin = PLOT_INSIDE_PX * e.length();
            // orientation · cross(e, p − q) > margin, times w > 0: linear in t.
            let f = |h: DVec3| {
                piece.orientation * e.perp_dot(DVec2::new(h.x, h.y) - q * h.z) - margin * h.z
            };
            if !keep(f(self.screen[0]), f(self.screen[1])) {
                return None;
            }
        }
        // Behind the plane: on the side away from the viewer.
        let side = |p: DVec3| -piece.viewer_side * piece.plane.signed_distance(p);
        let margin = PLOT_BEHIND * length;
        if !keep(side(self.ends[0]) - margin, side(self.ends[1]) - margin) {
            return None;
        }
        Some([lo, hi])
    }

    /// The kept range minus the union of `covered`, without parts shorter than
    /// [`PLOT_MIN_LENGTH_PX`].
    pub(crate) fn visible_parts(&self, covered: &mut [[f64; 2]]) -> Vec<[f64; 2]> {
        covered.sort_by(|a, b| a[0].total_cmp(&b[0]));
        let mut out = Vec::new();
        let mut from = self.range[0];
        let mut push = |a: f64, b: f64| {
            if b > a && self.at_pixel(a).distance(self.at_pixel(b)) >= PLOT_MIN_LENGTH_PX {
                out.push([a, b]);
            }
        };
        for &[a, b] in covered.iter() {
            if a > from {
                push(from, a.min(self.range[1]));
            }
            from = from.max(b);
            if from >= self.range[1] {
                break;
            }
        }
        push(from, self.range[1]);
        out
    }
}

/// One id per position of `mesh`: positions equal bit for bit (`-0.0` is `0.0`) share an id,
/// ids numbered in order of first appearance.
pub(crate) fn weld(mesh: &PolygonMesh) -> Vec<u32> {
    let key = |p: DVec3| (p + DVec3::ZERO).to_array().map(f64::to_bits);
    let mut welded: HashMap<[u64; 3], u32> = HashMap::new();
    mesh.positions()
        .iter()
        .map(|&p| {
            let next = welded.len() as u32;
            *welded.entry(key(p)).or_insert(next)
        })
        .collect()
}
