//! A uniform grid over screen boxes, rebuilt per frame, to find the polygons whose screen boxes
//! may overlap a given box without scanning them all.

use std::ops::ControlFlow;

use glam::DVec2;

use crate::polygon::Box2;
use crate::tolerance::UNDERFLOW_ABS;

/// Most cells along either side of the grid.
const MAX_SIDE: usize = 256;

/// Buckets of item indices by the grid cells their boxes touch.
///
/// # Guarantees
/// [`for_each_candidate`](Self::for_each_candidate) visits every inserted item whose box
/// overlaps the query box (and possibly others), each once per query.
#[derive(Clone, Debug, Default)]
pub(crate) struct ScreenGrid {
    origin: DVec2,
    inverse_cell: DVec2,
    columns: usize,
    rows: usize,
    cells: Vec<Vec<u32>>,
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
        let cell = (size.x * size.y / items.max(1) as f64).sqrt();
        let count = |extent: f64| ((extent / cell).ceil() as usize).clamp(1, MAX_SIDE);
        let (columns, rows) = (count(size.x), count(size.y));
        self.origin = bounds.min;
        self.columns = columns;
        self.rows = rows;
        self.inverse_cell = DVec2::new(columns as f64 / size.x, rows as f64 / size.y);
        if self.cells.len() < columns * rows {
            self.cells.resize_with(columns * rows, Vec::new);
        }
        for cell in &mut self.cells[..columns * rows] {
            cell.clear();
        }
        self.stamp.clear();
        self.query = 0;
    }

    fn range(&self, b: &Box2) -> Option<(usize, usize, usize, usize)> {
        if !(b.min.x <= b.max.x && b.min.y <= b.max.y) {
            return None;
        }
        let lo = (b.min - self.origin) * self.inverse_cell;
        let hi = (b.max - self.origin) * self.inverse_cell;
        // Truncation is the floor for the non-negative values kept (casts saturate; NaN is 0).
        let clamp = |v: f64, n: usize| (v.max(0.0) as usize).min(n - 1);
        Some((
            clamp(lo.x, self.columns),
            clamp(hi.x, self.columns),
            clamp(lo.y, self.rows),
            clamp(hi.y, self.rows),
        ))
    }

    /// Adds item `item` (items are numbered densely from 0) with screen box `b`.
    pub(crate) fn insert(&mut self, item: u32, b: &Box2) {
        if self.stamp.len() <= item as usize {
            self.stamp.resize(item as usize + 1, 0);
        }
        if let Some((x0, x1, y0, y1)) = self.range(b) {
            for y in y0..=y1 {
                for x in x0..=x1 {
                    self.cells[y * self.columns + x].push(item);
                }
            }
        }
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
        self.query = self.query.wrapping_add(1);
        if self.query == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.query = 1;
        }
        let query = self.query;
        let stamp = &mut self.stamp;
        for row in self.cells.chunks(self.columns).take(y1 + 1).skip(y0) {
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
}
