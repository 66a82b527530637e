//! Load options and the load report.

use crate::tolerance;

/// Which faces the caller accepts, and whether triangles are paired into quads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum FacePolicy {
    /// Every face must be a quad; any other face is a [`LoadError::NotAQuad`](crate::LoadError::NotAQuad).
    /// Faces that would need splitting (non-convex, or non-planar under
    /// [`NonPlanarPolicy::SplitFan`]) are errors too.
    QuadsOnly,
    /// Keep every planar convex polygon of any arity (the default).
    #[default]
    Polygons,
    /// Like [`Polygons`](Self::Polygons), then pair adjacent coplanar triangles
    /// whose union is a convex quad into quads. A merged pair takes the lower
    /// face index and sits at that position in the face order.
    MergeTriangles,
}

/// What to do with a face that is not convex.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum NonConvexPolicy {
    /// Split it into triangles by ear clipping in the face plane (the default).
    #[default]
    Triangulate,
    /// Fail with [`LoadError::NonConvexFace`](crate::LoadError::NonConvexFace).
    Reject,
}

/// What to do with a face whose corners are not within `1e-6 · D` of one plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum NonPlanarPolicy {
    /// Keep it as it is and count it (the default; downstream treats it as a
    /// fan of triangles).
    #[default]
    Keep,
    /// Split it into fan triangles from its first corner.
    SplitFan,
    /// Fail with [`LoadError::NonPlanarFace`](crate::LoadError::NonPlanarFace).
    Reject,
}

/// Options for every loader.
///
/// ```
/// use obj_quads::{FacePolicy, LoadOptions};
/// let options = LoadOptions {
///     face_policy: FacePolicy::MergeTriangles,
///     ..LoadOptions::default()
/// };
/// assert_eq!(options.max_face_corners, 1024);
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LoadOptions {
    /// Which faces are accepted (default [`FacePolicy::Polygons`]).
    pub face_policy: FacePolicy,
    /// What to do with non-convex faces (default: triangulate).
    pub non_convex: NonConvexPolicy,
    /// What to do with non-planar faces (default: keep).
    pub non_planar: NonPlanarPolicy,
    /// Largest accepted face arity (default 1024).
    pub max_face_corners: usize,
    /// Largest accepted number of faces read (default 2^24).
    pub max_faces: usize,
    /// Largest accepted number of vertices (default 2^26).
    pub max_vertices: usize,
    /// Largest accepted input file (and glTF buffer) size in bytes (default 1 GiB).
    pub max_file_bytes: u64,
}

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            face_policy: FacePolicy::default(),
            non_convex: NonConvexPolicy::default(),
            non_planar: NonPlanarPolicy::default(),
            max_face_corners: tolerance::DEFAULT_MAX_FACE_CORNERS,
            max_faces: tolerance::DEFAULT_MAX_FACES,
            max_vertices: tolerance::DEFAULT_MAX_VERTICES,
            max_file_bytes: tolerance::DEFAULT_MAX_FILE_BYTES,
        }
    }
}

/// What happened during a load, returned alongside the mesh.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct LoadReport {
    /// Faces read from the file (OBJ `f` lines; glTF triangles of every drawn
    /// primitive instance).
    pub faces_read: usize,
    /// Faces in the resulting mesh.
    pub faces_kept: usize,
    /// Zero-area faces (relative to face size) that were dropped.
    pub degenerate_dropped: usize,
    /// Faces found non-planar beyond `1e-6 · D` (kept, split or rejected per
    /// [`NonPlanarPolicy`]).
    pub non_planar: usize,
    /// Non-convex faces split into triangles.
    pub non_convex_split: usize,
    /// Triangles absorbed into quads by [`FacePolicy::MergeTriangles`] (two per
    /// quad formed).
    pub triangles_merged: usize,
    /// glTF primitives skipped because their mode is not `Triangles`.
    pub skipped_primitives: usize,
    /// Things worth knowing that did not stop the load (missing MTL, embedded
    /// textures, dropped texture coordinates, ...).
    pub warnings: Vec<String>,
}
