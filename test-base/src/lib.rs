//! What every test of the workspace stands on, and nothing of the workspace's own: where the
//! repository's files are ([`workspace_root`], [`model_path`], [`test_data_dir`]), the name
//! of a generated model ([`model_name`]), a peak-memory allocator ([`memory`]), the real
//! consumers the files are judged by ([`consumers`]: headless Chromium, poppler), and small
//! files written by hand ([`encoded`], [`gltf_scene`], [`textured_box`]).
//!
//! The crate is `publish = false` and depends on no crate of the workspace, so that every
//! library, the loader and the sorter among them, can take it as a dev-dependency. The
//! scaffolding that needs the workspace's types (loaded models as polygon meshes, named
//! generated models) is `test-support`, which stands on the loader and the sorter.
//!
//! ```
//! assert!(test_base::model_path("suzanne/suzanne.obj").exists());
//! assert_eq!(test_base::model_name("bumpy-torus", 10_000), "bumpy-torus-10k");
//! ```

pub mod consumers;
pub mod encoded;
pub mod gltf_scene;
pub mod memory;
mod paths;
pub mod textured_box;

pub use paths::{model_path, test_data_dir, workspace_root};

/// The name of a generated model in tables: `"{kind}-{faces}"` with `k` for thousands,
/// e.g. `model_name("bumpy-torus", 10_000) == "bumpy-torus-10k"`.
#[must_use]
pub fn model_name(kind: &str, faces: usize) -> String {
    if faces >= 1000 && faces.is_multiple_of(1000) {
        format!("{kind}-{}k", faces / 1000)
    } else {
        format!("{kind}-{faces}")
    }
}
