//! Exact vector files from a depth-sorted sprite tree ([`sprite_compose`]): SVG, PDF, and
//! HTML/CSS 3D pages (still, spinning, turning, and canvas players), with textures embedded
//! once per file, hidden parts removed on request, and plotter edges as SVG strokes or
//! HP-GL.
//!
//! The shortest path is [`Export`]: from a loaded model to SVG, PDF and HTML in the model's
//! own materials.
//!
//! ```
//! use vector_sink::face_sort::{Geometry, PolygonMesh, View};
//! use vector_sink::obj_quads::{LoadOptions, load};
//! use vector_sink::{Export, Materials};
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! # let model = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/models/keenan-crane/spot/spot_control_mesh_texture.obj");
//! # let out = std::env::temp_dir().join(format!("vector-sink-export-{}", std::process::id()));
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
//! # Layers
//! `sprite-compose` holds the sprite tree and links no encoder; this crate holds the file
//! writers (`pdf-writer`, `png` and `base64` for embedded textures, `i_overlay` for
//! hidden-part removal). `raster-sink` (PNG) stands on `sprite-compose` beside it; neither
//! sink depends on the other.
//!
//! # Feature flags
//! None. `sprite-compose`'s feature `obj-quads` is on: [`Export`] takes materials resolved
//! from a loaded `obj_quads::Mesh`.

mod canvas;
mod embed;
mod export;
mod hidden;
mod html;
mod lines;
mod numbers;
mod page;
mod page_pieces;
mod pdf;
mod spin;
mod spin_culled;
mod svg;
pub mod tolerance;
mod turn_page;

pub use canvas::{write_canvas_spin_html, write_canvas_turn_html};
pub use embed::{encoded_image, image_data_uri};
pub use export::Export;
pub use hidden::{HiddenParts, Visibility, visible_parts};
pub use html::{HtmlMode, HtmlOptions, HtmlPieces, css_matrix3d, write_html};
pub use lines::{outline_svg_path, overlay_svg, plot_hpgl, plot_svg};
pub use pdf::{PdfOptions, write_pdf};
pub use spin::{SpinOptions, write_spin_html};
pub use spin_culled::write_culled_spin_html;
pub use svg::{SvgOptions, write_svg};
pub use turn_page::{TurnPage, TurnPageOptions, write_turn_html};

pub use sprite_compose::{self, Materials};
pub use sprite_compose::{aspect_bake, face_sort, glam, obj_quads};

// The sprite tree's types the writers read, named once for the modules (`crate::Scene`).
use face_sort::colours::id_colour;
use sprite_compose::{
    BakedSpriteTree, Brush, DrawnOverlay, Image, Scene, SceneSprite, SpriteTransform,
    perspective_matrix, project_sprite, seams, sprite_polygon,
};

/// The crate's README: its examples are compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
