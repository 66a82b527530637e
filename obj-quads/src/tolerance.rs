//! Geometric tolerances, all relative to the size of the face at hand.
//!
//! `D` is a face's largest corner-to-corner distance. Names follow the workspace's rule (a
//! bare name is relative to the size its doc names), as in `face_sort::tolerance`.

/// A face is planar when every corner lies within `PLANARITY · D` of the
/// plane through the corners' mean with the Newell normal.
pub const PLANARITY: f64 = 1e-6;

/// A face is degenerate (dropped) when its area (half the Newell vector's
/// length) is at most `DEGENERATE_AREA · D²`.
pub const DEGENERATE_AREA: f64 = 1e-12;

/// Convexity test: a corner counts as turning the wrong way only when the
/// cross product of its two edges (in the face plane) is below
/// `-CONVEXITY · D²`; smaller values count as straight.
pub const CONVEXITY: f64 = 1e-9;

/// Triangle merging: the shared-edge corners must turn strictly convex, by at
/// least `MERGE_CONVEXITY · D²` (the cross product of the two edges).
pub const MERGE_CONVEXITY: f64 = 1e-9;
