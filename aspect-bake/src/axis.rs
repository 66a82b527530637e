//! The animation: a rotation by `θ` about a fixed axis, composed with a fixed base view.

use crate::BakeError;
use face_sort::{Plane, Projection, View};
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
    /// [`BakeError::Spin`] when an angle, the base matrix or the template's scale or eye
    /// distance is not finite, or a [`Axis::Direction`] axis has no length;
    /// [`BakeError::ViewOffset`] when the template has a view offset or an off-centre
    /// principal point.
    pub fn new(template: View, axis: Axis) -> Result<Self, BakeError> {
        let (a, k, b) = match axis {
            Axis::Yaw { pitch, roll } => (DMat3::IDENTITY, DVec3::Y, euler(0.0, pitch, roll)),
            Axis::Pitch { yaw, roll } => (euler(yaw, 0.0, 0.0), DVec3::X, euler(0.0, 0.0, roll)),
            Axis::Roll { yaw, pitch } => (euler(yaw, pitch, 0.0), DVec3::Z, DMat3::IDENTITY),
            Axis::Direction { axis, base } => {
                // Scaled by its largest component first: the squared length of an axis
                // near the smallest f64 is subnormal, and normalising it directly leaves a
                // vector measurably longer than 1 (1.0008 for a length of 3e-161).
                let v = DVec3::from_array(axis);
                let largest = v.abs().max_element();
                let k = (largest.is_finite() && largest > 0.0)
                    .then(|| (v / largest).try_normalize())
                    .flatten()
                    .ok_or(BakeError::Spin { what: "axis" })?;
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
        if !c.iter().all(|m| m.is_finite()) {
            return Err(BakeError::Spin {
                what: "rotation (angles or base matrix)",
            });
        }
        if !(template.scale().is_finite() && template.scale() > 0.0 && distance.is_finite()) {
            return Err(BakeError::Spin {
                what: "scale or eye distance",
            });
        }
        let centre =
            glam::DVec2::new(f64::from(template.width()), f64::from(template.height())) * 0.5;
        if template.view_offset() != DVec3::ZERO || template.principal_point() != centre {
            return Err(BakeError::ViewOffset);
        }
        Ok(Spin {
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

    /// `[C₀, C₁, C₂]` of `R(θ) = C₀ + C₁·cos θ + C₂·sin θ` (Rodrigues): what a realisation
    /// that turns the model itself needs (e.g. a canvas player's script).
    #[must_use]
    pub fn rodrigues(&self) -> [DMat3; 3] {
        self.c
    }

    /// `R(θ)`, `θ` in radians (the animated parameter itself for yaw, pitch and roll).
    #[must_use]
    pub fn rotation_rad(&self, theta: f64) -> DMat3 {
        let (s, c) = theta.sin_cos();
        self.c[0] + self.c[1] * c + self.c[2] * s
    }

    /// The view at `θ` radians.
    #[must_use]
    pub fn view_at_rad(&self, theta: f64) -> View {
        self.template.with_rotation(self.rotation_rad(theta))
    }

    /// The view at an angle in degrees (as [`Bake::cell_at`](crate::Bake::cell_at) takes it).
    #[must_use]
    pub fn view_at(&self, degrees: f64) -> View {
        self.view_at_rad(degrees.to_radians())
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

    /// The facing of polygon `i` of `set`: [`facing_fn`](Self::facing_fn) of its plane
    /// through its first corner (what the sorters cull by).
    pub(crate) fn polygon_facing(&self, set: &face_sort::PolygonSet, i: usize) -> EventFn {
        self.facing_fn(&set.plane(i).through(set.corners(i)[0]))
    }

    /// The facing value `n·point − w·offset` of `plane` along the spin: the quantity whose
    /// sign is a BSP node's eye side and a piece's facing.
    #[must_use]
    pub fn facing_fn(&self, plane: &Plane) -> EventFn {
        let (p, w) = self.viewer_track();
        let (n, offset) = (plane.normal(), plane.offset());
        EventFn {
            a: n.dot(p[1]),
            b: n.dot(p[2]),
            c: n.dot(p[0]) - w * offset,
            scale: n.length() * (p[0].length() + p[1].length() + p[2].length()) + w * offset.abs(),
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
    fn a_camera_off_the_centre_is_refused_and_degrees_match_radians() {
        let yaw = Axis::Yaw {
            pitch: 20.0,
            roll: 0.0,
        };
        let moved = template().with_view_offset(DVec3::new(0.1, 0.0, 0.0));
        assert!(matches!(Spin::new(moved, yaw), Err(BakeError::ViewOffset)));
        let off_centre = template().with_principal_point(10.0, 32.0);
        assert!(matches!(
            Spin::new(off_centre, yaw),
            Err(BakeError::ViewOffset)
        ));
        let spin = Spin::new(template(), yaw).unwrap();
        assert_eq!(spin.view_at(30.0), spin.view_at_rad(30f64.to_radians()));
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
            .is_err()
        );
        let zero = Axis::Direction {
            axis: [0.0; 3],
            base: DMat3::IDENTITY.to_cols_array_2d(),
        };
        assert!(Spin::new(template(), zero).is_err());
        let far = template().with_perspective(f64::INFINITY);
        assert!(
            Spin::new(
                far,
                Axis::Roll {
                    yaw: 0.0,
                    pitch: 0.0
                }
            )
            .is_err()
        );
    }

    #[test]
    fn axes_of_any_length_turn_by_a_rotation() {
        // A fuzzed axis 3e-161 long once normalised to a length of 1.0008, so the bake's
        // event functions and the live view (orthonormalised) disagreed by 1e-7 rad.
        for axis in [
            [-3.403e-161, 4.6e-246, 1.7e-308],
            [2.8e-309, 8.0e-304, -1.5e-310],
            [3.0e300, -4.0e300, 1.0e300],
            [0.3, 5e-324, -0.2],
        ] {
            let spin = Spin::new(
                template(),
                Axis::Direction {
                    axis,
                    base: DMat3::IDENTITY.to_cols_array_2d(),
                },
            )
            .unwrap();
            let k = spin.factors().1;
            assert!(
                (k.length() - 1.0).abs() < 4.0 * f64::EPSILON,
                "{axis:?}: {k}"
            );
            let r = spin.rotation_rad(1.0);
            let error = (r.transpose() * r - DMat3::IDENTITY).abs().to_cols_array();
            assert!(error.iter().all(|&e| e < 8.0 * f64::EPSILON), "{axis:?}");
        }
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
            let got = spin.rotation_rad(ypr[which].to_radians());
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
