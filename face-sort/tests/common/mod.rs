//! Test helpers: a minimal OBJ reader (face-sort does not depend on a loader) and runners.

#![allow(dead_code)]

use face_sort::glam::DVec3;
use face_sort::{DrawList, FaceSorter, Geometry, PolygonMesh, SorterKind, View, oracle};

/// Path of a model in the repository's assets.
pub fn asset(path: &str) -> String {
    format!("{}/../assets/models/{path}", env!("CARGO_MANIFEST_DIR"))
}

/// Reads `v` and `f` lines (ignoring texture/normal indices; negative indices supported).
pub fn read_obj(path: &str) -> PolygonMesh {
    let text = std::fs::read_to_string(path).expect("asset readable");
    let mut positions = Vec::new();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for line in text.lines() {
        let line = line.split('#').next().unwrap_or("");
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let c: Vec<f64> = words.take(3).map(|w| w.parse().unwrap()).collect();
                positions.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("f") => {
                let face = words
                    .map(|w| {
                        let i: i64 = w.split('/').next().unwrap().parse().unwrap();
                        if i < 0 {
                            (positions.len() as i64 + i) as u32
                        } else {
                            (i - 1) as u32
                        }
                    })
                    .collect();
                faces.push(face);
            }
            _ => {}
        }
    }
    PolygonMesh::new(positions, faces).expect("valid mesh")
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
