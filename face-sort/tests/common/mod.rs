//! Test helpers: models read with `obj-quads` (a dev-dependency: face-sort itself knows no
//! loader), the generated scenes, and runners.

#![allow(dead_code)]

use face_sort::{DrawList, FaceSorter, Geometry, PolygonMesh, SorterKind, View, oracle};

/// Path of a model in the repository's assets.
pub fn asset(path: &str) -> String {
    test_base::model_path(path).display().to_string()
}

/// Reads an OBJ model at `path` with `obj-quads`: its positions and face index lists.
pub fn read_obj(path: &(impl AsRef<std::path::Path> + ?Sized)) -> PolygonMesh {
    let path = path.as_ref();
    let (mesh, _) = obj_quads::load(path, &obj_quads::LoadOptions::default())
        .unwrap_or_else(|e| panic!("model {} does not load: {e}", path.display()));
    PolygonMesh::new(mesh.positions(), mesh.faces()).expect("a loaded mesh is a polygon mesh")
}

/// A model under `assets/models/` ([`read_obj`]).
pub fn load_model(relative: &str) -> PolygonMesh {
    read_obj(&test_base::model_path(relative))
}

/// `"instanced"` (test-support's `models::instanced_scene`): `count` instances of a unit
/// box, a UV sphere and suzanne, 2.2 units apart.
pub fn instanced_scene(count: usize, seed: u64) -> (Vec<PolygonMesh>, Vec<face_sort::Instance>) {
    use face_sort::generate::{boxes, scattered_instances, uv_sphere};
    let cube = boxes(&[(glam::DVec3::splat(-0.5), glam::DVec3::splat(0.5))]);
    let meshes = vec![cube, uv_sphere(12, 8), load_model("suzanne/suzanne.obj")];
    let instances = scattered_instances(meshes.len(), count, seed, 2.2);
    (meshes, instances)
}

/// Sorts with `sorter` and returns the oracle's violation count.
pub fn violations(sorter: &mut dyn FaceSorter, view: &View, list: &mut DrawList) -> usize {
    sorter.sort(view, list);
    oracle::count_violations(view, list)
}

/// The book grid of the issue: yaw 0–358° step 2 × pitch −40…40 step 10.
pub fn book_grid() -> impl Iterator<Item = (f64, f64)> {
    (0..180).flat_map(|y| (-4..=4).map(move |p| (f64::from(y) * 2.0, f64::from(p) * 10.0)))
}

/// Builds every sorter kind for a mesh.
pub fn all_sorters(geometry: &Geometry) -> Vec<(SorterKind, Box<dyn FaceSorter>)> {
    SorterKind::ALL
        .into_iter()
        .map(|k| (k, k.build(geometry)))
        .collect()
}
