//! Every tolerance the crate uses, in one place.
//!
//! Names follow the workspace's rule (as in `face_sort::tolerance` and
//! `raster_sink::tolerance`): a bare name is *relative* to the size its doc names; `_PX` is in
//! pixels; `_ABS` is an absolute guard against underflow. docs/ROBUSTNESS.md lists them all.

/// A quad is a parallelogram (and gets an exact affine map) when its corners satisfy
/// `|P0 + P2 − P1 − P3| ≤ PARALLELOGRAM · D`, `D` being the quad's longest diagonal.
pub const PARALLELOGRAM: f64 = 1e-9;

/// Two sprite axes `a`, `b` are parallel (no map solves for them) when the determinant of
/// their normal equations, `|a|²|b|² − (a·b)²`, is at most `SINGULAR_DET · |a|²|b|²`: the
/// sine of their angle below `1e-12`.
pub const SINGULAR_DET: f64 = 1e-24;

/// A general quad gets its homography only when the projective weight `w = g u + h v + 1`
/// stays above `HOMOGRAPHY_W` on the whole unit square (it is 1 for a parallelogram);
/// otherwise the quad is drawn through a clip polygon.
pub const HOMOGRAPHY_W: f64 = 1e-6;

/// Offset (pixels) to either side of an edge at which the selection outline tests which face
/// is on top.
pub const OUTLINE_PROBE_PX: f64 = 1e-4;

/// Crossings along an edge are parameters in `[0, 1]`: two closer than `EDGE_PARAMETER` are
/// one, and a crossing counts when it lies within `EDGE_PARAMETER` of the edge's ends.
pub const EDGE_PARAMETER: f64 = 1e-12;

/// Two edges are parallel (no crossing) when the cross product of their direction vectors is
/// at most `PARALLEL_EDGES` times the longer one's squared length.
pub const PARALLEL_EDGES: f64 = 1e-18;

/// Outline segments whose ends agree within this many pixels are one segment.
pub const SAME_POINT_PX: f64 = 1e-9;

/// Absolute: magnitudes below this count as zero (a determinant before dividing by it, a
/// matrix entry written to CSS), far below anything a model or page can hold.
pub const UNDERFLOW_ABS: f64 = 1e-300;

/// Seams (the module `seams`): edges of two drawn polygons whose endpoints (or, for
/// T-junctions, whose lines and overlap) agree within this many pixels count as shared for
/// the seam outset.
pub const SEAM_SHARED_EDGE_PX: f64 = 1e-3;

/// Seams: two edge normals (unit vectors) are parallel for the seam outset's miter when the
/// sine of their angle, `|n1 × n2|`, is at most `SEAM_PARALLEL_NORMALS`.
pub const SEAM_PARALLEL_NORMALS: f64 = 1e-9;

/// Plotter edges ([`plot_edges`](crate::plot_edges)): a point of an edge is covered by a
/// piece only when its projection is inside the piece's by more than this many pixels.
pub const PLOT_INSIDE_PX: f64 = 1e-6;

/// Plotter edges: a point of an edge is covered only when it lies behind the piece's plane
/// by more than this times the model's diagonal `L` (the oracle's depth tolerance).
pub const PLOT_BEHIND: f64 = 1e-9;

/// Plotter edges: visible parts shorter than this many pixels are dropped (the slivers a
/// piece that only touches an edge at its end leaves).
pub const PLOT_MIN_LENGTH_PX: f64 = 1e-3;

/// Plotter edges: polyline ends this close (pixels) are joined.
pub const PLOT_JOIN_PX: f64 = 1e-6;

/// Plotter edges: an edge lies on a piece of its own face when the piece has corners within
/// this times the model's diagonal `L` of both its ends (planar faces are snapped onto their
/// plane by up to `face_sort::tolerance::PLANARITY` of their size).
pub const PLOT_SAME_CORNER: f64 = 1e-5;

/// A face's uv map ([`UvMap::fit`](crate::UvMap::fit)) does not exist when its 3 × 3
/// least-squares system's determinant is at most `UV_SYSTEM_SINGULAR · m³`, `m` the
/// system's largest entry (the face is then painted without its texture).
pub const UV_SYSTEM_SINGULAR: f64 = 1e-12;

/// Texture coordinates within `UV_TILE_SLACK` (in texture widths) of a tile edge count as on
/// it when finding the tiles a face spans (a face with `u` from 0 to `1 − 1e-7`, as f32 files
/// store 1, spans one tile, not two).
pub const UV_TILE_SLACK: f64 = 1e-5;

/// Absolute: the largest image (pixels) a face's texture tiles are made into; beyond it the
/// face keeps its untiled map.
pub const MAX_TILED_PIXELS: u64 = 1 << 24;
