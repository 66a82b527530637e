//! The bake's data: angle ranges, cells, breakpoints, the delta timeline.

use std::sync::Arc;

use face_sort::sorter_api::DrawListWriter;
use face_sort::{DrawList, PolygonSet};

use crate::axis::Axis;
use crate::event::EventFn;

/// A half-open angle interval `[lo, hi)` in degrees; on a periodic axis it wraps (then
/// `lo > hi` after reduction means "from `lo` past the period to `hi`").
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct AngleRange {
    /// Start, degrees (inclusive).
    pub lo: f64,
    /// End, degrees (exclusive).
    pub hi: f64,
    /// Period in degrees (e.g. 360) for a periodic axis, `None` otherwise.
    pub period: Option<f64>,
}

impl AngleRange {
    /// Whether `angle` (degrees) lies in the range.
    #[must_use]
    pub fn contains(&self, angle: f64) -> bool {
        match self.period {
            None => angle >= self.lo && angle < self.hi,
            Some(p) => {
                if self.hi - self.lo >= p {
                    return true;
                }
                let (a, lo, hi) = (
                    angle.rem_euclid(p),
                    self.lo.rem_euclid(p),
                    self.hi.rem_euclid(p),
                );
                if lo <= hi {
                    a >= lo && a < hi
                } else {
                    a >= lo || a < hi
                }
            }
        }
    }

    /// The predicate as an expression over a variable holding the angle in degrees, in the
    /// C-like syntax most animation systems accept (`%`, `&&`, `||`, comparisons), e.g.
    /// `((a % 360 + 360) % 360 >= 10 && (a % 360 + 360) % 360 < 20)`.
    #[must_use]
    pub fn to_expression(&self, variable: &str) -> String {
        match self.period {
            None => format!("({variable} >= {} && {variable} < {})", self.lo, self.hi),
            Some(p) => {
                if self.hi - self.lo >= p {
                    return "true".to_owned();
                }
                let a = format!("({variable} % {p} + {p}) % {p}");
                let (lo, hi) = (self.lo.rem_euclid(p), self.hi.rem_euclid(p));
                if lo <= hi {
                    format!("({a} >= {lo} && {a} < {hi})")
                } else {
                    format!("({a} >= {lo} || {a} < {hi})")
                }
            }
        }
    }

    /// An interior angle at fraction `f ∈ (0, 1)` of the way from `lo` to `hi`.
    #[must_use]
    pub fn lerp(&self, f: f64) -> f64 {
        self.lo + (self.hi - self.lo) * f
    }
}

/// One cell of a bake: over `range` the painter order is `order` (indices into the bake's
/// polygon set, back to front; culled polygons are absent).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BakeCell {
    /// Where the order holds.
    pub range: AngleRange,
    /// Polygon indices in paint order.
    pub order: Vec<u32>,
}

/// A cell boundary where the draw list changes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Breakpoint {
    /// The animated parameter, degrees.
    pub degrees: f64,
    /// An event function that changes sign there (`None` for sampled bakes).
    pub event: Option<EventFn>,
}

/// How a bake was made.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Method {
    /// Closed-form events.
    Exact,
    /// Cells exact for the picture when the sink culls back faces ([`crate::bake_picture`]):
    /// each cell holds every piece, and its order is right for every overlapping pair of
    /// front-facing pieces.
    Picture,
    /// The seed's method: `samples` draw lists, changes bisected to `tolerance_deg`.
    Sampled {
        /// Samples over the domain.
        samples: usize,
        /// Bisection stops below this width, degrees.
        tolerance_deg: f64,
    },
}

/// Bytes of a bake in both encodings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Sizes {
    /// Full per-cell draw lists: per cell two f64 bounds and a u32 per item.
    pub full_bytes: usize,
    /// The first list in full, then per boundary one [`Delta`]: f64 angle, u32 start,
    /// u32 removed count, u32 per inserted item.
    pub delta_bytes: usize,
}

/// Every painter order along a spin: cells of constant draw list.
#[derive(Clone, Debug)]
pub struct Bake {
    /// What turns.
    pub(crate) axis: Axis,
    /// The sorter whose draw lists these are.
    pub(crate) sorter: String,
    /// How the bake was made.
    pub(crate) method: Method,
    /// The domain in degrees: `[lo, lo + 360)` for a full period, else `[lo, hi]`.
    pub(crate) domain: AngleRange,
    /// Polygons the orders refer to (the sorter's shared set, centred model space).
    pub(crate) polygons: Arc<PolygonSet>,
    /// Cells in increasing angle. Over a full period the first starts at the smallest
    /// breakpoint and the last wraps past 360.
    pub(crate) cells: Vec<BakeCell>,
    /// Where the list changes, increasing.
    pub(crate) breakpoints: Vec<Breakpoint>,
    /// Exact bakes: sign changes of every event function in the domain, before merging.
    /// Sampled bakes: sample steps whose two lists differ (each bisected once).
    pub(crate) events: usize,
    /// Wall time of the bake, milliseconds.
    pub(crate) bake_ms: f64,
}

/// One step of the delta timeline: entering the next cell, replace `removed` items from
/// `start` by `inserted` (the common head and tail of the two lists stay).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Delta {
    /// Position of the first changed item.
    pub start: u32,
    /// Items removed there.
    pub removed: u32,
    /// Items inserted there.
    pub inserted: Vec<u32>,
}

impl Delta {
    /// The splice turning `from` into `to`.
    #[must_use]
    pub fn between(from: &[u32], to: &[u32]) -> Self {
        let head = from.iter().zip(to).take_while(|(a, b)| a == b).count();
        let tail = from[head..]
            .iter()
            .rev()
            .zip(to[head..].iter().rev())
            .take_while(|(a, b)| a == b)
            .count();
        Delta {
            start: head as u32,
            removed: (from.len() - head - tail) as u32,
            inserted: to[head..to.len() - tail].to_vec(),
        }
    }

    /// Applies the splice to a list.
    pub fn apply(&self, list: &mut Vec<u32>) {
        let start = self.start as usize;
        list.splice(
            start..start + self.removed as usize,
            self.inserted.iter().copied(),
        );
    }

    /// Encoded bytes (see [`Sizes::delta_bytes`]).
    #[must_use]
    pub fn bytes(&self) -> usize {
        8 + 4 + 4 + 4 * self.inserted.len()
    }
}

/// Bytes of one cell in the full encoding.
#[must_use]
pub fn cell_bytes(items: usize) -> usize {
    16 + 4 * items
}

impl Bake {
    /// What turns.
    #[must_use]
    pub fn axis(&self) -> Axis {
        self.axis
    }
    /// The sorter whose draw lists these are (`"picture"` for picture bakes).
    #[must_use]
    pub fn sorter(&self) -> &str {
        &self.sorter
    }
    /// How the bake was made.
    #[must_use]
    pub fn method(&self) -> Method {
        self.method
    }
    /// The domain in degrees: `[lo, lo + 360)` for a full period, else `[lo, hi]`.
    #[must_use]
    pub fn domain(&self) -> AngleRange {
        self.domain
    }
    /// Polygons the orders refer to (centred model space).
    #[must_use]
    pub fn polygons(&self) -> &Arc<PolygonSet> {
        &self.polygons
    }
    /// Cells in increasing angle. Over a full period the first starts at the smallest
    /// breakpoint and the last wraps past 360.
    #[must_use]
    pub fn cells(&self) -> &[BakeCell] {
        &self.cells
    }
    /// Where the list changes, increasing.
    #[must_use]
    pub fn breakpoints(&self) -> &[Breakpoint] {
        &self.breakpoints
    }
    /// Exact bakes: sign changes of every event function in the domain, before merging.
    /// Sampled bakes: sample steps whose two lists differ (each bisected once).
    #[must_use]
    pub fn events(&self) -> usize {
        self.events
    }
    /// Wall time of the bake, milliseconds.
    #[must_use]
    pub fn bake_ms(&self) -> f64 {
        self.bake_ms
    }
    /// The paint order (polygon indices, back to front) at an angle in degrees: the order
    /// of [`cell_at`](Self::cell_at)'s cell; `None` outside the domain.
    #[must_use]
    pub fn draw_list_at(&self, degrees: f64) -> Option<&[u32]> {
        self.cell_at(degrees).map(|c| &self.cells[c].order[..])
    }
    /// Index of the cell holding `degrees`: O(log cells). `None` outside a bounded domain.
    #[must_use]
    pub fn cell_at(&self, degrees: f64) -> Option<usize> {
        let first = self.cells.first()?;
        let angle = match self.domain.period {
            Some(p) if degrees >= first.range.lo && degrees < first.range.lo + p => degrees,
            Some(p) => first.range.lo + (degrees - first.range.lo).rem_euclid(p),
            None => {
                if degrees < self.domain.lo || degrees > self.domain.hi {
                    return None;
                }
                degrees
            }
        };
        let after = self.cells.partition_point(|c| c.range.lo <= angle);
        Some(after.saturating_sub(1))
    }

    /// The delta timeline: for each cell after the first, the splice from the previous cell's
    /// list (over a full period also from the last back to the first, last).
    #[must_use]
    pub fn delta_timeline(&self) -> Vec<Delta> {
        let mut deltas: Vec<Delta> = self
            .cells
            .windows(2)
            .map(|w| Delta::between(&w[0].order, &w[1].order))
            .collect();
        if self.domain.period.is_some() && self.cells.len() > 1 {
            let (first, last) = (&self.cells[0], &self.cells[self.cells.len() - 1]);
            deltas.push(Delta::between(&last.order, &first.order));
        }
        deltas
    }

    /// Bytes in both encodings.
    #[must_use]
    pub fn sizes(&self) -> Sizes {
        let full_bytes = self.cells.iter().map(|c| cell_bytes(c.order.len())).sum();
        let first = self.cells.first().map_or(0, |c| cell_bytes(c.order.len()));
        let delta_bytes = first
            + self
                .delta_timeline()
                .iter()
                .map(Delta::bytes)
                .sum::<usize>();
        Sizes {
            full_bytes,
            delta_bytes,
        }
    }

    /// Breakpoints of `exact` with no breakpoint of `self` within `tolerance_deg` (on a full
    /// period, measured round the circle): the events a sampled bake missed.
    #[must_use]
    pub fn missed(&self, exact: &Bake, tolerance_deg: f64) -> Vec<f64> {
        let period = self.domain.period;
        let mine: Vec<f64> = self.breakpoints.iter().map(|b| b.degrees).collect();
        let distance = |a: f64, b: f64| match period {
            Some(p) => {
                let d = (a - b).rem_euclid(p);
                d.min(p - d)
            }
            None => (a - b).abs(),
        };
        exact
            .breakpoints
            .iter()
            .map(|b| b.degrees)
            .filter(|&e| !mine.iter().any(|&m| distance(m, e) <= tolerance_deg))
            .collect()
    }
}

/// Cell `cell`'s whole order as a draw list whose sink culls
/// ([`DrawList::set_sink_culls`]): what every consumer paints or judges at any angle of
/// the cell, skipping the pieces the view does not draw.
pub fn cell_list(bake: &Bake, cell: usize, list: &mut DrawList) {
    cell_list_where(bake, cell, list, |_| true);
}

/// Cell `cell`'s order, the pieces `keep` accepts, as a draw list whose sink culls.
pub(crate) fn cell_list_where(
    bake: &Bake,
    cell: usize,
    list: &mut DrawList,
    keep: impl Fn(u32) -> bool,
) {
    let set = &bake.polygons;
    list.begin(set);
    list.set_sink_culls(true);
    for &p in bake.cells[cell].order.iter().filter(|&&p| keep(p)) {
        list.push(p, set.face(p as usize));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delta_round_trips() {
        let cases: [(&[u32], &[u32]); 4] = [
            (&[1, 2, 3, 4], &[1, 3, 2, 4]),
            (&[1, 2, 3], &[1, 2, 3, 5]),
            (&[], &[7]),
            (&[5, 5, 5], &[5]),
        ];
        for (a, b) in cases {
            let d = Delta::between(a, b);
            let mut list = a.to_vec();
            d.apply(&mut list);
            assert_eq!(list, b);
        }
    }
}
