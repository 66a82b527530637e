//! The one error type of the crate.

use std::fmt;

/// Where a face sits in the input: object (OBJ object/group or glTF mesh and
/// primitive), face index in file order, and the source line where known.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FaceLocation {
    /// Name of the OBJ object/group, or `mesh N primitive M` for glTF.
    pub object: String,
    /// Face index in file order (the crate's face-index convention).
    pub face: usize,
    /// 1-based line number in an OBJ file, when known.
    pub line: Option<usize>,
}

impl fmt::Display for FaceLocation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "object `{}`, face {}", self.object, self.face)?;
        if let Some(line) = self.line {
            write!(f, " (line {line})")?;
        }
        Ok(())
    }
}

/// Formats an optional line number as `, line N` (or nothing).
pub(crate) struct LineSuffix(pub Option<usize>);

impl fmt::Display for LineSuffix {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(line) => write!(f, ", line {line}"),
            None => Ok(()),
        }
    }
}

/// Everything that can go wrong while loading or building a [`Mesh`](crate::Mesh).
///
/// Every message names the file (`<memory>` for in-memory input) and, where it
/// applies, the object, the face index in file order and the line.
///
/// `file` is the input's **display name**, not a path: loaders also read strings, readers,
/// data URIs and GLB chunks, which have none (raster-sink's `RasterError { path }` names a
/// file it opened). Where a real path matters it has its own field (`PathOutsideModel`).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LoadError {
    /// The file could not be opened or read.
    #[error("{file}: cannot read file: {source}")]
    Io {
        /// The file.
        file: String,
        /// The underlying I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The bytes are not valid text (OBJ must be UTF-8).
    #[error("{file}{}: not valid UTF-8 text", LineSuffix(*line))]
    InvalidText {
        /// The file.
        file: String,
        /// Line holding the first bad byte.
        line: Option<usize>,
    },
    /// The file's syntax or structure is invalid.
    #[error("{file}{}: {detail}", LineSuffix(*line))]
    Parse {
        /// The file.
        file: String,
        /// Line, where known.
        line: Option<usize>,
        /// What is wrong.
        detail: String,
    },
    /// A face refers to a vertex that does not exist (index 0, or past the end).
    #[error("{file}: {at}: vertex index {index} out of range ({count} vertices)")]
    IndexOutOfRange {
        /// The file.
        file: String,
        /// The face.
        at: FaceLocation,
        /// The index as written (OBJ: 1-based or negative; glTF: 0-based).
        index: i64,
        /// Number of vertices available.
        count: usize,
    },
    /// A position (or other coordinate) is NaN or infinite.
    #[error("{file}{}: {what} is not finite", LineSuffix(*line))]
    NonFiniteCoordinate {
        /// The file.
        file: String,
        /// Line, where known.
        line: Option<usize>,
        /// Which value, e.g. `vertex 12`.
        what: String,
    },
    /// The model has no faces (after dropping degenerate faces).
    #[error("{file}: model is empty: {detail}")]
    EmptyModel {
        /// The file.
        file: String,
        /// Why, e.g. how many faces were read and dropped.
        detail: String,
    },
    /// A face has fewer than 3 corners.
    #[error("{file}: {at}: face with fewer than 3 corners ({corners})")]
    TooFewCorners {
        /// The file.
        file: String,
        /// The face.
        at: FaceLocation,
        /// Its corner count.
        corners: usize,
    },
    /// A face has more corners than [`LoadOptions::max_face_corners`](crate::LoadOptions::max_face_corners).
    #[error("{file}: {at}: face has {corners} corners, more than the limit {max}")]
    TooManyCorners {
        /// The file.
        file: String,
        /// The face.
        at: FaceLocation,
        /// Its corner count.
        corners: usize,
        /// The limit.
        max: usize,
    },
    /// [`FacePolicy::QuadsOnly`](crate::FacePolicy::QuadsOnly) met a face that is not a quad.
    #[error("{file}: {at}: face has {corners} corners but only quads are accepted")]
    NotAQuad {
        /// The file.
        file: String,
        /// The face.
        at: FaceLocation,
        /// Its corner count.
        corners: usize,
    },
    /// A non-planar face under [`NonPlanarPolicy::Reject`](crate::NonPlanarPolicy::Reject)
    /// (or one that would have to be split under `QuadsOnly`).
    #[error("{file}: {at}: face is not planar (off-plane distance {distance:e}, limit {limit:e})")]
    NonPlanarFace {
        /// The file.
        file: String,
        /// The face.
        at: FaceLocation,
        /// Largest corner distance from the face plane.
        distance: f64,
        /// Allowed distance (`1e-6 · D`).
        limit: f64,
    },
    /// A non-convex face under [`NonConvexPolicy::Reject`](crate::NonConvexPolicy::Reject)
    /// (or one that would have to be split under `QuadsOnly`).
    #[error("{file}: {at}: face is not convex")]
    NonConvexFace {
        /// The file.
        file: String,
        /// The face.
        at: FaceLocation,
    },
    /// The input exceeds one of the size limits.
    #[error("{file}: too large: {what} is {actual}, limit {limit}")]
    TooLarge {
        /// The file.
        file: String,
        /// What was counted.
        what: &'static str,
        /// The value found (or a lower bound).
        actual: u64,
        /// The limit.
        limit: u64,
    },
    /// A file the model names (glTF buffer or image, OBJ `mtllib`) resolves
    /// outside the model's folder and
    /// [`LoadOptions::allow_outside_paths`](crate::LoadOptions::allow_outside_paths)
    /// is off.
    #[error(
        "{file}: {what} `{reference}` resolves to {} outside the model's folder {}; \
         not read (LoadOptions::allow_outside_paths allows it)",
        resolved.display(),
        folder.display()
    )]
    PathOutsideModel {
        /// The model (or MTL) file that names the path.
        file: String,
        /// What names it, e.g. `buffer 0 uri` or `mtllib`.
        what: String,
        /// The path or URI as written.
        reference: String,
        /// Where it resolves to.
        resolved: std::path::PathBuf,
        /// The model's folder.
        folder: std::path::PathBuf,
    },
    /// A texture image cannot be decoded (unknown format, corrupt data).
    /// Size-limit breaches are [`LoadError::TooLarge`].
    #[error("{file}: texture: {detail}")]
    Texture {
        /// The image file.
        file: String,
        /// What is wrong.
        detail: String,
    },
    /// The file extension is not one of `.obj`, `.gltf`, `.glb` (or its feature is off).
    #[error("{file}: unsupported model format `{extension}` (expected .obj, .gltf or .glb)")]
    UnsupportedFormat {
        /// The file.
        file: String,
        /// The extension found (empty if none).
        extension: String,
    },
    /// A glTF document is invalid or cannot be read.
    #[error("{file}: glTF: {detail}")]
    Gltf {
        /// The file.
        file: String,
        /// What is wrong.
        detail: String,
    },
    /// Invalid arguments to [`Mesh::from_faces`](crate::Mesh::from_faces) and friends.
    #[error("invalid mesh: {detail}")]
    InvalidMesh {
        /// What is wrong.
        detail: String,
    },
}
