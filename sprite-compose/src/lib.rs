//! TODO docs
mod compositor;
mod order;
mod painter;
mod recording;
mod root;
mod transform;

pub use compositor::{
    Brush, Compositor, OpCounts, SpriteId, TextureId, golden_angle_colour, id_colour,
};
pub use painter::{FrameStats, RotationHandle, RotationSource, SpritePainter};
pub use recording::{RecordingCompositor, Scene, SceneSprite};
pub use root::{perspective_matrix, root_transform, rotation_from_yaw_pitch_roll};
pub use transform::{
    MapKind, PARALLELOGRAM, PieceMap, PieceMaps, SpriteSpace, SpriteTransform, piece_map,
};

pub use face_sort;
pub use glam;
