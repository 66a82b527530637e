//! A retained in-memory scene and the recording backend that keeps it.

use face_sort::tolerance::NEAR_W;
use glam::{DMat4, DVec2, DVec4};

use crate::{Brush, Compositor, MapKind, OpCounts, SpriteId, SpriteTransform};

/// One sprite of a [`Scene`].
#[derive(Clone, Debug, PartialEq)]
pub struct SceneSprite {
    /// Source face.
    pub face: u32,
    /// Fixed transform.
    pub transform: SpriteTransform,
    /// Clip polygon in unit-square coordinates (`None`: the whole square).
    pub clip: Option<Vec<DVec2>>,
    /// Brush.
    pub brush: Brush,
    /// Whether it is shown.
    pub visible: bool,
    /// Whether its back may show ([`Compositor::set_back_visible`]).
    pub back_visible: bool,
}

/// What a retained compositor holds: sprites, their stacking order and the root transform.
/// The SVG and HTML writers render a `Scene`.
///
/// # Panics
/// As a [`Compositor`], on contract violations by the caller: an operation on a sprite that
/// does not exist, creating a sprite twice, or moving a sprite before itself.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    sprites: Vec<Option<SceneSprite>>,
    stack: Vec<SpriteId>,
    root: DMat4,
}

impl Scene {
    /// An empty scene with the identity root.
    #[must_use]
    pub fn new() -> Self {
        Scene {
            sprites: Vec::new(),
            stack: Vec::new(),
            root: DMat4::IDENTITY,
        }
    }

    /// The root transform.
    #[must_use]
    pub fn root(&self) -> &DMat4 {
        &self.root
    }

    /// A sprite, if it exists.
    #[must_use]
    pub fn sprite(&self, id: SpriteId) -> Option<&SceneSprite> {
        self.sprites.get(id.index()).and_then(Option::as_ref)
    }

    /// Every sprite, bottom of the stack first.
    #[must_use]
    pub fn stack(&self) -> &[SpriteId] {
        &self.stack
    }

    /// Visible sprites in paint order (bottom first): shown, and either their back may show
    /// or their front faces the viewer under the root transform (what the writers draw).
    pub fn visible(&self) -> impl Iterator<Item = (SpriteId, &SceneSprite)> + '_ {
        self.stack.iter().filter_map(|&id| {
            self.sprite(id)
                .filter(|s| s.visible && (s.back_visible || self.faces_viewer(s)))
                .map(|s| (id, s))
        })
    }

    /// Whether a sprite's front faces the viewer: the unit square's image under
    /// `root · transform` keeps the orientation that every front-facing piece's sprite has
    /// in pixel space (y down), `(p(1, 0) − p(0, 0)) × (p(0, 1) − p(0, 0)) > 0`, in front of
    /// the eye.
    #[must_use]
    pub fn faces_viewer(&self, sprite: &SceneSprite) -> bool {
        let m = self.root * sprite.transform.matrix;
        let project = |u: f64, v: f64| {
            let h = m * glam::DVec4::new(u, v, 0.0, 1.0);
            (h.w > 0.0).then(|| DVec2::new(h.x / h.w, h.y / h.w))
        };
        match (project(0.0, 0.0), project(1.0, 0.0), project(0.0, 1.0)) {
            (Some(a), Some(b), Some(c)) => (b - a).perp_dot(c - a) > 0.0,
            _ => false,
        }
    }

    /// Number of sprites.
    #[must_use]
    pub fn len(&self) -> usize {
        self.stack.len()
    }

    /// Whether the scene has no sprite.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.stack.is_empty()
    }

    fn sprite_mut(&mut self, id: SpriteId) -> &mut SceneSprite {
        self.sprites
            .get_mut(id.index())
            .and_then(Option::as_mut)
            .unwrap_or_else(|| panic!("sprite {id:?} does not exist"))
    }

    fn unstack(&mut self, id: SpriteId) {
        let at = self
            .stack
            .iter()
            .position(|&s| s == id)
            .unwrap_or_else(|| panic!("sprite {id:?} is not in the stack"));
        self.stack.remove(at);
    }
}

impl Compositor for Scene {
    fn create_sprite(&mut self, id: SpriteId, face: u32) {
        if self.sprites.len() <= id.index() {
            self.sprites.resize(id.index() + 1, None);
        }
        assert!(self.sprites[id.index()].is_none(), "sprite {id:?} exists");
        self.sprites[id.index()] = Some(SceneSprite {
            face,
            transform: SpriteTransform {
                matrix: DMat4::IDENTITY,
                kind: MapKind::Affine,
            },
            clip: None,
            brush: Brush::Palette,
            visible: false,
            back_visible: true,
        });
        self.stack.push(id);
    }
    fn destroy_sprite(&mut self, id: SpriteId) {
        self.sprite_mut(id);
        self.sprites[id.index()] = None;
        self.unstack(id);
    }
    fn set_transform(&mut self, id: SpriteId, transform: &SpriteTransform) {
        self.sprite_mut(id).transform = *transform;
    }
    fn set_clip(&mut self, id: SpriteId, clip: Option<&[DVec2]>) {
        self.sprite_mut(id).clip = clip.map(<[DVec2]>::to_vec);
    }
    fn set_brush(&mut self, id: SpriteId, brush: &Brush) {
        self.sprite_mut(id).brush = *brush;
    }
    fn set_visible(&mut self, id: SpriteId, visible: bool) {
        self.sprite_mut(id).visible = visible;
    }
    fn set_back_visible(&mut self, id: SpriteId, visible: bool) {
        self.sprite_mut(id).back_visible = visible;
    }
    fn move_to_top(&mut self, id: SpriteId) {
        self.unstack(id);
        self.stack.push(id);
    }
    fn move_before(&mut self, id: SpriteId, above: SpriteId) {
        assert_ne!(id, above, "a sprite cannot move before itself");
        self.unstack(id);
        let at = self
            .stack
            .iter()
            .position(|&s| s == above)
            .unwrap_or_else(|| panic!("sprite {above:?} is not in the stack"));
        self.stack.insert(at, id);
    }
    fn set_root_transform(&mut self, root: &DMat4) {
        self.root = *root;
    }
}

/// A test backend: keeps a [`Scene`] (checking every operation against it: unknown sprites
/// and double creation panic) and counts operations per frame.
#[derive(Clone, Debug, Default)]
pub struct RecordingCompositor {
    scene: Scene,
    frame: OpCounts,
    total: OpCounts,
    log: Option<Vec<String>>,
}

impl RecordingCompositor {
    /// A recorder with an empty scene.
    #[must_use]
    pub fn new() -> Self {
        RecordingCompositor {
            scene: Scene::new(),
            ..Default::default()
        }
    }

    /// Also keeps a text log of every operation (allocates: not for allocation tests).
    #[must_use]
    pub fn with_log(mut self) -> Self {
        self.log = Some(Vec::new());
        self
    }

    /// The retained scene.
    #[must_use]
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Operations since the last [`take_frame`](Self::take_frame).
    #[must_use]
    pub fn frame(&self) -> OpCounts {
        self.frame
    }

    /// Returns the operations since the last call and starts counting a new frame.
    pub fn take_frame(&mut self) -> OpCounts {
        std::mem::take(&mut self.frame)
    }

    /// Operations since creation.
    #[must_use]
    pub fn total(&self) -> OpCounts {
        self.total
    }

    /// The operation log (empty unless [`with_log`](Self::with_log)).
    #[must_use]
    pub fn log(&self) -> &[String] {
        self.log.as_deref().unwrap_or(&[])
    }

    fn record(&mut self, f: impl Fn(&mut OpCounts), text: impl FnOnce() -> String) {
        f(&mut self.frame);
        f(&mut self.total);
        if let Some(log) = &mut self.log {
            log.push(text());
        }
    }
}

impl Compositor for RecordingCompositor {
    fn create_sprite(&mut self, id: SpriteId, face: u32) {
        self.record(|o| o.create += 1, || format!("create {} face {face}", id.0));
        self.scene.create_sprite(id, face);
    }
    fn destroy_sprite(&mut self, id: SpriteId) {
        self.record(|o| o.destroy += 1, || format!("destroy {}", id.0));
        self.scene.destroy_sprite(id);
    }
    fn set_transform(&mut self, id: SpriteId, transform: &SpriteTransform) {
        self.record(|o| o.transform += 1, || format!("transform {}", id.0));
        self.scene.set_transform(id, transform);
    }
    fn set_clip(&mut self, id: SpriteId, clip: Option<&[DVec2]>) {
        self.record(|o| o.clip += 1, || format!("clip {}", id.0));
        self.scene.set_clip(id, clip);
    }
    fn set_brush(&mut self, id: SpriteId, brush: &Brush) {
        self.record(|o| o.brush += 1, || format!("brush {}", id.0));
        self.scene.set_brush(id, brush);
    }
    fn set_visible(&mut self, id: SpriteId, visible: bool) {
        self.record(|o| o.visible += 1, || format!("visible {} {visible}", id.0));
        self.scene.set_visible(id, visible);
    }
    fn set_back_visible(&mut self, id: SpriteId, visible: bool) {
        self.record(|o| o.back += 1, || format!("back {} {visible}", id.0));
        self.scene.set_back_visible(id, visible);
    }
    fn move_to_top(&mut self, id: SpriteId) {
        self.record(|o| o.reorder += 1, || format!("top {}", id.0));
        self.scene.move_to_top(id);
    }
    fn move_before(&mut self, id: SpriteId, above: SpriteId) {
        self.record(
            |o| o.reorder += 1,
            || format!("before {} {}", id.0, above.0),
        );
        self.scene.move_before(id, above);
    }
    fn set_root_transform(&mut self, root: &DMat4) {
        self.record(|o| o.root += 1, || "root".to_owned());
        self.scene.set_root_transform(root);
    }
}

/// The unit-square polygon a sprite shows: its clip, or the square (corners `0, 1, 2, 3` of a
/// quad).
#[must_use]
pub fn sprite_polygon(sprite: &SceneSprite) -> Vec<DVec2> {
    match &sprite.clip {
        Some(clip) => clip.clone(),
        None => vec![DVec2::ZERO, DVec2::Y, DVec2::ONE, DVec2::X],
    }
}

/// Projects a sprite's polygon to pixels through `root · transform`, clipping it against the
/// near plane `w ≥ NEAR_W` (CONVENTIONS.md) in homogeneous coordinates. Empty when nothing is
/// in front of the near plane.
#[must_use]
pub fn project_sprite(root: &DMat4, sprite: &SceneSprite) -> Vec<DVec2> {
    let matrix = sprite.transform.matrix;
    let full = *root * matrix;
    // Homogeneous (unit-square) points; the near test W − NEAR_W · w_sprite ≥ 0 is linear.
    let lifted: Vec<DVec4> = sprite_polygon(sprite)
        .iter()
        .map(|uv| DVec4::new(uv.x, uv.y, 0.0, 1.0))
        .collect();
    let near = |p: DVec4| (full * p).w - NEAR_W * (matrix * p).w;
    let mut kept: Vec<DVec4> = Vec::with_capacity(lifted.len() + 2);
    let n = lifted.len();
    for k in 0..n {
        let (a, b) = (lifted[k], lifted[(k + 1) % n]);
        let (da, db) = (near(a), near(b));
        if da >= 0.0 {
            kept.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let t = da / (da - db);
            kept.push(a + (b - a) * t);
        }
    }
    if kept.len() < 3 {
        return Vec::new();
    }
    kept.iter()
        .map(|&p| {
            let h = full * p;
            DVec2::new(h.x / h.w, h.y / h.w)
        })
        .collect()
}
