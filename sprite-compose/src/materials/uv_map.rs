//! The affine map from a face's plane to texture coordinates.

use glam::{DVec2, DVec3};

use crate::tolerance::{UNDERFLOW_ABS, UV_SYSTEM_SINGULAR};

/// An affine map from points of a face's plane (centred model space, the space of draw
/// lists) to normalised texture coordinates, `(0, 0)` the texture's top-left corner and
/// `(1, 1)` its bottom-right (OBJ and most DCC tools put `v = 0` at the bottom: pass
/// `1 − v`).
///
/// Fitted by least squares to the face's corners, so that fan triangles and split
/// fragments of the face get the uv of any of their points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvMap {
    origin: DVec3,
    axis_s: DVec3,
    axis_t: DVec3,
    /// `uv = s · k[0] + t · k[1] + k[2]`.
    k: [DVec2; 3],
}

impl UvMap {
    /// Fits the map to a face: `corners` in centred model space (model position minus
    /// `geometry.bounds().centre()`), `uvs` one per corner. `None` when the corners have no
    /// area, the counts differ or the uvs are degenerate (all on one line).
    #[must_use]
    pub fn fit(corners: &[DVec3], uvs: &[DVec2]) -> Option<Self> {
        if corners.len() < 3 || corners.len() != uvs.len() {
            return None;
        }
        let normal = face_sort::newell_normal(corners).try_normalize()?;
        let origin = corners.iter().copied().sum::<DVec3>() / corners.len() as f64;
        let axis_s = normal.any_orthonormal_vector();
        let axis_t = normal.cross(axis_s);
        // Least squares: [s t 1] · K = uv, normal equations (3×3) per uv component.
        let mut m = [[0.0f64; 3]; 3];
        let mut rhs = [DVec2::ZERO; 3];
        for (&c, &uv) in corners.iter().zip(uvs) {
            let d = c - origin;
            let row = [d.dot(axis_s), d.dot(axis_t), 1.0];
            for i in 0..3 {
                for j in 0..3 {
                    m[i][j] += row[i] * row[j];
                }
                rhs[i] += uv * row[i];
            }
        }
        let k = solve3(m, rhs)?;
        let map = UvMap {
            origin,
            axis_s,
            axis_t,
            k,
        };
        if !k.iter().all(|v| v.is_finite()) || k[0].perp_dot(k[1]).abs() < UNDERFLOW_ABS {
            return None;
        }
        Some(map)
    }

    /// The uv of a point (centred model space) on or near the face's plane.
    #[inline]
    #[must_use]
    pub fn uv(&self, p: DVec3) -> DVec2 {
        let d = p - self.origin;
        self.k[0] * d.dot(self.axis_s) + self.k[1] * d.dot(self.axis_t) + self.k[2]
    }

    /// This map followed by `uv ↦ uv · scale + offset` (per axis).
    #[must_use]
    #[cfg(feature = "obj-quads")]
    pub(crate) fn remapped(&self, scale: DVec2, offset: DVec2) -> Self {
        UvMap {
            k: [
                self.k[0] * scale,
                self.k[1] * scale,
                self.k[2] * scale + offset,
            ],
            ..*self
        }
    }
}

/// Solves `m · x = rhs` (3×3, two right-hand sides) by Cramer's rule.
fn solve3(m: [[f64; 3]; 3], rhs: [DVec2; 3]) -> Option<[DVec2; 3]> {
    let det3 = |a: [[f64; 3]; 3]| {
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    };
    let det = det3(m);
    let scale = m.iter().flatten().fold(0.0f64, |a, &b| a.max(b.abs()));
    if det.is_nan() || det.abs() <= UV_SYSTEM_SINGULAR * scale * scale * scale {
        return None;
    }
    let mut out = [DVec2::ZERO; 3];
    for (col, slot) in out.iter_mut().enumerate() {
        let (mut mx, mut my) = (m, m);
        for row in 0..3 {
            mx[row][col] = rhs[row].x;
            my[row][col] = rhs[row].y;
        }
        *slot = DVec2::new(det3(mx), det3(my)) / det;
    }
    Some(out)
}
