//! Regions of viewers: a spherical triangle of directions toward the viewer, times a range
//! of eye distances from the geometry's centre.

use glam::DVec3;

use crate::tolerance::PRESORT_GROWTH;

/// The viewers whose direction from the centre `u` (unit) lies in the spherical triangle
/// `corners` (counter-clockwise seen from outside) and whose eye is at a distance in
/// `[near, far]`. `far = ∞` also holds the orthographic viewers looking from any direction of
/// the triangle; `near = ∞` holds only those.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Region {
    pub corners: [DVec3; 3],
    pub near: f64,
    pub far: f64,
}

/// Where a region's viewers lie, as generators of a convex set: an eye at `t · u` is in the
/// convex hull of `points` plus the cone of `rays`.
#[derive(Clone, Debug, Default)]
pub(crate) struct EyeHull {
    pub points: Vec<DVec3>,
    pub rays: Vec<DVec3>,
}

impl Region {
    /// The eight octants of directions, with eyes from `near` outward.
    pub fn octants(near: f64) -> [Region; 8] {
        let mut out = [Region {
            corners: [DVec3::X, DVec3::Y, DVec3::Z],
            near,
            far: f64::INFINITY,
        }; 8];
        for (k, region) in out.iter_mut().enumerate() {
            let sx = if k & 1 == 0 { 1.0 } else { -1.0 };
            let sy = if k & 2 == 0 { 1.0 } else { -1.0 };
            let sz = if k & 4 == 0 { 1.0 } else { -1.0 };
            let (x, y, z) = (DVec3::X * sx, DVec3::Y * sy, DVec3::Z * sz);
            region.corners = if sx * sy * sz > 0.0 {
                [x, y, z]
            } else {
                [x, z, y]
            };
        }
        out
    }

    /// The octant holding direction `u` (index into [`octants`](Self::octants)).
    pub fn octant_of(u: DVec3) -> usize {
        usize::from(u.x < 0.0) | usize::from(u.y < 0.0) << 1 | usize::from(u.z < 0.0) << 2
    }

    /// The unit direction through the middle of the triangle.
    pub fn centre(&self) -> DVec3 {
        (self.corners[0] + self.corners[1] + self.corners[2]).normalize()
    }

    /// The largest angle from [`centre`](Self::centre) to a corner, in radians.
    pub fn angular_radius(&self) -> f64 {
        let m = self.centre();
        self.corners
            .iter()
            .map(|c| m.dot(*c).clamp(-1.0, 1.0).acos())
            .fold(0.0, f64::max)
    }

    /// The four triangles cut by the midpoints of the edges, in the order
    /// [`child_holding`](Self::child_holding) numbers them: corner 0's, 1's, 2's, the middle.
    pub fn split_directions(&self) -> [Region; 4] {
        let [a, b, c] = self.corners;
        let [ab, bc, ca] = self.midpoints();
        [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
            .map(|corners| Region { corners, ..*self })
    }

    /// Which of [`split_directions`](Self::split_directions) holds `u` (one of them when `u`
    /// lies on a shared edge).
    pub fn child_holding(&self, u: DVec3) -> usize {
        let [ab, bc, ca] = self.midpoints();
        if ca.cross(ab).dot(u) < 0.0 {
            0
        } else if ab.cross(bc).dot(u) < 0.0 {
            1
        } else if bc.cross(ca).dot(u) < 0.0 {
            2
        } else {
            3
        }
    }

    /// The unit midpoints of the edges `ab`, `bc`, `ca`.
    fn midpoints(&self) -> [DVec3; 3] {
        let [a, b, c] = self.corners;
        [
            (a + b).normalize(),
            (b + c).normalize(),
            (c + a).normalize(),
        ]
    }

    /// Inward normals of the three edges' great circles: `u` is in the triangle when it is on
    /// or in front of each.
    pub fn edge_normals(&self) -> [DVec3; 3] {
        let [a, b, c] = self.corners;
        [a.cross(b), b.cross(c), c.cross(a)]
    }

    /// The distance where [`split_distance`](Self::split_distance) cuts.
    pub fn distance_split(&self) -> f64 {
        if self.far.is_finite() {
            (self.near * self.far).sqrt()
        } else {
            2.0 * self.near
        }
    }

    /// The nearer and the farther half of the eye distances.
    pub fn split_distance(&self) -> [Region; 2] {
        let mid = self.distance_split();
        [Region { far: mid, ..*self }, Region { near: mid, ..*self }]
    }

    /// The region grown by [`PRESORT_GROWTH`] (corners pushed away from the centre, distances
    /// widened), so that what is certified for it holds for viewers that rounding places
    /// just outside the region.
    pub fn grown(&self) -> Region {
        let m = self.centre();
        Region {
            corners: self
                .corners
                .map(|c| (c + (c - m) * PRESORT_GROWTH).normalize()),
            near: self.near * (1.0 - PRESORT_GROWTH),
            far: self.far * (1.0 + PRESORT_GROWTH),
        }
    }

    /// Whether only orthographic viewers are in the region.
    pub fn orthographic_only(&self) -> bool {
        self.near.is_infinite()
    }

    /// Generators of a convex set holding every eye of the region (`near < ∞`): the frustum
    /// between the flat triangles through `near · corners` and `far / h · corners` (`h` the
    /// flat triangle's distance from the origin), or, when `far = ∞`, the flat triangle at
    /// `near` and the corner rays. A point `t · u` with `u` in the spherical triangle is
    /// `(t / |x|) · x` for `x` in the flat one, `h ≤ |x| ≤ 1`, so it lies in that frustum.
    pub fn eye_hull(&self, out: &mut EyeHull) {
        out.points.clear();
        out.rays.clear();
        out.points.extend(self.corners.map(|c| c * self.near));
        if self.far.is_finite() {
            let [a, b, c] = self.corners;
            let h = (b - a).cross(c - a).normalize().dot(a).abs();
            out.points.extend(self.corners.map(|c| c * (self.far / h)));
        } else {
            out.rays.extend(self.corners);
        }
    }

    /// Whether the viewer at distance `t` (∞ for orthographic) in direction `u` is in the
    /// distance range.
    pub fn holds_distance(&self, t: f64) -> bool {
        t >= self.near && t <= self.far
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn octants_are_counter_clockwise_and_hold_their_directions() {
        for (k, r) in Region::octants(1.0).iter().enumerate() {
            let [a, b, c] = r.corners;
            assert!(a.cross(b).dot(c) > 0.0, "octant {k}");
            assert_eq!(Region::octant_of(r.centre()), k);
        }
    }

    #[test]
    fn each_child_holds_the_directions_it_is_chosen_for() {
        let r = Region::octants(1.0)[5];
        let children = r.split_directions();
        for i in 0..200 {
            let s = f64::from(i) * 0.731;
            let w = DVec3::new(s.sin().abs() + 0.01, (2.0 * s).cos().abs() + 0.01, 1.0);
            let u = (r.corners[0] * w.x + r.corners[1] * w.y + r.corners[2] * w.z).normalize();
            let child = &children[r.child_holding(u)];
            let [a, b, c] = child.corners;
            for (p, q) in [(a, b), (b, c), (c, a)] {
                assert!(p.cross(q).dot(u) >= -1e-12, "direction {u} outside child");
            }
        }
    }
}
