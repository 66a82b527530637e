//! The root transform: what a frame's rotation and projection do to every sprite at once.

use face_sort::{Projection, View};
use glam::{DMat3, DMat4, DVec3, DVec4, EulerRot};

/// The root transform of a view: to-origin → rotation → perspective → from-origin, acting on
/// [`SpriteSpace`](crate::SpriteSpace) (rest pixel space, y down) and giving homogeneous pixel
/// coordinates (`x / w`, `y / w` are CONVENTIONS.md's pixel position).
///
/// `root = T(P₀) · P · T(F·s·t) · (F R F) · T(−O)`, with `O = (W/2, H/2, 0)` the sprite
/// space origin, `P₀` the view's principal point (`O` unless a camera moves it),
/// `F = diag(1, −1, 1)` (the model's rotation `R` written in y-down pixel axes), `t` the
/// view offset and `P` the identity with `M34 = −1/d` under perspective (row 4, column 3:
/// `w = 1 − z/d`), the identity when orthographic.
#[must_use]
pub fn root_transform(view: &View) -> DMat4 {
    let origin = DVec3::new(
        f64::from(view.width()) * 0.5,
        f64::from(view.height()) * 0.5,
        0.0,
    );
    let flip = DMat3::from_diagonal(DVec3::new(1.0, -1.0, 1.0));
    let rotation = DMat4::from_mat3(flip * view.rotation() * flip);
    let perspective = perspective_matrix(view.projection());
    let principal = view.principal_point().extend(0.0);
    let offset = flip * view.view_offset() * view.scale();
    DMat4::from_translation(principal)
        * perspective
        * DMat4::from_translation(offset)
        * rotation
        * DMat4::from_translation(-origin)
}

/// The perspective part of the root: identity, or `M34 = −1/d`.
#[must_use]
pub fn perspective_matrix(projection: Projection) -> DMat4 {
    match projection {
        Projection::Orthographic => DMat4::IDENTITY,
        Projection::Perspective { distance } => {
            let mut m = DMat4::IDENTITY;
            m.z_axis = DVec4::new(0.0, 0.0, 1.0, -1.0 / distance);
            m
        }
    }
}

/// The rotation `Ry(yaw) · Rx(pitch) · Rz(roll)` of CONVENTIONS.md, angles in degrees.
#[must_use]
pub fn rotation_from_yaw_pitch_roll(yaw: f64, pitch: f64, roll: f64) -> DMat3 {
    DMat3::from_euler(
        EulerRot::YXZ,
        yaw.to_radians(),
        pitch.to_radians(),
        roll.to_radians(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SpriteSpace;
    use face_sort::Bounds;
    use glam::DVec2;

    #[test]
    fn root_after_sprite_space_is_the_conventions_projection() {
        let bounds = Bounds {
            min: DVec3::new(-1.0, -2.0, -0.5),
            max: DVec3::new(3.0, 1.0, 2.0),
        };
        for (perspective, camera) in [(false, false), (true, false), (false, true), (true, true)] {
            let mut view = View::fit(&bounds, 300, 200).with_yaw_pitch_roll(35.0, 25.0, -10.0);
            if perspective {
                view = view.with_perspective(300.0);
            }
            if camera {
                view = view
                    .with_view_offset(DVec3::new(0.4, -0.3, -1.5))
                    .with_principal_point(170.0, 90.0);
            }
            let root = root_transform(&view);
            let space = SpriteSpace::of_view(&view);
            for p in [
                DVec3::new(0.3, -0.2, 0.9),
                DVec3::new(-1.0, 1.0, -0.5),
                DVec3::new(1.5, 0.0, 0.2),
            ] {
                let h = root * space.point(p).extend(1.0);
                let got = DVec2::new(h.x / h.w, h.y / h.w);
                let want = view.project_view_point(view.to_view(p)).unwrap();
                assert!((got - want).length() < 1e-9, "{got} vs {want}");
            }
        }
    }
}
