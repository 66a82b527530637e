//! The animation: a rotation by `θ` about a fixed axis, composed with a fixed base view.

use face_sort::{Projection, View};
use glam::{DMat3, DVec3, EulerRot};

use crate::event::EventFn;

/// Which parameter turns. Angles are degrees, as at every user-facing interface.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Axis {
    /// The yaw of `R = Ry(yaw)·Rx(pitch)·Rz(roll)` turns; pitch and roll stay.
    Yaw {
        /// Base pitch, degrees.
        pitch: f64,
        /// Base roll, degrees.
        roll: f64,
    },
    /// The pitch turns; yaw and roll stay.
    Pitch {
        /// Base yaw, degrees.
        yaw: f64,
        /// Base roll, degrees.
        roll: f64,
    },
    /// The roll turns; yaw and pitch stay.
    Roll {
        /// Base yaw, degrees.
        yaw: f64,
        /// Base pitch, degrees.
        pitch: f64,
    },
    /// `R(θ) = Rot(axis, θ)·base`: a turn about a view-space direction (normalised here)
    /// applied after the base rotation.
    Direction {
        /// The axis in view space (any length but zero).
        axis: [f64; 3],
        /// The base rotation, columns.
        base: [[f64; 3]; 3],
    },
}

impl Axis {
    /// Lower-case name: `yaw`, `pitch`, `roll` or `direction`.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Axis::Yaw { .. } => "yaw",
            Axis::Pitch { .. } => "pitch",
            Axis::Roll { .. } => "roll",
            Axis::Direction { .. } => "direction",
        }
    }
}

fn euler(yaw: f64, pitch: f64, roll: f64) -> DMat3 {
    DMat3::from_euler(
        EulerRot::YXZ,
        yaw.to_radians(),
        pitch.to_radians(),
        roll.to_radians(),
    )
}

fn cross_matrix(k: DVec3) -> DMat3 {
    DMat3::from_cols(
        DVec3::new(0.0, k.z, -k.y),
        DVec3::new(-k.z, 0.0, k.x),
        DVec3::new(k.y, -k.x, 0.0),
    )
}

fn outer(k: DVec3) -> DMat3 {
    DMat3::from_cols(k * k.x, k * k.y, k * k.z)
}

/// A view that turns: `R(θ) = A·Rot(k, θ)·B` with fixed `A`, `B` and unit `k`, every other
/// parameter (centre, scale, projection, culling) that of a template [`View`].
///
/// By Rodrigues, `Rot(k, θ) = k kᵀ + cos θ·(I − k kᵀ) + sin θ·[k]×`, so
/// `R(θ) = C₀ + cos θ·C₁ + sin θ·C₂` with constant matrices: every entry of the rotation is
/// of the form `a·cos θ + b·sin θ + c`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spin {
    axis: Axis,
    template: View,
    factors: (DMat3, DVec3, DMat3),
    c: [DMat3; 3],
}

impl Spin {
    /// The spin of `axis` with the other parameters of `template` (its rotation is ignored).
    /// `None` when an angle, the base matrix or the template's scale or eye distance is not
    /// finite, or a [`Axis::Direction`] axis has no length.
    #[must_use]
    pub fn new(template: View, axis: Axis) -> Option<Self> {
        let (a, k, b) = match axis {
            Axis::Yaw { pitch, roll } => (DMat3::IDENTITY, DVec3::Y, euler(0.0, pitch, roll)),
            Axis::Pitch { yaw, roll } => (euler(yaw, 0.0, 0.0), DVec3::X, euler(0.0, 0.0, roll)),
            Axis::Roll { yaw, pitch } => (euler(yaw, pitch, 0.0), DVec3::Z, DMat3::IDENTITY),
            Axis::Direction { axis, base } => {
                let k = DVec3::from_array(axis).try_normalize()?;
                (DMat3::IDENTITY, k, DMat3::from_cols_array_2d(&base))
            }
        };
        let kk = outer(k);
        let c = [
            a * kk * b,
            a * (DMat3::IDENTITY - kk) * b,
            a * cross_matrix(k) * b,
        ];
        let distance = match template.projection() {
            Projection::Orthographic => 1.0,
            Projection::Perspective { distance } => distance,
        };
        if !(c.iter().all(|m| m.is_finite())
            && template.scale().is_finite()
            && template.scale() > 0.0
            && distance.is_finite())
        {
            return None;
        }
        Some(Spin {
            axis,
            template,
            factors: (a, k, b),
            c,
        })
    }

    /// The axis.
    #[must_use]
    pub fn axis(&self) -> Axis {
        self.axis
    }

    /// `(A, k, B)` of `R(θ) = A·Rot(k, θ)·B` (`k` a unit vector in view space): what a
    /// realisation needs to animate the rotation itself (e.g. CSS `rotate3d`).
    #[must_use]
    pub fn factors(&self) -> (DMat3, DVec3, DMat3) {
        self.factors
    }

    /// The template view (its rotation is not used).
    #[must_use]
    pub fn template(&self) -> &View {
        &self.template
    }

    /// `R(θ)`, `θ` in radians (the animated parameter itself for yaw, pitch and roll).
    #[must_use]
    pub fn rotation(&self, theta: f64) -> DMat3 {
        let (s, c) = theta.sin_cos();
        self.c[0] + self.c[1] * c + self.c[2] * s
    }

    /// The view at `θ` (radians).
    #[must_use]
    pub fn view_at(&self, theta: f64) -> View {
        self.template.with_rotation(self.rotation(theta))
    }

    /// `Rᵀ·ẑ`, the unit vector toward the viewer in centred model space, as `(p₀, p₁, p₂)`:
    /// `p₀ + cos θ·p₁ + sin θ·p₂` (row 2 of each `Cᵢ`). It is also the centroid depth axis.
    #[must_use]
    pub fn toward_viewer(&self) -> [DVec3; 3] {
        [self.c[0].row(2), self.c[1].row(2), self.c[2].row(2)]
    }

    /// The viewer of [`face_sort::Viewer`] as a track `(p₀, p₁, p₂, w)`: the orthographic
    /// direction `Rᵀ·ẑ` with `w = 0`, or the perspective eye `Rᵀ·(0, 0, d/s)` with `w = 1`
    /// (the eye orbits with the model's rotation).
    #[must_use]
    pub fn viewer_track(&self) -> ([DVec3; 3], f64) {
        let t = self.toward_viewer();
        match self.template.projection() {
            Projection::Orthographic => (t, 0.0),
            Projection::Perspective { distance } => {
                let e = distance / self.template.scale();
                ([t[0] * e, t[1] * e, t[2] * e], 1.0)
            }
        }
    }

    /// The facing value `n·point − w·offset` of a plane row `[nx, ny, nz, offset]` along the
    /// spin: the quantity whose sign is a BSP node's eye side and a piece's facing.
    #[must_use]
    pub fn facing_fn(&self, row: &[f64; 4]) -> EventFn {
        let (p, w) = self.viewer_track();
        let n = DVec3::new(row[0], row[1], row[2]);
        EventFn {
            a: n.dot(p[1]),
            b: n.dot(p[2]),
            c: n.dot(p[0]) - w * row[3],
            scale: n.length() * (p[0].length() + p[1].length() + p[2].length()) + w * row[3].abs(),
        }
    }

    /// The view depth `(Rᵀ·ẑ)·point` of a centred model point along the spin (what
    /// [`face_sort::Centroid`] sorts by, in both projections).
    #[must_use]
    pub fn depth_fn(&self, point: DVec3) -> EventFn {
        let p = self.toward_viewer();
        EventFn {
            a: point.dot(p[1]),
            b: point.dot(p[2]),
            c: point.dot(p[0]),
            scale: point.length() * (p[0].length() + p[1].length() + p[2].length()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use face_sort::Bounds;

    fn template() -> View {
        let b = Bounds {
            min: DVec3::splat(-1.0),
            max: DVec3::splat(1.0),
        };
        View::fit(&b, 64, 64)
    }

    #[test]
    fn non_finite_input_is_refused() {
        assert!(
            Spin::new(
                template(),
                Axis::Yaw {
                    pitch: f64::NAN,
                    roll: 0.0
                }
            )
            .is_none()
        );
        let zero = Axis::Direction {
            axis: [0.0; 3],
            base: DMat3::IDENTITY.to_cols_array_2d(),
        };
        assert!(Spin::new(template(), zero).is_none());
        let far = template().with_perspective(f64::INFINITY);
        assert!(
            Spin::new(
                far,
                Axis::Roll {
                    yaw: 0.0,
                    pitch: 0.0
                }
            )
            .is_none()
        );
    }

    #[test]
    fn each_named_axis_matches_the_conventions_rotation() {
        let (y, p, r) = (31.0, -17.0, 64.0);
        for (axis, angles) in [
            (Axis::Yaw { pitch: p, roll: r }, (0, [y, p, r])),
            (Axis::Pitch { yaw: y, roll: r }, (1, [y, p, r])),
            (Axis::Roll { yaw: y, pitch: p }, (2, [y, p, r])),
        ] {
            let spin = Spin::new(template(), axis).unwrap();
            let (which, ypr) = angles;
            let want = euler(ypr[0], ypr[1], ypr[2]);
            let got = spin.rotation(ypr[which].to_radians());
            assert!(
                (want - got)
                    .abs()
                    .to_cols_array()
                    .iter()
                    .all(|&d| d < 1e-15),
                "{axis:?}: {want} vs {got}"
            );
        }
    }
}
