//! The retained-backend interface: sprites, brushes and the operations a painter sends.

use glam::{DAffine2, DMat4, DVec2};

use crate::SpriteTransform;

/// A sprite's identity, chosen by the painter (dense, starting at 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SpriteId(pub u32);

impl SpriteId {
    /// The one invalid value: "no sprite" in a table of ids.
    pub const NONE: SpriteId = SpriteId(u32::MAX);

    /// The id as an index.
    #[must_use]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A texture known to the backend, by index (the backend or writer owns the pixels).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TextureId(pub u32);

/// How a sprite is filled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Brush {
    /// A solid straight-alpha sRGB colour `[r, g, b, a]`.
    Solid([u8; 4]),
    /// A texture. `uv` maps unit-square coordinates (see [`SpriteTransform`]) to texture
    /// coordinates in `[0, 1]²` (`(0, 0)` top-left). Exact when the face's uv quad is a
    /// parallelogram; a projective uv mapping is not represented.
    Texture {
        /// The texture.
        texture: TextureId,
        /// Unit square → texture uv.
        uv: DAffine2,
        /// Colour used by backends that cannot draw textures.
        fallback: [u8; 4],
    },
    /// The golden-angle palette colour of the sprite's face
    /// ([`face_sort::colours::golden_angle_colour`]).
    Palette,
}

impl Brush {
    /// The solid colour a backend uses for this brush on a sprite of `face` when it draws
    /// no textures.
    #[must_use]
    pub fn solid_colour(&self, face: u32) -> [u8; 4] {
        match *self {
            Brush::Solid(c) => c,
            Brush::Texture { fallback, .. } => fallback,
            Brush::Palette => golden_angle_colour(face),
        }
    }
}

use face_sort::colours::golden_angle_colour;

/// A retained compositor without a depth buffer: a stack of sprites (bottom first, painted in
/// stack order) under one root transform.
///
/// # Contract
/// - [`create_sprite`](Self::create_sprite) adds a sprite **hidden, on top of the stack**, with
///   the identity transform, no clip and [`Brush::Palette`].
/// - A sprite's final pixel position is `root · transform · (u, v, 0, 1)` (homogeneous, divide
///   by `w`) for unit-square points `(u, v)` inside the clip polygon (or the whole square).
/// - Reorders move one sprite; the others keep their relative order.
pub trait Compositor {
    /// Adds sprite `id` (not in use) for source face `face`.
    fn create_sprite(&mut self, id: SpriteId, face: u32);
    /// Removes a sprite.
    fn destroy_sprite(&mut self, id: SpriteId);
    /// Sets a sprite's fixed transform.
    fn set_transform(&mut self, id: SpriteId, transform: &SpriteTransform);
    /// Sets a sprite's clip polygon in unit-square coordinates (`None`: the whole square).
    fn set_clip(&mut self, id: SpriteId, clip: Option<&[DVec2]>);
    /// Sets a sprite's brush.
    fn set_brush(&mut self, id: SpriteId, brush: &Brush);
    /// Shows or hides a sprite.
    fn set_visible(&mut self, id: SpriteId, visible: bool);
    /// Whether a sprite's back may show (`true` when created). A compositor hides a sprite
    /// whose back does not show while its final transform turns the back toward the viewer
    /// (CSS `backface-visibility: hidden`): the sprite's front is the side its source piece
    /// faces, so a baked order that holds pieces facing away stays right.
    fn set_back_visible(&mut self, id: SpriteId, visible: bool);
    /// Moves a sprite to the top of the stack (painted last).
    fn move_to_top(&mut self, id: SpriteId);
    /// Moves a sprite directly below `above` (painted just before it).
    fn move_before(&mut self, id: SpriteId, above: SpriteId);
    /// Sets the root transform (see [`root_transform`](crate::root_transform)).
    fn set_root_transform(&mut self, root: &DMat4);
}

/// Operations sent to a [`Compositor`], counted by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCounts {
    /// `create_sprite`.
    pub create: usize,
    /// `destroy_sprite`.
    pub destroy: usize,
    /// `set_transform`.
    pub transform: usize,
    /// `set_clip`.
    pub clip: usize,
    /// `set_brush`.
    pub brush: usize,
    /// `set_visible`.
    pub visible: usize,
    /// `move_to_top` and `move_before`.
    pub reorder: usize,
    /// `set_back_visible`.
    pub back: usize,
    /// `set_root_transform`.
    pub root: usize,
}

impl OpCounts {
    /// Every operation.
    #[must_use]
    pub fn total(&self) -> usize {
        self.create
            + self.destroy
            + self.transform
            + self.clip
            + self.brush
            + self.visible
            + self.reorder
            + self.back
            + self.root
    }
}

impl std::ops::AddAssign for OpCounts {
    fn add_assign(&mut self, o: Self) {
        self.create += o.create;
        self.destroy += o.destroy;
        self.transform += o.transform;
        self.clip += o.clip;
        self.brush += o.brush;
        self.visible += o.visible;
        self.reorder += o.reorder;
        self.back += o.back;
        self.root += o.root;
    }
}

/// Wraps a compositor and counts what is sent to it.
#[derive(Debug)]
pub(crate) struct Counting<'a, C: ?Sized> {
    pub inner: &'a mut C,
    pub ops: OpCounts,
}

impl<C: Compositor + ?Sized> Compositor for Counting<'_, C> {
    fn create_sprite(&mut self, id: SpriteId, face: u32) {
        self.ops.create += 1;
        self.inner.create_sprite(id, face);
    }
    fn destroy_sprite(&mut self, id: SpriteId) {
        self.ops.destroy += 1;
        self.inner.destroy_sprite(id);
    }
    fn set_transform(&mut self, id: SpriteId, transform: &SpriteTransform) {
        self.ops.transform += 1;
        self.inner.set_transform(id, transform);
    }
    fn set_clip(&mut self, id: SpriteId, clip: Option<&[DVec2]>) {
        self.ops.clip += 1;
        self.inner.set_clip(id, clip);
    }
    fn set_brush(&mut self, id: SpriteId, brush: &Brush) {
        self.ops.brush += 1;
        self.inner.set_brush(id, brush);
    }
    fn set_visible(&mut self, id: SpriteId, visible: bool) {
        self.ops.visible += 1;
        self.inner.set_visible(id, visible);
    }
    fn set_back_visible(&mut self, id: SpriteId, visible: bool) {
        self.ops.back += 1;
        self.inner.set_back_visible(id, visible);
    }
    fn move_to_top(&mut self, id: SpriteId) {
        self.ops.reorder += 1;
        self.inner.move_to_top(id);
    }
    fn move_before(&mut self, id: SpriteId, above: SpriteId) {
        self.ops.reorder += 1;
        self.inner.move_before(id, above);
    }
    fn set_root_transform(&mut self, root: &DMat4) {
        self.ops.root += 1;
        self.inner.set_root_transform(root);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use face_sort::colours::id_colour;

    #[test]
    fn id_colour_is_face_plus_one() {
        assert_eq!(id_colour(0), [0, 0, 1, 255]);
        assert_eq!(id_colour(0x01_02_03 - 1), [1, 2, 3, 255]);
    }

    #[test]
    fn palette_neighbours_differ() {
        for f in 0..100 {
            assert_ne!(golden_angle_colour(f), golden_angle_colour(f + 1));
        }
    }
}
