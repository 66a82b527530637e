//! Geometric tolerances, all relative to the size of the face at hand.
//!
//! `D` is a face's largest corner-to-corner distance.

/// A face is planar when every corner lies within `PLANARITY_REL · D` of the
/// plane through the corners' mean with the Newell normal.
pub const PLANARITY_REL: f64 = 1e-6;

/// A face is degenerate (dropped) when its area (half the Newell vector's
/// length) is at most `DEGENERATE_AREA_REL · D²`.
pub const DEGENERATE_AREA_REL: f64 = 1e-12;

/// Convexity test: a corner counts as turning the wrong way only when the
/// cross product of its two edges (in the face plane) is below
/// `-CONVEXITY_REL · D²`; smaller values count as straight.
pub const CONVEXITY_REL: f64 = 1e-9;

/// Triangle merging: the shared-edge corners must turn strictly convex, by at
/// least `MERGE_CONVEXITY_REL · D²` (the cross product of the two edges).
pub const MERGE_CONVEXITY_REL: f64 = 1e-9;

/// Default cap on the number of corners of one face.
pub const DEFAULT_MAX_FACE_CORNERS: usize = 1024;

/// Default cap on the number of faces in one model.
pub const DEFAULT_MAX_FACES: usize = 1 << 24;

/// Default cap on the number of vertices (positions) in one model.
pub const DEFAULT_MAX_VERTICES: usize = 1 << 26;

/// Default cap on the size of an input file (and of each external glTF buffer), in bytes.
pub const DEFAULT_MAX_FILE_BYTES: u64 = 1 << 30;

/// Hard cap on the corners of one face of any [`Mesh`](crate::Mesh).
pub const MESH_MAX_FACE_CORNERS: usize = 1 << 16;
