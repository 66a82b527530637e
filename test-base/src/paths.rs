//! Where the repository's models and committed test cases are.

use std::path::{Path, PathBuf};

/// The workspace root (the folder holding `assets/`, `docs/` and the crates).
#[must_use]
pub fn workspace_root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

/// Path of a model under `assets/models/`, e.g. `model_path("suzanne/suzanne.obj")`.
#[must_use]
pub fn model_path(relative: &str) -> PathBuf {
    workspace_root().join("assets/models").join(relative)
}

/// The committed regression cases (shrunk fuzz failures and other saved inputs):
/// `tests/data/` at the workspace root; loader cases live in `tests/data/loaders/`.
#[must_use]
pub fn test_data_dir() -> PathBuf {
    workspace_root().join("tests/data")
}
