//! The one trait every sorter implements.

use crate::{DrawList, View};

/// Figures a sorter reports about its cached state and its last frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SorterStats {
    /// Time spent building cached state, in milliseconds (0 when there is none).
    pub build_ms: f64,
    /// Polygons the sorter can draw: pieces, or pieces plus precomputed fragments (BSP).
    pub polygons: usize,
    /// Heap bytes of cached state kept between frames.
    pub cached_bytes: usize,
    /// Depth of the tree, for tree-based sorters.
    pub depth: usize,
    /// Cases in the last frame where the sorter gave up exactness (cycles broken by depth,
    /// or a split budget exhausted). Always 0 for exact sorters on valid input.
    pub fallbacks: usize,
    /// Cycles broken by cutting in the last frame (Newell; exactness kept).
    pub cycles: usize,
    /// Pieces drawn in the last frame without entering the sort, because a coverage test
    /// proved that no other drawn piece overlaps them on screen (Newell).
    pub drawn_alone: usize,
    /// Orders certified over regions of views ([`Presorted`](crate::Presorted); 0 for the
    /// others).
    pub orders: usize,
    /// Frames so far whose view no certificate covered, ordered by a fallback instead
    /// ([`Presorted`](crate::Presorted): eyes too near, other cull modes; exactness kept).
    pub fallback_frames: usize,
    /// Why the last frame fell back, when it did ([`Presorted`](crate::Presorted)).
    pub fallback: Option<crate::FallbackReason>,
}

/// Culls and orders a mesh's pieces for a view, back to front.
///
/// `sort` writes every drawn piece (or the fragments cut from it) into `out`, in paint order.
/// After the first frame of a geometry, sorting again allocates nothing.
pub trait FaceSorter: Send {
    /// Short lower-case name (`"centroid"`, `"bsp"`, …).
    fn name(&self) -> &'static str;

    /// Culls and orders for `view`, replacing the contents of `out`.
    fn sort(&mut self, view: &View, out: &mut DrawList);

    /// Figures about cached state and the last frame.
    fn stats(&self) -> SorterStats {
        SorterStats::default()
    }

    /// Where the order leaves pieces free among themselves (a cull-only order: any order of
    /// the pieces facing the viewer is exact), draw them grouped by `brush(face)` from now
    /// on, for backends where a brush change costs. Returns whether this sorter can (only
    /// cull-only orders can; the others keep their order and return false).
    fn group_by_brush(&mut self, brush: &dyn Fn(u32) -> u32) -> bool {
        let _ = brush;
        false
    }
}
