//! Oriented planes with unit normals.

use glam::DVec3;

/// Which side of a plane a point or polygon lies on, with a tolerance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// Strictly on the side the normal points to.
    Front,
    /// Strictly on the other side.
    Back,
    /// Within the tolerance of the plane.
    On,
    /// Polygons only: some corners in front, some behind.
    Spanning,
}

/// An oriented plane `normal · p = offset`.
///
/// # Guarantees
/// `normal` has unit length (it is normalised at construction).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    normal: DVec3,
    offset: f64,
}

impl Plane {
    /// The plane through `point` with the direction of `normal`; `None` when `normal` is zero
    /// or not finite.
    #[must_use]
    pub fn try_from_point_normal(point: DVec3, normal: DVec3) -> Option<Self> {
        let unit = normal.try_normalize()?;
        Some(Plane {
            normal: unit,
            offset: unit.dot(point),
        })
    }

    /// The fitted plane of a polygon: Newell's normal through the corners' mean.
    /// `None` when the polygon has no area.
    #[must_use]
    pub fn try_from_polygon(corners: &[DVec3]) -> Option<Self> {
        let normal = newell_normal(corners);
        let mean = corners.iter().copied().sum::<DVec3>() / corners.len().max(1) as f64;
        Self::try_from_point_normal(mean, normal)
    }

    /// Unit normal.
    #[must_use]
    pub fn normal(&self) -> DVec3 {
        self.normal
    }

    /// `normal · p` for points on the plane.
    #[must_use]
    pub fn offset(&self) -> f64 {
        self.offset
    }

    /// Signed distance of `p`: positive in front (the side the normal points to).
    #[inline]
    #[must_use]
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p) - self.offset
    }

    /// The parallel plane through `point`: the same normal, bit for bit, and offset
    /// `normal · point` (e.g. a polygon's plane through its first corner, as the sorters
    /// cull).
    #[must_use]
    pub fn through(&self, point: DVec3) -> Self {
        Plane {
            normal: self.normal,
            offset: self.normal.dot(point),
        }
    }

    /// The same plane facing the other way.
    #[must_use]
    pub fn flipped(&self) -> Self {
        Plane {
            normal: -self.normal,
            offset: -self.offset,
        }
    }

    /// Side of one point, `tolerance` in model units.
    #[inline]
    #[must_use]
    pub fn side_of_point(&self, p: DVec3, tolerance: f64) -> Side {
        let d = self.signed_distance(p);
        if d > tolerance {
            Side::Front
        } else if d < -tolerance {
            Side::Back
        } else {
            Side::On
        }
    }

    /// Side of a polygon: `On` when every corner is on the plane, `Spanning` when corners
    /// lie strictly on both sides.
    #[must_use]
    pub fn side_of_polygon(&self, corners: &[DVec3], tolerance: f64) -> Side {
        // `side_of_point` per corner, without a branch per corner.
        let (mut front, mut back) = (false, false);
        for &p in corners {
            let d = self.signed_distance(p);
            front |= d > tolerance;
            back |= d < -tolerance;
        }
        match (front, back) {
            (true, true) => Side::Spanning,
            (true, false) => Side::Front,
            (false, true) => Side::Back,
            (false, false) => Side::On,
        }
    }

    /// Projects `p` orthogonally onto the plane.
    #[must_use]
    pub fn project_point(&self, p: DVec3) -> DVec3 {
        p - self.normal * self.signed_distance(p)
    }
}

/// Newell's normal of a polygon (not normalised; its length is twice the area for a planar
/// polygon). Counter-clockwise corners seen from the tip give a normal toward the viewer.
#[must_use]
pub fn newell_normal(corners: &[DVec3]) -> DVec3 {
    // Relative to the first corner: the sums `a + b` then have the polygon's size, not the
    // size of its distance from the origin, so a small face far out keeps its precision.
    let origin = corners.first().copied().unwrap_or(DVec3::ZERO);
    let mut normal = DVec3::ZERO;
    let next = corners.iter().skip(1).chain(corners.first());
    for (&a, &b) in corners.iter().zip(next) {
        let (a, b) = (a - origin, b - origin);
        normal.x += (a.y - b.y) * (a.z + b.z);
        normal.y += (a.z - b.z) * (a.x + b.x);
        normal.z += (a.x - b.x) * (a.y + b.y);
    }
    normal
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn newell_normal_of_ccw_square_points_up() {
        let sq = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let n = newell_normal(&sq);
        assert_eq!(n, DVec3::new(0.0, 0.0, 2.0));
        let plane = Plane::try_from_polygon(&sq).unwrap();
        assert_eq!(
            plane.side_of_point(DVec3::new(0.3, 0.3, 0.5), 1e-9),
            Side::Front
        );
        assert_eq!(plane.side_of_polygon(&sq, 1e-9), Side::On);
        assert!(Plane::try_from_polygon(&[DVec3::ZERO; 3]).is_none());
    }

    #[test]
    fn a_small_face_far_from_the_origin_keeps_its_normal() {
        // A triangle about 1 unit across, 1e8 units out: sums of coordinates that size cost
        // its normal 1.8e-8 rad; relative to a corner, rounding. Its edges are differences
        // of nearby numbers (exact), so their cross product is the reference.
        let corners = [
            DVec3::new(99999999.2687285, -29999999.305132527, 70000000.52754924),
            DVec3::new(99999999.51013805, -30000000.009129826, 69999999.89898212),
            DVec3::new(100000000.30318594, -29999999.422553297, 69999999.18771917),
        ];
        let exact = (corners[1] - corners[0])
            .cross(corners[2] - corners[0])
            .normalize();
        let sine = newell_normal(&corners).normalize().cross(exact).length();
        assert!(sine < 1e-15, "{sine}");
    }
}
