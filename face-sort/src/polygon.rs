//! Convex polygon operations shared by every sorter, the oracle and the sinks:
//! splitting by a plane, 2D convex clipping, areas.

use glam::{DVec2, DVec3};

use crate::plane::Plane;
use crate::tolerance::AREA_ROUNDING;

/// A polygon's edges: each corner with the next, the last with the first (no `%` per corner:
/// an integer division costs tens of cycles).
#[inline]
pub(crate) fn edges<T: Copy>(corners: &[T]) -> impl Iterator<Item = (T, T)> + '_ {
    let next = corners.iter().skip(1).chain(corners.first());
    corners.iter().copied().zip(next.copied())
}

/// Splits a convex polygon by `plane`, appending the part in front to `front` and the part
/// behind to `back` (each left empty when that side has no part). Corners within `tolerance`
/// of the plane belong to both parts, so the two parts share the cut edge exactly.
pub fn split_polygon(
    corners: &[DVec3],
    plane: &Plane,
    tolerance: f64,
    front: &mut Vec<DVec3>,
    back: &mut Vec<DVec3>,
) {
    let start_front = front.len();
    let start_back = back.len();
    for (a, b) in edges(corners) {
        let da = plane.signed_distance(a);
        let db = plane.signed_distance(b);
        let a_on = da.abs() <= tolerance;
        if a_on {
            front.push(a);
            back.push(a);
        } else if da > 0.0 {
            front.push(a);
        } else {
            back.push(a);
        }
        let b_on = db.abs() <= tolerance;
        if !a_on && !b_on && (da > 0.0) != (db > 0.0) {
            let t = da / (da - db);
            let p = a + (b - a) * t;
            front.push(p);
            back.push(p);
        }
    }
    if front.len() - start_front < 3 {
        front.truncate(start_front);
    }
    if back.len() - start_back < 3 {
        back.truncate(start_back);
    }
}

/// Twice the signed area of a 2D polygon (positive when counter-clockwise, y up).
#[must_use]
pub fn signed_area_2d(corners: &[DVec2]) -> f64 {
    edges(corners).map(|(a, b)| a.perp_dot(b)).sum::<f64>() * 0.5
}

/// Whether the line through an edge of one convex polygon (either winding) has one polygon on
/// one side and the other on the other, touching allowed, and some corner strictly off it:
/// then their intersection lies in that line and has no area. Each line is checked against
/// both polygons, so that a line badly defined (a zero or tiny edge, repeated corners) never
/// separates what overlaps. A cheap first test before [`clip_convex_2d`]. (Whether a segment
/// enters a polygon of known turn is the coverage test's own, stricter `enters`.)
#[must_use]
pub(crate) fn separated_2d(a: &[DVec2], b: &[DVec2]) -> bool {
    let by_edge_of = |p: &[DVec2]| {
        edges(p).any(|(from, to)| {
            let edge = to - from;
            let range = |polygon: &[DVec2]| {
                polygon
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
                        let side = edge.perp_dot(x - from);
                        (lo.min(side), hi.max(side))
                    })
            };
            let ((a_lo, a_hi), (b_lo, b_hi)) = (range(a), range(b));
            let apart = (a_hi <= 0.0 && b_lo >= 0.0) || (a_lo >= 0.0 && b_hi <= 0.0);
            apart && (a_lo < 0.0 || a_hi > 0.0 || b_lo < 0.0 || b_hi > 0.0)
        })
    };
    by_edge_of(a) || by_edge_of(b)
}

/// Whether convex polygons `a` and `b` overlap by more than `min_area`, and by more than the
/// rounding of the overlap's own computation: their intersection (left in `out`) has three
/// corners or more and more area than both.
///
/// - *Rounding.* Corners carry errors of a few ulps of their largest coordinate (`r_a`,
///   `r_b`, far larger than the polygons where they lie far from the image centre, or come
///   from a near-plane clip), times `gain` where the projection itself rounds worse (the
///   oracle passes [`View::rounding_gain`](crate::View::rounding_gain), up to 1,000 next to
///   the near plane; the sorters pass 1, so they order every overlap the oracle could see).
///   An intersection no wider than a band of [`AREA_ROUNDING`]` · (r_a + r_b) · gain` along
///   its boundary cannot be told from none: it needs more area than that band times its
///   perimeter. Its area is summed
///   from its first corner, so that the sum's own rounding scales with its size, not with
///   its distance from the centre.
/// - *Convexity.* Pieces are convex only to within [`CONVEXITY`](crate::tolerance::CONVEXITY):
///   clipping by a polygon with a slightly reflex corner loses what lies beyond that corner's
///   edges. The intersection is therefore clipped both ways (`a` by `b`, then `b` by `a`),
///   which is exact when either is convex.
///
/// The overlap test of Newell, the oracle and the fragment merge.
pub(crate) fn overlap_exceeds(
    a: &[DVec2],
    b: &[DVec2],
    min_area: f64,
    gain: f64,
    out: &mut Vec<DVec2>,
    scratch: &mut Vec<DVec2>,
) -> bool {
    let reach = |p: &[DVec2]| {
        p.iter()
            .fold(0.0_f64, |m, p| m.max(p.x.abs()).max(p.y.abs()))
    };
    let band = AREA_ROUNDING * (reach(a) + reach(b)) * gain;
    let exceeds = |overlap: &[DVec2]| {
        if overlap.len() < 3 {
            return false;
        }
        let origin = overlap[0];
        let area = edges(overlap)
            .map(|(p, q)| (p - origin).perp_dot(q - origin))
            .sum::<f64>()
            .abs()
            * 0.5;
        let perimeter: f64 = edges(overlap).map(|(p, q)| p.distance(q)).sum();
        area > min_area && area > band * perimeter
    };
    clip_convex_2d(a, b, out, scratch);
    if exceeds(out) {
        return true;
    }
    clip_convex_2d(b, a, out, scratch);
    exceeds(out)
}

/// Clips the convex polygon `subject` by the convex polygon `clip` (either winding),
/// writing the intersection to `out` (cleared first). `scratch` is a reusable buffer.
pub fn clip_convex_2d(
    subject: &[DVec2],
    clip: &[DVec2],
    out: &mut Vec<DVec2>,
    scratch: &mut Vec<DVec2>,
) {
    out.clear();
    out.extend_from_slice(subject);
    let orientation = signed_area_2d(clip).signum();
    if orientation == 0.0 {
        out.clear();
        return;
    }
    for (a, b) in edges(clip) {
        if out.is_empty() {
            return;
        }
        let edge = b - a;
        std::mem::swap(out, scratch);
        out.clear();
        let inside = |p: DVec2| edge.perp_dot(p - a) * orientation;
        for (p, q) in edges(scratch) {
            let dp = inside(p);
            let dq = inside(q);
            if dp >= 0.0 {
                out.push(p);
            }
            if (dp >= 0.0) != (dq >= 0.0) {
                let t = dp / (dp - dq);
                out.push(p + (q - p) * t);
            }
        }
    }
}

/// Axis-aligned 2D box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Box2 {
    /// Smallest corner.
    pub min: DVec2,
    /// Largest corner.
    pub max: DVec2,
}

impl Box2 {
    /// An empty box (adding any point makes it that point).
    pub const EMPTY: Box2 = Box2 {
        min: DVec2::splat(f64::INFINITY),
        max: DVec2::splat(f64::NEG_INFINITY),
    };

    /// The bounding box of `points`.
    #[must_use]
    pub fn from_points(points: &[DVec2]) -> Self {
        let mut b = Self::EMPTY;
        for &p in points {
            b.min = b.min.min(p);
            b.max = b.max.max(p);
        }
        b
    }

    /// The smallest box holding both (either may be [`EMPTY`](Self::EMPTY)).
    #[inline]
    #[must_use]
    pub fn union(self, other: Box2) -> Box2 {
        Box2 {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// Whether the two closed boxes meet (touching counts).
    #[inline]
    #[must_use]
    pub fn touches(&self, other: &Box2) -> bool {
        self.min.x <= other.max.x
            && other.min.x <= self.max.x
            && self.min.y <= other.max.y
            && other.min.y <= self.max.y
    }

    /// Whether the two boxes overlap with positive width and height.
    #[inline]
    #[must_use]
    pub fn overlaps(&self, other: &Box2) -> bool {
        self.min.x < other.max.x
            && other.min.x < self.max.x
            && self.min.y < other.max.y
            && other.min.y < self.max.y
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_small_overlap_far_from_the_centre_counts() {
        // Two pieces a few units across, 1e8 units from the image centre, overlapping by
        // about 0.3 unit²: the rounding of their corners (ulps of 1e8, about 1e-8) is far
        // below that. A floor of `AREA_ROUNDING · r²` (1.4e2 here) dismissed it, as it did
        // the thin pieces of a model with one corner 2.7e8 units out
        // (fuzz/regressions/sorters/far-corner-*), which Newell then misordered.
        let far = 1e8;
        let a = [
            DVec2::new(far, far),
            DVec2::new(far + 2.0, far),
            DVec2::new(far, far + 2.0),
        ];
        let b = [
            DVec2::new(far + 0.5, far + 0.5),
            DVec2::new(far - 1.0, far + 0.5),
            DVec2::new(far + 0.5, far - 1.0),
        ];
        let (mut out, mut scratch) = (Vec::new(), Vec::new());
        assert!(overlap_exceeds(&a, &b, 1e-12, 1.0, &mut out, &mut scratch));
        assert!(overlap_exceeds(&b, &a, 1e-12, 1.0, &mut out, &mut scratch));
    }

    #[test]
    fn a_piece_convex_only_within_tolerance_is_clipped_both_ways() {
        // From fuzz/regressions/sorters/far-corner-newell-3c3d7b7f925b (view units): a
        // quad 5e8 long whose far end, 8,000 units across, turns the wrong way within
        // `CONVEXITY`, and a triangle that overlaps that end. Clipped by the quad, the
        // triangle loses everything (the quad's reflex corner cuts it away); the quad
        // clipped by the triangle keeps the overlap, about 4,900 units².
        let triangle = [
            DVec2::new(502890181.4041221, 558713484.9986705),
            DVec2::new(502898593.7474044, 558711992.2553277),
            DVec2::new(502898599.4959889, 558711994.3722461),
        ];
        let quad = [
            DVec2::new(400141931.88430625, 43307930.367754355),
            DVec2::new(502890181.37957746, 558713485.1579843),
            DVec2::new(502898594.9999259, 558711993.0477082),
            DVec2::new(502898594.18908846, 558711993.4374819),
        ];
        let (mut out, mut scratch) = (Vec::new(), Vec::new());
        clip_convex_2d(&triangle, &quad, &mut out, &mut scratch);
        assert!(out.len() < 3, "{out:?}");
        for (a, b) in [(&triangle[..], &quad[..]), (&quad[..], &triangle[..])] {
            assert!(overlap_exceeds(a, b, 1.0, 1.0, &mut out, &mut scratch));
            let area = signed_area_2d(&out).abs();
            assert!((4000.0..6000.0).contains(&area), "{area}");
        }
    }

    #[test]
    fn an_overlap_within_the_rounding_of_its_coordinates_is_none() {
        // Two near-plane clipped projections (view units) of pieces that only touch: Newell
        // once read their 3e-11 of "overlap" as an order between them and cycled until its
        // step budget ran out (fuzz/regressions/sorters/newell-sliver-overlap-near-eye-*).
        let touching = [
            DVec2::new(3498.360287825852, -116.98185199978042),
            DVec2::new(3482.8153735750457, -227.74890751105482),
            DVec2::new(2707.1296132837956, -2141.898520777107),
        ];
        let big = [
            DVec2::new(-802.3356131486217, -430.11102815752406),
            DVec2::new(4090.972794894092, 627.330596938173),
            DVec2::new(4029.1307471246732, 326.98584604826436),
            DVec2::new(421.28707683605467, -2690.8272615830833),
        ];
        let (mut out, mut scratch) = (Vec::new(), Vec::new());
        clip_convex_2d(&touching, &big, &mut out, &mut scratch);
        let sliver = signed_area_2d(&out).abs();
        assert!(out.len() >= 3 && sliver > 0.0 && sliver < 1e-9, "{sliver}");
        assert!(!overlap_exceeds(
            &touching,
            &big,
            1e-12,
            1.0,
            &mut out,
            &mut scratch
        ));
        // A real overlap a millionth of a unit² at the same coordinates still counts.
        let real = [
            DVec2::new(4000.0, 0.0),
            DVec2::new(4000.001, 0.0),
            DVec2::new(4000.0, 0.002),
        ];
        let under = [
            DVec2::new(3990.0, -10.0),
            DVec2::new(4010.0, -10.0),
            DVec2::new(4000.0, 10.0),
        ];
        assert!(overlap_exceeds(
            &real,
            &under,
            1e-12,
            1.0,
            &mut out,
            &mut scratch
        ));
    }

    #[test]
    fn a_repeated_corner_separates_nothing() {
        let square = |x: f64| {
            [
                DVec2::new(x, 0.0),
                DVec2::new(x + 2.0, 0.0),
                DVec2::new(x + 2.0, 2.0),
                DVec2::new(x, 2.0),
            ]
        };
        let (a, b) = (square(0.0), square(1.0));
        assert!(!separated_2d(&a, &b));
        // The first corner repeated: its zero edge has every point on its line.
        let repeated = [a[0], a[0], a[1], a[2], a[3]];
        assert!(!separated_2d(&repeated, &b));
        assert!(!separated_2d(&b, &repeated));
        // Apart, or only touching along an edge: separated.
        assert!(separated_2d(&repeated, &square(2.0)));
        assert!(separated_2d(&a, &square(3.0)));
    }

    #[test]
    fn split_square_in_half() {
        let sq = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 2.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ];
        let plane = Plane::try_from_point_normal(DVec3::new(1.0, 0.0, 0.0), DVec3::X).unwrap();
        let (mut f, mut b) = (Vec::new(), Vec::new());
        split_polygon(&sq, &plane, 1e-12, &mut f, &mut b);
        assert_eq!(f.len(), 4);
        assert_eq!(b.len(), 4);
        assert!(f.iter().all(|p| p.x >= 1.0));
        assert!(b.iter().all(|p| p.x <= 1.0));
    }

    #[test]
    fn clip_overlapping_squares() {
        let a = [
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(2.0, 2.0),
            DVec2::new(0.0, 2.0),
        ];
        let b: Vec<DVec2> = a.iter().rev().map(|p| *p + DVec2::splat(1.0)).collect();
        let (mut out, mut s) = (Vec::new(), Vec::new());
        clip_convex_2d(&a, &b, &mut out, &mut s);
        assert!((signed_area_2d(&out).abs() - 1.0).abs() < 1e-12);
    }
}
