//! The crate's error type.

use thiserror::Error;

/// Why a [`PolygonMesh`](crate::PolygonMesh) could not be built.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum MeshError {
    /// A position has a NaN or infinite coordinate.
    #[error("vertex {vertex} has a NaN or infinite coordinate")]
    NonFinitePosition {
        /// Vertex index (0-based).
        vertex: usize,
    },
    /// A face has fewer than 3 corners (or absurdly many).
    #[error("face {face} has {corners} corners; a face needs 3 to {max}", max = crate::mesh::MAX_FACE_CORNERS)]
    BadArity {
        /// Face index (0-based).
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
    /// A face refers to a vertex that does not exist.
    #[error("face {face} refers to vertex {index}, but there are only {positions} positions")]
    IndexOutOfRange {
        /// Face index (0-based).
        face: usize,
        /// The bad index.
        index: u32,
        /// Number of positions.
        positions: usize,
    },
    /// The mesh has more corners than 32-bit indices can address.
    #[error("the mesh has more than 2^32 face corners")]
    TooLarge,
    /// The mesh has no face with positive area.
    #[error("the mesh has no face with positive area")]
    Empty,
    /// A planar face that is not convex, or whose corners go round more than once (a star, a
    /// corner repeated out of turn): the sorters order convex pieces. Or a non-planar face
    /// whose fan of triangles would cover itself (a corner repeated out of turn, a fold with
    /// no net area). Triangulate it first (obj-quads' loaders do).
    #[error("face {face} is not convex (triangulate it first)")]
    NonConvex {
        /// The face index.
        face: usize,
    },
    /// The mesh's bounding-box diagonal is outside the range f64 orders exactly
    /// ([`MIN_EXTENT_ABS`](crate::tolerance::MIN_EXTENT_ABS) to
    /// [`MAX_EXTENT_ABS`](crate::tolerance::MAX_EXTENT_ABS)).
    #[error(
        "the mesh's bounding box is about 1e{exponent} across; face-sort orders meshes \
         whose diagonal is 1e-60 to 1e60 (scale the positions)"
    )]
    ExtentOutOfRange {
        /// Decimal exponent of the bounding box's largest side (`floor(log10 side)`).
        exponent: i32,
    },
}

/// Why a [`BspTree`](crate::BspTree) could not be built within its options.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum BspError {
    /// The splits would have made more fragments than the budget
    /// ([`BspOptions::fragment_budget`](crate::BspOptions::fragment_budget)) allows.
    #[error(
        "the BSP tree over {pieces} pieces needs more than its budget of {budget} fragments; \
         raise BspOptions::max_fragments_per_piece or use another exact sorter (Newell)"
    )]
    FragmentBudget {
        /// Pieces of the geometry.
        pieces: usize,
        /// The budget that was exceeded (fragments).
        budget: usize,
    },
}
