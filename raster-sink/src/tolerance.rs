//! Every tolerance the crate uses, in one place (CONVENTIONS.md sets the first two).
//!
//! Names follow the workspace's rule (as in `face_sort::tolerance`): a bare name is
//! *relative* to the size its doc names; `_PX` is in pixels; `_ABS` is an absolute guard
//! against underflow. docs/ROBUSTNESS.md lists them all.

/// A pixel is unambiguous only when its centre is at least this far (pixels) from every
/// projected edge of every drawn piece.
pub const EDGE_MARGIN_PX: f64 = 0.75;

/// A pixel is unambiguous only when the nearest two depths along its ray differ by more
/// than `DEPTH_GAP · L` in view units (`DEPTH_GAP · L · s` in pixel-space depth).
pub const DEPTH_GAP: f64 = 1e-6;

/// A projected polygon whose doubled area is at most `DEGENERATE_PROJECTED_AREA · D²`
/// (`D` the diagonal of its screen bounding box) has zero area: it draws nothing and is
/// excluded from the truth (CONVENTIONS.md: "faces whose projection has zero area").
pub const DEGENERATE_PROJECTED_AREA: f64 = 1e-12;

/// Absolute: magnitudes below this count as zero (the area of a texture's uv axes, a grid
/// line's pixel footprint before dividing by it).
pub const UNDERFLOW_ABS: f64 = 1e-300;

/// The truth for lines and points ([`OverlayTruth`](crate::OverlayTruth)): a point is judged
/// only where no nearer piece's outline is within this many pixels, the same answer holds
/// this far before and after along its line, and it is this far from the line's ends.
pub const OVERLAY_JUDGE_PX: f64 = 1.0;

/// The truth for lines and points: lines are sampled this many pixels apart.
pub const OVERLAY_STEP_PX: f64 = 0.25;

/// The truth for lines and points: a piece hides a point when its plane is nearer the viewer
/// along the ray by more than this times the model's diagonal `L` (a piece whose plane holds
/// the point, as the faces a line lies on, does not hide it).
pub const OVERLAY_DEPTH: f64 = 1e-7;

/// The truth for lines and points: a piece whose normal is this close to perpendicular to the
/// ray (sine, relative) is edge-on and only makes points near it ambiguous.
pub const OVERLAY_EDGE_ON: f64 = 1e-12;
