//! What the next frame must redo, from what changed since the last one.

use face_sort::View;

/// Dirty flags of a painter: each is set by an input change and cleared by a frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Dirty {
    /// Per-piece transforms and clips (centre, scale or image size changed).
    pub transforms: bool,
    /// The root transform.
    pub root: bool,
    /// Culling and order.
    pub sort: bool,
    /// Per-sprite brushes.
    pub brushes: bool,
}

impl Dirty {
    /// A painter that has not drawn yet: root and order to do.
    pub const FIRST_FRAME: Dirty = Dirty {
        transforms: false,
        root: true,
        sort: true,
        brushes: false,
    };

    /// Marks what a change of view from `old` to `new` requires (see the cost table of
    /// [`SpritePainter`](super::SpritePainter)).
    pub fn view_changed(&mut self, old: &View, new: &View) {
        if old.centre() != new.centre()
            || old.scale() != new.scale()
            || old.width() != new.width()
            || old.height() != new.height()
        {
            self.transforms = true;
            self.root = true;
            self.sort = true;
        }
        if old.rotation() != new.rotation()
            || old.projection() != new.projection()
            || old.view_offset() != new.view_offset()
            || old.principal_point() != new.principal_point()
        {
            self.root = true;
            self.sort = true;
        }
        if old.cull() != new.cull()
            || old.front_face() != new.front_face()
            || old.cull_margin() != new.cull_margin()
            || old.diagonal() != new.diagonal()
        {
            self.sort = true;
        }
    }
}
