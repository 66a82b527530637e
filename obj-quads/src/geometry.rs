//! Face geometry: Newell normal, planarity, convexity, ear clipping.

use glam::{DVec2, DVec3};

use crate::tolerance::{CONVEXITY, DEGENERATE_AREA, MERGE_CONVEXITY, PLANARITY};

/// Newell's vector of a polygon (twice its vector area).
pub(crate) fn newell(pts: &[DVec3]) -> DVec3 {
    let n = pts.len();
    if n == 0 {
        return DVec3::ZERO;
    }
    let c = mean(pts);
    let mut acc = DVec3::ZERO;
    for i in 0..n {
        let a = pts[i] - c;
        let b = pts[(i + 1) % n] - c;
        acc.x += (a.y - b.y) * (a.z + b.z);
        acc.y += (a.z - b.z) * (a.x + b.x);
        acc.z += (a.x - b.x) * (a.y + b.y);
    }
    acc
}

fn mean(pts: &[DVec3]) -> DVec3 {
    if pts.is_empty() {
        return DVec3::ZERO;
    }
    pts.iter().copied().sum::<DVec3>() / pts.len() as f64
}

/// Largest corner-to-corner distance.
pub(crate) fn diameter(pts: &[DVec3]) -> f64 {
    let mut d2: f64 = 0.0;
    for (i, a) in pts.iter().enumerate() {
        for b in &pts[i + 1..] {
            d2 = d2.max(a.distance_squared(*b));
        }
    }
    d2.sqrt()
}

/// The measured shape of one face.
#[derive(Debug, Clone)]
pub(crate) struct Shape {
    /// Largest corner-to-corner distance `D`.
    pub diameter: f64,
    /// Unit Newell normal (zero when degenerate).
    pub normal: DVec3,
    /// Mean of the corners.
    pub centroid: DVec3,
    /// Zero area relative to size.
    pub degenerate: bool,
    /// Largest distance of a corner from the plane.
    pub off_plane: f64,
    /// `off_plane <= PLANARITY * D`.
    pub planar: bool,
}

impl Shape {
    /// Measures a face.
    pub(crate) fn of(pts: &[DVec3]) -> Shape {
        let diameter = diameter(pts);
        let nv = newell(pts);
        let len = nv.length();
        let area = 0.5 * len;
        let degenerate =
            !(diameter > 0.0 && area > DEGENERATE_AREA * diameter * diameter && len.is_finite());
        let centroid = mean(pts);
        let normal = if degenerate { DVec3::ZERO } else { nv / len };
        let off_plane = pts
            .iter()
            .map(|p| (*p - centroid).dot(normal).abs())
            .fold(0.0, f64::max);
        Shape {
            diameter,
            normal,
            centroid,
            degenerate,
            off_plane,
            planar: off_plane <= PLANARITY * diameter,
        }
    }

    /// The planarity limit `1e-6 · D`.
    pub(crate) fn planar_limit(&self) -> f64 {
        PLANARITY * self.diameter
    }

    /// Projects the corners into the face plane, so that the face winds
    /// counter-clockwise (positive area) in 2D.
    pub(crate) fn project(&self, pts: &[DVec3]) -> Vec<DVec2> {
        let (a, _) = self.normal.any_orthonormal_pair();
        let b = self.normal.cross(a);
        pts.iter()
            .map(|p| {
                let d = *p - self.centroid;
                DVec2::new(d.dot(a), d.dot(b))
            })
            .collect()
    }
}

fn cross2(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Whether a counter-clockwise 2D polygon is convex (straight corners allowed)
/// and winds exactly once.
pub(crate) fn is_convex(q: &[DVec2], diameter: f64) -> bool {
    let n = q.len();
    if n < 4 {
        return true;
    }
    let eps = CONVEXITY * diameter * diameter;
    let mut turning = 0.0;
    for i in 0..n {
        let p = q[(i + n - 1) % n];
        let c = q[i];
        let nx = q[(i + 1) % n];
        let e1 = c - p;
        let e2 = nx - c;
        let cr = cross2(e1, e2);
        if cr < -eps {
            return false;
        }
        turning += cr.atan2(e1.dot(e2));
    }
    (turning - std::f64::consts::TAU).abs() < 0.5
}

/// Whether four corners (in order) form a planar, strictly convex quad.
pub(crate) fn is_good_quad(pts: &[DVec3; 4]) -> bool {
    let shape = Shape::of(pts);
    if shape.degenerate || !shape.planar {
        return false;
    }
    let q = shape.project(pts);
    let eps = MERGE_CONVEXITY * shape.diameter * shape.diameter;
    let mut turning = 0.0;
    for i in 0..4 {
        let e1 = q[i] - q[(i + 3) % 4];
        let e2 = q[(i + 1) % 4] - q[i];
        let cr = cross2(e1, e2);
        if cr <= eps {
            return false;
        }
        turning += cr.atan2(e1.dot(e2));
    }
    (turning - std::f64::consts::TAU).abs() < 0.5
}

/// Point strictly inside triangle `a b c` (counter-clockwise), with tolerance.
fn strictly_inside(p: DVec2, a: DVec2, b: DVec2, c: DVec2, eps: f64) -> bool {
    cross2(b - a, p - a) > eps && cross2(c - b, p - b) > eps && cross2(a - c, p - c) > eps
}

/// Upper bound on point-in-triangle tests of one ear clipping run; past it
/// ears are clipped without the containment test (keeps run time bounded).
const EAR_TEST_BUDGET: usize = 20_000_000;

/// Triangulates a counter-clockwise 2D polygon by ear clipping. Returns
/// triangles as corner positions in `q`. Handles weakly simple polygons
/// (repeated vertices) by ignoring points coincident with the ear's corners.
pub(crate) fn ear_clip(q: &[DVec2], diameter: f64) -> Vec<[usize; 3]> {
    let mut poly: Vec<usize> = (0..q.len()).collect();
    let mut out = Vec::with_capacity(q.len().saturating_sub(2));
    let eps = CONVEXITY * diameter * diameter;
    let mut budget = EAR_TEST_BUDGET;
    let mut start = 0;
    while poly.len() > 3 {
        let n = poly.len();
        let corner = |k: usize| q[poly[k % n]];
        let convex = |k: usize| {
            let (p, c, nx) = (corner(k + n - 1), corner(k), corner(k + 1));
            cross2(c - p, nx - c)
        };
        let reflex: Vec<usize> = (0..n).filter(|&k| convex(k) <= eps).collect();
        let mut chosen = None;
        for step in 0..n {
            let k = (start + step) % n;
            if convex(k) <= eps {
                continue;
            }
            let (ip, ic, inx) = ((k + n - 1) % n, k, (k + 1) % n);
            let (a, b, c) = (q[poly[ip]], q[poly[ic]], q[poly[inx]]);
            let mut ok = true;
            if budget > 0 {
                for &r in &reflex {
                    if r == ip || r == ic || r == inx {
                        continue;
                    }
                    budget = budget.saturating_sub(1);
                    let p = q[poly[r]];
                    if p == a || p == b || p == c {
                        continue;
                    }
                    if strictly_inside(p, a, b, c, eps) {
                        ok = false;
                        break;
                    }
                }
            }
            if ok {
                chosen = Some(k);
                break;
            }
        }
        // No proper ear (numerical trouble or a non-simple polygon): clip the
        // most convex corner, or failing that the first one, so the loop ends.
        let k = chosen.unwrap_or_else(|| {
            (0..n)
                .max_by(|&x, &y| convex(x).total_cmp(&convex(y)))
                .unwrap_or(0)
        });
        out.push([poly[(k + n - 1) % n], poly[k], poly[(k + 1) % n]]);
        poly.remove(k);
        start = k.saturating_sub(1);
    }
    if let [a, b, c] = poly[..] {
        out.push([a, b, c]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_is_convex_and_planar() {
        let pts = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        let s = Shape::of(&pts);
        assert!(s.planar && !s.degenerate);
        assert!((s.normal - DVec3::Z).length() < 1e-12);
        assert!(is_convex(&s.project(&pts), s.diameter));
        assert!(is_good_quad(&pts));
    }

    #[test]
    fn l_shape_is_clipped_into_four_triangles() {
        let q = [
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(2.0, 1.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 2.0),
            DVec2::new(0.0, 2.0),
        ];
        assert!(!is_convex(&q, 3.0));
        let tris = ear_clip(&q, 3.0);
        assert_eq!(tris.len(), 4);
        let area: f64 = tris
            .iter()
            .map(|t| 0.5 * cross2(q[t[1]] - q[t[0]], q[t[2]] - q[t[0]]))
            .sum();
        assert!((area - 3.0).abs() < 1e-12);
    }

    #[test]
    fn star_pentagon_is_not_convex() {
        let q: Vec<DVec2> = (0..5)
            .map(|i| {
                let a = (i * 2) as f64 * std::f64::consts::TAU / 5.0;
                DVec2::new(a.cos(), a.sin())
            })
            .collect();
        assert!(!is_convex(&q, 2.0));
    }
}
