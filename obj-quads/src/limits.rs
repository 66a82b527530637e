//! Default resource limits, defined once. Every limit is a field of
//! [`LoadOptions`](crate::LoadOptions) that the caller may change; these are
//! the values of [`LoadOptions::DEFAULT`](crate::LoadOptions::DEFAULT).
//!
//! A breach is a typed error ([`LoadError::TooLarge`](crate::LoadError::TooLarge),
//! [`LoadError::TooManyCorners`](crate::LoadError::TooManyCorners),
//! [`LoadError::Gltf`](crate::LoadError::Gltf) for the node walk,
//! [`LoadError::Texture`](crate::LoadError::Texture) for images) naming the
//! file and what was counted.

/// Default cap on the number of corners of one face.
pub const DEFAULT_MAX_FACE_CORNERS: usize = 1024;

/// Default cap on the number of faces in one model: 2²² (4,194,304). A loaded face costs
/// about 40 bytes of mesh and as much again while loading, so a model at the cap stays near
/// half a GiB; a larger file (a 10-million-face OBJ) is a
/// [`LoadError::TooLarge`](crate::LoadError::TooLarge) from the first pass over its text,
/// before any face is built. Raise it with
/// [`LoadOptions::with_max_faces`](crate::LoadOptions::with_max_faces).
pub const DEFAULT_MAX_FACES: usize = 1 << 22;

/// Default cap on the number of vertices (positions) in one model.
pub const DEFAULT_MAX_VERTICES: usize = 1 << 26;

/// Default cap on the size of an input file (model, MTL library, external
/// glTF buffer), in bytes: 1 GiB.
pub const DEFAULT_MAX_FILE_BYTES: u64 = 1 << 30;

/// Default cap on the depth of a glTF node hierarchy (root = depth 1).
pub const DEFAULT_MAX_NODE_DEPTH: usize = 64;

/// Default cap on node visits in one glTF scene walk (a node shared by
/// several parents is visited once per parent).
pub const DEFAULT_MAX_NODE_VISITS: usize = 1 << 16;

/// Default cap on a texture's width and on its height, in pixels, read from
/// the image header before decoding.
pub const DEFAULT_MAX_TEXTURE_SIDE: u32 = 16_384;

/// Default cap on a texture's pixel count (width × height), read from the
/// image header before decoding: 2^26 pixels, 256 MiB as RGBA8.
pub const DEFAULT_MAX_TEXTURE_PIXELS: u64 = 1 << 26;

/// Default cap on a texture file's size in bytes: 256 MiB.
pub const DEFAULT_MAX_TEXTURE_FILE_BYTES: u64 = 1 << 28;

/// Hard cap on the corners of one face of any [`Mesh`](crate::Mesh).
pub const MESH_MAX_FACE_CORNERS: usize = 1 << 16;
