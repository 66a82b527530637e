//! Fragment slots: sprites for the polygons a sorter splits off. Fragments of the sorter's
//! shared polygon set (BSP's) get sprites of their own, rebuilt only when the set changes;
//! per-frame fragments (Newell's) go to a pool of slots reused frame after frame.

use std::sync::Arc;

use face_sort::{Geometry, Plane, PolygonSet};
use glam::DVec2;

use super::State;
use face_sort::PieceId;

use crate::{Brush, Compositor, PieceMaps, SpriteId};

/// The polygon → sprite mapping of the sorter's shared set and the per-frame slots.
#[derive(Default)]
pub(super) struct FragmentSlots {
    /// The shared polygon set the mapping was built for.
    pub shared: Option<Arc<PolygonSet>>,
    /// Sprite id of each polygon of the shared set (`SpriteId::NONE`: not drawn).
    pub shared_to_sprite: Vec<SpriteId>,
    /// Sprites made for fragments of the shared set.
    pub shared_fragments: Vec<SpriteId>,
    /// Per-frame fragment slots, in use order.
    pub transient: Vec<SpriteId>,
    /// A fragment's clip polygon being built.
    pub clip_scratch: Vec<DVec2>,
}

/// Pieces of face `f`: `offsets[f]..offsets[f + 1]`.
pub(super) fn face_pieces(geometry: &Geometry) -> Vec<u32> {
    let pieces = geometry.pieces();
    let mut offsets = vec![0u32; geometry.face_count() + 1];
    for i in 0..pieces.len() {
        let f = pieces.face(i) as usize;
        if f < geometry.face_count() {
            offsets[f + 1] += 1;
        }
    }
    for f in 0..geometry.face_count() {
        offsets[f + 1] += offsets[f];
    }
    offsets
}

/// Fills `out` with the unit-square coordinates of `corners` on `piece`'s map; `false` when
/// the piece has no map.
pub(super) fn fragment_clip(
    maps: &PieceMaps,
    piece: u32,
    corners: &[glam::DVec3],
    out: &mut Vec<DVec2>,
) -> bool {
    out.clear();
    let Some(map) = maps.get(piece as usize) else {
        return false;
    };
    let space = *maps.space();
    out.extend(
        corners
            .iter()
            .map(|&c| map.transform.unit_coords(space.point(c))),
    );
    true
}

impl State {
    /// The piece of `face` that a polygon with `plane` was cut from.
    pub(super) fn source_piece(&self, face: u32, plane: &Plane) -> Option<u32> {
        let f = face as usize;
        let range = *self.face_pieces.get(f)?..*self.face_pieces.get(f + 1)?;
        let pieces = self.geometry.pieces();
        let mut best = (f64::NEG_INFINITY, None);
        for i in range {
            let p = pieces.plane(i as usize);
            let score = p.normal().dot(plane.normal()) - (p.offset() - plane.offset()).abs();
            if score > best.0 {
                best = (score, Some(i));
            }
        }
        best.1
    }

    /// Rebuilds the polygon → sprite mapping when the sorter's shared set changed.
    pub(super) fn update_shared(&mut self, out: &mut dyn Compositor) {
        let Some(shared) = self.list.shared().cloned() else {
            return;
        };
        if self
            .fragments
            .shared
            .as_ref()
            .is_some_and(|s| Arc::ptr_eq(s, &shared))
        {
            return;
        }
        for id in std::mem::take(&mut self.fragments.shared_fragments) {
            self.destroy(id, out);
        }
        let pieces = Arc::clone(self.geometry.pieces());
        self.fragments.shared_to_sprite.clear();
        if Arc::ptr_eq(&shared, &pieces) {
            self.fragments
                .shared_to_sprite
                .extend((0..pieces.len() as u32).map(|i| {
                    if self.pool.sprites[i as usize].piece.is_none() {
                        SpriteId::NONE
                    } else {
                        SpriteId(i)
                    }
                }));
        } else {
            for i in 0..shared.len() {
                let face = shared.face(i);
                let corners = shared.corners(i);
                let f = face as usize;
                let whole = match (self.face_pieces.get(f), self.face_pieces.get(f + 1)) {
                    (Some(&a), Some(&b)) => (a..b).find(|&p| pieces.corners(p as usize) == corners),
                    _ => None,
                };
                let id = match whole {
                    Some(p) if !self.pool.sprites[p as usize].piece.is_none() => SpriteId(p),
                    Some(_) => SpriteId::NONE,
                    None => match self.source_piece(face, shared.plane(i)) {
                        Some(piece)
                            if fragment_clip(
                                &self.maps,
                                piece,
                                corners,
                                &mut self.fragments.clip_scratch,
                            ) =>
                        {
                            let id = self.new_sprite_id(face, piece);
                            let sprite = &mut self.pool.sprites[id.index()];
                            sprite.polygon = Some(i as u32);
                            sprite.clip.clear();
                            sprite.clip.extend_from_slice(&self.fragments.clip_scratch);
                            sprite.has_clip = true;
                            self.fragments.shared_fragments.push(id);
                            if self.started {
                                self.create(id, out);
                            }
                            id
                        }
                        _ => SpriteId::NONE,
                    },
                };
                self.fragments.shared_to_sprite.push(id);
            }
        }
        self.fragments.shared = Some(shared);
    }

    /// Slot `k` of the per-frame fragment pool, showing a fragment of `piece`.
    pub(super) fn transient_slot(
        &mut self,
        k: usize,
        face: u32,
        piece: u32,
        out: &mut dyn Compositor,
    ) -> SpriteId {
        if k == self.fragments.transient.len() {
            let id = self.new_sprite_id(face, piece);
            let sprite = &mut self.pool.sprites[id.index()];
            sprite.clip.clear();
            sprite.clip.extend_from_slice(&self.fragments.clip_scratch);
            sprite.has_clip = true;
            self.create(id, out);
            self.fragments.transient.push(id);
            return id;
        }
        let id = self.fragments.transient[k];
        let maps = &self.maps;
        let sprite = &mut self.pool.sprites[id.index()];
        if sprite.piece != PieceId::new(piece)
            && let Some(map) = maps.get(piece as usize)
        {
            sprite.piece = PieceId::new(piece);
            out.set_transform(id, &map.transform);
        }
        if !sprite.has_clip || sprite.clip != self.fragments.clip_scratch {
            sprite.clip.clear();
            sprite.clip.extend_from_slice(&self.fragments.clip_scratch);
            sprite.has_clip = true;
            out.set_clip(id, Some(&sprite.clip));
        }
        if sprite.face != face {
            sprite.face = face;
            let brush = self
                .brushes
                .get(face as usize)
                .copied()
                .unwrap_or(Brush::Palette);
            if brush != sprite.brush {
                sprite.brush = brush;
                out.set_brush(id, &brush);
            }
        }
        id
    }
}
