//! Newell, Newell and Sancha's painter's algorithm, per frame, with splits: exact, and needs
//! no tree (only its pieces' edge neighbours, found once when it is made).

use std::sync::Arc;

use glam::{DVec2, DVec3};

use crate::coverage::Coverage;
use crate::plane::{Plane, Side};
use crate::polygon::{Box2, overlap_exceeds, split_polygon};
use crate::screen_grid::ScreenGrid;
use crate::tolerance::{OVERLAP_AREA, PLANE_SIDE};
use crate::view::Viewer;
use crate::{
    DrawItem, DrawList, FaceSorter, Geometry, PolygonSet, ProjectionScratch, SorterStats, View,
};

/// Frames drawing fewer pieces skip the coverage test: the cascade over so few costs less
/// than the test's grid (with the test on every frame, Newell was several times slower on the
/// book, cornell box and boxes scenes, 9–48 pieces; see docs/bench.md).
const COVERAGE_MIN_PIECES: usize = 64;

/// Frames with more boundary edges (silhouettes, the mesh's own boundary) than this per
/// drawn piece stop the coverage test once it has found them: the surface folds over itself
/// in much of the picture, few pieces are alone, and the test costs more than the cascade
/// it spares. Models that fold over themselves (suzanne, fandisk) cross it and gain from the
/// stop; smooth ones (spot, blub) stay below it and keep the test (per-frame figures in
/// docs/bench.md).
const COVERAGE_MAX_EDGES_PER_PIECE: f64 = 0.3;

/// Per-frame data of one polygon in the working list.
#[derive(Clone, Copy, Debug)]
struct Work {
    polygon: u32,
    face: u32,
    z_min: f64,
    z_max: f64,
    bounds: Box2,
    projected_start: u32,
    projected_len: u32,
    marked: bool,
    /// Whether a corner lay behind the near plane (its projection is the clipped polygon).
    clipped: bool,
}

/// The classic cascade per pair (depth extents, screen boxes, plane sides both ways, exact 2D
/// overlap), moving a polygon ahead when it must be drawn first, and splitting one polygon by
/// the other's plane when they interpenetrate or their planes cross.
///
/// A cycle (a polygon that was moved ahead must move ahead again) is broken by an
/// auto-partition of the polygons of the cycle (a BSP's fragments, without the tree), whose
/// fragments replace them: cutting one pair by its own planes does not always break a cycle
/// through several polygons (fuzzing found such cases among 60 crossing quads). Steady frames
/// allocate nothing, with cycles or without.
///
/// Only the pieces that another drawn piece overlaps on screen enter the cascade: the others
/// (on a closed mesh, all but those where the surface folds over itself in this view) are
/// drawn first, in piece order, found by a coverage test (`coverage.rs`) over the pieces' edge
/// neighbours, found when the sorter is made. For one picture they cost more than they save:
/// [`Newell::without_coverage`] skips them, and the planner makes that one for fewer frames
/// than it takes them to pay back (whole-process figures in docs/bench.md). A frame where the
/// surface folds over itself in much of the picture (many boundary edges per drawn piece)
/// stops the test early and sends every piece through the cascade;
/// [`SorterStats::drawn_alone`] counts the pieces the test spared.
///
/// Exact: the property tests and the book grid check zero order violations. Cost grows with
/// the number of overlapped pieces and of pairs whose depth extents overlap; nothing carries
/// over between frames.
#[derive(Debug)]
pub struct Newell {
    pieces: Arc<PolygonSet>,
    work: Vec<Work>,
    /// Work items not yet drawn, sorted by `z_min` (farthest first); drawn or split items are
    /// flagged `done` and skipped.
    remaining: Vec<u32>,
    /// `remaining` with its depths, for the frame's sort.
    keyed: Vec<(f64, u32)>,
    done: Vec<bool>,
    /// Items moved ahead of the one that was waiting below them (top = next candidate).
    stack: Vec<u32>,
    projected: Vec<DVec2>,
    projection_out: Vec<DVec2>,
    projection_scratch: ProjectionScratch,
    clip_out: Vec<DVec2>,
    clip_scratch: Vec<DVec2>,
    corners: Vec<DVec3>,
    split_front: Vec<DVec3>,
    split_back: Vec<DVec3>,
    /// A cycle's auto-partition: its polygons, the sets still to cut (ranges of `pool`), and
    /// one set's polygons in front of and behind its splitter.
    pool: Vec<DrawItem>,
    sets: Vec<(usize, usize)>,
    front_items: Vec<DrawItem>,
    back_items: Vec<DrawItem>,
    /// Screen grid over the work items' boxes, and the candidates of the current query.
    grid: ScreenGrid,
    candidates: Vec<u32>,
    /// Which pieces no other drawn piece overlaps (`None`: not tested); this frame's drawn
    /// pieces, and whether a projection was clipped by the near plane (then no piece is drawn
    /// early).
    coverage: Option<Box<Coverage>>,
    drawn: Vec<u32>,
    clipped: bool,
    drawn_alone: usize,
    tolerance: f64,
    min_area: f64,
    fallbacks: usize,
    cycles: usize,
}

enum Action {
    Draw,
    MoveAhead(u32),
    Split {
        polygon: u32,
        by: Plane,
    },
    /// A cycle: the stack from this position to the top. Replaced by the fragments of an
    /// auto-partition of its members, which cannot form a cycle among themselves.
    Untangle {
        from: usize,
    },
}

impl Newell {
    /// A Newell sorter over a geometry's pieces, with their edge neighbours for the coverage
    /// test (a one-time set-up per piece, paid here; its cost is in docs/bench.md).
    #[must_use]
    pub fn new(geometry: &Geometry) -> Self {
        Newell {
            coverage: Some(Box::new(Coverage::new(geometry.pieces()))),
            ..Newell::without_coverage(geometry)
        }
    }

    /// A Newell sorter that sends every piece through the cascade: nothing to find when it
    /// is made, for one picture.
    #[must_use]
    pub fn without_coverage(geometry: &Geometry) -> Self {
        let l = geometry.bounds().diagonal();
        Newell {
            pieces: Arc::clone(geometry.pieces()),
            work: Vec::new(),
            remaining: Vec::new(),
            keyed: Vec::new(),
            done: Vec::new(),
            stack: Vec::new(),
            projected: Vec::new(),
            projection_out: Vec::new(),
            projection_scratch: ProjectionScratch::default(),
            clip_out: Vec::new(),
            clip_scratch: Vec::new(),
            corners: Vec::new(),
            split_front: Vec::new(),
            split_back: Vec::new(),
            pool: Vec::new(),
            sets: Vec::new(),
            front_items: Vec::new(),
            back_items: Vec::new(),
            grid: ScreenGrid::default(),
            candidates: Vec::new(),
            coverage: None,
            drawn: Vec::new(),
            clipped: false,
            drawn_alone: 0,
            tolerance: PLANE_SIDE * l,
            min_area: OVERLAP_AREA * l * l,
            fallbacks: 0,
            cycles: 0,
        }
    }

    /// Adds a work item: the polygon's depth extent, its projection in view units (pixels / s,
    /// like the oracle) and screen box, in one pass over its corners; the near-plane clipped
    /// projection when a corner lies behind the near plane (then its `clipped` is set).
    fn add_work(&mut self, view: &View, out: &DrawList, polygon: u32, face: u32) -> u32 {
        let corners = out.corners(DrawItem { polygon, face });
        let inv_scale = 1.0 / view.scale();
        let start = self.projected.len();
        let (mut z_min, mut z_max) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut bounds = Box2::EMPTY;
        let mut behind = false;
        for &c in corners {
            let v = view.to_view(c);
            z_min = z_min.min(v.z);
            z_max = z_max.max(v.z);
            match view.project_view_point(v) {
                Some(p) => {
                    let p = p * inv_scale;
                    bounds.min = bounds.min.min(p);
                    bounds.max = bounds.max.max(p);
                    self.projected.push(p);
                }
                None => behind = true,
            }
        }
        if behind {
            self.projected.truncate(start);
            view.project_polygon(
                corners,
                &mut self.projection_out,
                &mut self.projection_scratch,
            );
            self.projected
                .extend(self.projection_out.iter().map(|&p| p * inv_scale));
            let projected = &self.projected[start..];
            bounds = if projected.is_empty() {
                Box2::EMPTY
            } else {
                Box2::from_points(projected)
            };
        }
        self.work.push(Work {
            polygon,
            face,
            z_min,
            z_max,
            bounds,
            projected_start: start as u32,
            projected_len: (self.projected.len() - start) as u32,
            marked: false,
            clipped: behind,
        });
        self.done.push(false);
        (self.work.len() - 1) as u32
    }

    /// Side of polygon `w` relative to `plane`, from the viewer's point of view:
    /// `Back` = entirely on the far side (or on), `Front` = entirely on the viewer's side (or on).
    fn side_seen(&self, out: &DrawList, w: u32, plane: &Plane, viewer: &Viewer) -> Side {
        let work = &self.work[w as usize];
        let corners = out.corners(DrawItem {
            polygon: work.polygon,
            face: work.face,
        });
        let side = plane.side_of_polygon(corners, self.tolerance);
        if viewer.facing(plane) >= 0.0 {
            side
        } else {
            match side {
                Side::Front => Side::Back,
                Side::Back => Side::Front,
                other => other,
            }
        }
    }

    fn plane_of(&self, out: &DrawList, w: u32) -> Plane {
        let work = &self.work[w as usize];
        *out.plane(DrawItem {
            polygon: work.polygon,
            face: work.face,
        })
    }

    fn projections_overlap(&mut self, p: u32, q: u32) -> bool {
        let (wp, wq) = (&self.work[p as usize], &self.work[q as usize]);
        let a = &self.projected
            [wp.projected_start as usize..(wp.projected_start + wp.projected_len) as usize];
        let b = &self.projected
            [wq.projected_start as usize..(wq.projected_start + wq.projected_len) as usize];
        overlap_exceeds(
            a,
            b,
            self.min_area,
            1.0,
            &mut self.clip_out,
            &mut self.clip_scratch,
        )
    }

    /// What to do with candidate `p`, scanning the remaining items from `first`.
    fn decide(&mut self, out: &DrawList, p: u32, viewer: &Viewer) -> Action {
        let plane_p = self.plane_of(out, p);
        let wp = self.work[p as usize];
        // Candidates: not drawn, overlapping P in depth extent and screen box.
        let mut candidates = std::mem::take(&mut self.candidates);
        candidates.clear();
        {
            // The grid's lists are in `z_min` order: each is read up to P's `z_max`.
            let (work, done) = (&self.work, &self.done);
            self.grid.for_each_ordered_candidate(
                &wp.bounds,
                |q| done[q as usize],
                |q| work[q as usize].z_min >= wp.z_max,
                |q| {
                    let wq = &work[q as usize];
                    if q != p && wq.z_min < wp.z_max && wp.bounds.overlaps(&wq.bounds) {
                        candidates.push(q);
                    }
                },
            );
        }
        let action = self.decide_among(out, p, &plane_p, &candidates, viewer);
        self.candidates = candidates;
        action
    }

    fn decide_among(
        &mut self,
        out: &DrawList,
        p: u32,
        plane_p: &Plane,
        candidates: &[u32],
        viewer: &Viewer,
    ) -> Action {
        let plane_p = *plane_p;
        for &q in candidates {
            let wq = self.work[q as usize];
            let plane_q = self.plane_of(out, q);
            let p_vs_q = self.side_seen(out, p, &plane_q, viewer);
            if matches!(p_vs_q, Side::Back | Side::On) {
                continue;
            }
            let q_vs_p = self.side_seen(out, q, &plane_p, viewer);
            if matches!(q_vs_p, Side::Front | Side::On) {
                continue;
            }
            if !self.projections_overlap(p, q) {
                continue;
            }
            // P may hide part of Q. Can Q be drawn first instead?
            let q_first = matches!(q_vs_p, Side::Back) || matches!(p_vs_q, Side::Front);
            if q_first && !wq.marked {
                return Action::MoveAhead(q);
            }
            // A cycle (Q was moved ahead before, so it waits on the stack below P)?
            if q_first && let Some(from) = self.stack.iter().rposition(|&x| x == q) {
                return Action::Untangle { from };
            }
            // An interpenetration, or planes that cross: cut one by the other's plane.
            if p_vs_q == Side::Spanning {
                return Action::Split {
                    polygon: p,
                    by: plane_q,
                };
            }
            if q_vs_p == Side::Spanning {
                return Action::Split {
                    polygon: q,
                    by: plane_p,
                };
            }
            // Unreachable for a P hiding Q (then Q goes first, or one of them spans the
            // other's plane and is cut); counted, should rounding ever lead here.
            self.fallbacks += 1;
            return Action::Draw;
        }
        Action::Draw
    }

    /// Replaces the cycle `stack[from..]` by the fragments of an auto-partition of its
    /// members: each set is cut by its first member's plane, the member and those on its
    /// plane are final, and the sets in front and behind are cut again. Any two final
    /// fragments then lie on either side of some member's plane (or on it), so no cycle can
    /// form among them; they go back into the cascade. Reuses its buffers (no allocation
    /// once they have grown). Returns the number of fragments put back.
    fn untangle(&mut self, view: &View, out: &mut DrawList, from: usize, first: usize) -> usize {
        let before = self.work.len();
        self.pool.clear();
        for &w in &self.stack[from..] {
            let work = self.work[w as usize];
            self.pool.push(DrawItem {
                polygon: work.polygon,
                face: work.face,
            });
            self.done[w as usize] = true;
        }
        self.stack.truncate(from);
        self.sets.clear();
        self.sets.push((0, self.pool.len()));
        while let Some((start, end)) = self.sets.pop() {
            let splitter = self.pool[start];
            let plane = *out.plane(splitter);
            self.add_fragment(view, out, splitter, first);
            self.front_items.clear();
            self.back_items.clear();
            for k in start + 1..end {
                let item = self.pool[k];
                match plane.side_of_polygon(out.corners(item), self.tolerance) {
                    Side::On => self.add_fragment(view, out, item, first),
                    Side::Front => self.front_items.push(item),
                    Side::Back => self.back_items.push(item),
                    Side::Spanning => {
                        let (front, back) = self.cut(out, item, &plane);
                        self.front_items.extend(front);
                        self.back_items.extend(back);
                    }
                }
            }
            for side in [&self.front_items, &self.back_items] {
                if !side.is_empty() {
                    let start = self.pool.len();
                    self.pool.extend_from_slice(side);
                    self.sets.push((start, self.pool.len()));
                }
            }
        }
        self.work.len() - before
    }

    /// Cuts `item` by `plane` into new frame polygons of `out`, keeping its face and plane:
    /// the parts in front and behind (`None` for a part with fewer than three corners). The
    /// BSP builder's `split` applies the same rule to its work polygons: change both together.
    fn cut(
        &mut self,
        out: &mut DrawList,
        item: DrawItem,
        plane: &Plane,
    ) -> (Option<DrawItem>, Option<DrawItem>) {
        let own = *out.plane(item);
        self.corners.clear();
        self.corners.extend_from_slice(out.corners(item));
        self.split_front.clear();
        self.split_back.clear();
        split_polygon(
            &self.corners,
            plane,
            self.tolerance,
            &mut self.split_front,
            &mut self.split_back,
        );
        let mut add = |corners: &[DVec3]| {
            (corners.len() >= 3).then(|| DrawItem {
                polygon: out.add_frame_polygon(corners, item.face, own),
                face: item.face,
            })
        };
        (add(&self.split_front), add(&self.split_back))
    }

    /// Adds a new polygon (a split part, a fragment of [`untangle`](Self::untangle)) to the
    /// cascade: a work item, in the grid's lists and the remaining list in `z_min` order.
    fn add_fragment(&mut self, view: &View, out: &DrawList, item: DrawItem, first: usize) {
        let new = self.add_work(view, out, item.polygon, item.face);
        let (work, z) = (&self.work, self.work[new as usize].z_min);
        self.grid
            .insert_ordered(new, &work[new as usize].bounds, |other| {
                work[other as usize].z_min.total_cmp(&z).is_le()
            });
        self.insert_sorted(first, new);
    }

    /// Draws the remaining work items that no other drawn piece overlaps on screen, and
    /// removes them from `remaining` (counted in `drawn_alone`).
    fn draw_alone(&mut self, out: &mut DrawList) {
        let Some(coverage) = &mut self.coverage else {
            return;
        };
        if self.clipped || self.remaining.len() < COVERAGE_MIN_PIECES {
            return;
        }
        let (work, projected) = (&self.work, &self.projected);
        let polygon = |w: &Work| {
            &projected[w.projected_start as usize..(w.projected_start + w.projected_len) as usize]
        };
        self.drawn.clear();
        self.drawn
            .extend(self.remaining.iter().map(|&w| work[w as usize].polygon));
        let remaining = &self.remaining;
        if !coverage.file(
            &self.drawn,
            |j| polygon(&work[remaining[j] as usize]),
            COVERAGE_MAX_EDGES_PER_PIECE,
        ) {
            return;
        }
        let (done, before) = (&mut self.done, self.remaining.len());
        self.remaining.retain(|&w| {
            let wk = &work[w as usize];
            let alone = coverage.alone(wk.polygon, polygon(wk), &wk.bounds);
            if alone {
                out.push(wk.polygon, wk.face);
                done[w as usize] = true;
            }
            !alone
        });
        self.drawn_alone = before - self.remaining.len();
    }

    /// Inserts work item `w` into the remaining list at or after `first`, keeping it sorted.
    fn insert_sorted(&mut self, first: usize, w: u32) {
        let z = self.work[w as usize].z_min;
        let work = &self.work;
        let offset = self.remaining[first..].partition_point(|&x| work[x as usize].z_min < z);
        self.remaining.insert(first + offset, w);
    }
}

impl FaceSorter for Newell {
    fn name(&self) -> &'static str {
        "newell"
    }

    fn sort(&mut self, view: &View, out: &mut DrawList) {
        let cull = view.cull_test();
        let viewer = cull.viewer;
        out.begin(&self.pieces);
        self.work.clear();
        self.remaining.clear();
        self.done.clear();
        self.stack.clear();
        self.projected.clear();
        self.clipped = false;
        self.fallbacks = 0;
        self.cycles = 0;
        self.drawn_alone = 0;
        // Frustum culling: a piece whose projection misses the image (in view units, like
        // the work boxes) covers no pixel and orders nothing that is seen; it is not drawn.
        let inv_scale = 1.0 / view.scale();
        let image = Box2 {
            min: DVec2::ZERO,
            max: DVec2::new(f64::from(view.width()), f64::from(view.height())) * inv_scale,
        };
        for i in 0..self.pieces.len() {
            if cull.is_drawn(self.pieces.plane(i), self.pieces.corners(i)[0]) {
                let w = self.add_work(view, out, i as u32, self.pieces.face(i));
                let added = self.work[w as usize];
                if added.bounds.overlaps(&image) {
                    self.clipped |= added.clipped;
                    self.remaining.push(w);
                } else {
                    let start = self.work[w as usize].projected_start as usize;
                    self.projected.truncate(start);
                    self.work.pop();
                    self.done.pop();
                }
            }
        }
        self.draw_alone(out);
        // Sorted by key pairs (no lookup per comparison); ties keep the work order.
        let work = &self.work;
        self.keyed.clear();
        self.keyed
            .extend(self.remaining.iter().map(|&w| (work[w as usize].z_min, w)));
        self.keyed
            .sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        self.remaining.clear();
        self.remaining.extend(self.keyed.iter().map(|&(_, w)| w));
        let all = (self.remaining.iter()).fold(Box2::EMPTY, |all, &w| {
            all.union(self.work[w as usize].bounds)
        });
        self.grid.reset(all, self.remaining.len());
        for &w in &self.remaining {
            self.grid.insert(w, &self.work[w as usize].bounds);
        }
        // Every move or split costs a step; the budget bounds time on adversarial input.
        let mut budget = 64 * self.remaining.len() + 1024;
        let mut first = 0;
        loop {
            while self.stack.last().is_some_and(|&w| self.done[w as usize]) {
                self.stack.pop();
            }
            while first < self.remaining.len() && self.done[self.remaining[first] as usize] {
                first += 1;
            }
            let p = match self.stack.last() {
                Some(&w) => w,
                None if first < self.remaining.len() => self.remaining[first],
                None => break,
            };
            let action = if budget == 0 {
                Action::Draw
            } else {
                budget -= 1;
                self.decide(out, p, &viewer)
            };
            match action {
                Action::Draw => {
                    let w = self.work[p as usize];
                    out.push(w.polygon, w.face);
                    self.done[p as usize] = true;
                }
                Action::Untangle { from } => {
                    // Every fragment it puts back costs a step too, so that a cycle formed
                    // again at tolerance level cannot grow the work without bound.
                    let added = self.untangle(view, out, from, first);
                    self.cycles += 1;
                    budget = budget.saturating_sub(added);
                }
                Action::MoveAhead(q) => {
                    self.work[q as usize].marked = true;
                    self.stack.push(q);
                }
                Action::Split { polygon: w, by } => {
                    self.done[w as usize] = true;
                    let work = self.work[w as usize];
                    let item = DrawItem {
                        polygon: work.polygon,
                        face: work.face,
                    };
                    let (front, back) = self.cut(out, item, &by);
                    for part in front.into_iter().chain(back) {
                        self.add_fragment(view, out, part, first);
                    }
                }
            }
        }
        if budget == 0 {
            self.fallbacks += 1;
        }
    }

    fn stats(&self) -> SorterStats {
        SorterStats {
            polygons: self.pieces.len(),
            cached_bytes: self.coverage.as_ref().map_or(0, |c| c.heap_bytes()),
            fallbacks: self.fallbacks,
            cycles: self.cycles,
            drawn_alone: self.drawn_alone,
            ..SorterStats::default()
        }
    }
}
