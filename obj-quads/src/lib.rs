//! Loads polygon models for a painter's-algorithm renderer: Wavefront OBJ
//! (with MTL materials) and glTF 2.0 / GLB, keeping quads and other convex
//! polygons instead of triangulating them.
//!
//! Every loader returns a validated [`Mesh`] and a [`LoadReport`], or one typed
//! [`LoadError`] naming the file, the object, the face index and (for OBJ) the
//! line. No input makes a loader panic, and sizes are capped (see
//! [`LoadOptions`]).
//!
//! Conventions:
//!
//! - Face index = order of faces in the file: OBJ `f` lines in file order
//!   across all objects and groups; glTF primitives in document order (scene
//!   nodes depth first), faces in index order. A merged triangle pair takes the
//!   lower index ([`Mesh::face_source`]).
//! - A face is a convex polygon with 3 or more corners, in file order. Its
//!   normal is Newell's vector. It is planar when every corner lies within
//!   `1e-6 · D` of the plane through the corners' mean (D = largest
//!   corner-to-corner distance); see [`tolerance`].
//! - Positions are in model space, as read (glTF node transforms applied).
//!
//! What happens to each face is chosen with [`LoadOptions`]: [`FacePolicy`]
//! (quads only, any polygon, or merge triangle pairs into quads),
//! [`NonConvexPolicy`] and [`NonPlanarPolicy`]. Zero-area faces are dropped and
//! counted.
//!
//! # Example
//!
//! ```
//! use obj_quads::{FacePolicy, LoadOptions, load_obj_str};
//!
//! // A unit square as one quad, plus a triangle.
//! let obj = "\
//! v 0 0 0
//! v 1 0 0
//! v 1 1 0
//! v 0 1 0
//! v 0 2 0
//! f 1 2 3 4
//! f 4 3 5
//! ";
//! let (mesh, report) = load_obj_str(obj, &LoadOptions::default())?;
//! assert_eq!(mesh.face_count(), 2);
//! assert_eq!(mesh.face(0), Some(&[0u32, 1, 2, 3][..]));
//! assert_eq!(mesh.arity_histogram().get(&4), Some(&1));
//! assert_eq!(report.faces_read, 2);
//!
//! // Under QuadsOnly the triangle is an error that names it.
//! let quads_only = LoadOptions::DEFAULT.with_face_policy(FacePolicy::QuadsOnly);
//! let err = load_obj_str(obj, &quads_only).unwrap_err();
//! assert!(err.to_string().contains("face 1 (line 7)"), "{err}");
//! # Ok::<(), obj_quads::LoadError>(())
//! ```
//!
//! # Feature flags
//!
//! - `obj` (default): OBJ + MTL loading through `tobj` ([`load_obj`],
//!   [`load_obj_str`], [`load_obj_reader`]).
//! - `gltf` (default): glTF 2.0 and GLB loading through `gltf`
//!   ([`load_gltf`], [`load_gltf_slice`]). Images are not decoded; texture
//!   paths are recorded.
//!
//! [`load`] dispatches on the file extension and reports
//! [`LoadError::UnsupportedFormat`] for formats whose feature is off.

#[cfg_attr(not(any(feature = "obj", feature = "gltf")), allow(dead_code))]
mod build;
mod error;
#[cfg_attr(not(any(feature = "obj", feature = "gltf")), allow(dead_code))]
mod geometry;
pub mod limits;
mod mesh;
mod options;
#[cfg_attr(not(any(feature = "obj", feature = "gltf")), allow(dead_code))]
mod paths;
#[cfg(feature = "texture")]
mod texture;
pub mod tolerance;

#[cfg(feature = "gltf")]
mod gltf_load;
#[cfg(feature = "obj")]
mod obj;

/// The crate's README: its examples are compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

use std::io::Read;
use std::path::Path;

pub use error::{FaceLocation, LoadError};
#[cfg(feature = "gltf")]
pub use gltf_load::{
    GltfCamera, GltfInstance, GltfProjection, GltfScene, load_gltf, load_gltf_cameras,
    load_gltf_cameras_slice, load_gltf_scene, load_gltf_scene_slice, load_gltf_slice,
};
pub use mesh::{AlphaMode, EmbeddedTexture, Material, Mesh, WrapMode};
#[cfg(feature = "obj")]
pub use obj::{load_obj, load_obj_reader, load_obj_str};
pub use options::{FacePolicy, LoadOptions, LoadReport, NonConvexPolicy, NonPlanarPolicy};
#[cfg(feature = "texture")]
pub use texture::{
    Texture, TextureFormat, TextureHeader, decode_texture, load_texture, texture_header,
};

/// Loads a model, choosing the loader by extension (case-insensitive):
/// `.obj`, `.gltf` or `.glb`.
///
/// ```
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/models/assimp-obj/box.obj");
/// let (mesh, _report) = obj_quads::load(path, &Default::default()).unwrap();
/// assert_eq!(mesh.face_count(), 6);
/// ```
pub fn load(
    path: impl AsRef<Path>,
    options: &LoadOptions,
) -> Result<(Mesh, LoadReport), LoadError> {
    let path = path.as_ref();
    let _ = options; // unused when both format features are off
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match extension.as_str() {
        #[cfg(feature = "obj")]
        "obj" => load_obj(path, options),
        #[cfg(feature = "gltf")]
        "gltf" | "glb" => load_gltf(path, options),
        _ => Err(LoadError::UnsupportedFormat {
            file: path.display().to_string(),
            extension,
        }),
    }
}

/// Display name of in-memory input in error messages.
#[allow(dead_code)]
pub(crate) fn obj_memory_name() -> String {
    "<memory>".to_owned()
}

/// Reads a whole file, refusing files larger than `max` bytes.
#[allow(dead_code)]
pub(crate) fn read_file_capped(path: &Path, file: &str, max: u64) -> Result<Vec<u8>, LoadError> {
    let io = |source| LoadError::Io {
        file: file.to_owned(),
        source,
    };
    // Check before opening: opening a FIFO or a device can block or have effects.
    let not_regular = || {
        io(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a regular file",
        ))
    };
    if !std::fs::metadata(path).map_err(io)?.is_file() {
        return Err(not_regular());
    }
    let f = std::fs::File::open(path).map_err(io)?;
    let meta = f.metadata().map_err(io)?;
    if !meta.is_file() {
        return Err(io(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a regular file",
        )));
    }
    if meta.len() > max {
        return Err(LoadError::TooLarge {
            file: file.to_owned(),
            what: "file size in bytes",
            actual: meta.len(),
            limit: max,
        });
    }
    read_capped(f, file, max)
}

/// Reads everything from `reader`, failing once more than `max` bytes arrive.
#[allow(dead_code)]
pub(crate) fn read_capped(reader: impl Read, file: &str, max: u64) -> Result<Vec<u8>, LoadError> {
    let mut bytes = Vec::new();
    reader
        .take(max.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|source| LoadError::Io {
            file: file.to_owned(),
            source,
        })?;
    if bytes.len() as u64 > max {
        return Err(LoadError::TooLarge {
            file: file.to_owned(),
            what: "input size in bytes",
            actual: bytes.len() as u64,
            limit: max,
        });
    }
    Ok(bytes)
}
