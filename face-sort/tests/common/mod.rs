//! Test helpers: models read with `obj-quads` (through `test-support`), and runners.

#![allow(dead_code)]

use face_sort::{DrawList, FaceSorter, Geometry, PolygonMesh, SorterKind, View, oracle};

/// Path of a model in the repository's assets.
pub fn asset(path: &str) -> String {
    test_support::model_path(path).display().to_string()
}

/// Reads an OBJ model with `obj-quads` (a dev-dependency only: face-sort itself knows no
/// loader), through the workspace's test scaffolding.
pub fn read_obj(path: &str) -> PolygonMesh {
    test_support::polygon_mesh(&test_support::load_model_at(path))
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
