//! TODO docs
mod bake;
mod compositor;
mod html;
mod pick;
mod svg;
mod order;
mod painter;
mod recording;
mod root;
mod transform;

pub use bake::{
    AngleRange, Bake, BakeCell, BakeSlot, BakedContainer, BakedGraph, BakedSprite, FacingPredicate,
    convex_facing_predicates,
};
pub use compositor::{
    Brush, Compositor, OpCounts, SpriteId, TextureId, golden_angle_colour, id_colour,
};
pub use html::{HtmlMode, HtmlOptions, css_matrix3d, write_html};
pub use painter::{FrameStats, RotationHandle, RotationSource, SpritePainter};
pub use pick::{OUTLINE_PROBE_PX, ProjectedFrame, contains, outline_svg_path};
pub use recording::{RecordingCompositor, Scene, SceneSprite};
pub use svg::{SvgOptions, project_sprite, write_svg};
pub use root::{perspective_matrix, root_transform, rotation_from_yaw_pitch_roll};
pub use transform::{
    MapKind, PARALLELOGRAM, PieceMap, PieceMaps, SpriteSpace, SpriteTransform, piece_map,
};

pub use face_sort;
pub use glam;
