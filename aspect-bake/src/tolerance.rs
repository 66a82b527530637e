//! Every tolerance of the crate, in one place (the workspace's naming rule: a bare name is
//! relative to a scale the caller states, `_RAD` is an angle in radians).

/// An event function `a·cos θ + b·sin θ + c` whose amplitude `hypot(a, b)` and constant `|c|`
/// are both at most this times its scale (the magnitudes that formed it) is identically zero:
/// its sign never changes, so it has no event (a face edge-on all the way round).
pub const IDENTICALLY_ZERO: f64 = 1e-12;

/// When `|c| / hypot(a, b)` is within this of 1 the two roots meet: a tangency, where the
/// function touches zero without changing sign. No event.
pub const TANGENT: f64 = 1e-12;

/// Roots (of different functions) closer than this, in radians, are one breakpoint. The draw
/// list between them cannot be told apart by any f64 evaluation of the live sorter
/// (5.7e-10 degrees; the unit-cube test asks for 1e-9 degrees).
pub const SAME_ROOT_RAD: f64 = 1e-11;

/// How far, in radians, on each side of a breakpoint `verify` evaluates the event function
/// and the live sorter (less when the neighbouring cells are narrower).
pub const VERIFY_SIDE_RAD: f64 = 1e-7;
