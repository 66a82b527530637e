//! The loader targets: OBJ (with MTL), glTF, GLB and textures, through the one loader check
//! of [`test_support::loaders::check_loader_input`]: no panic, and every input either loads
//! into a valid mesh or is refused with a typed error, under several option sets.

use std::path::PathBuf;
use std::sync::OnceLock;

use test_support::loaders::{LoaderFormat, check_loader_input};

/// A folder of this process's own for the files a check writes.
fn scratch() -> &'static PathBuf {
    static SCRATCH: OnceLock<PathBuf> = OnceLock::new();
    SCRATCH.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("fuzz-checks-{}", std::process::id()));
        std::fs::create_dir_all(&dir)
            .unwrap_or_else(|e| panic!("cannot make {}: {e}", dir.display()));
        dir
    })
}

fn check(format: LoaderFormat, data: &[u8]) {
    if let Err(bug) = check_loader_input(format, data, scratch()) {
        panic!("{format:?} loader: {bug}");
    }
}

/// OBJ text; a NUL and what follows is an MTL library written beside it as `case.mtl`.
pub fn obj(data: &[u8]) {
    check(LoaderFormat::Obj, data);
}

/// glTF JSON, loaded from memory and from a file beside the Box sample's buffer.
pub fn gltf(data: &[u8]) {
    check(LoaderFormat::Gltf, data);
}

/// Binary glTF.
pub fn glb(data: &[u8]) {
    check(LoaderFormat::Glb, data);
}

/// PNG or JPEG bytes, decoded under the default texture limits and under small ones.
pub fn texture(data: &[u8]) {
    check(LoaderFormat::Png, data);
}
