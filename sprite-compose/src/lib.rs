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
//! Also here: picking and selection outlines ([`ProjectedFrame`]), the visible lines of a
//! view (plotter edges, [`plot_edges`]; overlays, [`visible_overlay`]), materials as plain
//! data ([`Materials`]), and the realisation of an `aspect-bake` bake ([`Bake`]) as
//! containers of sprites ([`BakedSpriteTree`]) or on a retained compositor
//! ([`BakePlayer`]).
//!
//! The crate links no encoder and no loader: the file writers (SVG, PDF, HTML pages,
//! HP-GL) are the crate `vector-sink`, the PNG rasteriser `raster-sink`; both stand on
//! this one.
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
//! # Feature flags
//! - `obj-quads` (off by default): materials from a loaded `obj_quads::Mesh`
//!   (`FaceMaterials`, `Materials::resolve`, `Materials::of`, `load_image`,
//!   `decode_image`), decoding textures through obj-quads. Without it the crate depends on
//!   `face-sort`, `aspect-bake`, `glam` and `thiserror` only.

mod bake;
mod bake_player;
mod compositor;
mod copies;
mod materials;
mod occlusion;
mod order;
mod overlay;
mod painter;
mod pick;
mod plane_textures;
mod plot;
mod recording;
mod root;
pub mod seams;
pub mod tolerance;
mod transform;

pub use aspect_bake;
pub use aspect_bake::{AngleRange, Bake, BakeCell};
pub use bake::{
    BakedContainer, BakedSprite, BakedSpriteTree, BakedTreeSlot, FacingPredicate,
    convex_facing_predicates, polygon_maps,
};
pub use bake_player::BakePlayer;
pub use compositor::{Brush, Compositor, OpCounts, SpriteId, TextureId};
pub use copies::{CulledCopies, culled_copies};
#[cfg(feature = "obj-quads")]
pub use materials::{
    FaceMaterials, MaterialOptions, MaterialWarning, TextureError, decode_image, load_image,
};
pub use materials::{FacePaint, Image, Materials, UvMap};
pub use overlay::{
    Dot, DrawnOverlay, Line, OrderedPart, Overlay, Point, Stroke, overlay_in_order, visible_overlay,
};
pub use painter::{FrameStats, RotationHandle, RotationSource, SpritePainter};
pub use pick::{ProjectedFrame, contains};
pub use plane_textures::set_plane_textures;
pub use plot::{EdgeKind, Plot, PlotEdge, PlotOptions, plot_edges, plot_edges_where};
pub use recording::{RecordingCompositor, Scene, SceneSprite, project_sprite, sprite_polygon};
pub use root::{perspective_matrix, root_transform, rotation_from_yaw_pitch_roll};
pub use transform::{MapKind, PieceMap, PieceMaps, SpriteSpace, SpriteTransform, piece_map};

pub use face_sort;
pub use glam;
#[cfg(feature = "obj-quads")]
pub use obj_quads;

/// The crate's README: its examples are compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
