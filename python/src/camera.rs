//! `facesort.Camera`: the ways users hold a camera (yaw/pitch/roll per CONVENTIONS.md,
//! look-at, an engine's 4 × 4 matrices), resolved into a `View` of a mesh.

use face_sort::{CullMode, Geometry, Lens, View};
use glam::{DMat4, DVec3};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::guard::value_error;
use crate::input::floats2;

#[derive(Clone, Debug)]
enum Placement {
    /// CONVENTIONS.md: the model fitted to the image, turned by yaw, pitch, roll.
    Orbit {
        ypr: [f64; 3],
        perspective: Option<f64>,
    },
    /// An engine's camera (look-at or matrices).
    Engine(face_sort::Camera),
}

/// A camera and an image size: how a mesh is seen.
///
/// Make one with `Camera.orbit` (the conventions of the workspace: the model fitted to
/// the image and turned), `Camera.look_at`, or `Camera.from_matrices` (an engine's view and
/// projection matrices). Back faces are culled unless `cull` says otherwise.
#[pyclass(frozen, module = "facesort")]
#[derive(Clone, Debug)]
pub struct Camera {
    placement: Placement,
    width: u32,
    height: u32,
    cull: CullMode,
}

fn cull_mode(cull: &str) -> PyResult<CullMode> {
    CullMode::from_name(cull).ok_or_else(|| {
        PyValueError::new_err(format!(
            "cull must be \"back\", \"front\" or \"none\", not {cull:?}"
        ))
    })
}

fn size(width: u32, height: u32) -> PyResult<(u32, u32)> {
    const MAX: u32 = 1 << 15;
    if width == 0 || height == 0 || width > MAX || height > MAX {
        return Err(PyValueError::new_err(format!(
            "width and height must be in 1..={MAX}, got {width} x {height}"
        )));
    }
    Ok((width, height))
}

fn finite3(v: [f64; 3], what: &str) -> PyResult<DVec3> {
    let v = DVec3::from_array(v);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(PyValueError::new_err(format!("{what} = {v} is not finite")))
    }
}

/// A perspective eye distance in pixels: positive and finite.
fn eye_distance(d: f64) -> PyResult<f64> {
    if d.is_finite() && d > 0.0 {
        Ok(d)
    } else {
        Err(PyValueError::new_err(format!(
            "perspective distance must be positive and finite, got {d}"
        )))
    }
}

fn matrix(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<DMat4> {
    let rows = floats2(obj, what, 4)?;
    if rows.len() != 16 {
        return Err(PyValueError::new_err(format!(
            "{what} must have shape (4, 4)"
        )));
    }
    // numpy holds M row by row (M @ p with column vectors); glam reads columns.
    Ok(DMat4::from_cols_slice(&rows).transpose())
}

#[pymethods]
impl Camera {
    /// The conventions' camera: the model's bounding box centred and fitted to a
    /// `width` × `height` image, turned by `yaw`, `pitch`, `roll` (degrees,
    /// `R = Ry(yaw)·Rx(pitch)·Rz(roll)`), orthographic unless `perspective` gives the eye's
    /// distance in pixels (`True`: the image width).
    #[staticmethod]
    #[pyo3(signature = (yaw=0.0, pitch=0.0, roll=0.0, width=512, height=512, perspective=None, cull="back"))]
    fn orbit(
        yaw: f64,
        pitch: f64,
        roll: f64,
        width: u32,
        height: u32,
        perspective: Option<&Bound<'_, PyAny>>,
        cull: &str,
    ) -> PyResult<Self> {
        let (width, height) = size(width, height)?;
        let perspective = match perspective {
            None => None,
            Some(p) if p.is_instance_of::<pyo3::types::PyBool>() => {
                p.extract::<bool>()?.then_some(f64::from(width))
            }
            Some(p) => {
                let d: f64 = p.extract().map_err(|_| {
                    PyValueError::new_err("perspective must be a distance in pixels, True or None")
                })?;
                Some(eye_distance(d)?)
            }
        };
        finite3([yaw, pitch, roll], "(yaw, pitch, roll)")?;
        Camera::new(
            Placement::Orbit {
                ypr: [yaw, pitch, roll],
                perspective,
            },
            width,
            height,
            cull_mode(cull)?,
        )
    }

    /// A camera at `eye` looking at `target` with `up` upward (model space). Perspective
    /// with a vertical field of view `fov_y` (degrees) and near plane `near`, or orthographic
    /// spanning `ortho_height` model units vertically: give exactly one of the two.
    #[staticmethod]
    #[pyo3(signature = (eye, target, up=(0.0, 1.0, 0.0), fov_y=None, ortho_height=None, near=0.01, width=512, height=512, cull="back"))]
    #[allow(clippy::too_many_arguments)]
    fn look_at(
        eye: (f64, f64, f64),
        target: (f64, f64, f64),
        up: (f64, f64, f64),
        fov_y: Option<f64>,
        ortho_height: Option<f64>,
        near: f64,
        width: u32,
        height: u32,
        cull: &str,
    ) -> PyResult<Self> {
        let (width, height) = size(width, height)?;
        let lens = match (fov_y, ortho_height) {
            (Some(fov), None) => Lens::perspective(fov, near),
            (None, Some(h)) => Lens::orthographic(h),
            _ => {
                return Err(PyValueError::new_err(
                    "give exactly one of fov_y (perspective) and ortho_height (orthographic)",
                ));
            }
        };
        let camera = face_sort::Camera::look_at(
            finite3(eye.into(), "eye")?,
            finite3(target.into(), "target")?,
            finite3(up.into(), "up")?,
            lens,
        )
        .map_err(|e| value_error("look_at", e))?;
        Camera::new(Placement::Engine(camera), width, height, cull_mode(cull)?)
    }

    /// A camera from an engine's 4 × 4 view matrix (model → camera, rigid, the camera
    /// looking down its −Z) and projection matrix, both as numpy arrays applied to column
    /// vectors (`M @ p`). `clip` is the projection's clip space: `"opengl"` (depth −1..1,
    /// OpenGL, WebGL, three.js), `"directx"` (0..1) or `"vulkan"` (0..1, y down).
    #[staticmethod]
    #[pyo3(signature = (view, projection, width=512, height=512, clip="opengl", cull="back"))]
    fn from_matrices(
        view: &Bound<'_, PyAny>,
        projection: &Bound<'_, PyAny>,
        width: u32,
        height: u32,
        clip: &str,
        cull: &str,
    ) -> PyResult<Self> {
        let (width, height) = size(width, height)?;
        let clip = match clip {
            "opengl" => face_sort::ClipSpace::MinusOneToOne,
            "directx" => face_sort::ClipSpace::ZeroToOne,
            "vulkan" => face_sort::ClipSpace::ZeroToOneYDown,
            other => {
                return Err(PyValueError::new_err(format!(
                    "clip must be \"opengl\", \"directx\" or \"vulkan\", not {other:?}"
                )));
            }
        };
        let camera = face_sort::Camera::from_matrices(
            matrix(view, "view")?,
            matrix(projection, "projection")?,
            clip,
        )
        .map_err(|e| value_error("from_matrices", e))?;
        Camera::new(Placement::Engine(camera), width, height, cull_mode(cull)?)
    }

    /// This camera with another cull mode: `"back"`, `"front"` or `"none"`.
    fn with_cull(&self, cull: &str) -> PyResult<Self> {
        Ok(Camera {
            cull: cull_mode(cull)?,
            ..self.clone()
        })
    }

    /// Image width in pixels.
    #[getter]
    fn width(&self) -> u32 {
        self.width
    }

    /// Image height in pixels.
    #[getter]
    fn height(&self) -> u32 {
        self.height
    }

    fn __repr__(&self) -> String {
        let how = match &self.placement {
            Placement::Orbit { ypr, perspective } => format!(
                "orbit yaw {} pitch {} roll {}{}",
                ypr[0],
                ypr[1],
                ypr[2],
                perspective.map_or(String::new(), |d| format!(", perspective {d} px"))
            ),
            Placement::Engine(c) => format!("eye {} looking {:?}", c.eye(), c.lens()),
        };
        format!(
            "Camera({how}, {} x {}, cull {:?})",
            self.width, self.height, self.cull
        )
    }
}

impl Camera {
    /// The view of `geometry` through this camera.
    pub fn view(&self, geometry: &Geometry) -> PyResult<View> {
        let view = match &self.placement {
            Placement::Orbit { ypr, perspective } => {
                let view = View::fit(&geometry.bounds(), self.width, self.height)
                    .with_yaw_pitch_roll(ypr[0], ypr[1], ypr[2]);
                match perspective {
                    Some(d) => view.with_perspective(*d),
                    None => view,
                }
            }
            Placement::Engine(camera) => camera
                .view(geometry, self.width, self.height)
                .map_err(|e| value_error("camera", e))?,
        };
        Ok(view.with_cull(self.cull))
    }

    /// A camera of `placement` in a checked image size.
    fn new(placement: Placement, width: u32, height: u32, cull: CullMode) -> PyResult<Camera> {
        let (width, height) = size(width, height)?;
        Ok(Camera {
            placement,
            width,
            height,
            cull,
        })
    }

    /// The template camera of a yaw bake (yaw 0, pitch and roll set by the bake's axis).
    pub fn orbit_for_bake(width: u32, height: u32, perspective: Option<f64>) -> PyResult<Camera> {
        let perspective = perspective.map(eye_distance).transpose()?;
        let placement = Placement::Orbit {
            ypr: [0.0; 3],
            perspective,
        };
        Camera::new(placement, width, height, CullMode::Back)
    }

    /// `(width, height)` in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }
}
