//! Every tolerance the crate uses, in one place.
//!
//! Names follow the workspace's rule (as in `face_sort::tolerance`,
//! `sprite_compose::tolerance` and `raster_sink::tolerance`): a bare name is *relative* to
//! the size its doc names; `_PX` is in pixels; `_ABS` is an absolute guard against
//! underflow. docs/ROBUSTNESS.md lists them all.

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
