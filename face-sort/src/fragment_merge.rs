//! Drawing a split piece whole, per view, where nothing drawn between its fragments overlaps
//! it on screen.
//!
//! A BSP cuts a piece wherever a splitting plane crosses it, whatever the view. In most views
//! nothing drawn between its first and last fragment overlaps it on screen, and then one
//! polygon, the whole piece drawn at its last fragment's place, paints the same pixels.
//!
//! # Why it is exact
//! A BSP order is valid pair by pair: of two polygons that overlap on screen, the later one is
//! in front wherever they overlap. Replace the fragments of a piece `Q` by `Q` whole at the
//! place of its last fragment. Items drawn before its first fragment or after its last keep
//! their relation to every part of `Q`; only items drawn between change sides, and the merge
//! requires that none of them overlaps `Q`. Every item of another piece `R`, merged or not,
//! lies inside `R`'s projection and within `R`'s first and last fragments' places, so the
//! test is made on whole pieces and those places: it then holds whatever else is merged, and
//! merges are valid one by one in any order.
//!
//! # Two tests
//! 1. **Nothing overlaps `Q` at all** (most pieces; cheap): [`Coverage`].
//! 2. **Nothing between its fragments overlaps it** (the rest): candidates from a screen grid
//!    of every drawn piece, those drawn between `Q`'s first and last fragment tested with
//!    [`Newell`](crate::Newell)'s overlap test (the exact convex intersection has more than
//!    [`OVERLAP_AREA`]` · L²` of area).

use std::ops::ControlFlow;

use glam::DVec2;

use crate::coverage::Coverage;
use crate::polygon::{Box2, overlap_exceeds, separated_2d};
use crate::polygon_set::PolygonSet;
use crate::screen_grid::ScreenGrid;
use crate::tolerance::OVERLAP_AREA;
use crate::{DrawItem, View};

/// Frames with more boundary edges than this per drawn piece stop test 1 once it has found
/// them and send every split piece to test 2: where the surface folds over itself in much of
/// the picture, few pieces are alone. The stop pays on models that fold over themselves
/// (suzanne) and is about even on fandisk; spot and blub stay below it and never stop. It is
/// higher than the threshold at which [`Newell`](crate::Newell) stops, since test 2 costs more
/// per piece than Newell's cascade (measurements in docs/bench.md).
const TEST_1_MAX_EDGES_PER_PIECE: f64 = 0.5;

/// What the tree gives the merge.
pub(crate) struct MergeInput<'a> {
    /// The pieces (centred model space).
    pub pieces: &'a PolygonSet,
    /// Per piece, the index of its whole polygon in the draw list's set (`None`:
    /// not split), and its number of fragments.
    pub whole: &'a [Option<u32>],
    pub fragments_of: &'a [u32],
    /// Per fragment, its face and piece.
    pub fragment_face: &'a [[u32; 2]],
    /// The model's diagonal `L`.
    pub diagonal: f64,
}

/// Per-view buffers of the merge, kept between frames (steady frames allocate nothing).
#[derive(Debug, Default)]
pub(crate) struct FragmentMerge {
    /// Test 1, and the pieces' edge neighbours.
    coverage: Coverage,
    /// Per piece: the frame it was last drawn in, its index among that frame's drawn
    /// pieces, its fragments drawn, its first and last places, and the frame it was last
    /// merged in.
    seen: Vec<u32>,
    dense: Vec<u32>,
    count: Vec<u32>,
    first: Vec<u32>,
    last: Vec<u32>,
    merged: Vec<u32>,
    frame: u32,
    /// This frame's drawn pieces, their projections (pixels) and screen boxes.
    drawn: Vec<u32>,
    projected: Vec<DVec2>,
    projected_start: Vec<u32>,
    boxes: Vec<Box2>,
    /// Split pieces with two fragments or more drawn this frame, and those test 1 left.
    split: Vec<u32>,
    pending: Vec<u32>,
    /// Test 2: every drawn piece's box.
    grid: ScreenGrid,
    clip_out: Vec<DVec2>,
    clip_scratch: Vec<DVec2>,
}

impl FragmentMerge {
    /// The merge over `pieces`: their edge neighbours, and buffers.
    pub(crate) fn new(pieces: &PolygonSet) -> Self {
        let coverage = Coverage::new(pieces);
        let pieces = pieces.len();
        FragmentMerge {
            coverage,
            seen: vec![0; pieces],
            dense: vec![0; pieces],
            count: vec![0; pieces],
            first: vec![0; pieces],
            last: vec![0; pieces],
            merged: vec![0; pieces],
            ..FragmentMerge::default()
        }
    }

    /// Writes `items` (a BSP order of fragments) to `out`, each split piece that nothing
    /// drawn between its fragments overlaps on screen replaced by its whole polygon at its
    /// last fragment's place.
    pub(crate) fn merge(
        &mut self,
        view: &View,
        input: &MergeInput<'_>,
        items: &[DrawItem],
        out: &mut Vec<DrawItem>,
    ) {
        self.frame = self.frame.wrapping_add(1);
        if self.frame == 0 {
            self.seen.fill(0);
            self.merged.fill(0);
            self.frame = 1;
        }
        let frame = self.frame;
        self.drawn.clear();
        self.split.clear();
        for (i, item) in items.iter().enumerate() {
            let p = input.fragment_face[item.polygon as usize][1] as usize;
            if self.seen[p] != frame {
                self.seen[p] = frame;
                self.dense[p] = self.drawn.len() as u32;
                self.count[p] = 0;
                self.first[p] = i as u32;
                self.drawn.push(p as u32);
            }
            self.count[p] += 1;
            // Only pieces with every fragment drawn: one culled off the image leaves part of
            // the piece unordered against what it would overlap there.
            if self.count[p] == input.fragments_of[p] && input.whole[p].is_some() {
                self.split.push(p as u32);
            }
            self.last[p] = i as u32;
        }
        if !self.split.is_empty() && self.project(view, input.pieces) {
            self.alone();
            // Newell's overlap tolerance, `OVERLAP_AREA · L²` in view units, in pixels².
            let l = input.diagonal * view.scale();
            self.nothing_between(OVERLAP_AREA * l * l);
        }
        for (i, item) in items.iter().enumerate() {
            let p = input.fragment_face[item.polygon as usize][1] as usize;
            if self.merged[p] != frame {
                out.push(*item);
            } else if let Some(whole) = input.whole[p].filter(|_| self.last[p] == i as u32) {
                out.push(DrawItem {
                    polygon: whole,
                    face: item.face,
                });
            }
        }
    }

    /// Projects this frame's drawn pieces; `false` when a corner lies behind the near plane
    /// (no merge this frame).
    fn project(&mut self, view: &View, pieces: &PolygonSet) -> bool {
        self.projected.clear();
        self.projected_start.clear();
        self.boxes.clear();
        for &p in &self.drawn {
            self.projected_start.push(self.projected.len() as u32);
            let start = self.projected.len();
            for &c in pieces.corners(p as usize) {
                match view.project_view_point(view.to_view(c)) {
                    Some(q) => self.projected.push(q),
                    None => return false,
                }
            }
            self.boxes.push(Box2::from_points(&self.projected[start..]));
        }
        self.projected_start.push(self.projected.len() as u32);
        true
    }

    /// The projection of the drawn piece with dense index `j`.
    fn polygon(&self, j: usize) -> &[DVec2] {
        &self.projected[self.projected_start[j] as usize..self.projected_start[j + 1] as usize]
    }

    /// Test 1: merges the split pieces that no other drawn piece overlaps; leaves the others
    /// in `pending`.
    fn alone(&mut self) {
        self.pending.clear();
        let (projected, starts) = (&self.projected, &self.projected_start);
        let polygon = |j: usize| &projected[starts[j] as usize..starts[j + 1] as usize];
        if !self
            .coverage
            .file(&self.drawn, polygon, TEST_1_MAX_EDGES_PER_PIECE)
        {
            self.pending.extend_from_slice(&self.split);
            return;
        }
        for s in 0..self.split.len() {
            let q = self.split[s];
            let j = self.dense[q as usize] as usize;
            if self.coverage.alone(q, self.polygon(j), &self.boxes[j]) {
                self.merged[q as usize] = self.frame;
            } else {
                self.pending.push(q);
            }
        }
    }

    /// Test 2: merges each pending split piece that no piece drawn between its fragments
    /// overlaps.
    fn nothing_between(&mut self, min_area: f64) {
        if self.pending.is_empty() {
            return;
        }
        let all = self.boxes.iter().fold(Box2::EMPTY, |all, &b| all.union(b));
        self.grid.reset(all, self.drawn.len());
        for (j, b) in self.boxes.iter().enumerate() {
            self.grid.insert(j as u32, b);
        }
        for s in 0..self.pending.len() {
            let q = self.pending[s] as usize;
            let jq = self.dense[q] as usize;
            let (first, last) = (self.first[q], self.last[q]);
            let q_box = self.boxes[jq];
            let mut hidden = false;
            let (drawn, firsts, lasts, boxes) = (&self.drawn, &self.first, &self.last, &self.boxes);
            let (projected, starts) = (&self.projected, &self.projected_start);
            let polygon = |j: usize| &projected[starts[j] as usize..starts[j + 1] as usize];
            let (clip_out, clip_scratch) = (&mut self.clip_out, &mut self.clip_scratch);
            let coverage = &self.coverage;
            self.grid.for_each_candidate(&q_box, |j| {
                let r = drawn[j as usize] as usize;
                if r == q
                    || firsts[r] >= last
                    || lasts[r] <= first
                    || !boxes[j as usize].overlaps(&q_box)
                    || coverage.beside(q, r)
                    || separated_2d(polygon(jq), polygon(j as usize))
                {
                    return ControlFlow::Continue(());
                }
                hidden = overlap_exceeds(
                    polygon(jq),
                    polygon(j as usize),
                    min_area,
                    1.0,
                    clip_out,
                    clip_scratch,
                );
                if hidden {
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(())
                }
            });
            if !hidden {
                self.merged[q] = self.frame;
            }
        }
    }

    /// Heap bytes.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.coverage.heap_bytes()
            + (self.seen.capacity()
                + self.dense.capacity()
                + self.count.capacity()
                + self.first.capacity()
                + self.last.capacity()
                + self.merged.capacity()
                + self.drawn.capacity()
                + self.projected_start.capacity()
                + self.split.capacity()
                + self.pending.capacity())
                * 4
            + (self.projected.capacity() + self.clip_out.capacity() + self.clip_scratch.capacity())
                * size_of::<DVec2>()
            + self.boxes.capacity() * size_of::<Box2>()
    }
}
