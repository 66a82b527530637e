//! How a model under `assets/models/` becomes an `obj_quads::Mesh` and a
//! `face_sort::PolygonMesh`.

use std::path::Path;

use face_sort::PolygonMesh;

use crate::model_path;

/// Loads a model under `assets/models/` with `obj-quads` (default options).
///
/// # Panics
/// When the model does not load: tests and benches read committed models only.
#[must_use]
pub fn load_model(relative: &str) -> obj_quads::Mesh {
    load_model_at(model_path(relative))
}

/// Loads a model from any path with `obj-quads` (default options).
///
/// # Panics
/// When the model does not load.
#[must_use]
pub fn load_model_at(path: impl AsRef<Path>) -> obj_quads::Mesh {
    let path = path.as_ref();
    match obj_quads::load(path, &obj_quads::LoadOptions::default()) {
        Ok((mesh, _report)) => mesh,
        Err(e) => panic!("model {} does not load: {e}", path.display()),
    }
}

/// The sorters' view of a loaded mesh: its positions and face index lists.
pub fn try_polygon_mesh(mesh: &obj_quads::Mesh) -> Result<PolygonMesh, face_sort::MeshError> {
    PolygonMesh::new(mesh.positions().to_vec(), mesh.faces())
}

/// [`try_polygon_mesh`] for tests and benches.
///
/// # Panics
/// When `face_sort` rejects the mesh; `obj-quads` validates the same invariants, so this
/// does not happen for a loaded mesh.
#[must_use]
pub fn polygon_mesh(mesh: &obj_quads::Mesh) -> PolygonMesh {
    match try_polygon_mesh(mesh) {
        Ok(polygons) => polygons,
        Err(e) => panic!("a loaded mesh is a valid polygon mesh: {e}"),
    }
}

/// [`load_model`] then [`polygon_mesh`].
#[must_use]
pub fn load_polygon_mesh(relative: &str) -> PolygonMesh {
    polygon_mesh(&load_model(relative))
}
