//! Cells as long as possible: from a start angle, a cell takes every constraint active at
//! its start and then, in order of their starts, the constraints that begin later, until one
//! more would close a cycle; the next cell begins where that one does.

use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::f64::consts::TAU;

use rayon::prelude::*;

use super::cycles::{Acyclicity, CycleFinder, UNSET};
use super::pairs::Constraint;
use crate::arcs::ArcSet;
use crate::tolerance::{ARC_MARGIN_RAD, EVENT_GAP_RAD};

/// One constraint's arc, in angles relative to the sweep's origin: `behind` before `front`
/// over `(start, end)`, `0 ≤ start < end ≤ 2π`; valid while its constraint's `version` is
/// (0 as built, 1 once refined: a constraint is refined at most once).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Span {
    start: f64,
    end: f64,
    constraint: u32,
    version: u32,
    /// The constraint's ends, copied here so that checks read spans alone.
    behind: u32,
    front: u32,
}

impl Eq for Span {}

impl PartialOrd for Span {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Span {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.start
            .total_cmp(&other.start)
            .then(self.constraint.cmp(&other.constraint))
            .then(self.end.total_cmp(&other.end))
    }
}

/// An integer that orders as `f64::total_cmp` orders `x`.
fn total_order_key(x: f64) -> i64 {
    let bits = x.to_bits() as i64;
    bits ^ ((((bits >> 63) as u64) >> 1) as i64)
}

/// A cell of the sweep: `[lo, hi)` relative to the origin, and the edges that must hold.
#[derive(Clone, Debug)]
pub(crate) struct SweepCell {
    pub(crate) lo: f64,
    pub(crate) hi: f64,
    pub(crate) edges: Vec<(u32, u32)>,
    /// The cycle `(behind, front)` that one more constraint would have closed at `hi`
    /// (empty for the last cell).
    pub(crate) closing: Vec<(u32, u32)>,
}

/// Where the sweep could not continue: the constraints active at one angle form a cycle.
#[derive(Clone, Debug)]
pub(crate) struct CycleAt {
    /// Relative angle, radians.
    pub(crate) at: f64,
    /// The cycle's edges, `(behind, front)`.
    pub(crate) edges: Vec<(u32, u32)>,
}

/// Kahn's algorithm over `n` nodes with reusable buffers.
pub(crate) struct Dag {
    offsets: Vec<u32>,
    targets: Vec<u32>,
    indegree: Vec<u32>,
    ready: Vec<u32>,
}

impl Dag {
    pub(crate) fn new(n: usize) -> Self {
        Dag {
            offsets: vec![0; n + 1],
            targets: Vec::new(),
            indegree: vec![0; n],
            ready: Vec::new(),
        }
    }

    fn load(&mut self, edges: impl Iterator<Item = (u32, u32)> + Clone) {
        self.offsets.fill(0);
        self.indegree.fill(0);
        for (a, b) in edges.clone() {
            self.offsets[a as usize + 1] += 1;
            self.indegree[b as usize] += 1;
        }
        for k in 1..self.offsets.len() {
            self.offsets[k] += self.offsets[k - 1];
        }
        let total = self.offsets[self.offsets.len() - 1] as usize;
        // Every slot below `total` is written before it is read: only grow the buffer.
        if self.targets.len() < total {
            self.targets.resize(total, 0);
        }
        let mut fill = self.offsets.clone();
        for (a, b) in edges {
            self.targets[fill[a as usize] as usize] = b;
            fill[a as usize] += 1;
        }
    }

    /// Whether the edges form no cycle.
    pub(crate) fn acyclic(&mut self, edges: impl Iterator<Item = (u32, u32)> + Clone) -> bool {
        self.load(edges);
        let n = self.indegree.len();
        self.ready.clear();
        self.ready
            .extend((0..n as u32).filter(|&v| self.indegree[v as usize] == 0));
        let mut seen = 0;
        while let Some(v) = self.ready.pop() {
            seen += 1;
            for k in self.offsets[v as usize]..self.offsets[v as usize + 1] {
                let w = self.targets[k as usize];
                self.indegree[w as usize] -= 1;
                if self.indegree[w as usize] == 0 {
                    self.ready.push(w);
                }
            }
        }
        seen == n
    }

    /// An order of all nodes that keeps the edges where it can: Kahn's algorithm taking the
    /// free node of least `key`, and when none is free (a cycle), the remaining node of least
    /// `key`, dropping the edges still into it.
    pub(crate) fn order_breaking_cycles(
        &mut self,
        edges: impl Iterator<Item = (u32, u32)> + Clone,
        key: &[u32],
    ) -> Vec<u32> {
        self.load(edges);
        let n = self.indegree.len();
        let mut done = vec![false; n];
        let mut heap: BinaryHeap<Reverse<(u32, u32)>> = (0..n as u32)
            .filter(|&v| self.indegree[v as usize] == 0)
            .map(|v| Reverse((key[v as usize], v)))
            .collect();
        let mut out = Vec::with_capacity(n);
        // Every node by key, for when none is free.
        let mut by_key: Vec<u32> = (0..n as u32).collect();
        by_key.sort_unstable_by_key(|&v| std::cmp::Reverse(key[v as usize]));
        while out.len() < n {
            let v = match heap.pop() {
                Some(Reverse((_, v))) if done[v as usize] => continue,
                Some(Reverse((_, v))) => v,
                None => loop {
                    let v = by_key.pop().expect("a node is left");
                    if !done[v as usize] {
                        break v;
                    }
                },
            };
            done[v as usize] = true;
            out.push(v);
            for k in self.offsets[v as usize]..self.offsets[v as usize + 1] {
                let w = self.targets[k as usize];
                let d = &mut self.indegree[w as usize];
                *d = d.saturating_sub(1);
                if *d == 0 && !done[w as usize] {
                    heap.push(Reverse((key[w as usize], w)));
                }
            }
        }
        out
    }

    /// A topological order, among the free choices always the node of least `key`;
    /// `None` on a cycle.
    pub(crate) fn order(
        &mut self,
        edges: impl Iterator<Item = (u32, u32)> + Clone,
        key: &[u32],
    ) -> Option<Vec<u32>> {
        self.load(edges);
        let n = self.indegree.len();
        let mut heap: BinaryHeap<Reverse<(u32, u32)>> = (0..n as u32)
            .filter(|&v| self.indegree[v as usize] == 0)
            .map(|v| Reverse((key[v as usize], v)))
            .collect();
        let mut out = Vec::with_capacity(n);
        while let Some(Reverse((_, v))) = heap.pop() {
            out.push(v);
            for k in self.offsets[v as usize]..self.offsets[v as usize + 1] {
                let w = self.targets[k as usize];
                self.indegree[w as usize] -= 1;
                if self.indegree[w as usize] == 0 {
                    heap.push(Reverse((key[w as usize], w)));
                }
            }
        }
        (out.len() == n).then_some(out)
    }
}

/// The spans of constraint `c`'s arcs relative to `origin` (an arc through the origin is
/// two spans).
fn spans_of(
    c: &Constraint,
    constraint: u32,
    version: u32,
    origin: f64,
    out: &mut impl Extend<Span>,
) {
    let span = |start: f64, end: f64| Span {
        start,
        end,
        constraint,
        version,
        behind: c.behind,
        front: c.front,
    };
    if origin == 0.0 {
        // The arcs as they are: one through the origin is already its two spans.
        out.extend(c.arcs.as_slice().iter().map(|&(lo, hi)| span(lo, hi)));
        return;
    }
    for (start, length) in c.arcs.joined() {
        let s = (start - origin).rem_euclid(TAU);
        if length >= TAU {
            out.extend([span(0.0, TAU)]);
        } else if s + length > TAU {
            out.extend([span(0.0, s + length - TAU)]);
            out.extend([span(s, TAU)]);
        } else {
            out.extend([span(s, s + length)]);
        }
    }
}

/// Refinements in one batch from which they run on all cores.
const PARALLEL_REFINES: usize = 256;

/// Spans not taken yet, by start: the initial spans sorted once, and a heap for those added
/// later (refined constraints, spans put back when a cell is redone). Spans that a new cell
/// puts back return in front of the sorted ones where they fit ([`Queue::put_back`]).
#[derive(Default)]
struct Queue {
    sorted: Vec<Span>,
    next: usize,
    extra: BinaryHeap<Reverse<Span>>,
    /// Where [`Queue::rewind`] returns to: `next`, and the spans taken from the heap since.
    mark: usize,
    taken: Vec<Span>,
}

impl Queue {
    /// Starts taking spans that [`Queue::rewind`] may put back.
    fn begin(&mut self) {
        self.mark = self.next;
        self.taken.clear();
    }

    /// Puts back every span taken since [`Queue::begin`] (without re-sorting those that came
    /// from the sorted spans).
    fn rewind(&mut self) {
        self.next = self.mark;
        for s in self.taken.drain(..) {
            self.extra.push(Reverse(s));
        }
    }

    fn push(&mut self, s: Span) {
        self.extra.push(Reverse(s));
    }

    /// Puts back spans taken earlier: in front of the sorted spans not taken yet, in place of
    /// spans already taken, when they all come before those (as spans taken earlier do);
    /// else onto the heap.
    fn put_back(&mut self, mut spans: Vec<Span>) {
        spans.sort_unstable();
        let fits = spans.len() <= self.next
            && spans
                .last()
                .zip(self.sorted.get(self.next))
                .is_none_or(|(last, first)| last <= first);
        if fits {
            let start = self.next - spans.len();
            self.sorted[start..self.next].copy_from_slice(&spans);
            self.next = start;
        } else {
            self.extra.extend(spans.into_iter().map(Reverse));
        }
    }

    fn peek(&self) -> Option<Span> {
        let a = self.sorted.get(self.next).copied();
        let b = self.extra.peek().map(|r| r.0);
        match (a, b) {
            (Some(a), Some(b)) => Some(if b < a { b } else { a }),
            (a, b) => a.or(b),
        }
    }

    fn pop(&mut self) -> Option<Span> {
        let from_sorted = match (self.sorted.get(self.next), self.extra.peek()) {
            (Some(a), Some(b)) => a <= &b.0,
            (a, _) => a.is_some(),
        };
        if from_sorted {
            self.next += 1;
            Some(self.sorted[self.next - 1])
        } else {
            let s = self.extra.pop()?.0;
            self.taken.push(s);
            Some(s)
        }
    }
}

/// A refinement function: the exact arcs of a constraint.
pub(crate) type Refine<'a> = &'a (dyn Fn(&Constraint) -> ArcSet + Sync);

/// The fewest spans a cell takes at once; more at once as the cell grows (a quarter of what
/// it holds) checking the whole cell after each batch costs a constant factor.
const MIN_BATCH: usize = 1024;

/// A batch whose check finds more than this fraction (one in so many) of the window's spans
/// to be loose constraints on cycles is taken back and tried at half its size: refining one
/// costs about as much as checking forty spans, and a batch reaching far past where its cell
/// ends gathers large cycles of constraints that are loose only there.
const BACK_OFF_SHARE: usize = 32;

/// What [`Sweep::settle`] found.
enum Settle {
    /// No cycle (after refining).
    Acyclic,
    /// A cycle of exact constraints.
    Cycle(Settled),
    /// More loose constraints on cycles than allowed, none refined.
    TooLoose,
}

/// A cycle of exact constraints that [`Sweep::settle`] left, as indices into its spans.
struct Settled {
    /// Every span on some cycle.
    on_cycles: Vec<u32>,
    /// One cycle.
    cycle: Vec<u32>,
}

/// The spans of the cell being built, with their edges `(behind, front)` also kept apart in
/// a compact array: the cycle checks read only the edges, many times over.
#[derive(Default)]
struct Window {
    spans: Vec<Span>,
    edges: Vec<(u32, u32)>,
}

impl Window {
    fn len(&self) -> usize {
        self.spans.len()
    }

    fn push(&mut self, s: Span) {
        self.spans.push(s);
        self.edges.push((s.behind, s.front));
    }

    fn iter(&self) -> std::slice::Iter<'_, Span> {
        self.spans.iter()
    }

    fn truncate(&mut self, len: usize) {
        self.spans.truncate(len);
        self.edges.truncate(len);
    }

    fn retain(&mut self, mut keep: impl FnMut(&Span) -> bool) {
        let mut kept = 0;
        for k in 0..self.spans.len() {
            if keep(&self.spans[k]) {
                self.spans[kept] = self.spans[k];
                self.edges[kept] = self.edges[k];
                kept += 1;
            }
        }
        self.truncate(kept);
    }

    /// Empties the window, returning its spans.
    fn take(&mut self) -> Vec<Span> {
        self.edges.clear();
        std::mem::take(&mut self.spans)
    }

    /// The edges labelled by their index.
    fn labelled(&self) -> impl Iterator<Item = (u32, u32, u32)> + Clone + '_ {
        self.edges
            .iter()
            .zip(0..)
            .map(|(&(behind, front), k)| (behind, front, k))
    }
}

impl std::ops::Index<usize> for Window {
    type Output = Span;

    fn index(&self, k: usize) -> &Span {
        &self.spans[k]
    }
}

/// The sweep's working state.
struct Sweep<'a> {
    constraints: &'a mut [Constraint],
    /// Per constraint, one bit: whether it has been refined (its version is 1).
    refined: Vec<u64>,
    origin: f64,
    refine: Refine<'a>,
    /// Spans not taken yet.
    queue: Queue,
    finder: CycleFinder,
}

impl Sweep<'_> {
    /// Opens the cell at `lo`: the spans of `window` active at `lo` stay, those that start
    /// later go back to the queue, and the queue's spans that start by `lo` join.
    fn reopen(&mut self, window: &mut Window, lo: f64) {
        let mut later = Vec::new();
        for s in window.take() {
            if !self.valid(&s) || s.end <= lo {
                continue;
            }
            if s.start > lo {
                later.push(s);
            } else {
                window.push(s);
            }
        }
        self.queue.put_back(later);
        while let Some(s) = self.queue.peek() {
            if s.start > lo {
                break;
            }
            self.queue.pop();
            if self.valid(&s) && s.end > lo {
                window.push(s);
            }
        }
    }

    /// The length of the shortest prefix of `spans` (sorted by start, holding a cycle) that
    /// holds a cycle: its last span closes the first cycle (bisection).
    fn shortest_cyclic_prefix(&mut self, spans: &[Span]) -> usize {
        let (mut good, mut bad) = (0, spans.len());
        while bad - good > 1 {
            let mid = good + (bad - good) / 2;
            if self.cycle(&spans[..mid]).is_some() {
                bad = mid;
            } else {
                good = mid;
            }
        }
        bad
    }

    /// The current version of constraint `k`.
    fn version(&self, k: u32) -> u32 {
        let k = k as usize;
        ((self.refined[k / 64] >> (k % 64)) & 1) as u32
    }

    fn valid(&self, s: &Span) -> bool {
        self.version(s.constraint) == s.version
    }

    /// The `(behind, front)` edges of spans.
    fn edges<'s>(spans: impl Iterator<Item = &'s Span>) -> Vec<(u32, u32)> {
        spans.map(|s| (s.behind, s.front)).collect()
    }

    /// Checks `spans` for a cycle, returning one (indices into `spans`).
    fn cycle(&mut self, spans: &[Span]) -> Option<Vec<u32>> {
        let edges = spans
            .iter()
            .enumerate()
            .map(|(k, s)| (s.behind, s.front, k as u32));
        match self.finder.check(edges) {
            Acyclicity::Acyclic => None,
            Acyclicity::Cyclic { cycle, .. } => Some(cycle),
        }
    }

    /// Refines every constraint not exact yet that lies on a cycle of `spans`, until none
    /// does; returns a cycle of exact constraints that remains (indices into `spans`), if
    /// any. A refined constraint's spans leave `spans`; its new ones that start by `upto` and
    /// end after `lo` join it, later ones go to the queue. When the first check finds more
    /// than `max_loose` loose constraints on cycles it refines none ([`Settle::TooLoose`]).
    fn settle(&mut self, spans: &mut Window, lo: f64, upto: f64, max_loose: usize) -> Settle {
        // After a refinement the edges are a subset of those checked (a refined constraint's
        // exact arcs lie within its loose ones), so every cycle left lies inside a component
        // of the last check: only edges inside one are checked again.
        let mut within: Option<Vec<u32>> = None;
        loop {
            let edges = spans.labelled().filter(|&(behind, front, _)| {
                within.as_ref().is_none_or(|c| {
                    let part = c[behind as usize];
                    part != UNSET && part == c[front as usize]
                })
            });
            let ch = self.finder.check(edges);
            let Acyclicity::Cyclic { on_cycles, cycle } = ch else {
                return Settle::Acyclic;
            };
            let mut loose: Vec<u32> = on_cycles
                .iter()
                .map(|&l| spans[l as usize].constraint)
                .filter(|&k| !self.constraints[k as usize].exact)
                .collect();
            if loose.is_empty() {
                return Settle::Cycle(Settled { on_cycles, cycle });
            }
            loose.sort_unstable();
            loose.dedup();
            if within.is_none() && loose.len() > max_loose {
                return Settle::TooLoose;
            }
            within = Some(self.finder.components_found().to_vec());
            self.refine_all(&loose, spans, lo, upto);
        }
    }

    /// Replaces the arcs of constraints `ks` by their exact arcs (in parallel), as
    /// [`Sweep::settle`] describes.
    fn refine_all(&mut self, ks: &[u32], spans: &mut Window, lo: f64, upto: f64) {
        let refine = self.refine;
        let constraints = &*self.constraints;
        // Threads only pay for large batches.
        let exact: Vec<ArcSet> = if ks.len() >= PARALLEL_REFINES {
            ks.par_iter()
                .map(|&k| refine(&constraints[k as usize]))
                .collect()
        } else {
            ks.iter()
                .map(|&k| refine(&constraints[k as usize]))
                .collect()
        };
        let mut fresh = Vec::new();
        for (&k, arcs) in ks.iter().zip(exact) {
            let ku = k as usize;
            debug_assert_eq!(self.version(k), 0, "a constraint is refined once");
            self.refined[ku / 64] |= 1 << (ku % 64);
            let c = &mut self.constraints[ku];
            c.arcs = arcs;
            c.exact = true;
            spans_of(c, k, 1, self.origin, &mut fresh);
        }
        spans.retain(|s| self.version(s.constraint) == s.version);
        for s in fresh {
            if s.start > upto {
                self.queue.push(s);
            } else if s.end > lo {
                spans.push(s);
            }
        }
    }
}

/// The greedy cells over one turn from `origin`: each cell takes the constraints active at
/// its start, then those that start later in order, and ends where one would close a cycle.
/// Constraints not exact yet that lie on a cycle are refined (`refine`, in place) first, so
/// that every cell ends at a cycle of exact constraints. The last cell ends at `2π`
/// (relative).
///
/// Spans join a cell in batches (a quarter of what the cell holds): after each, the whole
/// cell is checked for cycles (Kahn's algorithm, and Tarjan's components of what it leaves),
/// and where one closed, a binary search over the batch finds the span that closed it.
pub(crate) fn sweep(
    constraints: &mut [Constraint],
    origin: f64,
    n: usize,
    refine: Refine<'_>,
) -> Result<Vec<SweepCell>, CycleAt> {
    let count = constraints.len();
    let mut state = Sweep {
        constraints,
        refined: vec![0; count.div_ceil(64)],
        origin,
        refine,
        queue: Queue::default(),
        finder: CycleFinder::new(n),
    };
    let mut sorted = Vec::with_capacity(state.constraints.len() + state.constraints.len() / 4);
    for (k, c) in state.constraints.iter().enumerate() {
        spans_of(c, k as u32, 0, origin, &mut sorted);
    }
    // In `Span`'s order: no two spans share a start and a constraint.
    sorted.par_sort_unstable_by_key(|s| (total_order_key(s.start), s.constraint));
    state.queue.sorted = sorted;
    let mut cells = Vec::new();
    let mut lo = 0.0;
    // Where the cell being built begins: the event that ended the previous one, which is
    // `lo` (the start of the span that closed a cycle) plus that span's margin.
    let mut boundary = 0.0;
    // The spans of the cell being built.
    let mut window = Window::default();
    'cells: loop {
        state.reopen(&mut window, lo);
        // A cycle among the constraints active at `lo`.
        while let Settle::Cycle(Settled { cycle, .. }) =
            state.settle(&mut window, lo, lo, usize::MAX)
        {
            // Constraints that end within a rounding gap of `lo` end with the event that
            // starts the others (a fold turning edge-on ends two pairs' overlap as it starts
            // a third's): they leave this cell.
            let ending = |s: &Span| s.end <= lo + EVENT_GAP_RAD;
            if !cycle.iter().any(|&l| ending(&window[l as usize])) {
                let edges = Sweep::edges(cycle.iter().map(|&l| &window[l as usize]));
                return Err(CycleAt { at: lo, edges });
            }
            window.retain(|s| !ending(s));
        }
        // The most spans a batch may take after one had too many loose constraints on cycles.
        let mut cap = usize::MAX;
        loop {
            let size = (window.len() / 4).min(cap).max(MIN_BATCH);
            let accepted = window.len();
            let mut upto = lo;
            state.queue.begin();
            while window.len() < accepted + size {
                let Some(s) = state.queue.pop() else {
                    break;
                };
                if state.valid(&s) {
                    upto = s.start;
                    window.push(s);
                }
            }
            if window.len() == accepted {
                let edges = Sweep::edges(window.iter());
                cells.push(SweepCell {
                    lo: boundary,
                    hi: TAU,
                    edges,
                    closing: Vec::new(),
                });
                return Ok(cells);
            }
            let max_loose = if size > MIN_BATCH {
                window.len() / BACK_OFF_SHARE
            } else {
                usize::MAX
            };
            let settled = match state.settle(&mut window, lo, upto, max_loose) {
                Settle::Acyclic => {
                    cap = cap.saturating_mul(2);
                    continue;
                }
                Settle::TooLoose => {
                    // Most of them lie beyond where the cell ends: take half as many.
                    window.truncate(accepted);
                    state.queue.rewind();
                    cap = size / 2;
                    continue;
                }
                Settle::Cycle(settled) => settled,
            };
            // The span that closed the first cycle: every cycle of a prefix (by start) lies
            // among the spans on the cycles just settled, so the search runs over those
            // alone, and none of them needs refining.
            let mut on_cycles: Vec<Span> = settled
                .on_cycles
                .iter()
                .map(|&l| window[l as usize])
                .collect();
            on_cycles.sort_unstable();
            let bad = state.shortest_cyclic_prefix(&on_cycles);
            let hi = on_cycles[bad - 1].start;
            if hi <= lo {
                // A refined constraint closed a cycle at `lo`: redo the cell.
                continue 'cells;
            }
            let cycle = state
                .cycle(&on_cycles[..bad])
                .expect("the prefix has a cycle");
            let closing = Sweep::edges(cycle.iter().map(|&l| &on_cycles[l as usize]));
            let edges = Sweep::edges(window.iter().filter(|s| s.start < hi));
            // The closing span is exact (refined if it was not), so its start is its event
            // less the margin: the cell holds until the event itself. There, constraints
            // that end with the same event (within `EVENT_GAP_RAD`, below) have truly ended.
            let event = (hi + ARC_MARGIN_RAD).min(TAU);
            cells.push(SweepCell {
                lo: boundary,
                hi: event,
                edges,
                closing,
            });
            lo = hi;
            boundary = event;
            continue 'cells;
        }
    }
}

/// The number of items of `next` outside a longest subsequence it shares, in order, with
/// `previous` (both orders of the same items): how many must move between them.
pub(crate) fn moved(previous: &[u32], next: &[u32]) -> usize {
    let size = previous.iter().max().map_or(0, |&m| m as usize + 1);
    let mut position = vec![0u32; size];
    for (k, &p) in previous.iter().enumerate() {
        position[p as usize] = k as u32;
    }
    // Longest increasing subsequence of positions, by patience sorting.
    let mut tails: Vec<u32> = Vec::new();
    for &p in next {
        let x = position[p as usize];
        let at = tails.partition_point(|&t| t < x);
        if at == tails.len() {
            tails.push(x);
        } else {
            tails[at] = x;
        }
    }
    next.len() - tails.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(behind: u32, front: u32, start: f64, length: f64) -> Constraint {
        Constraint {
            behind,
            front,
            arcs: ArcSet::arc(start, length),
            exact: true,
        }
    }

    #[test]
    fn a_cell_ends_where_a_cycle_would_close() {
        let exact = |c: &Constraint| c.arcs.clone();
        // 0 before 1 over [1, 2], 1 before 0 over [3, 4]: two cells.
        let mut constraints = vec![c(0, 1, 1.0, 1.0), c(1, 0, 3.0, 1.0)];
        let cells = sweep(&mut constraints, 0.0, 2, &exact).unwrap();
        assert_eq!(cells.len(), 2);
        // At the event: the closing span's start plus its margin.
        assert_eq!(cells[0].hi, 3.0 + ARC_MARGIN_RAD);
        assert_eq!(cells[1].lo, cells[0].hi);
        // Without the conflict: one cell.
        let cells = sweep(&mut constraints[..1], 0.0, 2, &exact).unwrap();
        assert_eq!(cells.len(), 1);
        // A cycle at one angle is reported.
        let mut both = vec![c(0, 1, 1.0, 1.0), c(1, 0, 1.5, 1.0)];
        assert!(sweep(&mut both, 1.6, 2, &exact).is_err());
        // A cycle through a constraint that is not exact refines it; here its exact arcs
        // miss the conflict, so one cell remains.
        let mut loose = vec![c(0, 1, 1.0, 1.0), c(1, 0, 1.5, 3.0)];
        loose[1].exact = false;
        let shrink = |c: &Constraint| {
            if c.exact {
                c.arcs.clone()
            } else {
                ArcSet::arc(3.0, 1.0)
            }
        };
        let cells = sweep(&mut loose, 0.0, 2, &shrink).unwrap();
        assert_eq!(cells.len(), 2);
        assert!(loose[1].exact);
        assert_eq!(cells[0].hi, 3.0 + ARC_MARGIN_RAD);
    }

    #[test]
    fn orders_follow_the_key_where_free() {
        let mut dag = Dag::new(4);
        let order = dag
            .order([(3u32, 0u32)].into_iter(), &[0, 1, 2, 3])
            .unwrap();
        assert_eq!(order, vec![1, 2, 3, 0]);
        assert_eq!(moved(&[0, 1, 2, 3], &[1, 2, 3, 0]), 1);
        assert!(
            dag.order([(0u32, 1u32), (1, 0)].into_iter(), &[0, 1, 0, 0])
                .is_none()
        );
    }
}
