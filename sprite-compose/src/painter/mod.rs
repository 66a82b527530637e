//! The sprite painter: one sprite per piece, minimal per-frame operations.
//!
//! One concern per module: the sprite id [`pool`], the [`fragments`] slots, [`stack`]
//! diffing, the [`dirty`] flags and cross-thread [`rotation`]; this module holds the public
//! [`SpritePainter`] and the frame that puts them together.

mod dirty;
mod fragments;
mod pool;
mod rotation;
mod stack;

use std::sync::Arc;
use std::time::Duration;

use face_sort::{CullMode, DrawList, FaceSorter, Geometry, PieceId, View};
use glam::{DMat3, DMat4, DVec2};

use crate::compositor::Counting;
use crate::{Brush, Compositor, OpCounts, PieceMaps, SpriteId, SpriteTransform, root_transform};
use dirty::Dirty;
use fragments::{FragmentSlots, face_pieces, fragment_clip};
use pool::{SpritePool, SpriteState};
use rotation::RotationInputs;
pub use rotation::{RotationHandle, RotationSource};
use stack::StackDiff;

/// What one [`SpritePainter::frame`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Operations sent to the compositor, by kind.
    pub ops: OpCounts,
    /// Whether the sorter ran (rotation, projection, culling or sorter changed).
    pub sorted: bool,
    /// Sprites shown.
    pub drawn: usize,
}

/// Draws a [`Geometry`] through a retained [`Compositor`]: one sprite per piece (plus one per
/// split fragment), created once; each frame sends only what changed.
///
/// # What each input change costs
/// | change | operations |
/// | --- | --- |
/// | model ([`set_geometry`](Self::set_geometry)) | destroy and create every sprite |
/// | scale or image size | a new transform (and clip where it changed) per sprite, the root, and a sort |
/// | rotation | the root (if it changed), then culling and order: visibility flips and moves |
/// | perspective / projection | the root, then order |
/// | cull mode, front face, cull margin | visibility flips and moves only |
/// | sorter ([`set_sorter`](Self::set_sorter)) | order only (fragment sprites follow the sorter's polygons) |
/// | materials ([`set_brushes`](Self::set_brushes)) | `set_brush` for sprites whose brush changed |
/// | nothing | nothing (zero operations) |
///
/// Visibility flips go only to sprites whose visibility changed; reorders keep the longest
/// increasing subsequence of the previous stack in place and move the rest. Once the pools
/// and buffers have grown (after the first frames), a frame allocates nothing.
///
/// # Fragments
/// Sprites are keyed by the polygons of the sorter's shared polygon set (a piece's sprite is
/// the piece's; a precomputed fragment, e.g. BSP's, gets its own sprite with its source
/// piece's transform and a clip polygon). The sprite mapping is rebuilt only when the shared
/// set changes (a new sorter). Per-frame fragments (Newell's) are not stable across frames:
/// they go to a pool of slots that grows to the largest count seen; slot `k` shows the `k`-th
/// per-frame fragment, with its transform, clip and brush re-sent only when they changed.
pub struct SpritePainter<C: Compositor> {
    compositor: C,
    state: State,
}

/// Everything a painter keeps between frames.
struct State {
    geometry: Geometry,
    sorter: Box<dyn FaceSorter>,
    list: DrawList,
    view: View,
    maps: PieceMaps,
    /// Pieces of face `f`: `face_pieces[f]..face_pieces[f + 1]`.
    face_pieces: Vec<u32>,
    brushes: Vec<Brush>,
    pool: SpritePool,
    fragments: FragmentSlots,
    stack: StackDiff,
    root_sent: Option<DMat4>,
    started: bool,
    dirty: Dirty,
    rotation: RotationInputs,
}

impl<C: Compositor> SpritePainter<C> {
    /// A painter for `geometry` seen through `view`, ordered by `sorter`, drawing into
    /// `compositor` (which must be empty). Nothing is sent until the first
    /// [`frame`](Self::frame). Every face starts with [`Brush::Palette`].
    #[must_use]
    pub fn new(
        geometry: &Geometry,
        sorter: Box<dyn FaceSorter>,
        view: View,
        compositor: C,
    ) -> Self {
        let state = State::new_like(geometry, sorter, view);
        SpritePainter { compositor, state }
    }

    /// The compositor.
    #[must_use]
    pub fn compositor(&self) -> &C {
        &self.compositor
    }

    /// The compositor, mutable (for backend-specific work between frames; sprite operations
    /// sent behind the painter's back break its mirror of the backend).
    pub fn compositor_mut(&mut self) -> &mut C {
        &mut self.compositor
    }

    /// Gives the compositor back.
    #[must_use]
    pub fn into_compositor(self) -> C {
        self.compositor
    }

    /// The current view.
    #[must_use]
    pub fn view(&self) -> &View {
        &self.state.view
    }

    /// The geometry drawn.
    #[must_use]
    pub fn geometry(&self) -> &Geometry {
        &self.state.geometry
    }

    /// The draw list of the last sorted frame (paint order).
    #[must_use]
    pub fn draw_list(&self) -> &DrawList {
        &self.state.list
    }

    /// The per-piece transforms (built once per geometry, scale and image size).
    #[must_use]
    pub fn piece_maps(&self) -> &PieceMaps {
        &self.state.maps
    }

    /// Number of sprites in the pool (pieces, fragments and per-frame fragment slots).
    #[must_use]
    pub fn sprite_count(&self) -> usize {
        self.state.pool.alive()
    }

    /// Sets the whole view; the next frame does only what the change requires (see the
    /// table above).
    pub fn set_view(&mut self, view: View) {
        let s = &mut self.state;
        let old = s.view;
        if old == view {
            return;
        }
        s.dirty.view_changed(&old, &view);
        s.view = view;
    }

    /// Sets the rotation only.
    pub fn set_rotation(&mut self, rotation: DMat3) {
        let view = self.state.view.with_rotation(rotation);
        self.set_view(view);
    }

    /// Replaces the sorter: the next frame re-sorts; transforms stay.
    pub fn set_sorter(&mut self, sorter: Box<dyn FaceSorter>) {
        self.state.sorter = sorter;
        self.state.dirty.sort = true;
    }

    /// Replaces the model: every sprite is destroyed and rebuilt at the next frame. `view`
    /// is usually `View::fit` of the new geometry. Brushes reset to the palette.
    pub fn set_geometry(&mut self, geometry: &Geometry, sorter: Box<dyn FaceSorter>, view: View) {
        let mut out = Counting {
            inner: &mut self.compositor,
            ops: OpCounts::default(),
        };
        let s = &mut self.state;
        for (i, sprite) in s.pool.sprites.iter().enumerate() {
            if sprite.alive {
                out.destroy_sprite(SpriteId(i as u32));
            }
        }
        let requests = s.rotation.requests.clone();
        let source = s.rotation.source.take();
        let mut fresh = State::new_like(geometry, sorter, view);
        fresh.rotation.requests = requests;
        fresh.rotation.source = source;
        fresh.root_sent = s.root_sent;
        *s = fresh;
    }

    /// Sets every face's brush (`brush(face)`); the next frame sends `set_brush` only to
    /// sprites whose brush changed.
    pub fn set_brushes(&mut self, mut brush: impl FnMut(u32) -> Brush) {
        for (face, b) in self.state.brushes.iter_mut().enumerate() {
            *b = brush(face as u32);
        }
        self.state.dirty.brushes = true;
    }

    /// A handle that other threads use to request rotations (applied at the next
    /// [`tick`](Self::tick), latest request wins).
    #[must_use]
    pub fn rotation_handle(&self) -> RotationHandle {
        self.state.rotation.requests.clone()
    }

    /// Sets (or clears) a rotation source sampled on every [`tick`](Self::tick).
    pub fn set_rotation_source(&mut self, source: Option<RotationSource>) {
        self.state.rotation.source = source;
    }

    /// Samples the rotation source at `time`, then applies the latest pending
    /// [`RotationHandle`] request (which wins over the source for this tick), then runs
    /// [`frame`](Self::frame).
    pub fn tick(&mut self, time: Duration) -> FrameStats {
        for rotation in self.state.rotation.at(time).into_iter().flatten() {
            self.set_rotation(rotation);
        }
        self.frame()
    }

    /// Sends the compositor what changed since the last frame.
    pub fn frame(&mut self) -> FrameStats {
        let mut out = Counting {
            inner: &mut self.compositor,
            ops: OpCounts::default(),
        };
        let s = &mut self.state;
        let mut sorted = false;
        if !s.started {
            s.start(&mut out);
            sorted = true;
        } else {
            if s.dirty.transforms {
                s.rebuild_transforms(&mut out);
            }
            if s.dirty.brushes {
                s.resend_brushes(&mut out);
            }
            if s.dirty.sort {
                s.sort_and_apply(&mut out);
                sorted = true;
            }
        }
        if s.dirty.root {
            let root = root_transform(&s.view);
            if s.root_sent != Some(root) {
                out.set_root_transform(&root);
                s.root_sent = Some(root);
            }
        }
        s.dirty = Dirty::default();
        FrameStats {
            ops: out.ops,
            sorted,
            drawn: s.stack.drawn(),
        }
    }
}

impl State {
    fn new_like(geometry: &Geometry, sorter: Box<dyn FaceSorter>, view: View) -> Self {
        State {
            geometry: geometry.clone(),
            sorter,
            list: DrawList::new(),
            view,
            maps: PieceMaps::new(geometry, &view),
            face_pieces: face_pieces(geometry),
            brushes: vec![Brush::Palette; geometry.face_count()],
            pool: SpritePool::default(),
            fragments: FragmentSlots::default(),
            stack: StackDiff::default(),
            root_sent: None,
            started: false,
            dirty: Dirty::FIRST_FRAME,
            rotation: RotationInputs::default(),
        }
    }

    /// First frame: sprites for every piece, stacked in the order of a sort without culling
    /// (so that faces turning visible later usually need no move), then the real frame.
    fn start(&mut self, out: &mut dyn Compositor) {
        self.started = true;
        let pieces = Arc::clone(self.geometry.pieces());
        self.pool.sprites.clear();
        for i in 0..pieces.len() {
            let has_map = self.maps.get(i).is_some();
            let piece = if has_map {
                PieceId::new(i as u32)
            } else {
                PieceId::NONE
            };
            self.pool
                .sprites
                .push(SpriteState::new(pieces.face(i), piece));
        }
        let unculled = self.view.with_cull(CullMode::None);
        self.sorter.sort(&unculled, &mut self.list);
        self.update_shared(out);
        for k in 0..self.list.len() {
            let item = self.list.items()[k];
            if let Some(&id) = self.fragments.shared_to_sprite.get(item.polygon as usize)
                && id != SpriteId::NONE
            {
                self.create(id, out);
            }
        }
        for i in 0..self.pool.sprites.len() {
            if !self.pool.sprites[i].piece.is_none() && !self.pool.sprites[i].alive {
                self.create(SpriteId(i as u32), out);
            }
        }
        self.stack.reserve(self.pool.sprites.len());
        self.sort_and_apply(out);
    }

    fn sort_and_apply(&mut self, out: &mut dyn Compositor) {
        self.sorter.sort(&self.view, &mut self.list);
        self.update_shared(out);
        self.stack.begin();
        let shared_len = self.fragments.shared_to_sprite.len();
        let mut transient_used = 0;
        for k in 0..self.list.len() {
            let item = self.list.items()[k];
            let id = if (item.polygon as usize) < shared_len {
                self.fragments.shared_to_sprite[item.polygon as usize]
            } else {
                // A per-frame fragment.
                let plane = *self.list.plane(item);
                match self.source_piece(item.face, &plane) {
                    Some(piece) => {
                        let ok = fragment_clip(
                            &self.maps,
                            piece,
                            self.list.corners(item),
                            &mut self.fragments.clip_scratch,
                        );
                        if ok {
                            transient_used += 1;
                            self.transient_slot(transient_used - 1, item.face, piece, out)
                        } else {
                            SpriteId::NONE
                        }
                    }
                    None => SpriteId::NONE,
                }
            };
            if id != SpriteId::NONE {
                self.stack.push(id.0, self.pool.sprites.len());
            }
        }
        self.stack.finish(&mut self.pool.sprites, out);
    }

    fn rebuild_transforms(&mut self, out: &mut dyn Compositor) {
        self.maps = PieceMaps::new(&self.geometry, &self.view);
        let space = *self.maps.space();
        let piece_count = self.geometry.pieces().len();
        let shared = self.fragments.shared.clone();
        for i in 0..self.pool.sprites.len() {
            let sprite = &self.pool.sprites[i];
            if !sprite.alive {
                continue;
            }
            let is_piece = i < piece_count;
            let shared_fragment = (shared.as_ref())
                .filter(|_| !is_piece)
                .zip(sprite.polygon)
                .map(|(set, polygon)| set.corners(polygon as usize));
            if !is_piece && shared_fragment.is_none() {
                // A per-frame fragment slot: force a resend when it is next used.
                self.pool.sprites[i].piece = PieceId::NONE;
                continue;
            }
            let Some(map) = sprite.piece.get().and_then(|p| self.maps.get(p as usize)) else {
                continue;
            };
            let id = SpriteId(i as u32);
            out.set_transform(id, &map.transform);
            // New clip: a piece's own, or a fragment's corners on its piece's map.
            self.fragments.clip_scratch.clear();
            if let Some(corners) = shared_fragment {
                let t = map.transform;
                self.fragments
                    .clip_scratch
                    .extend(corners.iter().map(|&c| t.unit_coords(space.point(c))));
            } else if let Some(clip) = &map.clip {
                self.fragments.clip_scratch.extend_from_slice(clip);
            }
            let sprite = &mut self.pool.sprites[i];
            let has = !self.fragments.clip_scratch.is_empty();
            if has != sprite.has_clip || sprite.clip != self.fragments.clip_scratch {
                sprite.clip.clear();
                sprite.clip.extend_from_slice(&self.fragments.clip_scratch);
                sprite.has_clip = has;
                out.set_clip(id, has.then_some(&sprite.clip[..]));
            }
        }
    }

    fn resend_brushes(&mut self, out: &mut dyn Compositor) {
        for (i, sprite) in self.pool.sprites.iter_mut().enumerate() {
            if !sprite.alive {
                continue;
            }
            let brush = self
                .brushes
                .get(sprite.face as usize)
                .copied()
                .unwrap_or(Brush::Palette);
            if brush != sprite.brush {
                sprite.brush = brush;
                out.set_brush(SpriteId(i as u32), &brush);
            }
        }
    }
}

impl<C: Compositor> SpritePainter<C> {
    /// The transform a sprite was last sent (for writers and tests).
    #[must_use]
    pub fn sprite_transform(&self, id: SpriteId) -> Option<&SpriteTransform> {
        let sprite = self
            .state
            .pool
            .sprites
            .get(id.index())
            .filter(|s| s.alive)?;
        let piece = sprite.piece.get()?;
        self.state.maps.get(piece as usize).map(|m| &m.transform)
    }
}

impl<C: Compositor> SpritePainter<C> {
    /// The drawn polygons of the current frame, projected to pixels (for picking, outlines
    /// and overlays). Allocates; not for the per-frame path.
    #[must_use]
    pub fn projected_frame(&self) -> crate::ProjectedFrame {
        crate::ProjectedFrame::new(&self.state.view, &self.state.list)
    }

    /// The topmost face at pixel position `(x, y)` of the current frame (a pixel's centre is
    /// `(x + 0.5, y + 0.5)`): front to back over the draw list, exact point-in-polygon on the
    /// projected polygons.
    #[must_use]
    pub fn pick(&self, x: f64, y: f64) -> Option<face_sort::DrawItem> {
        self.projected_frame().pick(DVec2::new(x, y))
    }
}
