//! Cameras as engines hold them: look-at, field of view, near plane, principal point, or a
//! pair of view and projection matrices; each turns into a [`View`] of a [`Geometry`].
//!
//! A camera is resolution-free (like an engine's matrices); [`Camera::view`] fixes the image
//! size. The view it builds keeps the geometry's centre as its centre `c` and places the
//! model with the view offset `t` (`v = R · (p − c) + t`), so one geometry, and every sorter
//! built from it, serves any camera.
//!
//! # How a camera becomes a view
//! With the camera's rotation `R` (model → camera: rows right, up, back), eye `E`, image
//! `W × H` and vertical focal length `f = (H/2) / tan(fov_y/2)` pixels:
//! - **perspective**: distance `d = f`, scale `s = NEAR_W · f / near` and offset
//!   `t = (0, 0, d/s) − R · (E − c)`. The eye then sits at `(0, 0, d/s)` in view space as
//!   CONVENTIONS.md has it, and its near plane `w = NEAR_W` is the camera's near plane;
//! - **orthographic**: `s = H / height` and `t = −R · (E − c)`; no near plane
//!   (CONVENTIONS.md clips only perspective views);
//! - the principal point moves from the image centre where the camera says.
//!
//! Pixels are square: the vertical extent (field of view or height) is exact, and a
//! camera's aspect ratio, when it has one, must match `W / H` to within half a pixel of
//! height ([`CameraError::Aspect`]).

use glam::{DMat3, DMat4, DQuat, DVec2, DVec3, DVec4};
use thiserror::Error;

use crate::convert::{Matrix4, Point3};
use crate::tolerance::{CAMERA_MATRIX, NEAR_W, ORTHONORMAL_ROUNDING};
use crate::{Geometry, View};

/// A camera's lens: perspective or orthographic, resolution-free.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lens {
    /// A pinhole camera.
    Perspective {
        /// Vertical field of view in degrees, in `(0, 180)`.
        fov_y_deg: f64,
        /// Distance of the near plane from the eye (model units, `> 0`): nothing nearer is
        /// drawn.
        near: f64,
        /// Width ÷ height of the image the camera was made for, if it says; checked against
        /// the image size by [`Camera::view`].
        aspect: Option<f64>,
    },
    /// A parallel projection.
    Orthographic {
        /// The height (model units) the image spans.
        height: f64,
        /// Width ÷ height, if the camera says; checked like the perspective one.
        aspect: Option<f64>,
    },
}

impl Lens {
    /// A perspective lens with this vertical field of view (degrees) and near plane, for any
    /// aspect ratio.
    #[must_use]
    pub fn perspective(fov_y_deg: f64, near: f64) -> Self {
        Lens::Perspective {
            fov_y_deg,
            near,
            aspect: None,
        }
    }

    /// An orthographic lens spanning `height` model units vertically, for any aspect ratio.
    #[must_use]
    pub fn orthographic(height: f64) -> Self {
        Lens::Orthographic {
            height,
            aspect: None,
        }
    }

    fn aspect(&self) -> Option<f64> {
        match *self {
            Lens::Perspective { aspect, .. } | Lens::Orthographic { aspect, .. } => aspect,
        }
    }
}

/// The clip-space convention of a projection matrix: which way its y points and where its
/// depth range starts (which says where the near plane is). Reverse-Z matrices (near at
/// depth 1) are recognised in every convention.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ClipSpace {
    /// Depth in `[0, 1]`, y up: Direct3D, Metal, wgpu; glam's `camera::rh::directx`.
    #[default]
    ZeroToOne,
    /// Depth in `[−1, 1]`, y up: OpenGL, WebGL; glam's `camera::rh::opengl`.
    MinusOneToOne,
    /// Depth in `[0, 1]`, y down: Vulkan; glam's `camera::rh::vulkan`.
    ZeroToOneYDown,
}

/// Why a camera could not be made, or could not give a view.
#[derive(Clone, Debug, Error, PartialEq)]
#[non_exhaustive]
pub enum CameraError {
    /// A number is NaN or infinite.
    #[error("the camera's {what} is not finite")]
    NotFinite {
        /// Which input.
        what: &'static str,
    },
    /// The eye and the target are the same point.
    #[error("the camera's eye and target are the same point")]
    EyeAtTarget,
    /// The up vector is zero or parallel to the viewing direction.
    #[error("the camera's up vector is zero or parallel to its viewing direction")]
    UpParallel,
    /// The view matrix's 3 × 3 part is not a rotation: scaled, sheared or mirrored beyond
    /// rounding.
    #[error(
        "the view matrix is not a rigid motion: its 3x3 part is {deviation:.1e} from orthonormal \
         (at most {limit:.0e}), or mirrors"
    )]
    NotARotation {
        /// Largest entry of `|MᵀM − I|`, or `∞` for a mirror.
        deviation: f64,
        /// The largest deviation accepted ([`CAMERA_MATRIX`]).
        limit: f64,
    },
    /// The projection matrix is neither a right-handed perspective nor an orthographic
    /// projection without skew.
    #[error(
        "the projection matrix is not a right-handed perspective or orthographic projection: {why}"
    )]
    Projection {
        /// What is wrong with it.
        why: &'static str,
    },
    /// The field of view is outside `(0°, 180°)`, or the near plane, height or aspect is
    /// not positive.
    #[error("the lens's {what} is {value}, outside its range")]
    Lens {
        /// Which parameter.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// The camera's aspect ratio does not fit the image: pixels would not be square.
    #[error(
        "the camera's aspect ratio {camera} does not fit a {width}x{height} image (its height \
         would be {wanted:.2} pixels); size the image as width / aspect"
    )]
    Aspect {
        /// The camera's aspect ratio (width ÷ height).
        camera: f64,
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
        /// The height that would fit: `width / aspect`.
        wanted: f64,
    },
    /// The image has no pixels.
    #[error("the image size {width}x{height} has no pixels")]
    EmptyImage {
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
    },
    /// A view's centre is not its geometry's centre ([`Geometry::check_view`]).
    #[error(
        "the view's centre {view} is not the geometry's centre {geometry}: build the view from \
         this geometry (Camera::view or View::fit(&geometry.bounds(), ..))"
    )]
    CentreMismatch {
        /// The view's centre.
        view: DVec3,
        /// The geometry's centre.
        geometry: DVec3,
    },
}

/// A camera: where the eye is, where it looks, and its lens.
///
/// ```
/// use face_sort::{Camera, Lens};
///
/// let camera = Camera::look_at([0.0, 1.0, 5.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0],
///     Lens::perspective(45.0, 0.1)).unwrap();
/// assert_eq!(camera.eye().to_array(), [0.0, 1.0, 5.0]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    eye: DVec3,
    rotation: DMat3,
    lens: Lens,
    /// Principal point as a fraction of the image, `(0.5, 0.5)` at its centre.
    principal: DVec2,
}

impl Camera {
    /// A camera at `eye` looking at `target`, with `up` giving the image's upward direction
    /// (model space; arrays, glam vectors of either precision, and, with the `mint` feature,
    /// mint points convert).
    pub fn look_at(
        eye: impl Into<Point3>,
        target: impl Into<Point3>,
        up: impl Into<Point3>,
        lens: Lens,
    ) -> Result<Self, CameraError> {
        let (eye, target, up) = (eye.into().0, target.into().0, up.into().0);
        for (what, v) in [("eye", eye), ("target", target), ("up vector", up)] {
            if !v.is_finite() {
                return Err(CameraError::NotFinite { what });
            }
        }
        let forward = target - eye;
        if forward.length_squared() == 0.0 {
            return Err(CameraError::EyeAtTarget);
        }
        let forward = forward.normalize();
        let right = forward.cross(up);
        if right.length() <= CAMERA_MATRIX * up.length() {
            return Err(CameraError::UpParallel);
        }
        let right = right.normalize();
        let up = right.cross(forward);
        let rotation = DMat3::from_cols(right, up, -forward).transpose();
        Self::new(eye, rotation, lens)
    }

    /// A camera from an engine's view matrix (model → camera, right-handed: the camera looks
    /// down its −Z) and projection matrix (glam's `camera::rh` perspective, infinite,
    /// reverse-Z, orthographic and frustum matrices, in each clip space). f32 matrices, as
    /// most engines hold them, are widened to f64 ([`Matrix4`] says what converts).
    ///
    /// The view matrix's rotation is checked (orthonormal to [`CAMERA_MATRIX`], not
    /// mirrored) and orthonormalised; the projection gives the field of view (or height),
    /// the aspect ratio, the near plane (by `depth`) and the principal point.
    pub fn from_matrices(
        view: impl Into<Matrix4>,
        projection: impl Into<Matrix4>,
        depth: ClipSpace,
    ) -> Result<Self, CameraError> {
        let (view, projection) = (view.into().0, projection.into().0);
        if !view.is_finite() {
            return Err(CameraError::NotFinite {
                what: "view matrix",
            });
        }
        if !projection.is_finite() {
            return Err(CameraError::NotFinite {
                what: "projection matrix",
            });
        }
        // An engine's inverse of its camera's world matrix leaves rounding in the bottom row
        // (three.js's `matrixWorldInverse` holds 0.9999999999999998 there).
        let bottom = (view.row(3) - DVec4::W).abs().max_element();
        if bottom > CAMERA_MATRIX {
            return Err(CameraError::NotARotation {
                deviation: bottom,
                limit: CAMERA_MATRIX,
            });
        }
        let linear = DMat3::from_mat4(view);
        let rotation = checked_rotation(linear)?;
        // cam = M·p + m  ⇒  the eye (cam = 0) is at −M⁻¹·m; M is orthonormal to rounding.
        let eye = -(linear.inverse() * view.w_axis.truncate());
        let (lens, principal) = lens_of(projection, depth)?;
        let mut camera = Self::new(eye, rotation, lens)?;
        camera.principal = principal;
        Ok(camera)
    }

    /// A camera placed by its pose: `camera_to_model` maps camera space (looking down −Z,
    /// +Y up) to model space, as a glTF camera node's world matrix or an engine's camera
    /// transform does. Its 3 × 3 part must be a rotation to [`CAMERA_MATRIX`] (no scale, no
    /// mirror); it is orthonormalised.
    pub fn from_pose(camera_to_model: impl Into<Matrix4>, lens: Lens) -> Result<Self, CameraError> {
        let pose = camera_to_model.into().0;
        if !pose.is_finite() {
            return Err(CameraError::NotFinite { what: "pose" });
        }
        if pose.row(3) != DVec4::W {
            return Err(CameraError::NotARotation {
                deviation: (pose.row(3) - DVec4::W).abs().max_element(),
                limit: CAMERA_MATRIX,
            });
        }
        let rotation = checked_rotation(DMat3::from_mat4(pose))?.transpose();
        Self::new(pose.w_axis.truncate(), rotation, lens)
    }

    fn new(eye: DVec3, rotation: DMat3, lens: Lens) -> Result<Self, CameraError> {
        check_lens(&lens)?;
        Ok(Camera {
            eye,
            rotation: orthonormalised(rotation),
            lens,
            principal: DVec2::splat(0.5),
        })
    }

    /// Moves the principal point to `(x, y)`, as fractions of the image's width and height
    /// from its top-left corner. Default: `(0.5, 0.5)`, the centre.
    #[must_use]
    pub fn with_principal_point(mut self, x: f64, y: f64) -> Self {
        self.principal = DVec2::new(x, y);
        self
    }

    /// The eye (model space).
    #[must_use]
    pub fn eye(&self) -> DVec3 {
        self.eye
    }

    /// The rotation from model space to camera space (orthonormal).
    #[must_use]
    pub fn rotation(&self) -> DMat3 {
        self.rotation
    }

    /// The lens.
    #[must_use]
    pub fn lens(&self) -> Lens {
        self.lens
    }

    /// The principal point as fractions of the image (`(0.5, 0.5)` is the centre).
    #[must_use]
    pub fn principal_point(&self) -> DVec2 {
        self.principal
    }

    /// The image size that fits the camera at this width: `(width, round(width / aspect))`,
    /// or a square image when the camera has no aspect ratio.
    #[must_use]
    pub fn image_size(&self, width: u32) -> (u32, u32) {
        let height = self
            .lens
            .aspect()
            .map_or(f64::from(width), |a| f64::from(width) / a);
        (width, (height.round() as u32).max(1))
    }

    /// The view of `geometry` through this camera in a `width × height` image, with the
    /// defaults of CONVENTIONS.md otherwise (cull back faces, counter-clockwise front). Its
    /// centre is the geometry's, so [`Geometry::check_view`] holds.
    pub fn view(&self, geometry: &Geometry, width: u32, height: u32) -> Result<View, CameraError> {
        if width == 0 || height == 0 {
            return Err(CameraError::EmptyImage { width, height });
        }
        let (w, h) = (f64::from(width), f64::from(height));
        if let Some(aspect) = self.lens.aspect() {
            let wanted = w / aspect;
            if (wanted - h).abs() > 0.5 + CAMERA_MATRIX * h {
                return Err(CameraError::Aspect {
                    camera: aspect,
                    width,
                    height,
                    wanted,
                });
            }
        }
        let bounds = geometry.bounds();
        let to_eye = self.rotation * (self.eye - bounds.centre());
        let base = View::fit(&bounds, width, height)
            .with_rotation(self.rotation)
            .with_principal_point(self.principal.x * w, self.principal.y * h);
        Ok(match self.lens {
            Lens::Perspective {
                fov_y_deg, near, ..
            } => {
                let focal = 0.5 * h / (0.5 * fov_y_deg.to_radians()).tan();
                let scale = NEAR_W * focal / near;
                base.with_scale(scale)
                    .with_perspective(focal)
                    .with_view_offset(DVec3::new(0.0, 0.0, focal / scale) - to_eye)
            }
            Lens::Orthographic { height: span, .. } => base
                .with_scale(h / span)
                .with_orthographic()
                .with_view_offset(-to_eye),
        })
    }
}

/// The nearest rotation to a nearly orthonormal matrix, orthonormal to f64 rounding: the
/// rotation of its normalised quaternion. A matrix already orthonormal to a few rounding
/// errors is kept bit for bit, so that setting a rotation read back from a view is no
/// change.
pub(crate) fn orthonormalised(m: DMat3) -> DMat3 {
    if deviation_from_orthonormal(m) <= ORTHONORMAL_ROUNDING && m.determinant() > 0.0 {
        return m;
    }
    DMat3::from_quat(DQuat::from_mat3(&m).normalize())
}

/// The largest entry of `|mᵀm − I|`.
fn deviation_from_orthonormal(m: DMat3) -> f64 {
    let gram = m.transpose() * m - DMat3::IDENTITY;
    [gram.x_axis, gram.y_axis, gram.z_axis]
        .iter()
        .map(|c| c.abs().max_element())
        .fold(0.0, f64::max)
}

/// `m` orthonormalised, or the error saying how far it is from a rotation.
fn checked_rotation(m: DMat3) -> Result<DMat3, CameraError> {
    let deviation = deviation_from_orthonormal(m);
    if deviation > CAMERA_MATRIX {
        return Err(CameraError::NotARotation {
            deviation,
            limit: CAMERA_MATRIX,
        });
    }
    if m.determinant() < 0.0 {
        return Err(CameraError::NotARotation {
            deviation: f64::INFINITY,
            limit: CAMERA_MATRIX,
        });
    }
    Ok(orthonormalised(m))
}

fn check_lens(lens: &Lens) -> Result<(), CameraError> {
    let positive = |what, value: f64| {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(CameraError::Lens { what, value })
        }
    };
    match *lens {
        Lens::Perspective {
            fov_y_deg,
            near,
            aspect,
        } => {
            if !(fov_y_deg > 0.0 && fov_y_deg < 180.0) {
                return Err(CameraError::Lens {
                    what: "vertical field of view (degrees)",
                    value: fov_y_deg,
                });
            }
            positive("near plane", near)?;
            aspect.map_or(Ok(()), |a| positive("aspect ratio", a))
        }
        Lens::Orthographic { height, aspect } => {
            positive("height", height)?;
            aspect.map_or(Ok(()), |a| positive("aspect ratio", a))
        }
    }
}

/// The lens and principal point (image fractions) of a projection matrix.
///
/// Perspective (column-major, camera looking down −Z): `x_ndc = P₀₀·x/(−z) − P₂₀`, so the
/// principal point is at `(1 − P₂₀)/2` of the width and `(1 + P₂₁)/2` of the height (pixel y
/// runs down), `tan(fov_y/2) = 1/P₁₁`, aspect `P₁₁/P₀₀`; depth `z_ndc = P₃₂/dist − P₂₂` meets
/// its near end (0 or −1, or 1 when it falls with distance: reverse-Z) at the near plane.
/// Orthographic: `x_ndc = P₀₀·x + P₃₀`, height `2/P₁₁`, principal point `(1 + P₃₀)/2`,
/// `(1 − P₃₁)/2`.
fn lens_of(p: DMat4, depth: ClipSpace) -> Result<(Lens, DVec2), CameraError> {
    let p = match depth {
        ClipSpace::ZeroToOneYDown => DMat4::from_diagonal(DVec4::new(1.0, -1.0, 1.0, 1.0)) * p,
        _ => p,
    };
    let scale = p.x_axis.x.abs().max(p.y_axis.y.abs());
    let zero = |v: f64| v.abs() <= CAMERA_MATRIX * scale;
    let bad = |why| Err(CameraError::Projection { why });
    let mixed = [
        p.x_axis.y, p.x_axis.z, p.x_axis.w, p.y_axis.x, p.y_axis.z, p.y_axis.w,
    ];
    if !mixed.into_iter().all(zero) {
        return bad("its first two columns mix axes (skew or rotation)");
    }
    if !(p.x_axis.x > 0.0 && p.y_axis.y > 0.0) {
        return bad("its x or y scale is not positive (a mirrored image)");
    }
    let aspect = p.y_axis.y / p.x_axis.x;
    let (w2, w3) = (p.z_axis.w, p.w_axis.w);
    if (w2 + 1.0).abs() <= CAMERA_MATRIX && zero(w3) {
        if !(zero(p.w_axis.x) && zero(p.w_axis.y)) {
            return bad("a perspective matrix with a translation in x or y");
        }
        let (p22, p32) = (p.z_axis.z, p.w_axis.z);
        let near = if p32 > 0.0 {
            p32 / (1.0 + p22)
        } else {
            match depth {
                ClipSpace::ZeroToOne | ClipSpace::ZeroToOneYDown => p32 / p22,
                ClipSpace::MinusOneToOne => p32 / (p22 - 1.0),
            }
        };
        let fov_y_deg = 2.0 * (1.0 / p.y_axis.y).atan().to_degrees();
        let principal = DVec2::new((1.0 - p.z_axis.x) * 0.5, (1.0 + p.z_axis.y) * 0.5);
        let lens = Lens::Perspective {
            fov_y_deg,
            near,
            aspect: Some(aspect),
        };
        check_lens(&lens)?;
        Ok((lens, principal))
    } else if zero(w2) && (w3 - 1.0).abs() <= CAMERA_MATRIX {
        if !(zero(p.z_axis.x) && zero(p.z_axis.y)) {
            return bad("an orthographic matrix whose x or y depends on depth");
        }
        let lens = Lens::Orthographic {
            height: 2.0 / p.y_axis.y,
            aspect: Some(aspect),
        };
        let principal = DVec2::new((1.0 + p.w_axis.x) * 0.5, (1.0 - p.w_axis.y) * 0.5);
        Ok((lens, principal))
    } else if (w2 - 1.0).abs() <= CAMERA_MATRIX {
        bad("it is left-handed (the camera looks down +Z); use the _rh matrices")
    } else {
        bad("its last row is neither (0, 0, −1, 0) nor (0, 0, 0, 1)")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PolygonMesh;
    use glam::dcamera::rh::proj::{directx, opengl, vulkan};
    use glam::dcamera::rh::view::look_at_mat4;
    use glam::{DVec2, Vec3};

    fn cube() -> Geometry {
        let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        let positions = vec![
            p(0., 0., 0.),
            p(1., 0., 0.),
            p(0., 1., 0.),
            p(1., 1., 0.),
            p(0., 0., 1.),
            p(1., 0., 1.),
            p(0., 1., 1.),
            p(1., 1., 1.),
        ];
        let faces = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
        ];
        Geometry::new(&PolygonMesh::new(positions, faces).unwrap()).unwrap()
    }

    /// The pixel of a model point by the textbook pipeline: projection · view, divide, NDC to
    /// pixels. Independent of `View`.
    fn textbook_pixel(clip_from_model: DMat4, p: DVec3, w: f64, h: f64) -> DVec2 {
        let c = clip_from_model * p.extend(1.0);
        let ndc = c.truncate() / c.w;
        DVec2::new(w * 0.5 * (1.0 + ndc.x), h * 0.5 * (1.0 - ndc.y))
    }

    #[test]
    fn rounding_in_the_view_matrix_bottom_row_is_accepted_and_more_is_not() {
        let projection = opengl::perspective(0.8, 1.0, 0.05, 50.0);
        let mut view = look_at_mat4(DVec3::new(2.5, 1.7, 3.1), DVec3::ZERO, DVec3::Y);
        // What three.js's matrixWorldInverse holds after inverting a camera's world matrix.
        view.w_axis.w = 0.9999999999999998;
        assert!(Camera::from_matrices(view, projection, ClipSpace::MinusOneToOne).is_ok());
        view.w_axis.w = 0.99;
        assert!(matches!(
            Camera::from_matrices(view, projection, ClipSpace::MinusOneToOne),
            Err(CameraError::NotARotation { .. })
        ));
    }

    #[test]
    fn views_project_as_the_matrices_do() {
        let geometry = cube();
        let centre = geometry.bounds().centre();
        let (w, h) = (320u32, 200u32);
        let aspect = 320.0 / 200.0;
        let eye = DVec3::new(2.5, 1.7, 3.1);
        let view_m = look_at_mat4(eye, DVec3::new(0.4, 0.6, 0.5), DVec3::Y);
        let projections = [
            (
                directx::perspective(0.8, aspect, 0.05, 50.0),
                ClipSpace::ZeroToOne,
            ),
            (
                opengl::perspective(0.8, aspect, 0.05, 50.0),
                ClipSpace::MinusOneToOne,
            ),
            (
                vulkan::perspective(0.8, aspect, 0.05, 50.0),
                ClipSpace::ZeroToOneYDown,
            ),
            (
                directx::perspective_infinite_reverse(0.8, aspect, 0.05),
                ClipSpace::ZeroToOne,
            ),
            (
                directx::frustum(-0.03, 0.05, -0.02, 0.03, 0.05, 50.0),
                ClipSpace::ZeroToOne,
            ),
            (
                directx::orthographic(-1.6, 2.4, -1.0, 1.5, 0.1, 10.0),
                ClipSpace::ZeroToOne,
            ),
        ];
        for (projection, depth) in projections {
            let camera = Camera::from_matrices(view_m, projection, depth).unwrap();
            if let Lens::Perspective { near, .. } = camera.lens() {
                assert!((near - 0.05).abs() < 1e-12, "near {near}");
            }
            let view = camera.view(&geometry, w, h).unwrap();
            assert!(geometry.check_view(&view).is_ok());
            for corner in [DVec3::ZERO, DVec3::ONE, DVec3::new(1.0, 0.0, 1.0)] {
                let ours = view
                    .project_view_point(view.to_view(corner - centre))
                    .unwrap();
                let y_down = depth == ClipSpace::ZeroToOneYDown;
                let flip = DMat4::from_diagonal(DVec4::new(
                    1.0,
                    if y_down { -1.0 } else { 1.0 },
                    1.0,
                    1.0,
                ));
                let theirs = textbook_pixel(
                    flip * projection * view_m,
                    corner,
                    f64::from(w),
                    f64::from(h),
                );
                assert!((ours - theirs).length() < 1e-9, "{ours} vs {theirs}");
            }
        }
    }

    #[test]
    fn look_at_matches_the_matrices_and_orthonormalises_f32() {
        let geometry = cube();
        let eye = Vec3::new(-1.5, 2.0, 2.5);
        let target = Vec3::new(0.5, 0.5, 0.5);
        let by_hand = Camera::look_at(
            eye,
            target,
            [0.0f32, 1.0, 0.0],
            Lens::perspective(50.0, 0.1),
        )
        .unwrap();
        let view_m = glam::camera::rh::view::look_at_mat4(eye, target, Vec3::Y);
        let projection =
            glam::camera::rh::proj::directx::perspective(50f32.to_radians(), 1.0, 0.1, 100.0);
        let matrices = Camera::from_matrices(view_m, projection, ClipSpace::ZeroToOne).unwrap();
        let r = matrices.rotation();
        let gram = r.transpose() * r - DMat3::IDENTITY;
        assert!(gram.abs_diff_eq(DMat3::ZERO, 1e-15), "{gram}");
        assert!(by_hand.rotation().abs_diff_eq(r, 1e-6));
        assert!((by_hand.eye() - matrices.eye()).length() < 1e-5);
        let a = by_hand.view(&geometry, 100, 100).unwrap();
        let b = matrices.view(&geometry, 100, 100).unwrap();
        assert!((a.scale() - b.scale()).abs() < 1e-4 * a.scale());
    }

    #[test]
    fn a_pose_is_the_inverse_of_a_view_matrix() {
        let eye = DVec3::new(0.3, 2.0, -4.0);
        let view_m = look_at_mat4(eye, DVec3::new(0.5, 0.2, 0.4), DVec3::Y);
        let lens = Lens::perspective(35.0, 0.2);
        let posed = Camera::from_pose(view_m.inverse(), lens).unwrap();
        let from_view = Camera::from_matrices(
            view_m,
            directx::perspective(35f64.to_radians(), 1.0, 0.2, 9.0),
            ClipSpace::ZeroToOne,
        )
        .unwrap();
        assert!((posed.eye() - eye).length() < 1e-12);
        assert!(posed.rotation().abs_diff_eq(from_view.rotation(), 1e-12));
    }

    #[test]
    fn bad_cameras_are_refused_with_reasons() {
        let lens = Lens::perspective(60.0, 0.1);
        let z = [0.0, 0.0, 0.0];
        assert_eq!(
            Camera::look_at(z, z, [0.0, 1.0, 0.0], lens),
            Err(CameraError::EyeAtTarget)
        );
        assert_eq!(
            Camera::look_at(z, [0.0, 1.0, 0.0], [0.0, 2.0, 0.0], lens),
            Err(CameraError::UpParallel)
        );
        assert!(matches!(
            Camera::look_at([f64::NAN, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], lens),
            Err(CameraError::NotFinite { what: "eye" })
        ));
        assert!(matches!(
            Camera::look_at(
                z,
                [0.0, 0.0, -1.0],
                [0.0, 1.0, 0.0],
                Lens::perspective(180.0, 0.1)
            ),
            Err(CameraError::Lens { .. })
        ));
        let scaled = DMat4::from_scale(DVec3::splat(2.0));
        let p = directx::perspective(1.0, 1.0, 0.1, 10.0);
        assert!(matches!(
            Camera::from_matrices(scaled, p, ClipSpace::ZeroToOne),
            Err(CameraError::NotARotation { .. })
        ));
        let mirrored = DMat4::from_scale(DVec3::new(1.0, 1.0, -1.0));
        assert!(matches!(
            Camera::from_matrices(mirrored, p, ClipSpace::ZeroToOne),
            Err(CameraError::NotARotation { .. })
        ));
        assert!(matches!(
            Camera::from_matrices(
                DMat4::IDENTITY,
                glam::dcamera::lh::proj::directx::perspective(1.0, 1.0, 0.1, 10.0),
                ClipSpace::ZeroToOne
            ),
            Err(CameraError::Projection { .. })
        ));
        let camera = Camera::from_matrices(DMat4::IDENTITY, p, ClipSpace::ZeroToOne).unwrap();
        assert!(matches!(
            camera.view(&cube(), 200, 100),
            Err(CameraError::Aspect { .. })
        ));
        assert_eq!(camera.image_size(200), (200, 200));
    }
}
