//! Every tolerance of the crate, in one place (the workspace's naming rule: a bare name is
//! relative to a scale the caller states, `_RAD` is an angle in radians).

/// An event function `a·cos θ + b·sin θ + c` whose amplitude `hypot(a, b)` and constant `|c|`
/// are both at most this times its scale (the magnitudes that formed it) is identically zero:
/// its sign never changes, so it has no event (a face edge-on all the way round).
pub const IDENTICALLY_ZERO: f64 = 1e-12;

/// When `|c| / hypot(a, b)` is within this of 1 the two roots meet: a tangency, where the
/// function touches zero without changing sign. No event.
pub const TANGENT: f64 = 1e-12;

/// Roots (of different functions) closer than this, in radians, are one breakpoint
/// (rounding of one root computation). Roots also merge when
/// closer than the sum of their uncertainties ([`ROOT_NOISE`]).
pub const SAME_ROOT_RAD: f64 = 1e-14;

/// The rounding error, relative to an event function's scale, of evaluating it in f64 the
/// way the live sorter does (a rotation built from `sin θ`, `cos θ`, then dot products):
/// a root is known only to within this times `scale / |f′|`. Between two roots closer
/// than their uncertainties no f64 evaluation can tell which side it is on, so they are one
/// breakpoint.
pub const ROOT_NOISE: f64 = 1e-13;

/// How far, in radians, on each side of a breakpoint `verify` evaluates the event function
/// and the live sorter (less when the neighbouring cells are narrower).
pub const VERIFY_SIDE_RAD: f64 = 1e-7;

/// Two-axis bakes: a cell continues from one pitch slab into the next only where its gap
/// between two curves is at least this wide (radians of yaw) at the boundary. A narrower gap
/// may pinch to a point there, through which a third curve can pass (three curves crossing
/// at one point, or crossings closer than their rounding), and then the two sides differ.
/// Too large only costs cells, never exactness.
pub const CONTINUE_GAP_RAD: f64 = 1e-9;

/// Two-axis bakes: a crossing of two event circles whose direction has `|cos yaw|` at most this
/// lies on the chart's pole lines (yaw ±90°), where every pitch gives the same view: it cuts
/// no pitch slab.
pub const CHART_POLE: f64 = 1e-12;

/// Two-axis bakes: circles whose normals make an angle with a sine at most this are parallel
/// and have no isolated crossing.
pub const PARALLEL_SIN: f64 = 1e-12;

/// Two-axis `verify_two_axes`: a gap narrower than this (radians of yaw) at the sampled pitch
/// is not sampled inside (no f64 angle there is clearly between its curves).
pub const VERIFY_MIN_GAP_RAD: f64 = 1e-9;

/// Two-axis `verify_two_axes`: a curve whose neighbouring gaps leave less than this (radians
/// of yaw) on either side is not checked for a sign change.
pub const VERIFY_MIN_SIDE_RAD: f64 = 1e-12;

/// Picture bakes: a corner within this times the model's diagonal `L` of a plane lies on it
/// when deciding which side of another piece's plane a piece lies on, and whether two pieces
/// cross. Below the oracle's depth tolerance (`1e-9 · L`), so a piece that dips behind a
/// plane by less than this is never a violation.
pub const PICTURE_SIDE: f64 = 1e-12;

/// Picture bakes: an edge of a piece shorter than this times the model's diagonal `L` (two
/// corners a rounding apart) has no direction rounding can tell, so its line separates no
/// projections. Leaving it out of the separating-axis test only widens the piece's
/// projection by less than that: the overlap found can only grow.
pub const PICTURE_SHORT_EDGE: f64 = 1e-12;

/// Picture bakes: every arc where a condition holds is widened (every arc that removes one
/// shrunk) by this many radians, against the rounding of its ends (about `1e-15` rad). Too
/// large makes events that coincide (a fold turning edge-on ends two pairs' overlap as it
/// starts a third's) overlap by twice this, which [`EVENT_GAP_RAD`] must absorb.
pub const ARC_MARGIN_RAD: f64 = 1e-12;

/// Picture bakes: the sight cone of a pair (the directions from the piece behind to the piece
/// in front) is widened by this: its cosine lowered by this, the eye's least distance to its
/// apex shortened by this fraction, and the front piece's radius grown by it. Far above the
/// rounding of unit-vector products (about `1e-15`); too large only keeps arcs longer.
pub const SIGHT_SLACK: f64 = 1e-9;

/// Picture bakes in perspective: the orbiting eye must stay farther from the centre than
/// every corner by this fraction of its distance (the near plane `w ≥ 1e-3`).
pub const NEAR_EYE: f64 = 1e-3;

/// Picture verification: degrees inside each end of a cell where the oracle also checks.
pub const PICTURE_BOUNDARY_DEG: f64 = 1e-6;

/// Picture bakes: the swept screen boxes of the candidate search grow by this fraction more
/// than the distance a point can move within a bin (rounding of the rotation).
pub const BOX_SLACK: f64 = 1e-9;

/// Picture bakes: constraints whose arcs end within this many radians after the start of the
/// span that opens a cell end with the event that opens it (their computed ends and the new
/// constraint's start are one event, rounded and widened apart), so they leave the cell. The
/// cell begins at the event itself, that span's start plus [`ARC_MARGIN_RAD`], where they
/// have ended (beginning at the widened start instead left them out while they still held:
/// found by fuzzing). Four times [`ARC_MARGIN_RAD`]. A cell no longer than this is dropped
/// and the next starts in its place (exact except within this of its start): a zero-length
/// cell's list held only at its one angle, and there it was wrong (found by fuzzing).
pub const EVENT_GAP_RAD: f64 = 4.0 * ARC_MARGIN_RAD;
