//! `facesort.Mesh` (a model: positions, faces, optional colours and texture), `Order` (a
//! sorted view of it) and `Presorted` (certified orders, looked up per view).

use std::sync::{Arc, Mutex, OnceLock};

use face_sort::{DrawList, FaceSorter, Geometry, PolygonMesh, ProjectionScratch, SorterKind, View};
use glam::{DVec2, Vec2};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods};
use obj_quads::{LoadOptions, Material};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;

use crate::camera::Camera;
use crate::guard::{caught, detached, value_error};
use crate::input;

/// A polygon mesh: vertex positions and faces (convex polygons of 3 or more corners, any
/// mix), with optional per-face colours or a texture.
///
/// `Mesh(vertices, faces, colours=None, uvs=None, texture=None)`:
/// - `vertices`: float64 (or float32) array of shape (n, 3), C-contiguous, finite;
/// - `faces`: an (m, k) integer array, or a list of index lists of any lengths ≥ 3;
/// - `colours`: (m, 3) or (m, 4) per face, uint8 or floats in 0..1;
/// - `uvs`: (n, 2) texture coordinates per vertex (v = 0 at the image's bottom), with
///   `texture`, the path of a PNG or JPEG.
///
/// Face ids are face positions in `faces`, as everywhere in the library. Bad input raises
/// `TypeError` (wrong kind of array) or `ValueError` (naming the face or vertex).
#[pyclass(frozen, module = "facesort")]
pub struct Mesh {
    pub(crate) model: obj_quads::Mesh,
    pub(crate) polygons: PolygonMesh,
    geometry: Arc<Geometry>,
    exact_geometry: OnceLock<Result<Arc<Geometry>, String>>,
}

impl Mesh {
    fn from_model(model: obj_quads::Mesh) -> PyResult<Self> {
        let polygons = PolygonMesh::new(model.positions().to_vec(), model.faces())
            .map_err(|e| value_error("mesh", e))?;
        // Prepared now, so that a mesh that cannot be ordered is refused where it is made.
        let geometry = Arc::new(Geometry::new(&polygons).map_err(|e| value_error("mesh", e))?);
        Ok(Mesh {
            model,
            polygons,
            geometry,
            exact_geometry: OnceLock::new(),
        })
    }

    /// The mesh prepared for ordering.
    pub(crate) fn geometry(&self) -> PyResult<Arc<Geometry>> {
        Ok(self.geometry.clone())
    }

    /// The mesh prepared with neighbours sharing corners bit for bit (certified orders and
    /// picture bakes).
    pub(crate) fn exact_geometry(&self) -> PyResult<Arc<Geometry>> {
        self.exact_geometry
            .get_or_init(|| {
                Geometry::with_exact_corners(&self.polygons)
                    .map(Arc::new)
                    .map_err(|e| e.to_string())
            })
            .clone()
            .map_err(|e| PyValueError::new_err(format!("mesh: {e}")))
    }
}

#[pymethods]
impl Mesh {
    #[new]
    #[pyo3(signature = (vertices, faces, colours=None, uvs=None, texture=None))]
    fn new(
        vertices: &Bound<'_, PyAny>,
        faces: &Bound<'_, PyAny>,
        colours: Option<&Bound<'_, PyAny>>,
        uvs: Option<&Bound<'_, PyAny>>,
        texture: Option<std::path::PathBuf>,
    ) -> PyResult<Self> {
        caught(|| {
            let positions = input::points(vertices, "vertices")?;
            let faces = input::faces(faces, positions.len())?;
            let count = faces.len();
            let mut model = obj_quads::Mesh::from_faces(positions, &faces)
                .map_err(|e| value_error("mesh", e))?;
            if let Some(colours) = colours {
                let colours = input::colours(colours, count)?;
                model = model
                    .with_face_colours(&colours)
                    .map_err(|e| value_error("colours", e))?;
            }
            match (uvs, texture) {
                (Some(uvs), Some(texture)) => {
                    let per_vertex = input::floats2(uvs, "uvs", 2)?;
                    if per_vertex.len() / 2 != model.positions().len() {
                        return Err(PyValueError::new_err(format!(
                            "uvs must have one row per vertex ({}), got {}",
                            model.positions().len(),
                            per_vertex.len() / 2
                        )));
                    }
                    let corners: Vec<Vec2> = faces
                        .iter()
                        .flatten()
                        .map(|&v| {
                            Vec2::new(
                                per_vertex[2 * v as usize] as f32,
                                per_vertex[2 * v as usize + 1] as f32,
                            )
                        })
                        .collect();
                    // A texture paints every face: it takes the place of any colours.
                    let texture = Material::new("texture", [1.0; 4]).with_texture(texture);
                    model = model
                        .with_materials(vec![texture], vec![Some(0); count])
                        .and_then(|m| m.with_uvs(corners))
                        .map_err(|e| value_error("uvs", e))?;
                }
                (None, None) => {}
                _ => {
                    return Err(PyValueError::new_err(
                        "uvs and texture go together: give both or neither",
                    ));
                }
            }
            Self::from_model(model)
        })
    }

    /// Loads an OBJ (with its MTL, colours and textures beside it) or glTF file, within the
    /// loader's default limits (file size, faces, vertices, texture sizes).
    #[staticmethod]
    fn load(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Self> {
        let model = detached(py, || {
            obj_quads::load(&path, &LoadOptions::DEFAULT)
                .map(|(mesh, _)| mesh)
                .map_err(|e| PyOSError::new_err(format!("{}: {e}", path.display())))
        })?;
        Self::from_model(model)
    }

    /// The vertex positions, (n, 3) float64 (a copy).
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let flat: Vec<f64> = self
            .model
            .positions()
            .iter()
            .flat_map(|p| p.to_array())
            .collect();
        let n = flat.len() / 3;
        flat.into_pyarray(py).reshape([n, 3]).expect("n × 3 values")
    }

    /// The number of faces.
    #[getter]
    fn face_count(&self) -> usize {
        self.model.face_count()
    }

    /// Orders the faces seen by `camera`, back to front. `sorter` is `"bsp"` (exact, a tree
    /// built once per mesh), `"newell"` (exact, nothing built), `"presorted"` (exact,
    /// certified orders; prefer `facesort.Presorted` to keep them), or the inexact
    /// `"centroid"` and `"topological"` for comparison. The GIL is released meanwhile.
    #[pyo3(signature = (camera, sorter="bsp"))]
    fn sort(&self, py: Python<'_>, camera: &Camera, sorter: &str) -> PyResult<Order> {
        let kind = SorterKind::from_name(sorter).ok_or_else(|| {
            PyValueError::new_err(format!(
                "sorter must be one of bsp, bsp-merged, newell, presorted, centroid, topological; not {sorter:?}"
            ))
        })?;
        let geometry = match kind {
            SorterKind::Presorted => self.exact_geometry()?,
            _ => self.geometry()?,
        };
        let view = camera.view(&geometry)?;
        detached(py, || {
            let mut list = DrawList::new();
            kind.build(&geometry).sort(&view, &mut list);
            Ok(Order { view, list })
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "Mesh({} vertices, {} faces)",
            self.model.positions().len(),
            self.model.face_count()
        )
    }
}

/// Faces in paint order for one view: paint `polygons()` in order and the picture is
/// what a depth buffer would show. Where a face had to be split, its fragments appear
/// with the face's id.
#[pyclass(frozen, module = "facesort")]
pub struct Order {
    pub(crate) view: View,
    pub(crate) list: DrawList,
}

#[pymethods]
impl Order {
    /// The face id of every item, back to front (uint32).
    #[getter]
    fn faces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u32>> {
        self.list
            .items()
            .iter()
            .map(|i| i.face)
            .collect::<Vec<_>>()
            .into_pyarray(py)
    }

    /// The items as polygons in pixels (x right, y down): `(points, offsets)`, where item
    /// `i` is `points[offsets[i]:offsets[i + 1]]`; points (k, 2) float64, offsets int64.
    fn polygons<'py>(
        &self,
        py: Python<'py>,
    ) -> (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<i64>>) {
        let (points, offsets) = projected(&self.view, &self.list);
        let n = points.len();
        let flat: Vec<f64> = points.iter().flat_map(|p| p.to_array()).collect();
        (
            flat.into_pyarray(py).reshape([n, 2]).expect("n × 2 values"),
            offsets.into_pyarray(py),
        )
    }

    /// The oracle's count of order violations: pairs of drawn polygons that overlap on
    /// screen with the later one behind (0 for an exact order). Resolution-free.
    fn violations(&self, py: Python<'_>) -> PyResult<usize> {
        detached(py, || {
            Ok(face_sort::oracle::count_violations(&self.view, &self.list))
        })
    }

    fn __len__(&self) -> usize {
        self.list.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "Order({} items, {} fragments cut this frame)",
            self.list.len(),
            self.list.frame_fragments()
        )
    }
}

/// Every item of `list` projected to pixels, with offsets.
pub(crate) fn projected(view: &View, list: &DrawList) -> (Vec<DVec2>, Vec<i64>) {
    let mut scratch = ProjectionScratch::default();
    let (mut points, mut offsets, mut polygon) = (Vec::new(), vec![0i64], Vec::new());
    for &item in list.items() {
        view.project_polygon(list.corners(item), &mut polygon, &mut scratch);
        points.extend_from_slice(&polygon);
        offsets.push(points.len() as i64);
    }
    (points, offsets)
}

/// Certified orders for every view of a rigid mesh, built once: a view then costs a
/// region lookup and a cull pass. `Presorted(mesh)` builds them (the GIL released); a
/// build over its budgets falls back to the BSP for every view, which `fell_back` says.
#[pyclass(frozen, module = "facesort")]
pub struct Presorted {
    sorter: Mutex<face_sort::Presorted>,
    geometry: Arc<Geometry>,
    refused: Option<String>,
}

#[pymethods]
impl Presorted {
    #[new]
    fn new(py: Python<'_>, mesh: &Mesh) -> PyResult<Self> {
        let geometry = mesh.exact_geometry()?;
        detached(py, || {
            let (sorter, refused) = match face_sort::Presorted::try_new(
                &geometry,
                &face_sort::PresortOptions::default(),
            ) {
                Ok(s) => (s, None),
                Err(e) => (face_sort::Presorted::new(&geometry), Some(e.to_string())),
            };
            Ok(Presorted {
                sorter: Mutex::new(sorter),
                geometry: geometry.clone(),
                refused,
            })
        })
    }

    /// The order for `camera`: a region lookup and a cull pass.
    fn sort(&self, py: Python<'_>, camera: &Camera) -> PyResult<Order> {
        let view = camera.view(&self.geometry)?;
        detached(py, || {
            let mut list = DrawList::new();
            let mut sorter = self
                .sorter
                .lock()
                .map_err(|_| PyValueError::new_err("Presorted is poisoned by an earlier error"))?;
            sorter.sort(&view, &mut list);
            Ok(Order { view, list })
        })
    }

    /// Regions of views the certificate covers.
    #[getter]
    fn regions(&self) -> usize {
        self.sorter.lock().map(|s| s.regions()).unwrap_or(0)
    }

    /// Distinct orders among the regions.
    #[getter]
    fn orders(&self) -> usize {
        self.sorter.lock().map(|s| s.orders()).unwrap_or(0)
    }

    /// Views so far that fell back to the BSP (eyes nearer than the certified distance, or
    /// every view when the build was refused).
    #[getter]
    fn fallback_frames(&self) -> usize {
        self.sorter.lock().map(|s| s.fallback_frames()).unwrap_or(0)
    }

    /// Why the build was refused (its budget), or `None` when it was built.
    #[getter]
    fn refused(&self) -> Option<String> {
        self.refused.clone()
    }
}
