//! Test support: the workspace's `test-support` crate (models read with `obj-quads`, the
//! seeded RNG, named generated models) and this crate's own generated meshes.

#![allow(
    dead_code,
    unused_imports,
    reason = "each test binary uses part of the support module"
)]

use sprite_compose::face_sort::{Geometry, PolygonMesh};

pub use test_support::Rng;
pub use test_support::models::boxes;

/// Reads an OBJ model under `assets/models` with `obj-quads`.
pub fn load_obj(relative: &str) -> PolygonMesh {
    test_support::load_polygon_mesh(relative)
}

/// The workspace's UV sphere ([`test_support::models::uv_sphere`]) with `rings` latitude
/// bands and `segments` around the axis.
pub fn uv_sphere(rings: u32, segments: u32) -> PolygonMesh {
    test_support::models::uv_sphere(segments as usize, rings as usize)
}

/// A geometry.
pub fn geometry(mesh: &PolygonMesh) -> Geometry {
    Geometry::new(mesh).expect("geometry")
}
