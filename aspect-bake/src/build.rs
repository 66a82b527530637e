//! Baking: events, intervals, the live sorter inside each, merged cells.

use std::f64::consts::TAU;
use web_time::Instant;

use face_sort::{DrawList, View};
use rayon::prelude::*;

use crate::BakeError;
use crate::axis::Spin;
use crate::cells::{AngleRange, Bake, BakeCell, Breakpoint, Method, cell_bytes};
use crate::event::EventFn;
use crate::source::{Event, EventSource};
use crate::tolerance::SAME_ROOT_RAD;
use crate::verify::{polygons_of, same_order};

/// How far a bake has got: `done` of `total` draw lists computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    /// Draw lists computed.
    pub done: usize,
    /// Draw lists to compute.
    pub total: usize,
}

/// Options of [`bake`] and [`bake_sampled`].
#[derive(Clone, Copy)]
pub struct BakeOptions<'a> {
    /// `Some((lo, hi))` degrees bakes `[lo, hi]` only; `None` the full period.
    pub range_deg: Option<(f64, f64)>,
    /// The bake stops with [`BakeError::SizeBudget`] when its full per-cell lists would
    /// exceed this many bytes.
    pub budget_bytes: usize,
    /// The bake stops with [`BakeError::EventBudget`] beyond this many sign changes.
    pub max_events: usize,
    /// Called from the baking thread after each block of draw lists.
    pub progress: Option<&'a (dyn Fn(Progress) + Sync)>,
}

impl std::fmt::Debug for BakeOptions<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BakeOptions")
            .field("range_deg", &self.range_deg)
            .field("budget_bytes", &self.budget_bytes)
            .field("max_events", &self.max_events)
            .field("progress", &self.progress.is_some())
            .finish()
    }
}

impl BakeOptions<'_> {
    /// Full period, 1 GiB, 50 million events, no progress callback.
    pub const DEFAULT: BakeOptions<'static> = BakeOptions {
        range_deg: None,
        budget_bytes: 1 << 30,
        max_events: 50_000_000,
        progress: None,
    };
}

impl Default for BakeOptions<'_> {
    fn default() -> Self {
        BakeOptions::DEFAULT
    }
}

/// The domain in radians: `(start, end, periodic)`.
fn domain(spin: &Spin, options: &BakeOptions) -> Result<(f64, f64, bool), BakeError> {
    refuse_cull_margin(spin.template())?;
    match options.range_deg {
        None => Ok((0.0, TAU, true)),
        Some(range) => {
            let (lo, hi) = check_range(range)?;
            Ok((lo.to_radians(), hi.to_radians(), false))
        }
    }
}

/// A bake's conditions are sign conditions of plane rows only without a cull margin.
pub(crate) fn refuse_cull_margin(template: &View) -> Result<(), BakeError> {
    match template.cull_margin() {
        degrees if degrees > 0.0 => Err(BakeError::CullMargin { degrees }),
        _ => Ok(()),
    }
}

/// An angle range in degrees: finite, not empty, at most one turn.
pub(crate) fn check_range((lo, hi): (f64, f64)) -> Result<(f64, f64), BakeError> {
    if lo.is_finite() && hi.is_finite() && hi > lo && hi - lo <= 360.0 {
        Ok((lo, hi))
    } else {
        Err(BakeError::Range { lo, hi })
    }
}

fn domain_range(start: f64, end: f64, periodic: bool) -> AngleRange {
    AngleRange {
        lo: start.to_degrees(),
        hi: if periodic {
            start.to_degrees() + 360.0
        } else {
            end.to_degrees()
        },
        period: periodic.then_some(360.0),
    }
}

/// Draw lists (polygon indices) of the live sorter at each point, `view` placing the point, on
/// all cores (one sorter per chunk of points).
pub(crate) fn lists_at<T: Sync>(
    source: &dyn EventSource,
    points: &[T],
    view: impl Fn(&T) -> View + Sync,
) -> Vec<Vec<u32>> {
    let threads = rayon::current_num_threads().max(1);
    let chunk = points.len().div_ceil(threads * 4).max(1);
    points
        .par_chunks(chunk)
        .flat_map_iter(|chunk| {
            let mut sorter = source.sorter();
            let mut list = DrawList::new();
            chunk
                .iter()
                .map(|point| {
                    sorter.sort(&view(point), &mut list);
                    polygons_of(&list)
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

/// Lists per interval, merged into cells as they come, under the size budget.
struct Merger<'a> {
    cells: Vec<(f64, f64, Vec<u32>, Option<EventFn>)>,
    bytes: usize,
    options: &'a BakeOptions<'a>,
}

impl Merger<'_> {
    fn push(&mut self, lo: f64, hi: f64, order: Vec<u32>, event: Option<EventFn>) {
        if let Some(last) = self.cells.last_mut()
            && last.2 == order
        {
            last.1 = hi;
            return;
        }
        self.bytes += cell_bytes(order.len());
        self.cells.push((lo, hi, order, event));
    }

    fn check(&self, done: usize, total: usize) -> Result<(), BakeError> {
        if let Some(progress) = self.options.progress {
            progress(Progress { done, total });
        }
        if self.bytes > self.options.budget_bytes {
            return Err(BakeError::SizeBudget {
                bytes_so_far: self.bytes,
                cells_so_far: self.cells.len(),
                done,
                total,
                estimated_bytes: (self.bytes as f64 * total as f64 / done.max(1) as f64) as usize,
                budget: self.options.budget_bytes,
            });
        }
        Ok(())
    }

    /// The cells (wrapping the last into the first over a full period) and breakpoints.
    fn finish(mut self, periodic: bool) -> (Vec<BakeCell>, Vec<Breakpoint>) {
        if periodic && self.cells.len() > 1 {
            let last = self.cells.len() - 1;
            if self.cells[0].2 == self.cells[last].2 {
                let first = self.cells.remove(0);
                let last = self.cells.last_mut().expect("more than one cell");
                last.1 = first.1 + TAU;
            }
        }
        let period = periodic.then_some(360.0);
        let skip = usize::from(!periodic || self.cells.len() == 1);
        let breakpoints = self
            .cells
            .iter()
            .skip(skip)
            .map(|c| Breakpoint {
                degrees: c.0.to_degrees(),
                event: c.3,
            })
            .collect();
        let cells = self
            .cells
            .into_iter()
            .map(|(lo, hi, order, _)| BakeCell {
                range: AngleRange {
                    lo: lo.to_degrees(),
                    hi: hi.to_degrees(),
                    period,
                },
                order,
            })
            .collect();
        (cells, breakpoints)
    }
}

/// Draw lists per block: bounded memory between budget checks (one- and two-axis bakes).
pub(crate) const BLOCK: usize = 2048;

/// Which group of roots a root joins while the exact bake groups them into breakpoints.
#[derive(Clone, Copy)]
enum Chain {
    /// The group of candidate `k`.
    Candidate(usize),
    /// The group merged into the first candidate across the turn's end (periodic).
    Wrap,
    /// The group merged into the domain's start or end (a range).
    End,
}

/// Where inside an interval between events the exact bake runs the live sorter, as a
/// fraction of its width: not the middle, because roots come in pairs about a tangency (a
/// function that touches zero without changing sign, where the live sorter's decision
/// follows rounding), so an interval is often symmetric about one.
const SAMPLE_AT: f64 = std::f64::consts::SQRT_2 - 1.0;

/// The exact bake: every sign change of the source's event functions in closed form, roots
/// closer than [`SAME_ROOT_RAD`] or than their rounding uncertainties merged into one
/// breakpoint at the best-determined of them, the live sorter run once inside each interval
/// between consecutive roots (in parallel), equal neighbours merged.
///
/// # Errors
/// [`BakeError::CullMargin`], [`BakeError::Range`], [`BakeError::EventBudget`],
/// [`BakeError::SizeBudget`].
pub fn bake(
    source: &dyn EventSource,
    spin: &Spin,
    options: &BakeOptions,
) -> Result<Bake, BakeError> {
    let started = Instant::now();
    let (start, end, periodic) = domain(spin, options)?;
    let mut events: Vec<Event> = Vec::new();
    source.events(spin, start, end, options.max_events, &mut events)?;
    events.sort_by(|a, b| a.theta.total_cmp(&b.theta));
    // Breakpoint candidates: chains of roots each within SAME_ROOT_RAD, or within the sum of
    // the two roots' uncertainties, of the chain's best-determined root so far are one
    // candidate, the domain's ends apart. A chain's breakpoint is its best-determined root:
    // near it every other function of the chain is zero within rounding (its value within
    // `ROOT_NOISE · scale` across its uncertainty), so the live sorter follows the sharp one
    // there. (A near-tangency's pair of roots is uncertain by far more than the roots are
    // apart; taken as the breakpoint, it would move a sharp root beside it by as much.)
    //
    // Near the best root, not merely near the last one: a root uncertain by tens of degrees
    // (a face nearly along the turning axis, its facing a near-tangency of amplitude 1e-9)
    // would otherwise chain sharp roots degrees apart into one breakpoint, and the cells
    // between them would be lost (found by fuzzing).
    let mut candidates: Vec<(Event, f64)> = Vec::new();
    let mut wrap_best: Option<(Event, f64)> = None;
    // The current chain, and its best root so far: where, and how uncertain.
    let mut previous: Option<(f64, f64, Chain)> = None;
    for e in &events {
        let mine = e.function.root_uncertainty();
        let near = |gap: f64, other: f64| gap < SAME_ROOT_RAD.max(mine + other);
        let near_end = !periodic && (near(e.theta - start, 0.0) || near(end - e.theta, 0.0));
        let near_wrap = periodic
            && candidates
                .first()
                .is_some_and(|c| near(c.0.theta + TAU - e.theta, c.1));
        let chain = match previous {
            _ if near_end => Chain::End,
            Some((t, u, chain)) if near(e.theta - t, u) => chain,
            _ if near_wrap => Chain::Wrap,
            _ => {
                candidates.push((*e, mine));
                Chain::Candidate(candidates.len() - 1)
            }
        };
        let best = match chain {
            Chain::Candidate(k) => {
                if mine < candidates[k].1 {
                    candidates[k] = (*e, mine);
                }
                (candidates[k].0.theta, candidates[k].1)
            }
            Chain::Wrap => {
                if wrap_best.is_none_or(|w| mine < w.1) {
                    wrap_best = Some((*e, mine));
                }
                wrap_best.map_or((e.theta, mine), |w| (w.0.theta, w.1))
            }
            Chain::End => (e.theta, mine),
        };
        previous = Some((best.0, best.1, chain));
    }
    // A chain that wraps round to the first one: its breakpoint moves to the turn's end
    // when its root is the better determined.
    if let Some(w) = wrap_best
        && w.1 < candidates[0].1
    {
        candidates[0] = w;
        candidates.rotate_left(1);
    }
    let candidates: Vec<Event> = candidates.into_iter().map(|c| c.0).collect();
    // Intervals [lo, hi) with the event at their start.
    let mut intervals: Vec<(f64, f64, Option<EventFn>)> = Vec::new();
    if periodic {
        if candidates.is_empty() {
            intervals.push((start, end, None));
        }
        for (k, c) in candidates.iter().enumerate() {
            let hi = candidates
                .get(k + 1)
                .map_or(candidates[0].theta + TAU, |n| n.theta);
            intervals.push((c.theta, hi, Some(c.function)));
        }
    } else {
        let mut lo = (start, None);
        for c in &candidates {
            intervals.push((lo.0, c.theta, lo.1));
            lo = (c.theta, Some(c.function));
        }
        intervals.push((lo.0, end, lo.1));
    }
    let mut merger = Merger {
        cells: Vec::new(),
        bytes: 0,
        options,
    };
    let total = intervals.len();
    for (b, block) in intervals.chunks(BLOCK).enumerate() {
        let mids: Vec<f64> = block
            .iter()
            .map(|i| i.0 + SAMPLE_AT * (i.1 - i.0))
            .collect();
        for (i, order) in block
            .iter()
            .zip(lists_at(source, &mids, |&t| spin.view_at_rad(t)))
        {
            merger.push(i.0, i.1, order, i.2);
        }
        merger.check((b * BLOCK + block.len()).min(total), total)?;
    }
    let (cells, breakpoints) = merger.finish(periodic);
    Ok(Bake {
        axis: spin.axis(),
        sorter: source.name().to_owned(),
        method: Method::Exact,
        domain: domain_range(start, end, periodic),
        polygons: std::sync::Arc::clone(source.polygons()),
        cells,
        breakpoints,
        events: events.len(),
        bake_ms: started.elapsed().as_secs_f64() * 1e3,
    })
}

/// The seed's baseline behind the same interface: the live sorter at `samples` evenly spaced
/// angles, and between two samples whose lists differ, bisection on "same list as the left
/// end" down to `tolerance_deg`. Two changes within one step are seen as one, or not at all
/// when the list comes back ([`Bake::missed`] counts them against an exact bake).
///
/// # Errors
/// As [`bake`], and [`BakeError::Samples`] for fewer than 2 samples or a tolerance that is
/// not positive.
pub fn bake_sampled(
    source: &dyn EventSource,
    spin: &Spin,
    samples: usize,
    tolerance_deg: f64,
    options: &BakeOptions,
) -> Result<Bake, BakeError> {
    let started = Instant::now();
    let (start, end, periodic) = domain(spin, options)?;
    if samples < 2 || tolerance_deg.is_nan() || tolerance_deg <= 0.0 {
        return Err(BakeError::Samples {
            samples,
            tolerance_deg,
        });
    }
    let tolerance = tolerance_deg.to_radians();
    let step = if periodic {
        (end - start) / samples as f64
    } else {
        (end - start) / (samples - 1) as f64
    };
    let thetas: Vec<f64> = (0..samples).map(|k| start + step * k as f64).collect();
    let lists = lists_at(source, &thetas, |&t| spin.view_at_rad(t));
    // Brackets (left angle, right angle) whose lists differ, the last wrapping round.
    let pairs = if periodic { samples } else { samples - 1 };
    let changes: Vec<usize> = (0..pairs)
        .filter(|&k| lists[k] != lists[(k + 1) % samples])
        .collect();
    let found: Vec<(f64, Vec<u32>)> = changes
        .par_iter()
        .map(|&k| {
            let mut sorter = source.sorter();
            let mut list = DrawList::new();
            let (mut lo, mut hi) = (thetas[k], thetas[k] + step);
            let mut right = lists[(k + 1) % samples].clone();
            while hi - lo > tolerance {
                let mid = 0.5 * (lo + hi);
                sorter.sort(&spin.view_at_rad(mid), &mut list);
                if same_order(&list, &lists[k]) {
                    lo = mid;
                } else {
                    hi = mid;
                    right = polygons_of(&list);
                }
            }
            (hi, right)
        })
        .collect();
    let mut merger = Merger {
        cells: Vec::new(),
        bytes: 0,
        options,
    };
    if periodic {
        if found.is_empty() {
            merger.push(start, end, lists[0].clone(), None);
        }
        for (j, (at, right)) in found.iter().enumerate() {
            let hi = found.get(j + 1).map_or(found[0].0 + TAU, |n| n.0);
            merger.push(*at, hi, right.clone(), None);
        }
    } else {
        let mut lo = (start, lists[0].clone());
        for (at, right) in &found {
            merger.push(lo.0, *at, lo.1, None);
            lo = (*at, right.clone());
        }
        merger.push(lo.0, end, lo.1, None);
    }
    merger.check(samples, samples)?;
    let (cells, mut breakpoints) = merger.finish(periodic);
    for b in &mut breakpoints {
        b.degrees = reduce_degrees(b.degrees, periodic);
    }
    breakpoints.sort_by(|a, b| a.degrees.total_cmp(&b.degrees));
    Ok(Bake {
        axis: spin.axis(),
        sorter: source.name().to_owned(),
        method: Method::Sampled {
            samples,
            tolerance_deg,
        },
        domain: domain_range(start, end, periodic),
        polygons: std::sync::Arc::clone(source.polygons()),
        cells,
        breakpoints,
        events: changes.len(),
        bake_ms: started.elapsed().as_secs_f64() * 1e3,
    })
}

fn reduce_degrees(d: f64, periodic: bool) -> f64 {
    if periodic { d.rem_euclid(360.0) } else { d }
}
