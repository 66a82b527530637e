//! The reference raster of the painter workspace: what a draw list looks like, and how wrong
//! its order is.
//!
//! - **ID images** ([`render_ids`]): every polygon of a [`face_sort::DrawList`] filled in
//!   paint order at pixel centres by the crate's own f64 scanline ([`for_each_span`], a
//!   top-left fill rule), so split fragments tile without cracks or double cover; 24-bit
//!   face index + 1 per pixel, written as 8-bit RGB PNG (CONVENTIONS.md).
//! - **Truth** ([`truth()`]): per pixel centre, the drawn piece whose plane the pixel's ray meets
//!   nearest, in f64, with the mask of unambiguous pixels; [`pixel_error`] compares a
//!   painter's ID image with it. An exact order gives exactly 0.
//! - **Colour** ([`render_colour`], [`run_steps`]) on tiny-skia: anti-aliased, with solid,
//!   textured ([`UvMap`]) and palette brushes ([`face_sort::colours::golden_angle_colour`]),
//!   flat Lambert shading ([`Light`]), supersampling, override brushes, a small list of
//!   render [`Step`]s, and a procedural [`GroundGrid`].
//! - **Materials** ([`Style::from_materials`], [`Style::from_resolved`],
//!   [`Style::sprite_brushes`]): raster brushes from sprite-compose's material resolution
//!   (`sprite_compose::Materials`, re-exported [`FaceMaterials`]), and a raster style
//!   (with its ground grid and shading) projected back onto sprite brushes.
//!
//! # Seams
//! Anti-aliased neighbours conflate: a pixel half covered by each of two adjacent polygons
//! keeps a quarter of the background. Each draw step finds the edges that two drawn
//! polygons share (same projected endpoints, or collinear overlap at T-junctions where a
//! sorter split one face but not its neighbour) and pushes the fill out across those edges
//! by [`RasterOptions::seam_outset`] (half a pixel); silhouette edges stay exact.
//!
//! # Textures and perspective
//! A texture is mapped per polygon by one affine transform (a tiny-skia `Pattern`), exact in
//! orthographic views. Perspective is projective: the affine map is exact only at the three
//! corners it is fitted to and drifts elsewhere (a quad's fourth corner, long polygons).
//! [`RasterOptions::texture_subdivision`] cuts each textured fan triangle into `n × n`
//! pieces with their own transforms, which shrinks the drift by about `n²`.
//!
//! ```
//! use raster_sink::face_sort::glam::DVec3;
//! use raster_sink::face_sort::{Centroid, DrawList, FaceSorter, Geometry, PolygonMesh, View};
//! use raster_sink::{RasterOptions, Style, pixel_error, render_colour, render_ids, truth};
//!
//! // Two squares, the second in front of the first and overlapping it.
//! let positions = vec![
//!     DVec3::new(0.0, 0.0, 0.0), DVec3::new(2.0, 0.0, 0.0),
//!     DVec3::new(2.0, 2.0, 0.0), DVec3::new(0.0, 2.0, 0.0),
//!     DVec3::new(1.0, 1.0, 1.0), DVec3::new(3.0, 1.0, 1.0),
//!     DVec3::new(3.0, 3.0, 1.0), DVec3::new(1.0, 3.0, 1.0),
//! ];
//! let mesh = PolygonMesh::new(positions, [[0, 1, 2, 3], [4, 5, 6, 7]]).unwrap();
//! let geometry = Geometry::new(&mesh).unwrap();
//! let view = View::fit(&geometry.bounds(), 64, 64);
//! let mut list = DrawList::new();
//! Centroid::new(&geometry).sort(&view, &mut list);
//!
//! let ids = render_ids(&view, &list);
//! let error = pixel_error(&ids, &truth(&view, &geometry));
//! assert!(error.pixels > 0);
//! assert_eq!(error.wrong, 0); // parallel layers: the centroid order is right
//!
//! let image = render_colour(&view, &list, &Style::palette(), &RasterOptions::DEFAULT).unwrap();
//! assert_eq!((image.width(), image.height()), (64, 64));
//! ```
//!
//! # From your own mesh and camera
//! A mesh held as `[f32; 3]` positions and triangles, an engine's glam f32 look-at and
//! perspective matrices, an exact order, and both checks: no order violation, no wrong pixel.
//!
//! ```
//! use raster_sink::face_sort::glam::camera::rh::{proj::directx, view::look_at_mat4};
//! use raster_sink::face_sort::glam::Vec3;
//! use raster_sink::face_sort::{Bsp, Camera, ClipSpace, DrawList, FaceSorter, Geometry};
//! use raster_sink::face_sort::{PolygonMesh, oracle};
//! use raster_sink::{pixel_error, render_ids, truth};
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let positions: Vec<[f32; 3]> = vec![
//!     [-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.5], [1.0, -0.2, -0.5],
//!     [0.5, 1.2, 0.3], [-1.2, 0.3, -0.4], [0.3, -1.2, 0.6], [1.2, 0.8, -0.1], [-0.9, -0.6, 0.7],
//!     [0.9, -0.4, 0.1], [-0.1, 0.7, 0.2], [-0.6, 1.0, -0.3], [0.2, -0.9, 0.4], [0.8, 0.9, 0.5],
//! ];
//! let triangles = [[0u32, 1, 2], [3, 4, 5], [6, 7, 8], [9, 10, 11], [12, 13, 14]];
//! let view_matrix = look_at_mat4(Vec3::new(1.0, 2.0, 5.0), Vec3::ZERO, Vec3::Y);
//! let projection = directx::perspective(0.8, 4.0 / 3.0, 0.1, 100.0);
//!
//! let geometry = Geometry::new(&PolygonMesh::new(&positions, triangles)?)?;
//! let view = Camera::from_matrices(view_matrix, projection, ClipSpace::ZeroToOne)?
//!     .view(&geometry, 320, 240)?;
//! let mut list = DrawList::new();
//! Bsp::new(&geometry).sort(&view, &mut list);
//! assert_eq!(oracle::count_violations(&view, &list), 0);
//! assert_eq!(pixel_error(&render_ids(&view, &list), &truth(&view, &geometry)).wrong, 0);
//! # Ok(()) }
//! ```
//!
//! # Feature flags
//! - `obj-quads`: [`FaceMaterials`] for `obj_quads::Mesh`, so that
//!   `Style::from_materials(&mesh, ..)` takes a loaded model directly.
//!
//! tiny-skia (with its PNG support), png and obj-quads' texture decoding are always on.

mod colour;
mod composite;
mod error;
mod fill;
mod grid;
mod ids;
mod materials;
mod overlay;
mod overlay_truth;
mod project;
mod style;
pub mod tolerance;
mod truth;

pub use colour::{
    Light, MAX_SUPERSAMPLE, MAX_TEXTURE_SUBDIVISION, Override, RasterOptions, Step, default_steps,
    new_pixmap, polygon_path, render_colour, run_steps, save_png, shade_colour,
};
pub use composite::{CompositeTruth, composite_truth};
pub use error::RasterError;
pub use fill::{for_each_pixel_near_segment, for_each_span};
pub use grid::GroundGrid;
pub use ids::{IdImage, MAX_ID_FACE, render_ids, render_ids_into};
pub use materials::{MaterialStyle, load_texture, load_texture_with};
// Materials are resolved by sprite-compose, which owns brushes; re-exported for raster users.
pub use overlay::draw_overlay;
pub use overlay_truth::{OverlayError, OverlayTruth, Seen};
pub use sprite_compose::{FaceMaterials, MaterialOptions, UvMap};
pub use style::{Brush, Style, TextureBrush};
pub use truth::{PixelError, Truth, pixel_error, truth};

pub use face_sort;
pub use sprite_compose;
pub use tiny_skia;

/// Largest image side the colour raster accepts (after supersampling).
pub const MAX_IMAGE_SIDE: u32 = 16384;
/// Largest pixel count the colour raster accepts (after supersampling).
pub const MAX_IMAGE_PIXELS: u64 = 1 << 28;

/// The crate's README: its examples are compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
