//! The sprite id pool: one sprite per piece, shared fragment and per-frame fragment slot,
//! ids reused after a destroy, and the operations that create and destroy sprites.

use face_sort::PieceId;
use glam::DVec2;

use super::State;
use crate::{Brush, Compositor, SpriteId};

/// What the painter last sent for one sprite.
#[derive(Clone, Debug)]
pub(super) struct SpriteState {
    pub alive: bool,
    pub face: u32,
    /// Source piece (its transform); `PieceId::NONE` for a free id, and for a per-frame
    /// fragment slot whose transform must be sent again.
    pub piece: PieceId,
    pub visible: bool,
    pub brush: Brush,
    /// Index in the shared polygon set for a shared fragment.
    pub polygon: Option<u32>,
    /// Clip polygon in unit-square coordinates; `has_clip == false`: the whole square.
    pub clip: Vec<DVec2>,
    pub has_clip: bool,
}

impl SpriteState {
    /// A sprite of `face` drawn with `piece`'s transform, not yet created.
    pub fn new(face: u32, piece: PieceId) -> Self {
        SpriteState {
            alive: false,
            face,
            piece,
            visible: false,
            brush: Brush::Palette,
            polygon: None,
            clip: Vec::new(),
            has_clip: false,
        }
    }
}

/// Every sprite the painter has made, by id, and the ids free for reuse.
#[derive(Default)]
pub(super) struct SpritePool {
    /// By id; dead entries keep their slot until reused.
    pub sprites: Vec<SpriteState>,
    /// Ids of destroyed sprites.
    pub free_ids: Vec<u32>,
}

impl SpritePool {
    /// Sprites alive in the compositor.
    pub fn alive(&self) -> usize {
        self.sprites.iter().filter(|s| s.alive).count()
    }
}

impl State {
    /// Sends create + transform + clip + brush for a sprite whose state is filled in.
    pub(super) fn create(&mut self, id: SpriteId, out: &mut dyn Compositor) {
        let sprite = &mut self.pool.sprites[id.index()];
        if sprite.alive {
            return;
        }
        let Some(map) = sprite.piece.get().and_then(|p| self.maps.get(p as usize)) else {
            return;
        };
        sprite.alive = true;
        out.create_sprite(id, sprite.face);
        self.stack.mirror.push(id);
        out.set_transform(id, &map.transform);
        if !sprite.has_clip
            && let Some(clip) = &map.clip
        {
            sprite.clip.clear();
            sprite.clip.extend_from_slice(clip);
            sprite.has_clip = true;
        }
        if sprite.has_clip {
            out.set_clip(id, Some(&sprite.clip));
        }
        let brush = self
            .brushes
            .get(sprite.face as usize)
            .copied()
            .unwrap_or(Brush::Palette);
        sprite.brush = brush;
        if brush != Brush::Palette {
            out.set_brush(id, &brush);
        }
    }

    pub(super) fn new_sprite_id(&mut self, face: u32, piece: u32) -> SpriteId {
        let state = SpriteState::new(face, PieceId::new(piece));
        if let Some(id) = self.pool.free_ids.pop() {
            self.pool.sprites[id as usize] = state;
            SpriteId(id)
        } else {
            self.pool.sprites.push(state);
            SpriteId(self.pool.sprites.len() as u32 - 1)
        }
    }

    pub(super) fn destroy(&mut self, id: SpriteId, out: &mut dyn Compositor) {
        let sprite = &mut self.pool.sprites[id.index()];
        if sprite.alive {
            out.destroy_sprite(id);
            self.stack.mirror.remove(id);
        }
        sprite.alive = false;
        sprite.visible = false;
        sprite.piece = PieceId::NONE;
        self.pool.free_ids.push(id.0);
    }
}
