//! Scaffolding shared by the workspace's tests, benches and `xtask`, written once:
//!
//! - where things are: [`workspace_root`], [`model_path`] (`assets/models/…`),
//!   [`test_data_dir`] (`tests/data/`, the committed fuzz regression cases);
//! - the one conversion from a loaded [`obj_quads::Mesh`] to a [`face_sort::PolygonMesh`]
//!   ([`polygon_mesh`], [`load_polygon_mesh`]);
//! - one seeded random generator ([`Rng`], SplitMix64);
//! - a polygon mesh written back as OBJ text ([`to_obj`]);
//! - named generated models ([`models`]): every generated model has one name, and one name
//!   means one model;
//! - loader fuzzing's seeds, its one check and the committed loader cases ([`loaders`]).
//!
//! The crate is `publish = false`; library crates take it as a dev-dependency only.
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

pub mod consumers;
pub mod gltf_scene;
pub mod loaders;
pub mod memory;
pub mod models;
mod obj_text;
mod paths;
mod rng;
pub mod textured_box;

pub use obj_text::to_obj;
pub use paths::{
    load_model, load_model_at, load_polygon_mesh, model_path, polygon_mesh, test_data_dir,
    try_polygon_mesh, workspace_root,
};
pub use rng::Rng;

pub use face_sort;
pub use obj_quads;
