//! Load options and the load report.

use crate::limits;

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

/// Options for every loader: face policies, resource limits and path
/// confinement.
///
/// The struct is `#[non_exhaustive]`: start from [`LoadOptions::DEFAULT`] (or
/// `LoadOptions::default()`) and change fields with the `with_*` builders, or
/// assign to a mutable value.
///
/// ```
/// use obj_quads::{FacePolicy, LoadOptions};
/// let options = LoadOptions::DEFAULT
///     .with_face_policy(FacePolicy::MergeTriangles)
///     .with_max_faces(1_000_000);
/// assert_eq!(options.max_face_corners, 1024);
/// assert!(!options.allow_outside_paths);
///
/// let mut trusted = LoadOptions::default();
/// trusted.allow_outside_paths = true; // the caller trusts the file
/// ```
///
/// Every limit's default is defined once, in [`limits`].
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub struct LoadOptions {
    /// Which faces are accepted (default [`FacePolicy::Polygons`]).
    pub face_policy: FacePolicy,
    /// What to do with non-convex faces (default: triangulate).
    pub non_convex: NonConvexPolicy,
    /// What to do with non-planar faces (default: keep).
    pub non_planar: NonPlanarPolicy,
    /// Largest accepted face arity (default [`limits::DEFAULT_MAX_FACE_CORNERS`]).
    pub max_face_corners: usize,
    /// Largest accepted number of faces read (default [`limits::DEFAULT_MAX_FACES`]).
    pub max_faces: usize,
    /// Largest accepted number of vertices (default [`limits::DEFAULT_MAX_VERTICES`]);
    /// OBJ texture coordinates (`vt`) and normals (`vn`) are capped by it too.
    pub max_vertices: usize,
    /// Largest accepted model file, MTL library and glTF buffer, in bytes
    /// (default [`limits::DEFAULT_MAX_FILE_BYTES`]).
    pub max_file_bytes: u64,
    /// Deepest accepted glTF node hierarchy (default [`limits::DEFAULT_MAX_NODE_DEPTH`]).
    pub max_node_depth: usize,
    /// Most node visits in one glTF scene walk (default [`limits::DEFAULT_MAX_NODE_VISITS`]).
    pub max_node_visits: usize,
    /// Largest accepted texture width and height in pixels, checked from the
    /// image header before decoding (default [`limits::DEFAULT_MAX_TEXTURE_SIDE`]).
    pub max_texture_side: u32,
    /// Largest accepted texture pixel count, checked from the image header
    /// before decoding (default [`limits::DEFAULT_MAX_TEXTURE_PIXELS`]).
    pub max_texture_pixels: u64,
    /// Largest accepted texture file in bytes (default
    /// [`limits::DEFAULT_MAX_TEXTURE_FILE_BYTES`]).
    pub max_texture_file_bytes: u64,
    /// Read files that a model names (glTF buffers and images, OBJ `mtllib`,
    /// MTL `map_Kd`) even when they resolve outside the model's folder (after
    /// `..`, symbolic links or absolute paths). Default `false`: such buffers
    /// and MTL libraries are a [`LoadError::PathOutsideModel`](crate::LoadError::PathOutsideModel),
    /// such textures are dropped with a warning. Set it only for files you trust.
    pub allow_outside_paths: bool,
}

impl LoadOptions {
    /// The defaults: [`FacePolicy::Polygons`], triangulate non-convex faces, keep
    /// non-planar faces, the limits of [`limits`], no paths outside the
    /// model's folder.
    pub const DEFAULT: LoadOptions = LoadOptions {
        face_policy: FacePolicy::Polygons,
        non_convex: NonConvexPolicy::Triangulate,
        non_planar: NonPlanarPolicy::Keep,
        max_face_corners: limits::DEFAULT_MAX_FACE_CORNERS,
        max_faces: limits::DEFAULT_MAX_FACES,
        max_vertices: limits::DEFAULT_MAX_VERTICES,
        max_file_bytes: limits::DEFAULT_MAX_FILE_BYTES,
        max_node_depth: limits::DEFAULT_MAX_NODE_DEPTH,
        max_node_visits: limits::DEFAULT_MAX_NODE_VISITS,
        max_texture_side: limits::DEFAULT_MAX_TEXTURE_SIDE,
        max_texture_pixels: limits::DEFAULT_MAX_TEXTURE_PIXELS,
        max_texture_file_bytes: limits::DEFAULT_MAX_TEXTURE_FILE_BYTES,
        allow_outside_paths: false,
    };

    /// Sets [`face_policy`](Self::face_policy).
    #[must_use]
    pub const fn with_face_policy(mut self, policy: FacePolicy) -> Self {
        self.face_policy = policy;
        self
    }

    /// Sets [`non_convex`](Self::non_convex).
    #[must_use]
    pub const fn with_non_convex(mut self, policy: NonConvexPolicy) -> Self {
        self.non_convex = policy;
        self
    }

    /// Sets [`non_planar`](Self::non_planar).
    #[must_use]
    pub const fn with_non_planar(mut self, policy: NonPlanarPolicy) -> Self {
        self.non_planar = policy;
        self
    }

    /// Sets [`max_face_corners`](Self::max_face_corners).
    #[must_use]
    pub const fn with_max_face_corners(mut self, max: usize) -> Self {
        self.max_face_corners = max;
        self
    }

    /// Sets [`max_faces`](Self::max_faces).
    #[must_use]
    pub const fn with_max_faces(mut self, max: usize) -> Self {
        self.max_faces = max;
        self
    }

    /// Sets [`max_vertices`](Self::max_vertices).
    #[must_use]
    pub const fn with_max_vertices(mut self, max: usize) -> Self {
        self.max_vertices = max;
        self
    }

    /// Sets [`max_file_bytes`](Self::max_file_bytes).
    #[must_use]
    pub const fn with_max_file_bytes(mut self, max: u64) -> Self {
        self.max_file_bytes = max;
        self
    }

    /// Sets [`max_node_depth`](Self::max_node_depth).
    #[must_use]
    pub const fn with_max_node_depth(mut self, max: usize) -> Self {
        self.max_node_depth = max;
        self
    }

    /// Sets [`max_node_visits`](Self::max_node_visits).
    #[must_use]
    pub const fn with_max_node_visits(mut self, max: usize) -> Self {
        self.max_node_visits = max;
        self
    }

    /// Sets [`max_texture_side`](Self::max_texture_side).
    #[must_use]
    pub const fn with_max_texture_side(mut self, max: u32) -> Self {
        self.max_texture_side = max;
        self
    }

    /// Sets [`max_texture_pixels`](Self::max_texture_pixels).
    #[must_use]
    pub const fn with_max_texture_pixels(mut self, max: u64) -> Self {
        self.max_texture_pixels = max;
        self
    }

    /// Sets [`max_texture_file_bytes`](Self::max_texture_file_bytes).
    #[must_use]
    pub const fn with_max_texture_file_bytes(mut self, max: u64) -> Self {
        self.max_texture_file_bytes = max;
        self
    }

    /// Sets [`allow_outside_paths`](Self::allow_outside_paths): `true` only
    /// for files you trust.
    #[must_use]
    pub const fn with_allow_outside_paths(mut self, allow: bool) -> Self {
        self.allow_outside_paths = allow;
        self
    }
}

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions::DEFAULT
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
