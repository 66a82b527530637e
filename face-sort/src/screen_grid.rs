//! A uniform grid over screen boxes, rebuilt per frame, to find the polygons whose screen boxes
//! may overlap a given box without scanning them all.

use std::ops::ControlFlow;

use glam::DVec2;

use crate::polygon::Box2;
use crate::tolerance::UNDERFLOW_ABS;

/// Most cells along either side of a grid.
const MAX_SIDE: usize = 256;

/// A uniform grid over a screen rectangle: about a given number of square cells (a wide
/// rectangle gets more columns than rows), at most 256 along either side, and the cells a
/// box touches. Shared by [`ScreenGrid`] and the coverage test's grid of boundary edges.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct GridFrame {
    pub origin: DVec2,
    pub inverse_cell: DVec2,
    pub columns: usize,
    pub rows: usize,
}

impl GridFrame {
    /// The grid with its lower corner at `origin`, `size` across (both positive), for about
    /// `items` cells.
    pub(crate) fn fit(origin: DVec2, size: DVec2, items: usize) -> Self {
        let cell = (size.x * size.y / items.max(1) as f64).sqrt();
        let count = |extent: f64| ((extent / cell).ceil() as usize).clamp(1, MAX_SIDE);
        let (columns, rows) = (count(size.x), count(size.y));
        GridFrame {
            origin,
            inverse_cell: DVec2::new(columns as f64 / size.x, rows as f64 / size.y),
            columns,
            rows,
        }
    }

    /// The cells `[x0, x1] × [y0, y1]` that the box `[lo, hi]` touches, clamped to the grid.
    #[inline]
    pub(crate) fn cells(&self, lo: DVec2, hi: DVec2) -> (usize, usize, usize, usize) {
        let a = (lo - self.origin) * self.inverse_cell;
        let b = (hi - self.origin) * self.inverse_cell;
        // Truncation is the floor for the non-negative values kept (casts saturate; NaN is 0).
        let index = |v: f64, n: usize| (v.max(0.0) as usize).min(n - 1);
        (
            index(a.x, self.columns),
            index(b.x, self.columns),
            index(a.y, self.rows),
            index(b.y, self.rows),
        )
    }
}

/// Buckets of item indices by the grid cells their boxes touch.
///
/// # Guarantees
/// [`for_each_candidate`](Self::for_each_candidate) visits every inserted item whose box
/// overlaps the query box (and possibly others), each once per query.
#[derive(Clone, Debug, Default)]
pub(crate) struct ScreenGrid {
    frame: GridFrame,
    cells: Vec<Vec<u32>>,
    /// Per cell, how many items at the front of its list are retired for good (see
    /// [`for_each_ordered_candidate`](Self::for_each_ordered_candidate)).
    heads: Vec<u32>,
    /// Query stamp per item, to visit each once per query.
    stamp: Vec<u32>,
    query: u32,
}

impl ScreenGrid {
    /// Empties the grid and sizes it for about `items` boxes inside `bounds`: about one item
    /// per cell, square cells (a wide band of boxes gets more columns than rows), at most
    /// 256 × 256 cells. Keeps every buffer's capacity.
    pub(crate) fn reset(&mut self, bounds: Box2, items: usize) {
        let size = (bounds.max - bounds.min).max(DVec2::splat(UNDERFLOW_ABS));
        self.frame = GridFrame::fit(bounds.min, size, items);
        let (columns, rows) = (self.frame.columns, self.frame.rows);
        if self.cells.len() < columns * rows {
            self.cells.resize_with(columns * rows, Vec::new);
        }
        for cell in &mut self.cells[..columns * rows] {
            cell.clear();
        }
        self.heads.clear();
        self.heads.resize(columns * rows, 0);
        self.stamp.clear();
        self.query = 0;
    }

    /// The cells a box touches (`None` for an empty or NaN box).
    fn range(&self, b: &Box2) -> Option<(usize, usize, usize, usize)> {
        (b.min.x <= b.max.x && b.min.y <= b.max.y).then(|| self.frame.cells(b.min, b.max))
    }

    /// Adds item `item` (items are numbered densely from 0) with screen box `b`.
    pub(crate) fn insert(&mut self, item: u32, b: &Box2) {
        self.insert_with(item, b, |cell, _| cell.push(item));
    }

    /// Adds item `item` with screen box `b` into each of its cells' lists after the items
    /// that `before` says go ahead of it (and after the retired ones): callers that insert
    /// in key order and then out of order this way keep every list in key order.
    pub(crate) fn insert_ordered(&mut self, item: u32, b: &Box2, before: impl Fn(u32) -> bool) {
        self.insert_with(item, b, |cell, head| {
            let at = head + cell[head..].partition_point(|&other| before(other));
            cell.insert(at, item);
        });
    }

    /// Makes room for `item`'s query stamp and calls `put` with each cell list `b` touches
    /// and the number of retired items at its front.
    fn insert_with(&mut self, item: u32, b: &Box2, mut put: impl FnMut(&mut Vec<u32>, usize)) {
        if self.stamp.len() <= item as usize {
            self.stamp.resize(item as usize + 1, 0);
        }
        if let Some((x0, x1, y0, y1)) = self.range(b) {
            let columns = self.frame.columns;
            for y in y0..=y1 {
                for c in y * columns + x0..=y * columns + x1 {
                    put(&mut self.cells[c], self.heads[c] as usize);
                }
            }
        }
    }

    /// Calls `f` once for every item in a cell that `b` touches that `retired` does not say
    /// is gone for good, reading each cell's list in order up to the first item that `past`
    /// says ends it (with lists in key order and `past` a key bound, the rest are past it
    /// too). Retired items at a list's front are skipped for every later query too.
    pub(crate) fn for_each_ordered_candidate(
        &mut self,
        b: &Box2,
        retired: impl Fn(u32) -> bool,
        past: impl Fn(u32) -> bool,
        mut f: impl FnMut(u32),
    ) {
        let Some((x0, x1, y0, y1)) = self.range(b) else {
            return;
        };
        let query = self.next_query();
        for y in y0..=y1 {
            for c in y * self.frame.columns + x0..=y * self.frame.columns + x1 {
                let cell = &self.cells[c];
                let mut head = self.heads[c] as usize;
                while head < cell.len() && retired(cell[head]) {
                    head += 1;
                }
                self.heads[c] = head as u32;
                for &item in &cell[head..] {
                    if past(item) {
                        break;
                    }
                    if retired(item) {
                        continue;
                    }
                    let seen = &mut self.stamp[item as usize];
                    if *seen != query {
                        *seen = query;
                        f(item);
                    }
                }
            }
        }
    }

    /// A new query stamp (restamping every item when the counter wraps).
    fn next_query(&mut self) -> u32 {
        self.query = self.query.wrapping_add(1);
        if self.query == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.query = 1;
        }
        self.query
    }

    /// Calls `f` once for every item inserted in a cell that `b` touches, until `f` breaks.
    pub(crate) fn for_each_candidate(
        &mut self,
        b: &Box2,
        mut f: impl FnMut(u32) -> ControlFlow<()>,
    ) {
        let Some((x0, x1, y0, y1)) = self.range(b) else {
            return;
        };
        let query = self.next_query();
        let stamp = &mut self.stamp;
        for row in self.cells.chunks(self.frame.columns).take(y1 + 1).skip(y0) {
            for cell in &row[x0..=x1] {
                for &item in cell {
                    let seen = &mut stamp[item as usize];
                    if *seen != query {
                        *seen = query;
                        if f(item).is_break() {
                            return;
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_overlapping_boxes_once() {
        let boxes: Vec<Box2> = (0..50)
            .map(|i| {
                let p = DVec2::new(f64::from(i % 10), f64::from(i / 10));
                Box2 {
                    min: p,
                    max: p + DVec2::splat(1.5),
                }
            })
            .collect();
        let all = Box2 {
            min: DVec2::ZERO,
            max: DVec2::new(10.5, 5.5),
        };
        let mut grid = ScreenGrid::default();
        grid.reset(all, boxes.len());
        for (i, b) in boxes.iter().enumerate() {
            grid.insert(i as u32, b);
        }
        for (i, query) in boxes.iter().enumerate() {
            let mut found = Vec::new();
            grid.for_each_candidate(query, |j| {
                found.push(j);
                ControlFlow::Continue(())
            });
            let mut unique = found.clone();
            unique.sort_unstable();
            unique.dedup();
            assert_eq!(unique.len(), found.len(), "visited twice");
            for (j, b) in boxes.iter().enumerate() {
                if b.overlaps(query) {
                    assert!(found.contains(&(j as u32)), "{i} misses {j}");
                }
            }
        }
    }

    /// Items inserted in key order, then some out of order with `insert_ordered`, some
    /// retired; queried; then more retired (the lists' heads move on) and more inserted out
    /// of order, some with keys below the retired ones': an ordered query finds each live
    /// item whose box overlaps and whose key is below the bound exactly once, and never a
    /// retired one.
    #[test]
    fn ordered_queries_find_live_items_below_the_bound() {
        let n = 60;
        let box_of = |i: usize| {
            let p = DVec2::new((i * 7 % 10) as f64, (i * 3 % 6) as f64);
            Box2 {
                min: p,
                max: p + DVec2::splat(1.5 + (i % 3) as f64),
            }
        };
        // Keys: the first 40 inserted ascending, the others out of order.
        let key = |i: usize| {
            if i < 40 {
                i as f64
            } else {
                ((i * 13) % 40) as f64 + 0.5
            }
        };
        let all = Box2 {
            min: DVec2::ZERO,
            max: DVec2::new(14.0, 10.0),
        };
        let mut grid = ScreenGrid::default();
        grid.reset(all, n);
        for i in 0..40 {
            grid.insert(i as u32, &box_of(i));
        }
        // (items inserted so far, the retired ones): the second round retires more, and
        // inserts items keyed 7.5 to 36.5 after the first ten, keyed 0 to 9, are retired.
        type Retired = fn(u32) -> bool;
        let rounds: [(usize, Retired); 2] = [
            (50, |i| i.is_multiple_of(5)),
            (60, |i| i.is_multiple_of(5) || i < 10),
        ];
        let mut inserted = 40;
        for (until, retired) in rounds {
            // Queried before the round's inserts (the heads move past the newly retired
            // items) and after them.
            for insert in [false, true] {
                if insert {
                    for i in inserted..until {
                        grid.insert_ordered(i as u32, &box_of(i), |o| key(o as usize) <= key(i));
                    }
                    inserted = until;
                }
                for bound in [3.0, 17.5, 41.0] {
                    for q in 0..n {
                        let query = box_of(q);
                        let mut found = Vec::new();
                        grid.for_each_ordered_candidate(
                            &query,
                            retired,
                            |i| key(i as usize) >= bound,
                            |i| found.push(i),
                        );
                        let mut unique = found.clone();
                        unique.sort_unstable();
                        unique.dedup();
                        assert_eq!(unique.len(), found.len(), "visited twice");
                        for i in 0..inserted {
                            let live = !retired(i as u32);
                            if live && key(i) < bound && box_of(i).overlaps(&query) {
                                assert!(
                                    found.contains(&(i as u32)),
                                    "bound {bound}: {q} misses {i}"
                                );
                            }
                            if !live {
                                assert!(!found.contains(&(i as u32)), "{q} finds retired {i}");
                            }
                        }
                    }
                }
            }
        }
    }
}
