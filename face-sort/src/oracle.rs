//! The exact, resolution-free judge of a draw order (CONVENTIONS.md).
//!
//! An **order violation** is a pair of drawn polygons whose projections overlap with positive
//! area, where the one drawn later lies behind the other at a point inside the overlap by more
//! than `1e-9 · L` in view depth. Everything is computed in f64 from the polygons' planes; a
//! depth gap counts only beyond the rounding bound of the two depths
//! ([`PixelRays::depth_error`](crate::PixelRays::depth_error)), which is negligible except for
//! a piece seen almost edge-on, whose depth along a ray f64 cannot tell, and next to the near
//! plane, where projecting rounds up to a thousand times worse ([`View::rounding_gain`]).

use glam::{DVec2, DVec3};

use crate::polygon::{Box2, overlap_exceeds};
use crate::tolerance::{ORACLE_DEPTH, ORACLE_INTERIOR, OVERLAP_AREA};
use crate::{DrawList, PixelRays, ProjectionScratch, View};

/// One violating pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Violation {
    /// Position in the draw list of the polygon drawn first.
    pub earlier: usize,
    /// Position of the polygon drawn later, which lies behind the earlier one.
    pub later: usize,
    /// By how much (view depth, model units) the later polygon is behind, at the worst point
    /// of the overlap found, less the rounding bound of the two depths there.
    pub depth_gap: f64,
}

/// Number of order violations of `list` under `view`.
#[must_use]
pub fn count_violations(view: &View, list: &DrawList) -> usize {
    let mut count = 0;
    for_each_violation(view, list, |_| count += 1);
    count
}

/// The violations of `list` under `view`, at most `limit` of them.
#[must_use]
pub fn find_violations(view: &View, list: &DrawList, limit: usize) -> Vec<Violation> {
    let mut found = Vec::new();
    for_each_violation(view, list, |v| {
        if found.len() < limit {
            found.push(v);
        }
    });
    found
}

struct Projected {
    points: Vec<DVec2>,
    starts: Vec<usize>,
    boxes: Vec<Box2>,
    /// View-space plane per item: normal and offset.
    planes: Vec<(DVec3, f64)>,
    /// Per item, how much worse than a few ulps its projection rounds
    /// ([`View::rounding_gain`]).
    gains: Vec<f64>,
}

fn project_all(view: &View, list: &DrawList) -> Projected {
    let mut p = Projected {
        points: Vec::new(),
        starts: vec![0],
        boxes: Vec::new(),
        planes: Vec::new(),
        gains: Vec::new(),
    };
    let mut out = Vec::new();
    let mut scratch = ProjectionScratch::default();
    let test = view.cull_test();
    for &item in list.items() {
        p.gains.push(view.rounding_gain(list.corners(item)));
        if list.paints(item, &test) {
            view.project_polygon(list.corners(item), &mut out, &mut scratch);
        } else {
            out.clear(); // a sink that culls hides it: nothing to judge
        }
        p.points.extend_from_slice(&out);
        p.starts.push(p.points.len());
        p.boxes.push(if out.is_empty() {
            Box2::EMPTY
        } else {
            Box2::from_points(&out)
        });
        let plane = list.plane(item);
        p.planes
            .push(view.plane_to_view(plane.normal(), plane.offset()));
    }
    p
}

fn for_each_violation(view: &View, list: &DrawList, mut report: impl FnMut(Violation)) {
    let projected = project_all(view, list);
    let n = list.len();
    let scale_area = view.diagonal() * view.scale();
    let min_area = OVERLAP_AREA * scale_area * scale_area;
    let tolerance = ORACLE_DEPTH * view.diagonal();
    let mut by_x: Vec<usize> = (0..n)
        .filter(|&i| projected.starts[i + 1] > projected.starts[i])
        .collect();
    by_x.sort_unstable_by(|&a, &b| {
        projected.boxes[a]
            .min
            .x
            .total_cmp(&projected.boxes[b].min.x)
    });
    let rays = PixelRays::new(view);
    let (mut overlap, mut scratch) = (Vec::new(), Vec::new());
    let poly = |i: usize| &projected.points[projected.starts[i]..projected.starts[i + 1]];
    for (pos, &a) in by_x.iter().enumerate() {
        let box_a = projected.boxes[a];
        for &b in &by_x[pos + 1..] {
            let box_b = projected.boxes[b];
            if box_b.min.x >= box_a.max.x {
                break;
            }
            if !box_a.overlaps(&box_b) {
                continue;
            }
            let gain = projected.gains[a].max(projected.gains[b]);
            if !overlap_exceeds(poly(a), poly(b), min_area, gain, &mut overlap, &mut scratch) {
                continue;
            }
            let (earlier, later) = if a < b { (a, b) } else { (b, a) };
            let (ne, ke) = projected.planes[earlier];
            let (nl, kl) = projected.planes[later];
            let centroid = overlap.iter().copied().sum::<DVec2>() / overlap.len() as f64;
            let mut worst = f64::NEG_INFINITY;
            for &corner in overlap.iter().chain(std::iter::once(&centroid)) {
                // A hair inside the overlap, so the point is interior.
                let point = corner + (centroid - corner) * ORACLE_INTERIOR;
                // Beyond the depths' own rounding: a piece seen edge-on has no depth that f64
                // can tell (see `PixelRays::depth_error`).
                let gap = rays.depth(point, ne, ke)
                    - rays.depth(point, nl, kl)
                    - rays.depth_error(point, ne, ke, gain)
                    - rays.depth_error(point, nl, kl, gain);
                if gap.is_finite() {
                    worst = worst.max(gap);
                }
            }
            if worst > tolerance {
                report(Violation {
                    earlier,
                    later,
                    depth_gap: worst,
                });
            }
        }
    }
}
