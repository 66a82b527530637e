//! The sprite painter: one sprite per piece, minimal per-frame operations.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use face_sort::{CullMode, DrawList, FaceSorter, Geometry, Plane, PolygonSet, View};
use glam::{DMat3, DMat4, DVec2};

use crate::compositor::Counting;
use crate::order::StackMirror;
use crate::{Brush, Compositor, OpCounts, PieceMaps, SpriteId, SpriteTransform, root_transform};

const NONE: u32 = u32::MAX;

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

/// A thread-safe handle that requests a rotation for the painter's next
/// [`tick`](SpritePainter::tick). Requests coalesce: only the latest one is applied.
#[derive(Clone, Debug, Default)]
pub struct RotationHandle {
    pending: Arc<Mutex<Option<DMat3>>>,
}

impl RotationHandle {
    /// Requests `rotation` (CONVENTIONS.md's `R`) for the next tick, replacing any request not
    /// yet applied. Callable from any thread.
    pub fn request_rotation(&self, rotation: DMat3) {
        match self.pending.lock() {
            Ok(mut slot) => *slot = Some(rotation),
            Err(poisoned) => *poisoned.into_inner() = Some(rotation),
        }
    }

    fn take(&self) -> Option<DMat3> {
        match self.pending.lock() {
            Ok(mut slot) => slot.take(),
            Err(poisoned) => poisoned.into_inner().take(),
        }
    }
}

/// A rotation as a function of time, sampled on every [`tick`](SpritePainter::tick).
pub type RotationSource = Box<dyn FnMut(Duration) -> DMat3 + Send>;

#[derive(Clone, Debug)]
struct SpriteState {
    alive: bool,
    face: u32,
    /// Source piece (its transform), `NONE` for a free id.
    piece: u32,
    visible: bool,
    brush: Brush,
    /// Index in the shared polygon set for a shared fragment, else `NONE`.
    polygon: u32,
    /// Clip polygon in unit-square coordinates; `has_clip == false`: the whole square.
    clip: Vec<DVec2>,
    has_clip: bool,
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

struct State {
    geometry: Geometry,
    sorter: Box<dyn FaceSorter>,
    list: DrawList,
    view: View,
    maps: PieceMaps,
    /// Pieces of face `f`: `face_pieces[f]..face_pieces[f + 1]`.
    face_pieces: Vec<u32>,
    brushes: Vec<Brush>,
    sprites: Vec<SpriteState>,
    free_ids: Vec<u32>,
    shared: Option<Arc<PolygonSet>>,
    shared_to_sprite: Vec<u32>,
    shared_fragments: Vec<SpriteId>,
    transient: Vec<SpriteId>,
    mirror: StackMirror,
    sequence: Vec<SpriteId>,
    previous: Vec<SpriteId>,
    shown: Vec<u32>,
    stamp: u32,
    root_sent: Option<DMat4>,
    clip_scratch: Vec<DVec2>,
    started: bool,
    dirty_transforms: bool,
    dirty_root: bool,
    dirty_sort: bool,
    dirty_brushes: bool,
    requests: RotationHandle,
    source: Option<RotationSource>,
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
        self.state.sprites.iter().filter(|s| s.alive).count()
    }

    /// Sets the whole view; the next frame does only what the change requires (see the
    /// table above).
    pub fn set_view(&mut self, view: View) {
        let s = &mut self.state;
        let old = s.view;
        if old == view {
            return;
        }
        if old.centre() != view.centre()
            || old.scale() != view.scale()
            || old.width() != view.width()
            || old.height() != view.height()
        {
            s.dirty_transforms = true;
            s.dirty_root = true;
            s.dirty_sort = true;
        }
        if old.rotation() != view.rotation() || old.projection() != view.projection() {
            s.dirty_root = true;
            s.dirty_sort = true;
        }
        if old.cull() != view.cull()
            || old.front_face() != view.front_face()
            || old.cull_margin() != view.cull_margin()
            || old.diagonal() != view.diagonal()
        {
            s.dirty_sort = true;
        }
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
        self.state.dirty_sort = true;
    }

    /// Replaces the model: every sprite is destroyed and rebuilt at the next frame. `view`
    /// is usually `View::fit` of the new geometry. Brushes reset to the palette.
    pub fn set_geometry(&mut self, geometry: &Geometry, sorter: Box<dyn FaceSorter>, view: View) {
        let mut out = Counting {
            inner: &mut self.compositor,
            ops: OpCounts::default(),
        };
        let s = &mut self.state;
        for (i, sprite) in s.sprites.iter().enumerate() {
            if sprite.alive {
                out.destroy_sprite(SpriteId(i as u32));
            }
        }
        let requests = s.requests.clone();
        let source = s.source.take();
        let mut fresh = State::new_like(geometry, sorter, view);
        fresh.requests = requests;
        fresh.source = source;
        fresh.root_sent = s.root_sent;
        *s = fresh;
    }

    /// Sets every face's brush (`brush(face)`); the next frame sends `set_brush` only to
    /// sprites whose brush changed.
    pub fn set_brushes(&mut self, mut brush: impl FnMut(u32) -> Brush) {
        for (face, b) in self.state.brushes.iter_mut().enumerate() {
            *b = brush(face as u32);
        }
        self.state.dirty_brushes = true;
    }

    /// A handle that other threads use to request rotations (applied at the next
    /// [`tick`](Self::tick), latest request wins).
    #[must_use]
    pub fn rotation_handle(&self) -> RotationHandle {
        self.state.requests.clone()
    }

    /// Sets (or clears) a rotation source sampled on every [`tick`](Self::tick).
    pub fn set_rotation_source(&mut self, source: Option<RotationSource>) {
        self.state.source = source;
    }

    /// Samples the rotation source at `time`, then applies the latest pending
    /// [`RotationHandle`] request (which wins over the source for this tick), then runs
    /// [`frame`](Self::frame).
    pub fn tick(&mut self, time: Duration) -> FrameStats {
        if let Some(source) = &mut self.state.source {
            let r = source(time);
            self.set_rotation(r);
        }
        if let Some(r) = self.state.requests.take() {
            self.set_rotation(r);
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
            if s.dirty_transforms {
                s.rebuild_transforms(&mut out);
            }
            if s.dirty_brushes {
                s.resend_brushes(&mut out);
            }
            if s.dirty_sort {
                s.sort_and_apply(&mut out);
                sorted = true;
            }
        }
        if s.dirty_root {
            let root = root_transform(&s.view);
            if s.root_sent != Some(root) {
                out.set_root_transform(&root);
                s.root_sent = Some(root);
            }
        }
        s.dirty_transforms = false;
        s.dirty_brushes = false;
        s.dirty_sort = false;
        s.dirty_root = false;
        FrameStats {
            ops: out.ops,
            sorted,
            drawn: s.previous.len(),
        }
    }
}

fn face_pieces(geometry: &Geometry) -> Vec<u32> {
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
            sprites: Vec::new(),
            free_ids: Vec::new(),
            shared: None,
            shared_to_sprite: Vec::new(),
            shared_fragments: Vec::new(),
            transient: Vec::new(),
            mirror: StackMirror::default(),
            sequence: Vec::new(),
            previous: Vec::new(),
            shown: Vec::new(),
            stamp: 0,
            root_sent: None,
            clip_scratch: Vec::new(),
            started: false,
            dirty_transforms: false,
            dirty_root: true,
            dirty_sort: true,
            dirty_brushes: false,
            requests: RotationHandle::default(),
            source: None,
        }
    }

    /// First frame: sprites for every piece, stacked in the order of a sort without culling
    /// (so that faces turning visible later usually need no move), then the real frame.
    fn start(&mut self, out: &mut dyn Compositor) {
        self.started = true;
        let pieces = Arc::clone(self.geometry.pieces());
        self.sprites.clear();
        for i in 0..pieces.len() {
            let has_map = self.maps.get(i).is_some();
            self.sprites.push(SpriteState {
                alive: false,
                face: pieces.face(i),
                piece: if has_map { i as u32 } else { NONE },
                visible: false,
                brush: Brush::Palette,
                polygon: NONE,
                clip: Vec::new(),
                has_clip: false,
            });
        }
        let unculled = self.view.with_cull(CullMode::None);
        self.sorter.sort(&unculled, &mut self.list);
        self.update_shared(out);
        for k in 0..self.list.len() {
            let item = self.list.items()[k];
            if let Some(&id) = self.shared_to_sprite.get(item.polygon as usize)
                && id != NONE
            {
                self.create(SpriteId(id), out);
            }
        }
        for i in 0..self.sprites.len() {
            if self.sprites[i].piece != NONE && !self.sprites[i].alive {
                self.create(SpriteId(i as u32), out);
            }
        }
        let n = self.sprites.len();
        self.mirror.reserve(n);
        self.sequence.reserve(n);
        self.previous.reserve(n);
        self.shown.resize(n, 0);
        self.sort_and_apply(out);
    }

    /// Sends create + transform + clip + brush for a sprite whose state is filled in.
    fn create(&mut self, id: SpriteId, out: &mut dyn Compositor) {
        let sprite = &mut self.sprites[id.index()];
        if sprite.alive {
            return;
        }
        let Some(map) = self.maps.get(sprite.piece as usize) else {
            return;
        };
        sprite.alive = true;
        out.create_sprite(id, sprite.face);
        self.mirror.push(id);
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

    fn new_sprite_id(&mut self, face: u32, piece: u32) -> SpriteId {
        let state = SpriteState {
            alive: false,
            face,
            piece,
            visible: false,
            brush: Brush::Palette,
            polygon: NONE,
            clip: Vec::new(),
            has_clip: false,
        };
        if let Some(id) = self.free_ids.pop() {
            self.sprites[id as usize] = state;
            SpriteId(id)
        } else {
            self.sprites.push(state);
            SpriteId(self.sprites.len() as u32 - 1)
        }
    }

    fn destroy(&mut self, id: SpriteId, out: &mut dyn Compositor) {
        let sprite = &mut self.sprites[id.index()];
        if sprite.alive {
            out.destroy_sprite(id);
            self.mirror.remove(id);
        }
        sprite.alive = false;
        sprite.visible = false;
        sprite.piece = NONE;
        self.free_ids.push(id.0);
    }

    /// The piece of `face` that a polygon with `plane` was cut from.
    fn source_piece(&self, face: u32, plane: &Plane) -> Option<u32> {
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
    fn update_shared(&mut self, out: &mut dyn Compositor) {
        let Some(shared) = self.list.shared().cloned() else {
            return;
        };
        if self
            .shared
            .as_ref()
            .is_some_and(|s| Arc::ptr_eq(s, &shared))
        {
            return;
        }
        for id in std::mem::take(&mut self.shared_fragments) {
            self.destroy(id, out);
        }
        let pieces = Arc::clone(self.geometry.pieces());
        self.shared_to_sprite.clear();
        if Arc::ptr_eq(&shared, &pieces) {
            self.shared_to_sprite
                .extend((0..pieces.len() as u32).map(|i| {
                    if self.sprites[i as usize].piece != NONE {
                        i
                    } else {
                        NONE
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
                    Some(p) if self.sprites[p as usize].piece != NONE => p,
                    Some(_) => NONE,
                    None => match self.source_piece(face, shared.plane(i)) {
                        Some(piece)
                            if fragment_clip(
                                &self.maps,
                                piece,
                                corners,
                                &mut self.clip_scratch,
                            ) =>
                        {
                            let id = self.new_sprite_id(face, piece);
                            let sprite = &mut self.sprites[id.index()];
                            sprite.polygon = i as u32;
                            sprite.clip.clear();
                            sprite.clip.extend_from_slice(&self.clip_scratch);
                            sprite.has_clip = true;
                            self.shared_fragments.push(id);
                            if self.started {
                                self.create(id, out);
                            }
                            id.0
                        }
                        _ => NONE,
                    },
                };
                self.shared_to_sprite.push(id);
            }
        }
        self.shared = Some(shared);
    }

    /// Slot `k` of the per-frame fragment pool, showing a fragment of `piece`.
    fn transient_slot(
        &mut self,
        k: usize,
        face: u32,
        piece: u32,
        out: &mut dyn Compositor,
    ) -> SpriteId {
        if k == self.transient.len() {
            let id = self.new_sprite_id(face, piece);
            let sprite = &mut self.sprites[id.index()];
            sprite.clip.clear();
            sprite.clip.extend_from_slice(&self.clip_scratch);
            sprite.has_clip = true;
            self.create(id, out);
            self.transient.push(id);
            return id;
        }
        let id = self.transient[k];
        let maps = &self.maps;
        let sprite = &mut self.sprites[id.index()];
        if sprite.piece != piece
            && let Some(map) = maps.get(piece as usize)
        {
            sprite.piece = piece;
            out.set_transform(id, &map.transform);
        }
        if !sprite.has_clip || sprite.clip != self.clip_scratch {
            sprite.clip.clear();
            sprite.clip.extend_from_slice(&self.clip_scratch);
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

    fn sort_and_apply(&mut self, out: &mut dyn Compositor) {
        self.sorter.sort(&self.view, &mut self.list);
        self.update_shared(out);
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.shown.iter_mut().for_each(|s| *s = 0);
            self.stamp = 1;
        }
        let shared_len = self.shared_to_sprite.len();
        self.sequence.clear();
        let mut transient_used = 0;
        for k in 0..self.list.len() {
            let item = self.list.items()[k];
            let id = if (item.polygon as usize) < shared_len {
                self.shared_to_sprite[item.polygon as usize]
            } else {
                // A per-frame fragment.
                let plane = *self.list.plane(item);
                match self.source_piece(item.face, &plane) {
                    Some(piece) => {
                        let ok = fragment_clip(
                            &self.maps,
                            piece,
                            self.list.corners(item),
                            &mut self.clip_scratch,
                        );
                        if ok {
                            transient_used += 1;
                            self.transient_slot(transient_used - 1, item.face, piece, out)
                                .0
                        } else {
                            NONE
                        }
                    }
                    None => NONE,
                }
            };
            if id == NONE {
                continue;
            }
            if self.shown.len() <= id as usize {
                self.shown
                    .resize(self.sprites.len().max(id as usize + 1), 0);
            }
            if self.shown[id as usize] == self.stamp {
                continue;
            }
            self.shown[id as usize] = self.stamp;
            self.sequence.push(SpriteId(id));
        }
        for &id in &self.sequence {
            let sprite = &mut self.sprites[id.index()];
            if !sprite.visible {
                sprite.visible = true;
                out.set_visible(id, true);
            }
        }
        for &id in &self.previous {
            let sprite = &mut self.sprites[id.index()];
            if sprite.visible && self.shown.get(id.index()) != Some(&self.stamp) {
                sprite.visible = false;
                out.set_visible(id, false);
            }
        }
        self.mirror.reorder(&self.sequence, out);
        std::mem::swap(&mut self.sequence, &mut self.previous);
    }

    fn rebuild_transforms(&mut self, out: &mut dyn Compositor) {
        self.maps = PieceMaps::new(&self.geometry, &self.view);
        let space = *self.maps.space();
        let piece_count = self.geometry.pieces().len();
        let shared = self.shared.clone();
        for i in 0..self.sprites.len() {
            let sprite = &self.sprites[i];
            if !sprite.alive {
                continue;
            }
            let is_piece = i < piece_count;
            let shared_fragment = shared
                .as_ref()
                .filter(|_| !is_piece && sprite.polygon != NONE)
                .map(|set| set.corners(sprite.polygon as usize));
            if !is_piece && shared_fragment.is_none() {
                // A per-frame fragment slot: force a resend when it is next used.
                self.sprites[i].piece = NONE - 1;
                continue;
            }
            let Some(map) = self.maps.get(sprite.piece as usize) else {
                continue;
            };
            let id = SpriteId(i as u32);
            out.set_transform(id, &map.transform);
            // New clip: a piece's own, or a fragment's corners on its piece's map.
            self.clip_scratch.clear();
            if let Some(corners) = shared_fragment {
                let t = map.transform;
                self.clip_scratch
                    .extend(corners.iter().map(|&c| t.unit_coords(space.point(c))));
            } else if let Some(clip) = &map.clip {
                self.clip_scratch.extend_from_slice(clip);
            }
            let sprite = &mut self.sprites[i];
            let has = !self.clip_scratch.is_empty();
            if has != sprite.has_clip || sprite.clip != self.clip_scratch {
                sprite.clip.clear();
                sprite.clip.extend_from_slice(&self.clip_scratch);
                sprite.has_clip = has;
                out.set_clip(id, has.then_some(&sprite.clip[..]));
            }
        }
    }

    fn resend_brushes(&mut self, out: &mut dyn Compositor) {
        for (i, sprite) in self.sprites.iter_mut().enumerate() {
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
        let sprite = self.state.sprites.get(id.index()).filter(|s| s.alive)?;
        self.state
            .maps
            .get(sprite.piece as usize)
            .map(|m| &m.transform)
    }
}

/// Fills `out` with the unit-square coordinates of `corners` on `piece`'s map; `false` when
/// the piece has no map.
fn fragment_clip(
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
