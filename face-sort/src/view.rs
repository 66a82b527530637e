//! The camera of CONVENTIONS.md: rotation, centre, scale, projection, culling.

use glam::{DMat3, DQuat, DVec2, DVec3, EulerRot};

use crate::Bounds;
use crate::plane::Plane;
use crate::tolerance::{DEPTH_ROUNDING, NEAR_W};

/// Orthographic or perspective projection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Parallel projection along −Z (the default).
    Orthographic,
    /// Eye at `(0, 0, distance)` in pixel space; `distance > 0` in pixels.
    Perspective {
        /// Eye distance `d` in pixels.
        distance: f64,
    },
}

/// Which faces culling removes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum CullMode {
    /// Remove back faces (the default).
    #[default]
    Back,
    /// Remove front faces.
    Front,
    /// Keep every face.
    None,
}

impl CullMode {
    /// The mode a command line or a binding names: `"back"`, `"front"` or `"none"`.
    ///
    /// ```
    /// use face_sort::CullMode;
    /// assert_eq!(CullMode::from_name("none"), Some(CullMode::None));
    /// assert_eq!(CullMode::from_name("sideways"), None);
    /// ```
    #[must_use]
    pub fn from_name(name: &str) -> Option<CullMode> {
        match name {
            "back" => Some(CullMode::Back),
            "front" => Some(CullMode::Front),
            "none" => Some(CullMode::None),
            _ => None,
        }
    }
}

/// Which winding, seen from outside, is the front.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum FrontFace {
    /// Counter-clockwise (the default).
    #[default]
    CounterClockwise,
    /// Clockwise.
    Clockwise,
}

/// A view of a model per CONVENTIONS.md.
///
/// `v = R · (p − c) + t` (view space, model units), `q = s · v` (pixel space),
/// orthographic `x = x₀ + q.x, y = y₀ − q.y`; perspective `w = 1 − q.z/d`,
/// `x = x₀ + q.x/w, y = y₀ − q.y/w`. The view offset `t` is zero and the principal point
/// `(x₀, y₀)` is the image centre `(W/2, H/2)` unless a [`Camera`](crate::Camera) (or
/// [`with_view_offset`](Self::with_view_offset), [`with_principal_point`](Self::with_principal_point))
/// sets them.
///
/// The centre `c` must be the centre of the [`Geometry`](crate::Geometry) the view is used
/// with (its frame's centre): [`Geometry::check_view`](crate::Geometry::check_view) says
/// whether it is, and [`Camera::view`](crate::Camera::view) builds views that are.
///
/// Most methods take **centred** model coordinates `p − c`, the coordinates of
/// [`PolygonSet`](crate::PolygonSet).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    rotation: DMat3,
    centre: DVec3,
    diagonal: f64,
    scale: f64,
    width: u32,
    height: u32,
    projection: Projection,
    cull: CullMode,
    front: FrontFace,
    cull_margin_deg: f64,
    offset: DVec3,
    principal: Option<DVec2>,
}

impl View {
    /// The default view of a model with these bounds in a `width × height` image: identity
    /// rotation, centre `c`, scale "fit" `0.9 · min(W, H) / L`, orthographic, cull back faces,
    /// counter-clockwise front, no cull margin.
    #[must_use]
    pub fn fit(bounds: &Bounds, width: u32, height: u32) -> Self {
        let diagonal = bounds.diagonal();
        View {
            rotation: DMat3::IDENTITY,
            centre: bounds.centre(),
            diagonal,
            scale: 0.9 * f64::from(width.min(height).max(1)) / diagonal,
            width,
            height,
            projection: Projection::Orthographic,
            cull: CullMode::Back,
            front: FrontFace::CounterClockwise,
            cull_margin_deg: 0.0,
            offset: DVec3::ZERO,
            principal: None,
        }
    }

    /// Rotation `Ry(yaw) · Rx(pitch) · Rz(roll)`, angles in degrees.
    #[must_use]
    pub fn with_yaw_pitch_roll(mut self, yaw: f64, pitch: f64, roll: f64) -> Self {
        self.rotation = DMat3::from_euler(
            EulerRot::YXZ,
            yaw.to_radians(),
            pitch.to_radians(),
            roll.to_radians(),
        );
        self
    }

    /// A rotation matrix, orthonormalised here (through a normalised quaternion), so a
    /// rotation that is orthonormal only to f32 precision, as `glam::Mat3` look-at matrices
    /// are, enters exact. A matrix far from a rotation (scaled, sheared, mirrored) gives an
    /// unspecified rotation: [`Camera`](crate::Camera) checks matrices and refuses those
    /// with a [`CameraError`](crate::CameraError).
    #[must_use]
    pub fn with_rotation(mut self, rotation: DMat3) -> Self {
        self.rotation = crate::camera::orthonormalised(rotation);
        self
    }

    /// A rotation given as a quaternion (normalised here).
    #[must_use]
    pub fn with_quaternion(mut self, rotation: DQuat) -> Self {
        self.rotation = DMat3::from_quat(rotation.normalize());
        self
    }

    /// Scale `s` in pixels per model unit. Default: fit.
    #[must_use]
    pub fn with_scale(mut self, scale: f64) -> Self {
        self.scale = scale;
        self
    }

    /// Perspective with eye distance `distance` pixels (CONVENTIONS default: `d = W`).
    #[must_use]
    pub fn with_perspective(mut self, distance: f64) -> Self {
        self.projection = Projection::Perspective { distance };
        self
    }

    /// Orthographic projection (the default).
    #[must_use]
    pub fn with_orthographic(mut self) -> Self {
        self.projection = Projection::Orthographic;
        self
    }

    /// Cull mode. Default: back.
    #[must_use]
    pub fn with_cull(mut self, cull: CullMode) -> Self {
        self.cull = cull;
        self
    }

    /// Front winding. Default: counter-clockwise.
    #[must_use]
    pub fn with_front_face(mut self, front: FrontFace) -> Self {
        self.front = front;
        self
    }

    /// Cull margin in degrees: faces up to this far past edge-on stay drawn. Default: 0.
    #[must_use]
    pub fn with_cull_margin(mut self, degrees: f64) -> Self {
        self.cull_margin_deg = degrees;
        self
    }

    /// The view offset `t` (view space, model units): `v = R · (p − c) + t`. Default: zero.
    /// It moves the model relative to the eye without changing the centre `c`, so the
    /// geometry (and a sorter built from it) serves every camera.
    #[must_use]
    pub fn with_view_offset(mut self, offset: DVec3) -> Self {
        self.offset = offset;
        self
    }

    /// The principal point `(x₀, y₀)` in pixels: where the view axis meets the image.
    /// Default: the image centre.
    #[must_use]
    pub fn with_principal_point(mut self, x: f64, y: f64) -> Self {
        self.principal = Some(DVec2::new(x, y));
        self
    }

    /// Image size in pixels (the scale is kept).
    #[must_use]
    pub fn with_size(mut self, width: u32, height: u32) -> Self {
        self.width = width;
        self.height = height;
        self
    }

    /// The rotation `R`.
    #[must_use]
    pub fn rotation(&self) -> DMat3 {
        self.rotation
    }
    /// The centre `c` (model space).
    #[must_use]
    pub fn centre(&self) -> DVec3 {
        self.centre
    }
    /// The model's bounding-box diagonal `L`, the unit of every tolerance.
    #[must_use]
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }
    /// Scale `s`, pixels per model unit.
    #[must_use]
    pub fn scale(&self) -> f64 {
        self.scale
    }
    /// Image width in pixels.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }
    /// Image height in pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }
    /// The projection.
    #[must_use]
    pub fn projection(&self) -> Projection {
        self.projection
    }
    /// The cull mode.
    #[must_use]
    pub fn cull(&self) -> CullMode {
        self.cull
    }
    /// The front winding.
    #[must_use]
    pub fn front_face(&self) -> FrontFace {
        self.front
    }
    /// The cull margin in degrees.
    #[must_use]
    pub fn cull_margin(&self) -> f64 {
        self.cull_margin_deg
    }
    /// The view offset `t` (view space, model units).
    #[must_use]
    pub fn view_offset(&self) -> DVec3 {
        self.offset
    }
    /// The principal point `(x₀, y₀)` in pixels.
    #[must_use]
    pub fn principal_point(&self) -> DVec2 {
        self.principal
            .unwrap_or(DVec2::new(f64::from(self.width), f64::from(self.height)) * 0.5)
    }

    /// View-space position of a centred model point: `R · p + t`.
    #[inline]
    #[must_use]
    pub fn to_view(&self, centred: DVec3) -> DVec3 {
        self.rotation * centred + self.offset
    }

    /// The model-space point of a centred point (draw-list corners are centred): `p + c`.
    #[inline]
    #[must_use]
    pub fn to_model(&self, centred: DVec3) -> DVec3 {
        centred + self.centre
    }

    /// View-space direction of a model-space direction (a normal, an axis): `R · d`.
    #[inline]
    #[must_use]
    pub fn direction_to_view(&self, direction: DVec3) -> DVec3 {
        self.rotation * direction
    }

    /// The view-space plane `n′ · v = offset′` of the centred plane `n · p = offset`:
    /// `n′ = R · n`, `offset′ = offset + n′ · t`.
    #[inline]
    #[must_use]
    pub fn plane_to_view(&self, normal: DVec3, offset: f64) -> (DVec3, f64) {
        let n = self.rotation * normal;
        (n, offset + n.dot(self.offset))
    }

    /// The centred model point of a view-space point: `Rᵀ · (v − t)`.
    #[inline]
    #[must_use]
    pub fn to_centred(&self, view_point: DVec3) -> DVec3 {
        self.rotation.transpose() * (view_point - self.offset)
    }

    /// Eye position in view space, `(0, 0, d/s)`; `None` when orthographic.
    #[must_use]
    pub fn eye_in_view(&self) -> Option<DVec3> {
        match self.projection {
            Projection::Orthographic => None,
            Projection::Perspective { distance } => {
                Some(DVec3::new(0.0, 0.0, distance / self.scale))
            }
        }
    }

    /// Where the viewer is, in centred model space: `Eye(point)` for perspective, or
    /// `Direction(unit vector toward the viewer)` for orthographic.
    #[must_use]
    pub fn viewer(&self) -> Viewer {
        match self.eye_in_view() {
            Some(eye) => Viewer::Eye(self.to_centred(eye)),
            None => Viewer::Direction(self.rotation.transpose() * DVec3::Z),
        }
    }

    /// Screen position (pixels) of a view-space point; `None` when it lies behind the near plane.
    #[inline]
    #[must_use]
    pub fn project_view_point(&self, v: DVec3) -> Option<DVec2> {
        let w = self.w_of_view_point(v);
        (w >= NEAR_W).then(|| self.pixel_of(v, w))
    }

    /// Homogeneous pixel coordinates `(x·w, y·w, w)` of a centred model point: linear in the
    /// point, so along a segment they interpolate linearly (divide by `w` for pixels).
    #[must_use]
    pub fn homogeneous_pixel(&self, centred: DVec3) -> DVec3 {
        let v = self.to_view(centred);
        let w = self.w_of_view_point(v);
        let half = self.principal_point();
        let q = v * self.scale;
        DVec3::new(half.x * w + q.x, half.y * w - q.y, w)
    }

    /// The bounding box (pixels, `(min, max)`) of the projection of a sphere (centred model
    /// space), exact up to rounding; `None` when the sphere reaches the near plane (it may
    /// then cover anything).
    ///
    /// Orthographic: the centre's pixel ± the radius in pixels. Perspective: along each image
    /// axis the extremes are where a plane through the eye, containing the other image axis'
    /// direction, touches the sphere; in the plane of that axis and the view direction they
    /// are the two tangents from the eye to a circle of the same radius, at angles `a ± b`
    /// from the view direction, `tan a = x / (d − z)` and `sin b = r / h` (`h` the eye's
    /// distance from the centre in that plane), at pixel offsets `d · tan(a ± b)`; with the
    /// tangent's length `t = √(h² − r²)`, `tan(a ± b) = (x·t ± r·(d − z)) / ((d − z)·t ∓ x·r)`,
    /// so no trigonometric function is needed (both denominators are positive: the sphere lies
    /// in front of the eye, so every tangent points forward).
    #[must_use]
    pub fn project_sphere(&self, centre: DVec3, radius: f64) -> Option<(DVec2, DVec2)> {
        let half = self.principal_point();
        let u = self.to_view(centre) * self.scale;
        let r = radius * self.scale;
        match self.projection {
            Projection::Orthographic => {
                let c = DVec2::new(half.x + u.x, half.y - u.y);
                Some((c - DVec2::splat(r), c + DVec2::splat(r)))
            }
            Projection::Perspective { distance } => {
                if u.z + r >= distance * (1.0 - NEAR_W) {
                    return None;
                }
                // In front of the near plane: d − z > r, so both tangents point forward.
                let dz = distance - u.z;
                let extent = |across: f64| {
                    let t = ((across * across + dz * dz) - r * r).sqrt();
                    (
                        distance * (across * t - r * dz) / (dz * t + across * r),
                        distance * (across * t + r * dz) / (dz * t - across * r),
                    )
                };
                let (x0, x1) = extent(u.x);
                let (y0, y1) = extent(u.y);
                Some((
                    DVec2::new(half.x + x0, half.y - y1),
                    DVec2::new(half.x + x1, half.y - y0),
                ))
            }
        }
    }

    /// Pixel position of view-space point `v` whose `w` is `w`.
    #[inline]
    fn pixel_of(&self, v: DVec3, w: f64) -> DVec2 {
        let half = self.principal_point();
        let q = v * self.scale;
        DVec2::new(half.x + q.x / w, half.y - q.y / w)
    }

    /// `w = 1 − q.z/d` for perspective, 1 for orthographic.
    #[inline]
    #[must_use]
    pub fn w_of_view_point(&self, v: DVec3) -> f64 {
        match self.projection {
            Projection::Orthographic => 1.0,
            Projection::Perspective { distance } => 1.0 - v.z * self.scale / distance,
        }
    }

    /// Projects a polygon (centred model space) to pixel coordinates, clipping it first against
    /// the near plane `w ≥ 1e-3` in perspective. `out` is cleared; it stays empty when
    /// nothing is in front of the near plane. `scratch` holds reusable buffers.
    pub fn project_polygon(
        &self,
        corners: &[DVec3],
        out: &mut Vec<DVec2>,
        scratch: &mut ProjectionScratch,
    ) {
        out.clear();
        let view = &mut scratch.view;
        view.clear();
        view.extend(corners.iter().map(|&p| self.to_view(p)));
        if let Projection::Perspective { distance } = self.projection {
            // Keep w ≥ NEAR_W  ⇔  z ≤ (1 − NEAR_W)·d/s.
            let z_max = (1.0 - NEAR_W) * distance / self.scale;
            if view.iter().any(|v| v.z > z_max) {
                let near = Plane::try_from_point_normal(DVec3::new(0.0, 0.0, z_max), -DVec3::Z)
                    .expect("a unit normal is never zero");
                scratch.kept.clear();
                scratch.dropped.clear();
                crate::polygon::split_polygon(
                    view,
                    &near,
                    0.0,
                    &mut scratch.kept,
                    &mut scratch.dropped,
                );
                view.clear();
                view.extend(
                    scratch
                        .kept
                        .iter()
                        .map(|v| DVec3::new(v.x, v.y, v.z.min(z_max))),
                );
            }
        }
        // After clipping every corner has w ≥ NEAR_W up to round-off; clamp that away.
        out.extend(
            view.iter()
                .map(|&v| self.pixel_of(v, self.w_of_view_point(v).max(NEAR_W))),
        );
        if out.len() < 3 {
            out.clear();
        }
    }

    /// How many times the rounding of a projected polygon's pixel coordinates exceeds a few
    /// ulps of their size: `1 / w` for the smallest `w` among `corners` (centred model space),
    /// clamped to the near plane's `w ≥ 1e-3` as [`project_polygon`](Self::project_polygon)
    /// clamps it; 1 in orthographic.
    ///
    /// Projection divides by `w = 1 − z·s/d`. Near the eye that is a difference of two numbers
    /// close to 1, known only to about `ε`, so its relative error `ε / w` passes to every pixel
    /// coordinate: up to a thousand times more than far from the eye.
    #[must_use]
    pub fn rounding_gain(&self, corners: &[DVec3]) -> f64 {
        match self.projection {
            Projection::Orthographic => 1.0,
            Projection::Perspective { .. } => corners
                .iter()
                .map(|&p| 1.0 / self.w_of_view_point(self.to_view(p)).max(NEAR_W))
                .fold(1.0, f64::max),
        }
    }

    /// Whether a piece with this plane and first corner (centred model space) is drawn under
    /// the view's cull mode, front winding and margin (CONVENTIONS.md).
    #[inline]
    #[must_use]
    pub fn is_drawn(&self, plane: &Plane, corner0: DVec3) -> bool {
        is_drawn_for(&self.cull_test(), plane, corner0)
    }

    /// The culling parameters of this view, precomputed for a loop over many pieces.
    #[must_use]
    pub fn cull_test(&self) -> CullTest {
        let sign = match self.front {
            FrontFace::CounterClockwise => 1.0,
            FrontFace::Clockwise => -1.0,
        };
        let (keep_front, keep_back) = match self.cull {
            CullMode::Back => (true, false),
            CullMode::Front => (false, true),
            CullMode::None => (true, true),
        };
        CullTest {
            viewer: self.viewer(),
            sign,
            keep_front,
            keep_back,
            sin_margin: self.cull_margin_deg.to_radians().sin().max(0.0),
        }
    }
}

/// Where the viewer is, in centred model space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Viewer {
    /// Orthographic: unit direction toward the viewer.
    Direction(DVec3),
    /// Perspective: the eye point.
    Eye(DVec3),
}

impl Viewer {
    /// Signed "toward the viewer" value of a plane: positive when the viewer is on the side
    /// the plane's normal points to. Orthographic: `n · dir`; perspective: signed distance of the eye.
    #[inline]
    #[must_use]
    pub fn facing(&self, plane: &Plane) -> f64 {
        match *self {
            Viewer::Direction(d) => plane.normal().dot(d),
            Viewer::Eye(e) => plane.signed_distance(e),
        }
    }
}

/// Precomputed culling parameters of a [`View`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CullTest {
    /// The viewer.
    pub viewer: Viewer,
    sign: f64,
    keep_front: bool,
    keep_back: bool,
    sin_margin: f64,
}

impl CullTest {
    /// The same test for geometry placed by an affine map: `to_local` maps this test's
    /// (centred) coordinates to the geometry's (centred) coordinates. The viewer is mapped
    /// (an eye as a point, a direction by the linear part, normalised), so a piece's facing
    /// sign in its own coordinates is its facing sign in these: plane sides are preserved by
    /// affine maps. A mirroring map (negative determinant) keeps each piece's own front, as
    /// glTF asks of mirrored nodes. Under a non-uniform scale the cull margin is measured in
    /// the geometry's coordinates.
    #[must_use]
    pub fn transformed(&self, to_local: &glam::DAffine3) -> CullTest {
        let viewer = match self.viewer {
            Viewer::Eye(e) => Viewer::Eye(to_local.transform_point3(e)),
            Viewer::Direction(d) => {
                Viewer::Direction(to_local.transform_vector3(d).normalize_or_zero())
            }
        };
        CullTest { viewer, ..*self }
    }

    /// The test a GPU's back-face culling makes for `viewer` (centred coordinates):
    /// counter-clockwise fronts kept, back faces culled, no margin.
    #[must_use]
    pub fn back_faces_culled(viewer: Viewer) -> CullTest {
        CullTest {
            viewer,
            sign: 1.0,
            keep_front: true,
            keep_back: false,
            sin_margin: 0.0,
        }
    }

    /// Whether a piece with this plane and first corner is drawn.
    #[inline]
    #[must_use]
    pub fn is_drawn(&self, plane: &Plane, corner0: DVec3) -> bool {
        is_drawn_for(self, plane, corner0)
    }

    /// The viewer as `(point, w)` such that a plane's facing value is
    /// `normal · point − w · offset` ([`Viewer::facing`]), for loops over plane arrays.
    #[inline]
    #[must_use]
    pub fn viewer_point(&self) -> (DVec3, f64) {
        match self.viewer {
            Viewer::Direction(d) => (d, 0.0),
            Viewer::Eye(e) => (e, 1.0),
        }
    }

    /// When the view has no cull margin, the cull decision follows from a piece's facing value
    /// alone: returns `(keep when facing > 0, keep when facing < 0)`; `None` with a margin.
    /// (For planar pieces, `n · (e − v₀)` equals the facing value `n · e − offset`.)
    #[inline]
    #[must_use]
    pub fn facing_rule(&self) -> Option<(bool, bool)> {
        if self.sin_margin > 0.0 {
            return None;
        }
        let (front, back) = if self.sign > 0.0 {
            (self.keep_front, self.keep_back)
        } else {
            (self.keep_back, self.keep_front)
        };
        Some((front, back))
    }
}

#[inline]
fn is_drawn_for(test: &CullTest, plane: &Plane, corner0: DVec3) -> bool {
    if test.keep_front && test.keep_back {
        return true;
    }
    let n = plane.normal() * test.sign;
    let (value, scale) = match test.viewer {
        Viewer::Direction(d) => (n.dot(d), 1.0),
        Viewer::Eye(e) => {
            let to_eye = e - corner0;
            let value = n.dot(to_eye);
            let scale = if test.sin_margin > 0.0 {
                to_eye.length()
            } else {
                1.0
            };
            (value, scale)
        }
    };
    let threshold = -test.sin_margin * scale;
    if test.keep_front {
        value > threshold
    } else {
        -value > threshold
    }
}

/// Reusable buffers for [`View::project_polygon`].
#[derive(Clone, Debug, Default)]
pub struct ProjectionScratch {
    view: Vec<DVec3>,
    kept: Vec<DVec3>,
    dropped: Vec<DVec3>,
}

/// Pixel rays of one view: where the ray through a pixel point meets a plane, in f64. The one
/// place that turns pixels back into view space, shared by the oracle and the z-buffer truth.
///
/// Orthographic rays run along −Z from the `z = 0` plane; perspective rays start at the eye
/// `(0, 0, d/s)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelRays {
    half: DVec2,
    inverse_scale: f64,
    /// Eye height `d/s` in view units, for perspective.
    eye: Option<f64>,
}

impl PixelRays {
    /// The rays of `view`.
    #[must_use]
    pub fn new(view: &View) -> Self {
        PixelRays {
            half: view.principal_point(),
            inverse_scale: 1.0 / view.scale(),
            eye: view.eye_in_view().map(|e| e.z),
        }
    }

    /// The view-space point on the `z = 0` plane that the ray through pixel point `p` crosses.
    #[inline]
    #[must_use]
    pub fn base(&self, p: DVec2) -> DVec2 {
        DVec2::new(p.x - self.half.x, self.half.y - p.y) * self.inverse_scale
    }

    /// View-space ray through pixel point `p`: origin and direction.
    #[inline]
    #[must_use]
    pub fn ray(&self, p: DVec2) -> (DVec3, DVec3) {
        let a = self.base(p);
        match self.eye {
            None => (a.extend(0.0), DVec3::NEG_Z),
            Some(e) => (DVec3::new(0.0, 0.0, e), DVec3::new(a.x, a.y, -e)),
        }
    }

    /// View depth (view-space `z`, larger is nearer) where the ray through pixel point `p`
    /// meets the view-space plane `n · v = offset`; not finite when the ray is parallel to it.
    #[inline]
    #[must_use]
    pub fn depth(&self, p: DVec2, n: DVec3, offset: f64) -> f64 {
        let a = self.base(p);
        match self.eye {
            None => (offset - n.x * a.x - n.y * a.y) / n.z,
            Some(e) => {
                let t = (offset - n.z * e) / (n.x * a.x + n.y * a.y - n.z * e);
                e * (1.0 - t)
            }
        }
    }

    /// A bound on the rounding error of [`depth`](Self::depth) at the same arguments: the
    /// magnitudes of the terms it sums, [`DEPTH_ROUNDING`] relative, over its divisor; plus
    /// how far the depth moves when `p` itself moves by `gain ·` [`DEPTH_ROUNDING`] of its
    /// coordinates (a point computed by projecting and clipping lies that close to where it
    /// should; `gain` is [`View::rounding_gain`] of the polygons it came from). Small except
    /// where the plane is nearly parallel to the ray (a piece seen edge-on), where no f64
    /// evaluation can tell its depth better, or next to the near plane.
    #[inline]
    #[must_use]
    pub fn depth_error(&self, p: DVec2, n: DVec3, offset: f64, gain: f64) -> f64 {
        let a = self.base(p);
        let across = (n.x * a.x).abs() + (n.y * a.y).abs();
        // The point's own rounding, in view units, and the depth's slope across the screen.
        let moved = DEPTH_ROUNDING * gain * (p.x.abs() + p.y.abs()) * self.inverse_scale;
        let tilt = n.x.abs() + n.y.abs();
        match self.eye {
            None => DEPTH_ROUNDING * (offset.abs() + across) / n.z.abs() + moved * tilt / n.z.abs(),
            Some(e) => {
                let divisor = n.x * a.x + n.y * a.y - n.z * e;
                let t = (offset - n.z * e) / divisor;
                let terms = offset.abs() + (n.z * e).abs() + t.abs() * (across + (n.z * e).abs());
                DEPTH_ROUNDING * e.abs() * (terms / divisor.abs() + t.abs())
                    + e.abs() * t.abs() * moved * tilt / divisor.abs()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The box holds every projected point of the sphere and is tight: points of a dense
    /// sampling reach each side within a small fraction of a pixel.
    #[test]
    fn a_sphere_projects_inside_its_box_and_touches_each_side() {
        let bounds = Bounds {
            min: DVec3::splat(-1.0),
            max: DVec3::splat(1.0),
        };
        let base = View::fit(&bounds, 200, 150);
        for (yaw, pitch, persp, centre, radius) in [
            (0.0, 0.0, None, DVec3::new(0.3, -0.2, 0.1), 0.4),
            (30.0, 20.0, Some(200.0), DVec3::ZERO, 0.8),
            (75.0, -40.0, Some(120.0), DVec3::new(0.5, 0.4, -0.3), 0.3),
            (200.0, 10.0, Some(400.0), DVec3::new(-0.6, 0.1, 0.2), 0.5),
        ] {
            let mut view = base.with_yaw_pitch_roll(yaw, pitch, 0.0);
            if let Some(d) = persp {
                view = view.with_perspective(d);
            }
            let (lo, hi) = view
                .project_sphere(centre, radius)
                .expect("in front of the eye");
            let (mut seen_lo, mut seen_hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
            let n = 400;
            for i in 0..=n {
                let theta = std::f64::consts::PI * f64::from(i) / f64::from(n);
                for j in 0..2 * n {
                    let phi = std::f64::consts::PI * f64::from(j) / f64::from(n);
                    let dir = DVec3::new(
                        theta.sin() * phi.cos(),
                        theta.cos(),
                        theta.sin() * phi.sin(),
                    );
                    let p = view
                        .project_view_point(view.to_view(centre + dir * radius))
                        .expect("in front");
                    assert!(
                        p.cmpge(lo - DVec2::splat(1e-9)).all()
                            && p.cmple(hi + DVec2::splat(1e-9)).all(),
                        "{p} outside {lo} {hi}"
                    );
                    seen_lo = seen_lo.min(p);
                    seen_hi = seen_hi.max(p);
                }
            }
            assert!(
                (seen_lo - lo).abs().max_element() < 0.05,
                "{seen_lo} vs {lo}"
            );
            assert!(
                (seen_hi - hi).abs().max_element() < 0.05,
                "{seen_hi} vs {hi}"
            );
        }
    }

    #[test]
    fn a_sphere_reaching_the_near_plane_has_no_box() {
        let bounds = Bounds {
            min: DVec3::splat(-1.0),
            max: DVec3::splat(1.0),
        };
        let view = View::fit(&bounds, 100, 100).with_perspective(60.0);
        // The eye is 60 / 26 ≈ 2.3 model units from the centre.
        assert!(view.project_sphere(DVec3::ZERO, 3.0).is_none());
        assert!(view.project_sphere(DVec3::ZERO, 2.0).is_some());
    }
}
