//! Files and pen plots from a mesh and a camera: SVG, PDF, HTML/CSS 3D (sprite-compose's
//! writers), visible plotter edges with HP-GL, and yaw bakes with their spinning page.

use face_sort::Geometry;
use numpy::{IntoPyArray, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use sprite_compose::Materials;
use vector_sink::{
    Export, HiddenParts, HtmlOptions, PdfOptions, SpinOptions, SvgOptions, write_html, write_pdf,
    write_svg,
};

use crate::camera::Camera;
use crate::guard::{detached, value_error};
use crate::mesh::Mesh;

fn hidden_parts(hidden: &str) -> PyResult<HiddenParts> {
    match hidden {
        "remove" => Ok(HiddenParts::Remove),
        "keep" => Ok(HiddenParts::Keep),
        other => Err(PyValueError::new_err(format!(
            "hidden must be \"remove\" or \"keep\", not {other:?}"
        ))),
    }
}

fn materials(mesh: &Mesh, geometry: &Geometry) -> PyResult<Materials> {
    Materials::of(&mesh.model, geometry).map_err(|e| value_error("texture", e))
}

/// `write` applied to the export of `mesh` through `camera` in its materials (BSP order),
/// all without the GIL.
fn with_export<T: Send>(
    py: Python<'_>,
    mesh: &Mesh,
    camera: &Camera,
    hidden: HiddenParts,
    write: impl FnOnce(&Export) -> T + Send,
) -> PyResult<T> {
    let geometry = mesh.geometry()?;
    let view = camera.view(&geometry)?;
    let materials = materials(mesh, &geometry)?;
    detached(py, || {
        let export = Export::new(&geometry, view)
            .with_materials(&materials)
            .with_hidden(hidden);
        Ok(write(&export))
    })
}

/// The SVG of `mesh` seen by `camera`, in its colours and texture, exactly ordered; with
/// `hidden="remove"` (default) it holds only what can be seen. `ids=True` paints every face
/// in its ID colour (face id + 1 as 24-bit RGB) on no background, for checking.
#[pyfunction]
#[pyo3(signature = (mesh, camera, hidden="remove", ids=false))]
pub fn svg(
    py: Python<'_>,
    mesh: &Mesh,
    camera: &Camera,
    hidden: &str,
    ids: bool,
) -> PyResult<String> {
    let hidden = hidden_parts(hidden)?;
    let (width, height) = camera.size();
    with_export(py, mesh, camera, hidden, |export| {
        if ids {
            let options = SvgOptions::DEFAULT
                .with_size(width, height)
                .with_hidden(hidden)
                .with_ids(true)
                .with_background(None);
            write_svg(export.scene(), &options)
        } else {
            export.svg()
        }
    })
}

/// The one-page PDF (one pixel to one point) of `mesh` seen by `camera`, as `svg`.
#[pyfunction]
#[pyo3(signature = (mesh, camera, hidden="remove", ids=false))]
pub fn pdf<'py>(
    py: Python<'py>,
    mesh: &Mesh,
    camera: &Camera,
    hidden: &str,
    ids: bool,
) -> PyResult<Bound<'py, PyBytes>> {
    let hidden = hidden_parts(hidden)?;
    let (width, height) = camera.size();
    let bytes = with_export(py, mesh, camera, hidden, |export| {
        if ids {
            let options = PdfOptions::DEFAULT
                .with_size(width, height)
                .with_hidden(hidden)
                .with_ids(true)
                .with_background(None);
            write_pdf(export.scene(), &options)
        } else {
            export.pdf()
        }
    })?;
    Ok(PyBytes::new(py, &bytes))
}

/// The HTML/CSS 3D page of `mesh` seen by `camera`: one element per face or fragment,
/// stacked in paint order.
#[pyfunction]
#[pyo3(signature = (mesh, camera, ids=false))]
pub fn html(py: Python<'_>, mesh: &Mesh, camera: &Camera, ids: bool) -> PyResult<String> {
    let (width, height) = camera.size();
    with_export(py, mesh, camera, HiddenParts::Keep, |export| {
        if ids {
            write_html(
                export.scene(),
                &HtmlOptions::DEFAULT.with_size(width, height).with_ids(true),
            )
        } else {
            export.html()
        }
    })
}

/// The visible edges of a mesh in one view, for a pen plotter.
#[pyclass(frozen, module = "facesort")]
pub struct Plot {
    plot: sprite_compose::Plot,
}

#[pymethods]
impl Plot {
    /// The visible edges joined into polylines, in pen order: a list of (k, 2) float64
    /// arrays in pixels (x right, y down).
    #[getter]
    fn polylines<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray2<f64>>> {
        self.plot
            .polylines
            .iter()
            .map(|line| {
                let flat: Vec<f64> = line.iter().flat_map(|p| p.to_array()).collect();
                flat.into_pyarray(py)
                    .reshape([line.len(), 2])
                    .expect("k × 2 values")
            })
            .collect()
    }

    /// Pen-down length in pixels.
    #[getter]
    fn pen_down(&self) -> f64 {
        self.plot.pen_down_px
    }

    /// Pen-up travel between polylines in pixels.
    #[getter]
    fn pen_up(&self) -> f64 {
        self.plot.pen_up_px
    }

    /// An SVG of the polylines, stroked `stroke` pixels wide.
    #[pyo3(signature = (stroke=1.0))]
    fn svg(&self, stroke: f64) -> PyResult<String> {
        if !(stroke.is_finite() && stroke > 0.0) {
            return Err(PyValueError::new_err(format!(
                "stroke must be positive, got {stroke}"
            )));
        }
        Ok(vector_sink::plot_svg(&self.plot, stroke))
    }

    /// HP-GL for a pen plotter, `units_per_px` plotter units per pixel (HP-GL's unit is
    /// 0.025 mm: 40 per mm).
    #[pyo3(signature = (units_per_px=10.0))]
    fn hpgl(&self, units_per_px: f64) -> PyResult<String> {
        if !(units_per_px.is_finite() && units_per_px > 0.0) {
            return Err(PyValueError::new_err(format!(
                "units_per_px must be positive, got {units_per_px}"
            )));
        }
        Ok(vector_sink::plot_hpgl(&self.plot, units_per_px))
    }
}

/// The visible edges of `mesh` seen by `camera`: boundaries, silhouettes, creases (faces
/// meeting at `crease` degrees or more) and intersection lines, clipped exactly where faces
/// hide them.
#[pyfunction]
#[pyo3(signature = (mesh, camera, crease=30.0))]
pub fn plot_edges(py: Python<'_>, mesh: &Mesh, camera: &Camera, crease: f64) -> PyResult<Plot> {
    if !(crease.is_finite() && (0.0..=180.0).contains(&crease)) {
        return Err(PyValueError::new_err(format!(
            "crease must be in 0..=180 degrees, got {crease}"
        )));
    }
    let geometry = mesh.geometry()?;
    let view = camera.view(&geometry)?;
    let options = sprite_compose::PlotOptions::DEFAULT.with_crease_deg(crease);
    detached(py, || {
        Ok(Plot {
            plot: sprite_compose::plot_edges(&mesh.polygons, &geometry, &view, &options),
        })
    })
}

/// A yaw turn baked once: every exact paint order of the turn as cells of yaw angles.
#[pyclass(frozen, module = "facesort")]
pub struct YawBake {
    bake: sprite_compose::Bake,
    spin: aspect_bake::Spin,
    geometry: std::sync::Arc<Geometry>,
    colours: Vec<[u8; 4]>,
}

#[pymethods]
impl YawBake {
    /// The cells as (start, end) yaw angles in degrees; one order holds over each.
    #[getter]
    fn cells(&self) -> Vec<(f64, f64)> {
        self.bake
            .cells()
            .iter()
            .map(|c| (c.range.lo, c.range.hi))
            .collect()
    }

    /// A self-contained HTML page that spins the model once every `period` seconds with no
    /// script (CSS animations only). `paused` (seconds) freezes it at that time; `ids=True`
    /// paints ID colours for checking.
    #[pyo3(signature = (period=8.0, paused=None, ids=false))]
    fn spin_html(
        &self,
        py: Python<'_>,
        period: f64,
        paused: Option<f64>,
        ids: bool,
    ) -> PyResult<String> {
        if !(period.is_finite() && period > 0.0) {
            return Err(PyValueError::new_err(format!(
                "period must be positive, got {period}"
            )));
        }
        if paused.is_some_and(|t| !t.is_finite()) {
            return Err(PyValueError::new_err("paused must be finite"));
        }
        detached(py, || {
            let lists = aspect_bake::drawn_lists(&self.bake, &self.spin)
                .map_err(|e| value_error("bake", e))?;
            let options = SpinOptions::DEFAULT
                .with_period(period)
                .with_ids(ids)
                .with_paused_at(paused)
                .with_materials(&Materials::solid(self.colours.iter().copied()));
            Ok(vector_sink::write_culled_spin_html(
                &self.bake,
                &lists,
                &self.spin,
                &self.geometry,
                &options,
            ))
        })
    }
}

/// Bakes a full yaw turn of `mesh` at `pitch` (degrees): the exact picture orders, a few
/// cells per turn, for a `width` × `height` image, orthographic unless `perspective` gives
/// the eye distance in pixels. The work (seconds for 10⁴ faces) releases the GIL; a model
/// past the bake's budgets raises `ValueError` saying which.
#[pyfunction]
#[pyo3(signature = (mesh, pitch=20.0, width=512, height=512, perspective=None))]
pub fn bake_yaw(
    py: Python<'_>,
    mesh: &Mesh,
    pitch: f64,
    width: u32,
    height: u32,
    perspective: Option<f64>,
) -> PyResult<YawBake> {
    if !pitch.is_finite() {
        return Err(PyValueError::new_err("pitch must be finite"));
    }
    let camera = Camera::orbit_for_bake(width, height, perspective)?;
    let geometry = mesh.exact_geometry()?;
    let template = camera.view(&geometry)?;
    let materials = materials(mesh, &geometry)?;
    let colours: Vec<[u8; 4]> = (0..geometry.face_count() as u32)
        .map(|f| materials.brush(f).solid_colour(f))
        .collect();
    detached(py, || {
        let spin = aspect_bake::Spin::new(template, aspect_bake::Axis::Yaw { pitch, roll: 0.0 })
            .map_err(|e| value_error("bake", e))?;
        let (bake, _) =
            aspect_bake::bake_picture(&geometry, &spin, &aspect_bake::PictureOptions::DEFAULT)
                .map_err(|e| value_error("bake", e))?;
        Ok(YawBake {
            bake,
            spin,
            geometry: geometry.clone(),
            colours,
        })
    })
}
