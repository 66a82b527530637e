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

/// Hidden-part removal ([`visible_parts`](crate::visible_parts)) does not write visible parts
/// or holes smaller than this many square pixels: the square of the 1e-4 px to which the
/// writers print coordinates. What it drops are the slivers, one grid step wide, that
/// rounding leaves where a corner of one polygon lies on an edge of another (T-junctions); a
/// dropped hole is painted over by the polygon in front.
pub const MIN_PART_AREA_PX2: f64 = 1e-8;

/// Bits of hidden-part removal's integer grid across the largest coordinate of a picture:
/// an f64's mantissa, so that rounding onto it moves no corner by more than the coordinate's
/// own precision.
pub const HIDDEN_GRID_BITS: i32 = 52;

/// The SVG writer draws a texture under a projective map (perspective, projective quads) as
/// a grid of cells, each with the affine map nearest the exact (projective) one at its four
/// projected corners, fine enough that every corner lands within `SVG_TEXTURE_PX` pixels of
/// where the exact map puts it (a tenth of a pixel: far below what a texel placement shows).
pub const SVG_TEXTURE_PX: f64 = 0.1;

/// At most this many cells along each side of a sprite's unit square in that grid (a cap on
/// the output size; the miss can then exceed [`SVG_TEXTURE_PX`]).
pub const SVG_TEXTURE_MAX_CELLS: u32 = 64;

/// Each cell's clip polygon reaches this many pixels past the cell (each corner moved away
/// from the cell's centre), so that neighbouring cells overlap and anti-aliased cell edges
/// let no background through; the sprite's own clip keeps the exact outline.
pub const SVG_CELL_OVERLAP_PX: f64 = 0.5;

/// The HTML writer draws a piece of a clip polygon as a quad under a projective `matrix3d`
/// only when its projective weights at the four corners differ by at most this factor (1 for
/// a parallelogram); else it cuts the piece's triangles into three quads each (factor 3).
/// Chromium dropped whole layers whose quad had an edge 1e-5 of its size (weights about
/// 1e5 apart).
pub const HTML_QUAD_WEIGHT_RATIO: f64 = 4.0;

/// The HTML writer draws a strip reaching this many pixels to both sides of each edge a
/// clipped sprite shares with a later-drawn sprite of its face, under the later one, to fill
/// the cracks Chromium leaves between layers that share an edge (float transforms, then
/// edges on Skia's 1/64 px fixed-point grid): a crack showed the background at a pixel
/// centre 0.0016 px inside a fragment (docs/html-fragment-crack.png). Four grid steps.
pub const HTML_SEAM_PX: f64 = 1.0 / 16.0;

/// Two projected sprite edges are one shared edge (a split line) when the ends of one lie
/// within this many pixels of the other's line and they overlap by more than it.
pub const HTML_SHARED_EDGE_PX: f64 = 1e-6;

/// In colour pages, the HTML writer grows each opaque sprite this many pixels across every
/// edge it shares with another sprite (silhouettes stay), as raster-sink's PNG does
/// (`seam_outset`): anti-aliased neighbours then overlap instead of showing hairlines of
/// background, and the two pictures agree along shared edges.
pub const HTML_SEAM_OUTSET_PX: f64 = 0.5;

/// Seams ([`seams`](crate::seams)): edges of two drawn polygons whose endpoints (or, for
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

/// Pixels: a textured HTML element reaches this far beyond its sprite's unit square, and an
/// opaque flat one of a colour page this far beyond its polygon's box (both clipped back to the
/// sprite), so that the element's box edges, which Chromium's compositor anti-aliases, lie
/// outside the picture.
pub const HTML_TEXTURE_MARGIN_PX: f64 = 4.0;

/// Relative: the PDF writer cuts a texture tile into strips when the `x` reach of its
/// parallelogram's two edges from the top corner differ by at most this fraction of the
/// larger one, where poppler's Splash rasteriser could take either for the left edge
/// (`pdf.rs`, `Tile::strips_for_splash`).
pub const SPLASH_ORDER_MARGIN: f64 = 1e-3;
