//! Scaffolding shared by the workspace's tests, benches and `xtask`, written once:
//!
//! - where things are: [`workspace_root`], [`model_path`] (`assets/models/…`),
//!   [`test_data_dir`] (`tests/data/`, the committed fuzz regression cases);
//! - the one conversion from a loaded [`obj_quads::Mesh`] to a [`face_sort::PolygonMesh`]
//!   ([`polygon_mesh`], [`load_polygon_mesh`]);
//! - the seeded random generator ([`Rng`], SplitMix64; face-sort's, which its generated
//!   scenes draw from);
//! - a polygon mesh written as OBJ text ([`to_obj`], face-sort's);
//! - named generated models ([`models`]): every generated model has one name, and one name
//!   means one model;
//! - loader fuzzing's seeds, its one check and the committed loader cases ([`loaders`]).
//!
//! The crate is `publish = false`. It stands on the loader and the sorter, so those two take
//! only `test-base` (what every test stands on: paths, memory, consumers), which it
//! re-exports; the other crates take this one as a dev-dependency.
//!
//! ```
//! use test_support::{Rng, load_polygon_mesh, models};
//!
//! let box_mesh = load_polygon_mesh("assimp-obj/box.obj");
//! assert_eq!(box_mesh.face_count(), 6);
//!
//! let mut a = Rng::new(7);
//! let mut b = Rng::new(7);
//! assert_eq!(a.next_u64(), b.next_u64()); // seeded: the same seed, the same numbers
//!
//! assert_eq!(models::planar_torus(1_000).face_count(), models::planar_torus(1_000).face_count());
//! ```

pub mod loaders;
pub mod models;
mod obj_text;
mod paths;

pub use face_sort::generate::{Rng, to_obj};
pub use paths::{load_model, load_model_at, load_polygon_mesh, polygon_mesh, try_polygon_mesh};
pub use test_base::{
    consumers, encoded, gltf_scene, memory, model_path, test_data_dir, textured_box, workspace_root,
};

/// The geometry of a mesh the tests built or loaded.
///
/// # Panics
/// When `face_sort` refuses the mesh: test meshes are valid.
#[must_use]
pub fn geometry(mesh: &face_sort::PolygonMesh) -> face_sort::Geometry {
    match face_sort::Geometry::new(mesh) {
        Ok(geometry) => geometry,
        Err(e) => panic!("a test mesh is a valid geometry: {e}"),
    }
}

pub use face_sort;
pub use obj_quads;
pub use test_base;
