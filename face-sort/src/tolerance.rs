//! Every tolerance the crate uses, in one place.
//!
//! All of them are *relative*: multiply by the model's bounding-box diagonal `L`
//! (see [`Bounds::diagonal`](crate::Bounds::diagonal)) or by a face's own size.

/// A face is planar when every corner lies within `PLANARITY · D` of its fitted plane,
/// `D` being the face's largest corner-to-corner distance (CONVENTIONS.md).
pub const PLANARITY: f64 = 1e-6;

/// A piece whose Newell normal is shorter than `DEGENERATE_AREA · D²` has no area and is dropped.
pub const DEGENERATE_AREA: f64 = 1e-12;

/// Plane-side classification (BSP build, Newell tests, splits): a point within
/// `PLANE_SIDE · L` of a plane is on it. Far below the oracle's depth tolerance and far
/// above f64 round-off of centred coordinates (about `1e-16 · L`).
pub const PLANE_SIDE: f64 = 1e-11;

/// Order-violation depth tolerance: a later polygon must lie behind an earlier one by
/// more than `ORACLE_DEPTH · L` in view depth to count (CONVENTIONS.md).
pub const ORACLE_DEPTH: f64 = 1e-9;

/// Two projections overlap "with positive area" when their intersection is larger than
/// `OVERLAP_AREA · L²` (in view units, resolution-free).
pub const OVERLAP_AREA: f64 = 1e-14;

/// Perspective near plane: geometry is clipped to `w ≥ NEAR_W` (CONVENTIONS.md).
pub const NEAR_W: f64 = 1e-3;
