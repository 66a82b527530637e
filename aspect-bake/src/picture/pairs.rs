//! Which pairs of pieces need an order, and over which arcs of the turn.
//!
//! A pair needs an order exactly where both pieces are drawn (front-facing) and their
//! projections overlap with positive area. Both conditions are unions and intersections of
//! sign conditions `a·cos θ + b·sin θ + c`, solved in closed form ([`ArcSet`]).

use std::sync::atomic::{AtomicUsize, Ordering};

use face_sort::glam::{DVec2, DVec3};
use face_sort::{
    PixelRays, PolygonSet, ProjectionScratch, Side, View, clip_convex_2d, signed_area_2d,
};
use rayon::prelude::*;
use smallvec::SmallVec;

use crate::BakeError;
use crate::arcs::ArcSet;
use crate::axis::Spin;
use crate::event::{EventFn, Roots, magnitude};
use crate::tolerance::{
    ARC_MARGIN_RAD, BOX_SLACK, NEAR_EYE, PICTURE_SHORT_EDGE, PICTURE_SIDE, SIGHT_SLACK,
};

/// The pieces along a spin: everything the pair tests read.
pub(crate) struct Pieces<'a> {
    pub(crate) spin: &'a Spin,
    pub(crate) set: &'a PolygonSet,
    /// `+1` when a piece is drawn where its facing value is positive, `−1` where negative.
    pub(crate) sigma: f64,
    /// Where each piece is drawn, widened by its margin.
    pub(crate) drawn: Vec<ArcSet>,
    /// Boxes grow by at least this (model units), beyond rounding.
    box_floor: f64,
    /// The viewer's track along the spin, for event functions.
    track: Track,
    /// The turning axis in centred model space (unit).
    axis_model: DVec3,
    /// Per view axis, `√(1 − aₑ²)` for the axis's view direction `a`: how much of a
    /// point's motion can show along that axis.
    across_axis: DVec3,
    /// Plane-side tolerance (model units).
    side_tolerance: f64,
    /// Per piece, a ball holding it: centre and radius.
    balls: Vec<(DVec3, f64)>,
    /// Edges no longer than this separate nothing (model units).
    short_edge: f64,
}

/// How far an arc is widened (or shrunk) against the rounding of its ends:
/// [`ARC_MARGIN_RAD`], far above the rounding of a root in f64 (about `1e-15` rad where the
/// function crosses zero at a slope of its size).
fn margin(_f: &EventFn) -> f64 {
    ARC_MARGIN_RAD
}

impl<'a> Pieces<'a> {
    /// The pieces of `set` along `spin`, drawn where `sigma ×` facing is positive.
    pub(crate) fn new(spin: &'a Spin, set: &'a PolygonSet, sigma: f64, diagonal: f64) -> Self {
        let track = Track::of(spin);
        let drawn = (0..set.len())
            .map(|i| {
                let n = set.plane(i).normal() * sigma;
                let f = track.event(n, n.dot(set.corners(i)[0]));
                ArcSet::where_sign(&f, true, margin(&f))
            })
            .collect();
        let (a, k, b) = spin.factors();
        let axis_model = (b.transpose() * k).normalize();
        let axis_view = a * k;
        Pieces {
            track,
            spin,
            set,
            sigma,
            drawn,
            box_floor: PICTURE_SIDE * diagonal,
            axis_model,
            across_axis: (DVec3::ONE - axis_view * axis_view)
                .max(DVec3::ZERO)
                .powf(0.5),
            side_tolerance: PICTURE_SIDE * diagonal,
            balls: (0..set.len())
                .map(|i| {
                    let c = set.corners(i);
                    let centre = c.iter().copied().sum::<DVec3>() / c.len() as f64;
                    let radius = c.iter().map(|p| p.distance(centre)).fold(0.0, f64::max);
                    (
                        centre,
                        radius * (1.0 + SIGHT_SLACK) + PICTURE_SIDE * diagonal,
                    )
                })
                .collect(),
            short_edge: PICTURE_SHORT_EDGE * diagonal,
        }
    }

    /// Side of piece `i` relative to piece `j`'s plane, the front being the side a drawn `j`
    /// faces.
    pub(crate) fn side(&self, i: usize, j: usize) -> Side {
        let side = self
            .set
            .plane(j)
            .side_of_polygon(self.set.corners(i), self.side_tolerance);
        match (side, self.sigma < 0.0) {
            (Side::Front, true) => Side::Back,
            (Side::Back, true) => Side::Front,
            (s, _) => s,
        }
    }

    /// Which of two pieces occludes the other wherever both are drawn and overlap.
    pub(crate) fn relation(&self, i: usize, j: usize) -> Relation {
        // `i` in front of a drawn `j` exactly when `i` lies on `j`'s front side.
        let front = |s: Side| match s {
            Side::Front => Some(true),
            Side::Back => Some(false),
            _ => None,
        };
        let (si, sj) = (self.side(i, j), self.side(j, i));
        let fixed = |i_in_front: bool| {
            let (behind, front) = if i_in_front { (j, i) } else { (i, j) };
            Relation::Fixed {
                behind: behind as u32,
                front: front as u32,
            }
        };
        match (front(si), front(sj)) {
            // Both in front of the other (or both behind): never both drawn and overlapping.
            (Some(a), Some(b)) if a == b => Relation::Never,
            (Some(a), _) if sj != Side::On => fixed(a),
            (_, Some(b)) if si != Side::On => fixed(!b),
            _ if si == Side::Spanning && sj == Side::Spanning => Relation::Depth,
            // Coplanar: equal depth wherever they overlap.
            _ => Relation::Never,
        }
    }

    /// Where, within `within`, pieces `i` and `j` are both drawn and their projections overlap
    /// with positive area, over-approximated by the margins: the drawn arcs less, for every edge of either
    /// piece, the arcs where that edge's line separates the two projections (every corner of
    /// the other piece on its outer side or on it).
    pub(crate) fn overlap(&self, i: usize, j: usize, within: &ArcSet) -> ArcSet {
        let mut rest = self.drawn[i].intersect(&self.drawn[j]).intersect(within);
        let mut probes = rest.probes();
        let mut lines: SmallVec<[EventFn; 8]> = SmallVec::new();
        for (p, q) in [(i, j), (j, i)] {
            let (cp, cq) = (self.set.corners(p), self.set.corners(q));
            for k in 0..cp.len() {
                if rest.is_empty() {
                    return rest;
                }
                let (a, b) = (cp[k], cp[(k + 1) % cp.len()]);
                if a.distance(b) <= self.short_edge {
                    continue; // no line that rounding can tell
                }
                // The side of each corner of `q` relative to the edge's line.
                lines.clear();
                let mut level = false;
                for &v in cq {
                    let m = (b - a).cross(v - a) * self.sigma;
                    if m == DVec3::ZERO {
                        continue; // on the edge's line itself (a shared corner)
                    }
                    let f = self.track.event(m, m.dot(a));
                    if f.is_identically_zero() {
                        // The viewer stays level with the plane of the edge and this corner,
                        // within rounding: the corner projects within a sliver of the line,
                        // on a side that rounding decides. The line cannot be shown to
                        // separate.
                        level = true;
                        break;
                    }
                    lines.push(f);
                }
                if level {
                    continue;
                }
                // The line separates only where every corner is on its outer side: not over
                // an arc where some corner surely stays inside.
                let open: SmallVec<[bool; 2]> = (0..probes.len())
                    .map(|arc| !lines.iter().any(|f| probes.positive_over(arc, f)))
                    .collect();
                if !open.contains(&true) {
                    continue;
                }
                // Only the separation within what is left matters.
                let mut separated = rest.arcs_where(|arc| open[arc]);
                for f in &lines {
                    separated = separated.where_negative(f, margin(f));
                    if separated.is_empty() {
                        break;
                    }
                }
                if !separated.is_empty() {
                    rest = rest.minus(&separated);
                    probes = rest.probes();
                }
            }
        }
        rest
    }

    /// Every angle (radians, any turn) within `arcs` where the pair's overlap can appear,
    /// vanish or change shape: a piece turning edge-on, a corner of one crossing an edge line
    /// of the other. Functions that surely keep one sign over every arc are not solved (they
    /// have no root there); others may give roots outside `arcs` too.
    fn events_within(&self, i: usize, j: usize, arcs: &ArcSet) -> Vec<f64> {
        let probes = arcs.probes();
        let mut out = Vec::new();
        let mut push = |f: &EventFn| {
            if (0..probes.len()).all(|k| probes.one_sign_over(k, f)) {
                return;
            }
            if let Roots::Two { down, up } = f.roots() {
                out.push(down);
                out.push(up);
            }
        };
        for k in [i, j] {
            push(&self.spin.polygon_facing(self.set, k));
        }
        for (p, q) in [(i, j), (j, i)] {
            let (cp, cq) = (self.set.corners(p), self.set.corners(q));
            for k in 0..cp.len() {
                let (a, b) = (cp[k], cp[(k + 1) % cp.len()]);
                for &v in cq {
                    let m = (b - a).cross(v - a);
                    if m != DVec3::ZERO {
                        push(&self.track.event(m, m.dot(a)));
                    }
                }
            }
        }
        out
    }

    /// For a pair that spans each other's planes without crossing, which one is in front at
    /// `theta`, judged at the centroid of the overlap of their projections: the overlap's
    /// area (view units²) and `true` when `i` is in front; `None` when the projections do not
    /// overlap there at all.
    fn front_sample(
        &self,
        i: usize,
        j: usize,
        theta: f64,
        scratch: &mut SampleScratch,
    ) -> Option<FrontSample> {
        let view = self.spin.view_at_rad(theta);
        let SampleScratch {
            projection,
            pi,
            pj,
            overlap,
            clip,
        } = scratch;
        view.project_polygon(self.set.corners(i), pi, projection);
        view.project_polygon(self.set.corners(j), pj, projection);
        clip_convex_2d(pi, pj, overlap, clip);
        if overlap.len() < 3 {
            return None;
        }
        let centroid = overlap.iter().copied().sum::<DVec2>() / overlap.len() as f64;
        let rays = PixelRays::new(&view);
        let depth = |k: usize| {
            let plane = self.set.plane(k);
            let (n, offset) = view.plane_to_view(plane.normal(), plane.offset());
            rays.depth(centroid, n, offset)
        };
        Some(FrontSample {
            area: signed_area_2d(overlap).abs(),
            i_front: depth(i) > depth(j),
        })
    }

    /// The overlap area (view units²) above which one [`Self::front_sample`] decides its
    /// stretch by itself: `OVERLAP_AREA · L²` at the view's scale.
    fn decisive_area(&self) -> f64 {
        let extent = self.box_floor / PICTURE_SIDE * self.spin.view_at_rad(0.0).scale();
        face_sort::tolerance::OVERLAP_AREA * extent * extent
    }

    /// A box around piece `i`'s projection at every angle of the bin `[mid − half, mid + half]`,
    /// in the view at `mid` (view units; perspective: divided by `w`). Turning by `φ` moves a
    /// corner about the axis by `r·(cos φ − 1) + t·sin φ`, where `r` is its offset from the
    /// axis and `t` the axis crossed with `r`; so along view axis `e` it moves by at most
    /// `|rₑ|·(1 − cos h) + |tₑ|·sin h` (`h = half`, the sine capped at 1). A corner moving
    /// toward the viewer barely moves across the screen, and one moving across it barely
    /// changes depth: per-corner bounds keep perspective boxes tight. The view-space box of
    /// each corner grown by that much holds the corner throughout, and so does the projection
    /// of that box's corners (`x / w` is extreme at a corner); the projection of the piece
    /// (their convex hull) lies in the box of them all. Unbounded when a box reaches the eye's
    /// near plane.
    fn swept_box(&self, view: &View, i: usize, half: f64) -> (DVec2, DVec2) {
        let corners = self.set.corners(i);
        // |sin φ| ≤ sin h and 1 − cos φ ≤ 1 − cos h for |φ| ≤ h ≤ π/2 (|sin φ| ≤ 1 beyond).
        let sin = if half < std::f64::consts::FRAC_PI_2 {
            half.sin()
        } else {
            1.0
        };
        let versine = 1.0 - half.cos();
        let (mut a, mut b) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        let eye = view.eye_in_view();
        for &c in corners {
            let v = view.to_view(c);
            let radial = c.reject_from_normalized(self.axis_model);
            let tangent = self.axis_model.cross(radial);
            let r = view.direction_to_view(radial).abs();
            let t = view.direction_to_view(tangent).abs();
            let grow = (t * sin + r * versine) * (1.0 + BOX_SLACK) + DVec3::splat(self.box_floor);
            let (lo, hi) = (v - grow, v + grow);
            match eye {
                None => {
                    a = a.min(lo.truncate());
                    b = b.max(hi.truncate());
                }
                Some(eye) => {
                    let near = eye.z * (1.0 - NEAR_EYE);
                    if hi.z >= near {
                        return (DVec2::splat(f64::NEG_INFINITY), DVec2::splat(f64::INFINITY));
                    }
                    for z in [lo.z, hi.z] {
                        let w = 1.0 - z / eye.z;
                        for x in [lo.x, hi.x] {
                            for y in [lo.y, hi.y] {
                                let p = DVec2::new(x, y) / w;
                                a = a.min(p);
                                b = b.max(p);
                            }
                        }
                    }
                }
            }
        }
        (a, b)
    }
}

/// The viewer along the spin, `p₀ + cos θ·p₁ + sin θ·p₂` with `w` (0: a direction, 1: the
/// eye), and the sum of the `|pₖ|`: [`Spin::facing_fn`] without recomputing them per call.
struct Track {
    p: [DVec3; 3],
    w: f64,
    reach: f64,
}

impl Track {
    fn of(spin: &Spin) -> Self {
        let (p, w) = spin.viewer_track();
        Track {
            p,
            w,
            reach: p[0].length() + p[1].length() + p[2].length(),
        }
    }

    /// `n·viewer(θ) − w·offset` as an event function (what `Spin::facing_fn` gives for the
    /// row `[n, offset]`).
    #[inline]
    fn event(&self, n: DVec3, offset: f64) -> EventFn {
        EventFn {
            a: n.dot(self.p[1]),
            b: n.dot(self.p[2]),
            c: n.dot(self.p[0]) - self.w * offset,
            scale: n.length() * self.reach + self.w * offset.abs(),
        }
    }
}

/// Buffers that [`Pieces::front_sample`] reuses from one sample to the next.
#[derive(Default)]
struct SampleScratch {
    projection: ProjectionScratch,
    pi: Vec<DVec2>,
    pj: Vec<DVec2>,
    overlap: Vec<DVec2>,
    clip: Vec<DVec2>,
}

/// Which of two pieces is in front where their projections overlap, at one angle.
#[derive(Clone, Copy, Debug)]
struct FrontSample {
    /// The overlap's area (view units²).
    area: f64,
    /// Whether the first piece is in front.
    i_front: bool,
}

/// How two pieces' depths relate where both are drawn and overlap.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Relation {
    /// They never need an order.
    Never,
    /// `behind` is always behind `front` there.
    Fixed { behind: u32, front: u32 },
    /// Each spans the other's plane (without crossing): decided per arc of overlap.
    Depth,
}

/// One pair's need for an order: `behind` before `front` over `arcs`. An arc set that is not
/// `exact` is a superset of the true one (both drawn, boxes meeting), refined on demand.
#[derive(Clone, Debug)]
pub(crate) struct Constraint {
    pub(crate) behind: u32,
    pub(crate) front: u32,
    pub(crate) arcs: ArcSet,
    /// Whether `arcs` are the closed-form arcs of overlap (else only a superset: where both
    /// are drawn while their boxes meet, which [`Pieces::refine`] narrows).
    pub(crate) exact: bool,
}

impl Pieces<'_> {
    /// Where the viewer can see piece `front` in front of piece `behind` at all, as a
    /// superset: their sight cone.
    ///
    /// Where `front` hides part of `behind`, a ray toward the viewer leaves a point `b` of
    /// `behind` and passes a point `f` of `front`, so the viewer's direction (orthographic)
    /// or the eye minus `f` (perspective) is a positive multiple of `f − b`. With each piece
    /// inside a ball (centre `m`, radius `r`), every `f − b` lies in the ball about
    /// `m_f − m_b` of radius `r_f + r_b`, so in the circular cone `C` about its direction
    /// `ĉ` of half-angle `α`, `sin α = (r_f + r_b) / |m_f − m_b|`.
    /// - Orthographic: `ĉ·v(θ) ≥ cos α` for the unit direction `v(θ)` toward the viewer.
    /// - Perspective: the eye lies in the front piece's ball plus `C`, which is the cone `C`
    ///   from the apex `A = m_f − ĉ·r_f / sin α`; so `ĉ·(E(θ) − A) ≥ cos α · |E(θ) − A|`.
    ///   Along the eye's circle `|E(θ) − A|² = v₀ + v₁·cos θ + v₂·sin θ`, and the square
    ///   root is at least its chord over the range of that, which is again of that form.
    ///
    /// Both are `a·cos θ + b·sin θ + c ≥ 0`. Every quantity is widened by [`SIGHT_SLACK`];
    /// balls that meet, or a cone as wide as a half-space, give the whole turn.
    pub(crate) fn sight(&self, behind: usize, front: usize) -> ArcSet {
        let (mf, rf) = self.balls[front];
        let (mb, rb) = self.balls[behind];
        let between = mf - mb;
        let distance = between.length();
        let sin = (rf + rb) / distance * (1.0 + SIGHT_SLACK);
        if sin.is_nan() || sin >= 1.0 {
            return ArcSet::full();
        }
        let axis = between / distance;
        let cos = (1.0 - sin * sin).sqrt() - SIGHT_SLACK;
        if cos.is_nan() || cos <= 0.0 {
            return ArcSet::full();
        }
        let p = &self.track.p;
        let g = if self.track.w == 0.0 {
            EventFn {
                a: axis.dot(p[1]),
                b: axis.dot(p[2]),
                c: axis.dot(p[0]) - cos,
                scale: self.track.reach + cos,
            }
        } else {
            let apex = mf - axis * (rf / (1.0 - cos * cos).sqrt());
            // |E(θ) − A|² = v₀ + v₁·cos θ + v₂·sin θ (p₁ ⟂ p₂, |p₁| = |p₂|): the distance
            // is at least the chord of √v over the range of v, again of that form.
            let from = p[0] - apex;
            let radius2 = 0.5 * (p[1].length_squared() + p[2].length_squared());
            let (v0, v1, v2) = (
                from.length_squared() + radius2,
                2.0 * from.dot(p[1]),
                2.0 * from.dot(p[2]),
            );
            let reach = self.track.reach + apex.length();
            let spread = magnitude(v1, v2);
            let rounding = SIGHT_SLACK * reach * reach;
            let low = ((v0 - spread) * (1.0 - SIGHT_SLACK) - rounding).max(0.0);
            let high = (v0 + spread) * (1.0 + SIGHT_SLACK) + rounding;
            let (s_low, s_high) = (low.sqrt(), high.sqrt());
            let slope = if high > low {
                (s_high - s_low) / (high - low)
            } else {
                0.0
            };
            // cos α · (chord(v) · (1 − slack) − slack · reach), never above cos α · |E − A|.
            let scaled = cos * (1.0 - SIGHT_SLACK);
            EventFn {
                a: axis.dot(p[1]) - scaled * slope * v1,
                b: axis.dot(p[2]) - scaled * slope * v2,
                c: axis.dot(from) - scaled * (s_low + slope * (v0 - low))
                    + cos * SIGHT_SLACK * reach,
                scale: 2.0 * reach,
            }
        };
        ArcSet::where_sign(&g, true, margin(&g))
    }

    /// The exact arcs of a constraint made by [`constraints`] (a fixed relation's pair).
    pub(crate) fn refine(&self, c: &Constraint) -> ArcSet {
        self.overlap(c.behind as usize, c.front as usize, &c.arcs)
    }
}

/// Bits of a piece index in a candidate key (two of them make the key).
const PIECE_BITS: u32 = 24;

/// The most pieces a picture bake takes (candidate keys hold two piece indices).
pub(crate) const MAX_PIECES: usize = (1 << PIECE_BITS) - 1;

/// The most angular bins.
pub(crate) const MAX_BINS: usize = 16_383;

/// Keys a bin's search counts at once toward the budget.
const KEY_BLOCK: usize = 4096;

/// The f32 at or below `x`.
fn down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) > x { f.next_down() } else { f }
}

/// The f32 at or above `x`.
fn up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) < x { f.next_up() } else { f }
}

/// A screen box as f32 rounded outward (so still conservative), written `(min along, min
/// across, max along, max across)`: along the screen axis that the turn moves least (a yaw
/// spin's boxes grow only sideways, so sweeping down the screen meets few of them).
type ScreenBox = [f32; 4];

/// No box: meets nothing.
const NO_BOX: ScreenBox = [
    f32::INFINITY,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::NEG_INFINITY,
];

/// Whether a box holds nothing ([`NO_BOX`]).
fn is_empty(a: &ScreenBox) -> bool {
    !(a[0] <= a[2] && a[1] <= a[3])
}

/// Whether two boxes meet. [`NO_BOX`] meets nothing, not even an unbounded box (a piece
/// reaching the eye's near plane), which its infinities alone would compare as meeting.
fn meet(a: &ScreenBox, b: &ScreenBox) -> bool {
    !is_empty(a) && !is_empty(b) && a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3]
}

/// Every piece's box over bin `bin` of `bins` ([`NO_BOX`] where the piece is not drawn).
fn bin_boxes(pieces: &Pieces, bin: usize, bins: usize) -> Vec<ScreenBox> {
    let width = std::f64::consts::TAU / bins as f64;
    let (lo, hi) = (bin as f64 * width, (bin + 1) as f64 * width);
    let view = pieces.spin.view_at_rad(0.5 * (lo + hi));
    let swap = pieces.across_axis.y < pieces.across_axis.x;
    (0..pieces.set.len())
        .map(|i| {
            if !pieces.drawn[i].meets(lo, hi) {
                return NO_BOX;
            }
            let (min, max) = pieces.swept_box(&view, i, 0.5 * width);
            let (min, max) = if swap {
                (DVec2::new(min.y, min.x), DVec2::new(max.y, max.x))
            } else {
                (min, max)
            };
            [down(min.x), down(min.y), up(max.x), up(max.y)]
        })
        .collect()
}

/// Bits of a candidate key below its pair: how the pair relates.
const RELATION_BITS: u32 = 2;

/// A candidate key: the pair `i < j` and their relation (not [`Relation::Never`]), so that
/// keys sort by pair and the relation is tested once.
fn key(i: u32, j: u32, relation: Relation) -> u64 {
    let code = match relation {
        Relation::Never => unreachable!("never-related pairs are not keyed"),
        Relation::Fixed { front, .. } if front == j => 0,
        Relation::Fixed { .. } => 1,
        Relation::Depth => 2,
    };
    (u64::from(i) << (PIECE_BITS + RELATION_BITS)) | (u64::from(j) << RELATION_BITS) | code
}

/// The pair of a candidate key, and their relation.
fn pair_of(key: u64) -> (u32, u32, Relation) {
    let piece_mask = (1u64 << PIECE_BITS) - 1;
    let i = (key >> (PIECE_BITS + RELATION_BITS)) as u32;
    let j = ((key >> RELATION_BITS) & piece_mask) as u32;
    let relation = match key & ((1 << RELATION_BITS) - 1) {
        0 => Relation::Fixed {
            behind: i,
            front: j,
        },
        1 => Relation::Fixed {
            behind: j,
            front: i,
        },
        _ => Relation::Depth,
    };
    (i, j, relation)
}

/// Candidate pairs: pieces whose conservative screen boxes meet in some angular bin while
/// both may be drawn, and whose planes allow one to occlude the other. Each bin's search
/// compares a pair's boxes in the bin before, and keys a pair only where a run of bins in
/// which they meet starts (or at bin 0, for a pair whose boxes meet in every bin), so a pair
/// costs one plane test per run and the keys stay few. Sorted and without repeats.
fn candidate_keys(pieces: &Pieces, bins: usize, max_pairs: usize) -> Result<Vec<u64>, BakeError> {
    // Keys found so far over all bins, counted in blocks as they come, so that a search over
    // the budget stops before its keys cost more than the budget states.
    let limit = max_pairs.saturating_mul(4);
    let found = AtomicUsize::new(0);
    // Each task takes a run of bins, so that a bin's boxes are made once for it and its
    // neighbour; four tasks per thread even out the bins' uneven work.
    let tasks = (4 * rayon::current_num_threads()).clamp(1, bins);
    let per_task: Vec<Vec<u64>> = (0..tasks)
        .into_par_iter()
        .map(|task| {
            let (first, last) = (task * bins / tasks, (task + 1) * bins / tasks);
            let mut keys = Vec::new();
            let mut before = bin_boxes(pieces, (first + bins - 1) % bins, bins);
            'bins: for bin in first..last {
                let here = bin_boxes(pieces, bin, bins);
                let mut order: Vec<(ScreenBox, u32)> = here
                    .iter()
                    .zip(0..)
                    .filter(|(b, _)| !is_empty(b))
                    .map(|(b, i)| (*b, i))
                    .collect();
                order.sort_unstable_by(|a, b| a.0[0].total_cmp(&b.0[0]));
                for (k, &(box_a, a)) in order.iter().enumerate() {
                    for &(box_b, b) in &order[k + 1..] {
                        if box_b[0] > box_a[2] {
                            break;
                        }
                        if box_b[1] > box_a[3] || box_a[1] > box_b[3] {
                            continue;
                        }
                        let (i, j) = (a.min(b), a.max(b));
                        let (iu, ju) = (i as usize, j as usize);
                        let starts = !meet(&before[iu], &before[ju]);
                        if !(starts || bin == 0) {
                            continue;
                        }
                        let relation = pieces.relation(iu, ju);
                        if relation == Relation::Never {
                            continue;
                        }
                        keys.push(key(i, j, relation));
                        if keys.len() % KEY_BLOCK == 0
                            && found.fetch_add(KEY_BLOCK, Ordering::Relaxed) + KEY_BLOCK > limit
                        {
                            break 'bins;
                        }
                    }
                }
                before = here;
            }
            found.fetch_add(keys.len() % KEY_BLOCK, Ordering::Relaxed);
            keys
        })
        .collect();
    let total = found.load(Ordering::Relaxed);
    if total > limit {
        return Err(BakeError::PairBudget {
            pairs: total,
            budget: max_pairs,
        });
    }
    let mut keys = Vec::with_capacity(total);
    for task in per_task {
        keys.extend_from_slice(&task);
    }
    keys.par_sort_unstable();
    keys.dedup();
    Ok(keys)
}

/// Loose arcs longer than this (radians) are refined at once. They belong to near
/// neighbours, whose sight cone is most of the turn: left loose, each sits in the window of
/// every batch along its arcs and closes cycles that the sweep must refine anyway.
const REFINE_AT_ONCE: f64 = 45.0 * std::f64::consts::PI / 180.0;

/// The constraint of a candidate pair of fixed relation: loose, where both are drawn and in
/// sight ([`Pieces::sight`]), or exact where that is longer than [`REFINE_AT_ONCE`]. Empty
/// arcs for a pair that needs none, or is decided by depth.
fn loose_constraint(pieces: &Pieces, key: u64) -> Constraint {
    let (i, j, relation) = pair_of(key);
    let Relation::Fixed { behind, front } = relation else {
        return Constraint {
            behind: i,
            front: j,
            arcs: ArcSet::empty(),
            exact: true,
        };
    };
    let arcs = pieces.drawn[i as usize].intersect(&pieces.drawn[j as usize]);
    let arcs = if arcs.is_empty() {
        arcs
    } else {
        arcs.intersect(&pieces.sight(behind as usize, front as usize))
    };
    let loose = Constraint {
        behind,
        front,
        arcs,
        exact: false,
    };
    if loose.arcs.total_length() > REFINE_AT_ONCE {
        Constraint {
            arcs: pieces.refine(&loose),
            exact: true,
            ..loose
        }
    } else {
        loose
    }
}

/// The exact constraints of a pair decided by depth: one per stretch of overlap in which
/// the same piece is in front.
fn depth_constraints(
    pieces: &Pieces,
    i: u32,
    j: u32,
    scratch: &mut SampleScratch,
) -> SmallVec<[Constraint; 2]> {
    let (iu, ju) = (i as usize, j as usize);
    let mut out = SmallVec::new();
    // Between two events of the pair the overlap neither vanishes nor splits, and pieces
    // that do not cross keep one relation over a connected overlap: one direction per
    // stretch between events, judged at its middle.
    let overlap = pieces.overlap(iu, ju, &ArcSet::full());
    let events = pieces.events_within(iu, ju, &overlap);
    let decisive = pieces.decisive_area();
    for (start, length) in overlap.joined() {
        let end = start + length;
        let mut cuts: Vec<f64> = events
            .iter()
            .map(|&e| start + (e - start).rem_euclid(std::f64::consts::TAU))
            .filter(|&e| e < end)
            .collect();
        cuts.push(start);
        cuts.push(end);
        cuts.sort_by(f64::total_cmp);
        let stretches: Vec<(f64, f64)> = cuts
            .windows(2)
            .map(|w| (w[0], w[1]))
            .filter(|&(a, b)| b > a)
            .collect();
        let samples: Vec<Option<FrontSample>> = stretches
            .iter()
            .map(|&(a, b)| pieces.front_sample(iu, ju, 0.5 * (a + b), scratch))
            .collect();
        // Within one arc of overlap the same piece is in front throughout (module docs,
        // point 2). A stretch whose own overlap is too small to judge at its middle (one
        // that just starts: docs/ROBUSTNESS.md, finding 27) takes the direction of the
        // arc's largest overlap, instead of no order at all.
        let largest = samples
            .iter()
            .flatten()
            .max_by(|x, y| x.area.total_cmp(&y.area))
            .map(|s| s.i_front);
        // Neighbouring stretches of one direction make one constraint.
        let mut stretch: Option<(f64, f64, bool)> = None;
        // The overlap's ends are already widened by the margin; events between them are
        // roots as computed, widened here.
        let mut emit = |(a, b, i_front): (f64, f64, bool)| {
            let (behind, front) = if i_front { (j, i) } else { (i, j) };
            let a = if a > start { a - ARC_MARGIN_RAD } else { a };
            let b = if b < end { b + ARC_MARGIN_RAD } else { b };
            out.push(Constraint {
                behind,
                front,
                arcs: ArcSet::arc(a, b - a),
                exact: true,
            });
        };
        for (&(a, b), sample) in stretches.iter().zip(&samples) {
            let own = sample.filter(|s| s.area > decisive).map(|s| s.i_front);
            let Some(i_front) = own.or(largest) else {
                if let Some(done) = stretch.take() {
                    emit(done);
                }
                continue;
            };
            stretch = match stretch {
                Some((lo, _, same)) if same == i_front => Some((lo, b, same)),
                other => {
                    if let Some(done) = other {
                        emit(done);
                    }
                    Some((a, b, i_front))
                }
            };
        }
        if let Some(done) = stretch {
            emit(done);
        }
    }
    out
}

/// Every pair's constraint, with the number of candidate pairs. A pair of fixed relation
/// gets the superset "both drawn and in sight" ([`Pieces::sight`]), to be refined only where
/// it matters ([`Pieces::refine`]); a pair decided by depth gets its exact arcs at once
/// (each arc has its own direction).
pub(crate) fn constraints(
    pieces: &Pieces,
    bins: usize,
    max_pairs: usize,
) -> Result<(Vec<Constraint>, usize), BakeError> {
    let keys = candidate_keys(pieces, bins, max_pairs)?;
    let pairs = keys.len();
    if pairs > max_pairs {
        return Err(BakeError::PairBudget {
            pairs,
            budget: max_pairs,
        });
    }
    // One slot per pair, written in place: a fixed pair's loose constraint (its arcs empty
    // where it needs none, and for the other pairs); the arcs of pairs decided by depth
    // follow.
    let mut found: Vec<Constraint> = Vec::new();
    keys.par_iter()
        .map(|&key| loose_constraint(pieces, key))
        .collect_into_vec(&mut found);
    let by_depth: Vec<Constraint> = keys
        .par_iter()
        .filter(|&&key| matches!(pair_of(key).2, Relation::Depth))
        .map_init(SampleScratch::default, |scratch, &key| {
            let (i, j, _) = pair_of(key);
            depth_constraints(pieces, i, j, scratch)
        })
        .flat_map_iter(|found| found)
        .collect();
    found.extend(by_depth);
    Ok((found, pairs))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::axis::Axis;
    use face_sort::{Bounds, Plane};

    /// Squares of random size and attitude in a box, from a fixed seed.
    fn squares(count: usize, seed: u64) -> PolygonSet {
        let mut state = seed;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut set = PolygonSet::new();
        for k in 0..count {
            let centre = DVec3::new(next(), next(), next());
            let normal = DVec3::new(next(), next(), next()).normalize();
            let u = normal.any_orthonormal_vector();
            let v = normal.cross(u);
            let size = 0.05 + 0.2 * (next() + 1.0);
            let corners = [
                centre - size * u - size * v,
                centre + size * u - size * v,
                centre + size * u + size * v,
                centre - size * u + size * v,
            ];
            let plane = Plane::try_from_point_normal(centre, normal).expect("a plane");
            set.push(&corners, k as u32, plane);
        }
        set
    }

    /// The box [`squares`] places its squares in, with room for their size.
    const SQUARES_BOUNDS: Bounds = Bounds {
        min: DVec3::splat(-1.5),
        max: DVec3::splat(1.5),
    };

    /// Yaw spins at pitch 20° around [`SQUARES_BOUNDS`] at 64 × 64, orthographic and in
    /// perspective (the eye 256 px away), with that perspective distance.
    fn yaw_spins() -> impl Iterator<Item = (Option<f64>, Spin)> {
        [None, Some(256.0)].into_iter().map(|persp| {
            let mut view = View::fit(&SQUARES_BOUNDS, 64, 64);
            if let Some(d) = persp {
                view = view.with_perspective(d);
            }
            let axis = Axis::Yaw {
                pitch: 20.0,
                roll: 0.0,
            };
            (persp, Spin::new(view, axis).expect("a spin"))
        })
    }

    /// Every fixed pair's exact overlap (3,600 angles a turn) lies inside its sight cone, in
    /// both projections; a cone that missed the chord or pointed the wrong way fails here.
    #[test]
    fn a_fixed_pair_overlaps_only_inside_its_sight_cone() {
        let set = squares(40, 7);
        for (persp, spin) in yaw_spins() {
            let pieces = Pieces::new(&spin, &set, 1.0, SQUARES_BOUNDS.diagonal());
            let (mut overlapping, mut narrowed) = (0, 0);
            for i in 0..set.len() {
                for j in i + 1..set.len() {
                    let Relation::Fixed { behind, front } = pieces.relation(i, j) else {
                        continue;
                    };
                    let exact = pieces.overlap(i, j, &ArcSet::full());
                    let sight = pieces.sight(behind as usize, front as usize);
                    narrowed += usize::from(sight != ArcSet::full());
                    for step in 0..3600 {
                        let theta = std::f64::consts::TAU * f64::from(step) / 3600.0;
                        if exact.contains(theta) {
                            overlapping += 1;
                            assert!(
                                sight.contains(theta),
                                "{persp:?}: pieces {behind} and {front} overlap at {theta} \
                                 outside their sight cone {sight:?}"
                            );
                        }
                    }
                }
            }
            // Not vacuous: pairs overlap, and the cones narrow some of them.
            assert!(overlapping > 1000, "{persp:?}: {overlapping}");
            assert!(narrowed > 10, "{persp:?}: {narrowed}");
        }
    }

    /// Every corner of every piece, at angles all over a bin (its ends included), projects
    /// inside the piece's swept box of that bin, in both projections and for bins wider and
    /// narrower than a quarter turn (and the boxes are bounded).
    #[test]
    fn a_swept_box_holds_its_piece_all_over_the_bin() {
        let set = squares(40, 11);
        for (persp, spin) in yaw_spins() {
            let pieces = Pieces::new(&spin, &set, 1.0, SQUARES_BOUNDS.diagonal());
            for bins in [1, 3, 32] {
                let width = std::f64::consts::TAU / bins as f64;
                for bin in 0..bins {
                    let (lo, hi) = (bin as f64 * width, (bin + 1) as f64 * width);
                    let mid_view = spin.view_at_rad(0.5 * (lo + hi));
                    for i in 0..set.len() {
                        let (min, max) = pieces.swept_box(&mid_view, i, 0.5 * width);
                        assert!(min.is_finite() && max.is_finite(), "{persp:?}: unbounded");
                        for step in 0..=64 {
                            let theta = lo + width * f64::from(step) / 64.0;
                            let view = spin.view_at_rad(theta);
                            for &c in set.corners(i) {
                                let v = view.to_view(c);
                                let w = view.eye_in_view().map_or(1.0, |eye| 1.0 - v.z / eye.z);
                                let p = DVec2::new(v.x, v.y) / w;
                                assert!(
                                    p.cmpge(min).all() && p.cmple(max).all(),
                                    "{persp:?}, {bins} bins: piece {i} at {theta} projects to \
                                     {p} outside its box {min}..{max}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn no_box_meets_nothing_not_even_an_unbounded_box() {
        // A fuzzed perspective bake lost a run of bins: in the bin before it one piece was
        // not drawn (NO_BOX) and the other reached the near plane (unbounded), and
        // `inf <= inf` made them "meet" there, so no run started (a cell then missed the
        // pair's order: fuzz/regressions/bake/picture-unbounded-box-*).
        let unbounded: ScreenBox = [
            f32::NEG_INFINITY,
            f32::NEG_INFINITY,
            f32::INFINITY,
            f32::INFINITY,
        ];
        let unit: ScreenBox = [0.0, 0.0, 1.0, 1.0];
        assert!(!meet(&NO_BOX, &unbounded));
        assert!(!meet(&unbounded, &NO_BOX));
        assert!(!meet(&NO_BOX, &NO_BOX));
        assert!(!meet(&NO_BOX, &unit));
        assert!(meet(&unbounded, &unit));
        assert!(meet(&unbounded, &unbounded));
    }
}
