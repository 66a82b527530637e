//! A backend-agnostic sprite tree for drawing polygon meshes without a depth buffer.
//!
//! Every face (more exactly every planar piece of [`face_sort::Geometry`], and every split
//! fragment a sorter keeps) becomes one **sprite**: the unit square under a fixed
//! [`SpriteTransform`] (exact affine map for parallelograms and triangles, the exact
//! homography for general planar quads, a clip polygon for triangles, n-gons and fragments).
//! A frame moves only the [`root_transform`] (rotation and perspective), visibility and the
//! stacking order. [`SpritePainter`] asks a [`face_sort::FaceSorter`] for the paint order
//! and sends a retained [`Compositor`] only what changed, with few reorders (the longest
//! increasing subsequence of the previous stack stays in place).
//!
//! Also here: picking and selection outlines ([`ProjectedFrame`]), the SVG writer
//! ([`write_svg`]) and the HTML/CSS 3D writer ([`write_html`], flat or `preserve-3d`), both
//! with a CONVENTIONS.md ID-colour mode, and the realisation of an `aspect-bake` bake
//! ([`Bake`]) as containers of sprites ([`BakedSpriteTree`], [`FacingPredicate`]).
//!
//! ```
//! use sprite_compose::face_sort::{Geometry, PolygonMesh, SorterKind, View};
//! use sprite_compose::glam::DVec3;
//! use sprite_compose::{RecordingCompositor, SpritePainter, rotation_from_yaw_pitch_roll};
//!
//! // A unit cube.
//! let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
//! let positions = vec![
//!     p(0., 0., 0.), p(1., 0., 0.), p(0., 1., 0.), p(1., 1., 0.),
//!     p(0., 0., 1.), p(1., 0., 1.), p(0., 1., 1.), p(1., 1., 1.),
//! ];
//! let faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3]];
//! let geometry = Geometry::new(&PolygonMesh::new(positions, faces).unwrap()).unwrap();
//! let view = View::fit(&geometry.bounds(), 256, 256).with_yaw_pitch_roll(30.0, 20.0, 0.0);
//! let sorter = SorterKind::Bsp.build(&geometry);
//! let mut painter = SpritePainter::new(&geometry, sorter, view, RecordingCompositor::new());
//!
//! let first = painter.frame();
//! assert_eq!(first.ops.create, 6); // one sprite per face, created once
//! assert_eq!(first.drawn, 3); // three faces face the viewer
//! assert_eq!(painter.frame().ops.total(), 0); // nothing changed: nothing sent
//!
//! // Turning costs the root transform plus visibility flips and moves, never transforms.
//! painter.set_rotation(rotation_from_yaw_pitch_roll(120.0, 20.0, 0.0));
//! let turned = painter.frame();
//! assert_eq!((turned.ops.root, turned.ops.transform), (1, 0));
//!
//! // The topmost face at the centre pixel.
//! assert!(painter.pick(128.0, 128.0).is_some());
//! ```
//!
//! # Export a loaded model
//! From a model file to SVG, PDF and HTML in the model's own materials, without a raster
//! crate: the size is the view's, textures are embedded once per file.
//!
//! ```
//! use sprite_compose::face_sort::{Geometry, PolygonMesh, View};
//! use sprite_compose::obj_quads::{LoadOptions, load};
//! use sprite_compose::{Export, Materials};
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! # let model = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/models/keenan-crane/spot/spot_control_mesh_texture.obj");
//! # let out = std::env::temp_dir().join(format!("sprite-compose-export-{}", std::process::id()));
//! # std::fs::create_dir_all(&out)?;
//! let (mesh, _) = load(model, &LoadOptions::DEFAULT)?;
//! let geometry = Geometry::new(&PolygonMesh::new(mesh.positions(), mesh.faces())?)?;
//! let view = View::fit(&geometry.bounds(), 512, 512).with_yaw_pitch_roll(145.0, -25.0, 0.0);
//! let export = Export::new(&geometry, view).with_materials(&Materials::of(&mesh, &geometry)?);
//! std::fs::write(out.join("spot.svg"), export.svg())?;
//! std::fs::write(out.join("spot.pdf"), export.pdf())?;
//! std::fs::write(out.join("spot.html"), export.html())?;
//! # let svg = export.svg();
//! # let uris: Vec<&str> = svg.split("xlink:href=\"data:").skip(1).map(|u| &u[..u.find('"').unwrap()]).collect();
//! # let distinct: std::collections::HashSet<&&str> = uris.iter().collect();
//! # assert!(!uris.is_empty() && distinct.len() == uris.len(), "each image once");
//! # assert!(export.html().contains("data:image/png;base64,"));
//! # std::fs::remove_dir_all(&out)?;
//! # Ok(()) }
//! ```
//!
//! # Feature flags
//! None yet. Beside `face-sort` and `glam` the crate depends on `i_overlay` (hidden-part
//! removal: 2D boolean operations), `pdf-writer` (the PDF writer) and `aspect-bake` (the
//! bake it realises).

mod bake;
mod bake_player;
mod canvas;
mod compositor;
mod export;
mod hidden;
mod html;
mod materials;
mod numbers;
mod occlusion;
mod order;
mod overlay;
mod page_pieces;
mod painter;
mod pdf;
mod pick;
mod plane_textures;
mod plot;
mod recording;
mod root;
pub mod seams;
mod spin;
mod spin_culled;
mod svg;
pub mod tolerance;
mod transform;
mod turn_page;

pub use aspect_bake;
pub use aspect_bake::{AngleRange, Bake, BakeCell};
pub use bake::{
    BakedContainer, BakedSprite, BakedSpriteTree, BakedTreeSlot, FacingPredicate,
    convex_facing_predicates,
};
pub use bake_player::BakePlayer;
pub use canvas::{write_canvas_spin_html, write_canvas_turn_html};
pub use compositor::{Brush, Compositor, OpCounts, SpriteId, TextureId};
pub use export::Export;
pub use hidden::{HiddenParts, Visibility, visible_parts};
pub use html::{HtmlMode, HtmlOptions, HtmlPieces, css_matrix3d, write_html};
pub use materials::{
    FaceMaterials, FacePaint, Image, MaterialOptions, Materials, TextureError, UvMap, decode_image,
    load_image,
};
pub use overlay::{
    Dot, DrawnOverlay, Line, OrderedPart, Overlay, Point, Stroke, overlay_in_order, visible_overlay,
};
pub use painter::{FrameStats, RotationHandle, RotationSource, SpritePainter};
pub use pdf::{PdfOptions, write_pdf};
pub use pick::{ProjectedFrame, contains, outline_svg_path};
pub use plane_textures::set_plane_textures;
pub use plot::{EdgeKind, Plot, PlotEdge, PlotOptions, plot_edges, plot_edges_where};
pub use recording::{RecordingCompositor, Scene, SceneSprite};
pub use root::{perspective_matrix, root_transform, rotation_from_yaw_pitch_roll};
pub use spin::{SpinOptions, write_spin_html};
pub use spin_culled::write_culled_spin_html;
pub use svg::{SvgOptions, project_sprite, write_svg};
pub use transform::{MapKind, PieceMap, PieceMaps, SpriteSpace, SpriteTransform, piece_map};
pub use turn_page::{TurnPage, TurnPageOptions, write_turn_html};

pub use face_sort;
pub use obj_quads;
// The ID colour for the writers (`crate::id_colour`); exported once, by face-sort.
use face_sort::colours::id_colour;
pub use glam;

/// The crate's README: its examples are compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
