//! The output of a sorter: polygons to paint, back to front.

use std::sync::Arc;

use glam::DVec3;

use crate::plane::Plane;
use crate::polygon_set::PolygonSet;

/// One polygon to paint: a whole piece or a fragment cut from one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DrawItem {
    /// Index of the polygon in the list's polygon sets (see [`DrawList::corners`]).
    pub polygon: u32,
    /// Index of the source face in the input mesh.
    pub face: u32,
}

/// Polygons in paint order (back to front), reused from frame to frame.
///
/// Polygons are stored in two places: a shared, immutable set (a sorter's pieces or
/// precomputed fragments, held by `Arc` so that a frame costs no copy) and a per-frame set of
/// fragments that a sorter cut during this frame. A polygon index below the shared set's
/// length refers to the shared set, any other to the per-frame set.
#[derive(Clone, Debug, Default)]
pub struct DrawList {
    shared: Option<Arc<PolygonSet>>,
    frame: PolygonSet,
    items: Vec<DrawItem>,
    /// A number that no other content of any list has had, set by [`seal`](Self::seal); 0
    /// once the content changes.
    seal: u64,
    /// Whether the sink hides back faces itself (see [`set_sink_culls`](Self::set_sink_culls)).
    sink_culls: bool,
}

/// The last number handed out by [`DrawList::seal`].
static SEALS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

impl DrawList {
    /// An empty list.
    #[must_use]
    pub fn new() -> Self {
        DrawList {
            shared: None,
            frame: PolygonSet::new(),
            items: Vec::new(),
            seal: 0,
            sink_culls: false,
        }
    }

    /// Declares that the sink hides back faces itself: the list may then hold pieces that
    /// the view does not draw (an order baked for many views, e.g. aspect-bake's picture
    /// cells), and every consumer skips them (raster-sink while painting, the oracle, the
    /// writers). A sorter's next run into the list keeps it.
    pub fn set_sink_culls(&mut self, culls: bool) {
        self.sink_culls = culls;
        self.seal = 0;
    }

    /// Whether the sink hides back faces itself ([`set_sink_culls`](Self::set_sink_culls)).
    #[must_use]
    pub fn sink_culls(&self) -> bool {
        self.sink_culls
    }

    /// Whether `item` is painted under `test` (the view's [`CullTest`](crate::CullTest)):
    /// always, unless the sink culls and the view does not draw it.
    #[inline]
    #[must_use]
    pub fn paints(&self, item: DrawItem, test: &crate::CullTest) -> bool {
        !self.sink_culls || test.is_drawn(self.plane(item), self.corners(item)[0])
    }

    /// The items in paint order.
    #[must_use]
    pub fn items(&self) -> &[DrawItem] {
        &self.items
    }

    /// Number of items.
    #[must_use]
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// Whether nothing is drawn.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Corners of an item's polygon (centred model space).
    #[inline]
    #[must_use]
    pub fn corners(&self, item: DrawItem) -> &[DVec3] {
        let (set, i) = self.locate(item.polygon);
        set.corners(i)
    }

    /// Plane of an item's polygon (centred model space).
    #[inline]
    #[must_use]
    pub fn plane(&self, item: DrawItem) -> &Plane {
        let (set, i) = self.locate(item.polygon);
        set.plane(i)
    }

    /// Number of polygons cut during the last frame (Newell's splits).
    #[must_use]
    pub fn frame_fragments(&self) -> usize {
        self.frame.len()
    }

    #[inline]
    fn locate(&self, polygon: u32) -> (&PolygonSet, usize) {
        let shared_len = self.shared.as_ref().map_or(0, |s| s.len());
        let p = polygon as usize;
        if p < shared_len {
            (self.shared.as_deref().expect("shared set present"), p)
        } else {
            (&self.frame, p - shared_len)
        }
    }

    // --- for sorters (public through crate::sorter_api::DrawListWriter) ---

    /// Starts a frame over `shared` polygons: clears the items and the per-frame set.
    /// Costs no allocation when the same `Arc` (or any, once capacity is reached) is passed.
    pub(crate) fn begin(&mut self, shared: &Arc<PolygonSet>) {
        match &self.shared {
            Some(current) if Arc::ptr_eq(current, shared) => {}
            _ => self.shared = Some(Arc::clone(shared)),
        }
        self.frame.clear();
        self.items.clear();
        self.seal = 0;
    }

    /// Appends an item.
    #[inline]
    pub(crate) fn push(&mut self, polygon: u32, face: u32) {
        self.items.push(DrawItem { polygon, face });
        self.seal = 0;
    }

    /// Adds a per-frame polygon (a fragment cut this frame) and returns its polygon index
    /// (not yet an item: push it to draw it).
    pub(crate) fn add_frame_polygon(&mut self, corners: &[DVec3], face: u32, plane: Plane) -> u32 {
        let shared_len = self.shared.as_ref().map_or(0, |s| s.len()) as u32;
        self.seal = 0;
        shared_len + self.frame.push(corners, face, plane)
    }

    /// The items, mutable, for sorters that fill them in place.
    pub(crate) fn items_mut(&mut self) -> &mut Vec<DrawItem> {
        self.seal = 0;
        &mut self.items
    }

    /// Marks the current content with a number that no other content of any list has had
    /// (a clone keeps it, with the same content), and returns it: a caller that finds the
    /// same number later knows the list is unchanged without comparing it.
    pub(crate) fn seal(&mut self) -> u64 {
        self.seal = SEALS.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        self.seal
    }

    /// The number of the last [`seal`](Self::seal), if the content has not changed since.
    pub(crate) fn sealed(&self) -> Option<u64> {
        (self.seal != 0).then_some(self.seal)
    }

    /// The shared set of the current frame.
    #[must_use]
    pub fn shared(&self) -> Option<&Arc<PolygonSet>> {
        self.shared.as_ref()
    }
}
