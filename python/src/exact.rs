//! `facesort._native.ExactScene`: the engine of `facesort.mpl`. Polygons given once
//! (prepared once: cut into convex pieces, each piece's outline edges marked), then per
//! view: the exact paint order with fragments, and where the visible parts of lines go in
//! it.
//!
//! Views are given by the viewer alone, as a homogeneous point of the scene's space: an
//! eye `(x, y, z, 1)`, or a direction toward the viewer `(x, y, z, 0)` for a parallel
//! projection. Paint order depends on nothing else (which side of each plane the viewer is
//! on), so any projective camera with that centre, matplotlib's included, sees the picture
//! this order paints.

use std::sync::Arc;

use face_sort::{
    Camera, CullMode, DrawList, FaceSorter, Geometry, Lens, PolygonMesh, SorterKind, View,
};
use glam::DVec3;
use numpy::{IntoPyArray, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sprite_compose::{Line, Overlay, overlay_in_order};

use crate::guard::{detached, value_error};
use crate::input;

/// Polygons ordered exactly for any viewer (see the module docs of the Rust crate).
///
/// `ExactScene(points, offsets, sorter="newell")`: polygon `i` is
/// `points[offsets[i]:offsets[i+1]]` (float64 (n, 3); int offsets of length m + 1).
/// Non-planar convex polygons are painted as the fan of triangles from their first corner;
/// non-convex ones are cut into triangles (ear clipping in their plane). `sorter` is an exact one: `"newell"` (splits only what overlaps
/// cyclically: the fewest items), `"bsp"` (a tree built here, then a walk per view) or
/// `"bsp-merged"`.
#[pyclass(module = "facesort")]
pub struct ExactScene {
    /// The polygons as given (their outlines say which item edges are real).
    polygons: PolygonMesh,
    /// The polygon of each face of `geometry` (a non-convex polygon is cut into triangles).
    source: Vec<u32>,
    geometry: Arc<Geometry>,
    /// Per corner of each piece of `geometry` (in its order), whether the edge from it to the
    /// next lies on its polygon's outline: made once, read for every unsplit item.
    piece_edges: Vec<Vec<bool>>,
    sorter: Box<dyn FaceSorter + Send + Sync>,
    list: DrawList,
}

/// A view of `geometry` from `toward` (unit, from the centre toward the viewer): the
/// rotation of a camera looking back at the centre from there (face-sort's look-at).
fn view_from(geometry: &Geometry, toward: DVec3, width: u32, height: u32) -> PyResult<View> {
    let up = if toward.z.abs() < 0.9 {
        DVec3::Z
    } else {
        DVec3::Y
    };
    let camera = Camera::look_at(toward, DVec3::ZERO, up, Lens::orthographic(1.0))
        .map_err(|e| value_error("viewer", e))?;
    Ok(View::fit(&geometry.bounds(), width, height)
        .with_cull(CullMode::None)
        .with_rotation(camera.rotation()))
}

impl ExactScene {
    fn view(&self, viewer: [f64; 4], width: u32, height: u32) -> PyResult<View> {
        let bounds = self.geometry.bounds();
        let [x, y, z, w] = viewer;
        if !viewer.iter().all(|v| v.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "viewer {viewer:?} is not finite"
            )));
        }
        if w == 0.0 {
            let d = DVec3::new(x, y, z);
            if d.length_squared() == 0.0 {
                return Err(PyValueError::new_err("viewer direction is zero"));
            }
            return view_from(&self.geometry, d.normalize(), width, height);
        }
        let eye = DVec3::new(x, y, z) / w - bounds.centre();
        let distance = eye.length();
        if distance.is_nan() || distance <= 0.5 * bounds.diagonal() {
            return Err(PyValueError::new_err(format!(
                "the eye is inside the scene's bounding sphere ({distance} from its centre, radius {})",
                0.5 * bounds.diagonal()
            )));
        }
        let view = view_from(&self.geometry, eye / distance, width, height)?;
        Ok(view.with_perspective(view.scale() * distance))
    }

    /// Per corner of a piece or fragment of `face` (centred corners), whether the edge from
    /// it to the next lies on an edge of its polygon (`source[face]`).
    fn outline_edges(&self, face: u32, corners: &[DVec3]) -> Vec<bool> {
        let polygon = self.source[face as usize];
        let tolerance = 1e-7 * self.geometry.bounds().diagonal();
        (0..corners.len())
            .map(|k| {
                self.on_boundary(
                    polygon,
                    corners[k],
                    corners[(k + 1) % corners.len()],
                    tolerance,
                )
            })
            .collect()
    }

    /// Whether fragment edge `a`–`b` (centred) lies on an edge of `polygon`.
    fn on_boundary(&self, polygon: u32, a: DVec3, b: DVec3, tolerance: f64) -> bool {
        let centre = self.geometry.bounds().centre();
        let corners = self.polygons.face(polygon as usize);
        let positions = self.polygons.positions();
        (0..corners.len()).any(|k| {
            let p = positions[corners[k] as usize] - centre;
            let q = positions[corners[(k + 1) % corners.len()] as usize] - centre;
            let e = q - p;
            let len2 = e.length_squared();
            if len2 == 0.0 {
                return false;
            }
            let near = |x: DVec3| {
                let t = (x - p).dot(e) / len2;
                (-1e-9..=1.0 + 1e-9).contains(&t) && (x - (p + e * t)).length() <= tolerance
            };
            near(a) && near(b)
        })
    }
}

#[pymethods]
impl ExactScene {
    #[new]
    #[pyo3(signature = (points, offsets, sorter="newell"))]
    fn new(
        py: Python<'_>,
        points: &Bound<'_, PyAny>,
        offsets: &Bound<'_, PyAny>,
        sorter: &str,
    ) -> PyResult<Self> {
        let kind = match SorterKind::from_name(sorter) {
            Some(k @ (SorterKind::Newell | SorterKind::Bsp | SorterKind::BspMerged)) => k,
            _ => {
                return Err(PyValueError::new_err(format!(
                    "sorter must be \"newell\", \"bsp\" or \"bsp-merged\", not {sorter:?}"
                )));
            }
        };
        let positions = input::points(points, "points")?;
        let offsets = input::ints1(offsets, "offsets")?;
        let mut faces = Vec::with_capacity(offsets.len().saturating_sub(1));
        for (n, w) in offsets.windows(2).enumerate() {
            let (a, b) = (w[0], w[1]);
            if a < 0 || b > positions.len() as i64 || b < a {
                return Err(PyValueError::new_err(format!(
                    "offsets[{n}..{}] = {a}..{b} is not a range of points (0..{})",
                    n + 1,
                    positions.len()
                )));
            }
            if b - a < 3 {
                return Err(PyValueError::new_err(format!(
                    "polygon {n} has {} corners (at least 3 needed)",
                    b - a
                )));
            }
            faces.push((a as u32..b as u32).collect::<Vec<u32>>());
        }
        detached(py, || {
            let polygons =
                PolygonMesh::new(positions, faces).map_err(|e| value_error("polygons", e))?;
            let (geometry, source) = convex_parts(&polygons)?;
            let geometry = Arc::new(geometry);
            let sorter: Box<dyn FaceSorter + Send + Sync> = match kind {
                SorterKind::Newell => Box::new(face_sort::Newell::new(&geometry)),
                SorterKind::BspMerged => {
                    Box::new(face_sort::Bsp::new(&geometry).with_fragment_merge(true))
                }
                _ => Box::new(face_sort::Bsp::new(&geometry)),
            };
            let mut scene = ExactScene {
                polygons,
                source,
                geometry,
                piece_edges: Vec::new(),
                sorter,
                list: DrawList::new(),
            };
            let pieces = scene.geometry.pieces().clone();
            scene.piece_edges = (0..pieces.len())
                .map(|i| scene.outline_edges(pieces.face(i), pieces.corners(i)))
                .collect();
            Ok(scene)
        })
    }

    /// The number of polygons.
    #[getter]
    fn polygon_count(&self) -> usize {
        self.polygons.face_count()
    }

    /// The exact paint order for `viewer` (a homogeneous point, module docs), with the
    /// visible parts of `lines` ((l, 2, 3) ends) placed in it.
    /// `opaque[i]` says whether polygon `i` hides what is behind it (else it is
    /// translucent). `width` × `height` is the picture's size in pixels (it sets the
    /// sub-pixel tolerances). Returns a dict of arrays:
    ///
    /// - `faces` (k,): the polygon of each item, back to front;
    /// - `points` (n, 3), `offsets` (k + 1,): each item's corners in the scene's space;
    /// - `edges` (n,): whether the edge from each corner to the next lies on its polygon's
    ///   outline (else the item was cut there);
    /// - `line`, `line_t` (q, 2), `line_before`: visible line parts as parameter intervals
    ///   of their line, each painted before item `line_before` (k: after every item).
    ///
    /// With `merge=True`, neighbours in the order that are pieces of the same polygon
    /// sharing an edge and turned the same way (a non-planar polygon's fan triangles, a
    /// split polygon's fragments) come as one item: the same picture with fewer, possibly
    /// non-convex, items. Line parts are never merged across.
    #[pyo3(signature = (viewer, width, height, opaque, lines=None, merge=false))]
    #[allow(clippy::too_many_arguments)]
    fn order<'py>(
        &mut self,
        py: Python<'py>,
        viewer: (f64, f64, f64, f64),
        width: u32,
        height: u32,
        opaque: &Bound<'py, PyAny>,
        lines: Option<&Bound<'py, PyAny>>,
        merge: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        if width == 0 || height == 0 || width > 1 << 15 || height > 1 << 15 {
            return Err(PyValueError::new_err(format!(
                "width and height must be in 1..=32768, got {width} x {height}"
            )));
        }
        let view = self.view(viewer.into(), width, height)?;
        let opaque = input::flags(opaque, "opaque", self.polygons.face_count())?;
        let line_ends = match lines {
            Some(l) => input::points(&l.call_method1("reshape", ((-1, 3),))?, "lines")?,
            None => Vec::new(),
        };
        let result = detached(py, || {
            let ordered = self.order_detached(&view, &opaque, &line_ends)?;
            Ok(if merge { merged(ordered) } else { ordered })
        })?;
        let dict = PyDict::new(py);
        let k = result.faces.len();
        dict.set_item("faces", result.faces.into_pyarray(py))?;
        let n = result.corners.len() / 3;
        dict.set_item("points", result.corners.into_pyarray(py).reshape([n, 3])?)?;
        dict.set_item("offsets", result.offsets.into_pyarray(py))?;
        dict.set_item("edges", result.edges.into_pyarray(py))?;
        let q = result.line.len();
        dict.set_item("line", result.line.into_pyarray(py))?;
        dict.set_item("line_t", result.line_t.into_pyarray(py).reshape([q, 2])?)?;
        dict.set_item("line_before", result.line_before.into_pyarray(py))?;
        dict.set_item("items", k)?;
        Ok(dict)
    }
}

/// What [`ExactScene::order`] returns, before it becomes numpy arrays.
#[derive(Default)]
struct Ordered {
    faces: Vec<u32>,
    /// Per item: the sign of its facing (which way it turns on screen; 0 edge-on).
    turns: Vec<f64>,
    corners: Vec<f64>,
    offsets: Vec<i64>,
    edges: Vec<bool>,
    line: Vec<i64>,
    line_t: Vec<f64>,
    line_before: Vec<i64>,
}

impl ExactScene {
    fn order_detached(
        &mut self,
        view: &View,
        opaque: &[bool],
        line_ends: &[DVec3],
    ) -> PyResult<Ordered> {
        self.sorter.sort(view, &mut self.list);
        let bounds = self.geometry.bounds();
        let centre = bounds.centre();
        let viewer = view.viewer();
        // The list's shared polygons are the prepared pieces (Newell's), or not (the BSP's
        // fragments): only then do the pieces' edge flags serve.
        let shared = match self.list.shared() {
            Some(set) if Arc::ptr_eq(set, self.geometry.pieces()) => set.len(),
            _ => 0,
        };
        let mut out = Ordered {
            offsets: Vec::with_capacity(self.list.len() + 1),
            faces: Vec::with_capacity(self.list.len()),
            turns: Vec::with_capacity(self.list.len()),
            ..Ordered::default()
        };
        out.offsets.push(0);
        for &item in self.list.items() {
            let corners = self.list.corners(item);
            out.faces.push(self.source[item.face as usize]);
            out.turns
                .push(viewer.facing(self.list.plane(item)).signum());
            for &c in corners {
                out.corners.extend_from_slice(&(c + centre).to_array());
            }
            // A piece as prepared keeps its edge flags; a fragment cut this frame is tested.
            if (item.polygon as usize) < shared {
                out.edges
                    .extend_from_slice(&self.piece_edges[item.polygon as usize]);
            } else {
                out.edges.extend(self.outline_edges(item.face, corners));
            }
            out.offsets.push((out.corners.len() / 3) as i64);
        }
        if line_ends.is_empty() {
            return Ok(out);
        }
        // The order as a geometry whose face index is the paint position: the occluders.
        let k = out.faces.len() as i64;
        let fragment_points: Vec<DVec3> = out
            .corners
            .chunks_exact(3)
            .map(|c| DVec3::new(c[0], c[1], c[2]))
            .collect();
        let fragments = out.offsets.windows(2).map(|w| w[0] as u32..w[1] as u32);
        let ordered_mesh =
            PolygonMesh::new(fragment_points, fragments.map(|r| r.collect::<Vec<u32>>()))
                .map_err(|e| value_error("fragments", e))?;
        let ordered = Geometry::new_in_frame(&ordered_mesh, bounds)
            .map_err(|e| value_error("fragments", e))?;
        let overlay = Overlay {
            lines: line_ends
                .chunks_exact(2)
                .map(|e| Line {
                    ends: [e[0], e[1]],
                    colour: [0; 4],
                    width_px: 1.0,
                    faces: Vec::new(),
                })
                .collect(),
            points: Vec::new(),
        };
        let item_faces = &out.faces;
        let is_opaque = |item: u32| opaque[item_faces[item as usize] as usize];
        let (line_parts, _) = overlay_in_order(&ordered, view, &overlay, &is_opaque);
        for part in line_parts {
            out.line.push(part.index as i64);
            out.line_t.extend_from_slice(&part.t);
            out.line_before.push(part.before.map_or(k, i64::from));
        }
        Ok(out)
    }
}

/// A polygon's corners with the flag of the edge from each to the next.
type Outline = Vec<(DVec3, bool)>;

/// `a` and `b` joined along an edge that `a` walks one way and `b` the other (the same two
/// points bit for bit), or `None` when they share none.
fn join(a: &[(DVec3, bool)], b: &[(DVec3, bool)]) -> Option<Outline> {
    let (n, m) = (a.len(), b.len());
    for i in 0..n {
        let (p, q) = (a[i].0, a[(i + 1) % n].0);
        for j in 0..m {
            if b[j].0 == q && b[(j + 1) % m].0 == p {
                let mut out = Vec::with_capacity(n + m - 2);
                out.extend_from_slice(&a[..i]);
                // p now leads into b: its edge is b's edge from p.
                out.push((p, b[(j + 1) % m].1));
                out.extend((2..m).map(|t| b[(j + t) % m]));
                out.extend_from_slice(&a[i + 1..]);
                return Some(out);
            }
        }
    }
    None
}

/// [`ExactScene::order`]'s `merge`: runs of same-polygon neighbours joined (see there).
fn merged(raw: Ordered) -> Ordered {
    let k = raw.faces.len();
    let offsets: Vec<usize> = raw.offsets.iter().map(|&o| o as usize).collect();
    let corner = |j: usize| {
        DVec3::new(
            raw.corners[3 * j],
            raw.corners[3 * j + 1],
            raw.corners[3 * j + 2],
        )
    };
    let mut breaks = vec![false; k + 1];
    for &b in &raw.line_before {
        breaks[b as usize] = true;
    }
    let mut out = Ordered {
        offsets: vec![0],
        ..Ordered::default()
    };
    let mut group_of = vec![0i64; k + 1];
    let mut current: Option<(u32, f64, Outline)> = None;
    let flush = |out: &mut Ordered, group: Option<(u32, f64, Outline)>| {
        if let Some((face, turn, outline)) = group {
            out.faces.push(face);
            out.turns.push(turn);
            for (c, edge) in outline {
                out.corners.extend_from_slice(&c.to_array());
                out.edges.push(edge);
            }
            out.offsets.push((out.corners.len() / 3) as i64);
        }
    };
    for i in 0..k {
        let item: Outline = (offsets[i]..offsets[i + 1])
            .map(|j| (corner(j), raw.edges[j]))
            .collect();
        let turn = raw.turns[i];
        if let Some((face, o, outline)) = &mut current
            && !breaks[i]
            && *face == raw.faces[i]
            && *o == turn
            && turn != 0.0
            && let Some(joined) = join(outline, &item)
        {
            *outline = joined;
            group_of[i] = out.faces.len() as i64;
            continue;
        }
        flush(&mut out, current.take());
        group_of[i] = out.faces.len() as i64;
        current = Some((raw.faces[i], turn, item));
    }
    flush(&mut out, current.take());
    group_of[k] = out.faces.len() as i64;
    out.line = raw.line;
    out.line_t = raw.line_t;
    out.line_before = raw
        .line_before
        .iter()
        .map(|&b| group_of[b as usize])
        .collect();
    out
}

/// The polygons prepared as convex faces: each convex one as it is, each other one cut into
/// triangles; with the polygon of each face. A polygon is cut when it turns both ways
/// around its Newell normal, or when `Geometry` finds it non-convex within its tolerance.
fn convex_parts(polygons: &PolygonMesh) -> PyResult<(Geometry, Vec<u32>)> {
    let positions = polygons.positions();
    let mut cut: Vec<bool> = polygons
        .faces()
        .map(|f| !turns_one_way(&f.iter().map(|&i| positions[i as usize]).collect::<Vec<_>>()))
        .collect();
    // Geometry's own test has a tolerance: what it still calls non-convex is cut too
    // (each polygon at most once, so this ends).
    loop {
        let mut faces: Vec<Vec<u32>> = Vec::new();
        let mut source = Vec::new();
        for (n, f) in polygons.faces().enumerate() {
            if cut[n] {
                let corners: Vec<DVec3> = f.iter().map(|&i| positions[i as usize]).collect();
                for [a, b, c] in ear_clip(&corners) {
                    faces.push(vec![f[a], f[b], f[c]]);
                    source.push(n as u32);
                }
            } else {
                faces.push(f.to_vec());
                source.push(n as u32);
            }
        }
        let mesh =
            PolygonMesh::new(positions.to_vec(), faces).map_err(|e| value_error("polygons", e))?;
        match Geometry::new(&mesh) {
            Err(face_sort::MeshError::NonConvex { face }) if !cut[source[face] as usize] => {
                cut[source[face] as usize] = true;
            }
            Err(e) => return Err(value_error("polygons", e)),
            Ok(geometry) => return Ok((geometry, source)),
        }
    }
}

/// The polygon's Newell normal and its corners in the plane across it (2D).
fn flattened(corners: &[DVec3]) -> Vec<glam::DVec2> {
    let normal = face_sort::newell_normal(corners);
    let axis = normal.abs().max_position();
    let (u, v) = match axis {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    };
    let flip = if normal[axis] < 0.0 { -1.0 } else { 1.0 };
    corners
        .iter()
        .map(|c| glam::DVec2::new(c[u], flip * c[v]))
        .collect()
}

/// Whether every corner turns the same way (collinear corners allowed).
fn turns_one_way(corners: &[DVec3]) -> bool {
    let p = flattened(corners);
    let n = p.len();
    let turn = |k: usize| (p[(k + 1) % n] - p[k]).perp_dot(p[(k + 2) % n] - p[(k + 1) % n]);
    (0..n).all(|k| turn(k) >= 0.0) || (0..n).all(|k| turn(k) <= 0.0)
}

/// Triangles covering a simple polygon (ear clipping in its plane, counter-clockwise around
/// its Newell normal), as corner positions in the polygon.
fn ear_clip(corners: &[DVec3]) -> Vec<[usize; 3]> {
    let p = flattened(corners);
    let mut left: Vec<usize> = (0..p.len()).collect();
    let mut out = Vec::with_capacity(p.len().saturating_sub(2));
    let cross = |a: usize, b: usize, c: usize| (p[b] - p[a]).perp_dot(p[c] - p[b]);
    let inside = |q: usize, a: usize, b: usize, c: usize| {
        cross(a, b, q) >= 0.0 && cross(b, c, q) >= 0.0 && cross(c, a, q) >= 0.0
    };
    while left.len() > 3 {
        let n = left.len();
        let ear = (0..n).find(|&k| {
            let (a, b, c) = (left[(k + n - 1) % n], left[k], left[(k + 1) % n]);
            cross(a, b, c) > 0.0
                && !left.iter().any(|&q| {
                    q != a
                        && q != b
                        && q != c
                        && p[q] != p[a]
                        && p[q] != p[b]
                        && p[q] != p[c]
                        && inside(q, a, b, c)
                })
        });
        // A polygon with no ear (self-intersecting, or degenerate): its fan, as a last resort.
        let k = ear.unwrap_or(1 % n);
        out.push([left[(k + n - 1) % n], left[k], left[(k + 1) % n]]);
        left.remove(k);
    }
    if left.len() == 3 {
        out.push([left[0], left[1], left[2]]);
    }
    out
}
