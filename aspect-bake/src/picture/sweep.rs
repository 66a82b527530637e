//! Cells as long as possible: from a start angle, a cell takes every constraint active at
//! its start and then, in order of their starts, the constraints that begin later, until one
//! more would close a cycle; the next cell begins where that one does.

use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::f64::consts::TAU;

use rayon::prelude::*;

use super::pairs::Constraint;
use crate::arcs::ArcSet;
use crate::tolerance::EVENT_GAP_RAD;

/// One constraint's arc, in angles relative to the sweep's origin: `behind` before `front`
/// over `(start, end)`, `0 ≤ start < end ≤ 2π`; valid while its constraint's `version` is.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Span {
    start: f64,
    end: f64,
    constraint: u32,
    version: u32,
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

/// A topological order kept while edges arrive one by one (Pearce and Kelly's dynamic
/// topological sort): an edge that agrees with the order costs nothing; one that does not
/// reorders only the nodes between its ends, or reports the cycle it closes.
struct DynamicOrder {
    out: Vec<Vec<(u32, u32)>>,
    into: Vec<Vec<(u32, u32)>>,
    position: Vec<u32>,
    touched: Vec<u32>,
    is_touched: Vec<bool>,
    seen: Vec<u32>,
    epoch: u32,
    parent: Vec<(u32, u32)>,
    stack: Vec<u32>,
    forward: Vec<u32>,
    backward: Vec<u32>,
    pool: Vec<u32>,
}

impl DynamicOrder {
    fn new(n: usize) -> Self {
        DynamicOrder {
            out: vec![Vec::new(); n],
            into: vec![Vec::new(); n],
            position: (0..n as u32).collect(),
            touched: Vec::new(),
            is_touched: vec![false; n],
            seen: vec![0; n],
            epoch: 0,
            parent: vec![(0, 0); n],
            stack: Vec::new(),
            forward: Vec::new(),
            backward: Vec::new(),
            pool: Vec::new(),
        }
    }

    /// Places the nodes in `order` (any order suits a graph without edges; a good guess
    /// saves reordering later).
    fn place(&mut self, order: &[u32]) {
        debug_assert!(self.touched.is_empty());
        for (k, &v) in order.iter().enumerate() {
            self.position[v as usize] = k as u32;
        }
    }

    /// Drops every edge (the order stays: any order suits no edges).
    fn clear(&mut self) {
        for &t in &self.touched {
            self.out[t as usize].clear();
            self.into[t as usize].clear();
            self.is_touched[t as usize] = false;
        }
        self.touched.clear();
    }

    fn touch(&mut self, v: u32) {
        if !self.is_touched[v as usize] {
            self.is_touched[v as usize] = true;
            self.touched.push(v);
        }
    }

    /// Removes edge `u → v` labelled `id` (the order stays valid).
    fn remove(&mut self, u: u32, v: u32, id: u32) {
        if let Some(k) = self.out[u as usize].iter().position(|&e| e == (v, id)) {
            self.out[u as usize].swap_remove(k);
        }
        if let Some(k) = self.into[v as usize].iter().position(|&e| e == (u, id)) {
            self.into[v as usize].swap_remove(k);
        }
    }

    /// Adds edge `u → v` labelled `id`, or returns the labels of a cycle it would close
    /// (the new edge's first).
    fn insert(&mut self, u: u32, v: u32, id: u32) -> Result<(), Vec<u32>> {
        self.touch(u);
        self.touch(v);
        let (ui, vi) = (u as usize, v as usize);
        if self.position[ui] > self.position[vi] {
            self.epoch = self.epoch.wrapping_add(1);
            if self.epoch == 0 {
                self.seen.fill(0);
                self.epoch = 1;
            }
            let epoch = self.epoch;
            let upper = self.position[ui];
            // Forward from v among nodes placed before u.
            self.forward.clear();
            self.stack.clear();
            self.stack.push(v);
            self.seen[vi] = epoch;
            while let Some(w) = self.stack.pop() {
                self.forward.push(w);
                for &(x, label) in &self.out[w as usize] {
                    if x == u {
                        let mut cycle = vec![id, label];
                        let mut y = w;
                        while y != v {
                            let (p, l) = self.parent[y as usize];
                            cycle.push(l);
                            y = p;
                        }
                        return Err(cycle);
                    }
                    let xi = x as usize;
                    if self.seen[xi] != epoch && self.position[xi] < upper {
                        self.seen[xi] = epoch;
                        self.parent[xi] = (w, label);
                        self.stack.push(x);
                    }
                }
            }
            // Backward from u among nodes placed after v.
            let lower = self.position[vi];
            self.backward.clear();
            self.stack.push(u);
            self.seen[ui] = epoch;
            while let Some(w) = self.stack.pop() {
                self.backward.push(w);
                for &(x, _) in &self.into[w as usize] {
                    let xi = x as usize;
                    if self.seen[xi] != epoch && self.position[xi] > lower {
                        self.seen[xi] = epoch;
                        self.stack.push(x);
                    }
                }
            }
            // The backward set before the forward set, in the positions they held.
            let position = &self.position;
            self.forward.sort_unstable_by_key(|&w| position[w as usize]);
            self.backward
                .sort_unstable_by_key(|&w| position[w as usize]);
            self.pool.clear();
            self.pool.extend(
                self.backward
                    .iter()
                    .chain(&self.forward)
                    .map(|&w| position[w as usize]),
            );
            self.pool.sort_unstable();
            for (k, &w) in self.backward.iter().chain(&self.forward).enumerate() {
                self.position[w as usize] = self.pool[k];
            }
        }
        self.out[ui].push((v, id));
        self.into[vi].push((u, id));
        Ok(())
    }
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
        self.targets.clear();
        self.targets.resize(total, 0);
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
fn spans_of(c: &Constraint, constraint: u32, version: u32, origin: f64, out: &mut Vec<Span>) {
    for (start, length) in c.arcs.joined() {
        let s = (start - origin).rem_euclid(TAU);
        let span = |start: f64, end: f64| Span {
            start,
            end,
            constraint,
            version,
        };
        if length >= TAU {
            out.push(span(0.0, TAU));
        } else if s + length > TAU {
            out.push(span(0.0, s + length - TAU));
            out.push(span(s, TAU));
        } else {
            out.push(span(s, s + length));
        }
    }
}

/// Refinements in one batch from which they run on all cores.
const PARALLEL_REFINES: usize = 256;

/// Spans not taken yet, by start: the initial spans sorted once, and a heap for those added
/// later (refined constraints, spans put back when a cell is redone).
#[derive(Default)]
struct Queue {
    sorted: Vec<Span>,
    next: usize,
    extra: BinaryHeap<Reverse<Span>>,
}

impl Queue {
    fn push(&mut self, s: Span) {
        self.extra.push(Reverse(s));
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
        let s = self.peek()?;
        if self.sorted.get(self.next) == Some(&s) {
            self.next += 1;
        } else {
            self.extra.pop();
        }
        Some(s)
    }
}

/// A likely order of the pieces at an absolute angle (back to front).
pub(crate) type Guess<'a> = &'a dyn Fn(f64) -> Vec<u32>;

/// A refinement function: the exact arcs of a constraint.
pub(crate) type Refine<'a> = &'a (dyn Fn(&Constraint) -> ArcSet + Sync);

/// The sweep's working state.
struct Sweep<'a> {
    constraints: &'a mut [Constraint],
    version: Vec<u32>,
    origin: f64,
    refine: Refine<'a>,
    /// Spans not taken yet.
    queue: Queue,
    /// A likely order of the pieces at an (absolute) angle: where each cell's dynamic order
    /// starts.
    guess: Guess<'a>,
    /// Spans taken in this cell (an edge's label is its index here).
    live: Vec<Span>,
    /// Labels of the live spans of each constraint (only for constraints in `listed`).
    labels: Vec<Vec<u32>>,
    listed: Vec<u32>,
    order: DynamicOrder,
}

impl Sweep<'_> {
    fn valid(&self, s: &Span) -> bool {
        self.version[s.constraint as usize] == s.version
    }

    fn take(&mut self, s: Span) -> u32 {
        let label = self.live.len() as u32;
        self.live.push(s);
        let k = s.constraint as usize;
        if self.labels[k].is_empty() {
            self.listed.push(s.constraint);
        }
        self.labels[k].push(label);
        label
    }

    fn insert(&mut self, label: u32) -> Result<(), Vec<u32>> {
        let c = &self.constraints[self.live[label as usize].constraint as usize];
        self.order.insert(c.behind, c.front, label)
    }

    /// Starts cell `lo` afresh: the live spans that reach past `lo` stay (their edges not yet
    /// in the graph), those that start after it go back to the queue.
    fn reset(&mut self, lo: f64) {
        let old = std::mem::take(&mut self.live);
        for &k in &self.listed {
            self.labels[k as usize].clear();
        }
        self.listed.clear();
        self.order.clear();
        self.order.place(&(self.guess)(self.origin + lo));
        let mut kept: Vec<Span> = Vec::new();
        for s in old {
            if !self.valid(&s) || s.end <= lo {
                continue;
            }
            if s.start > lo {
                self.queue.push(s);
            } else {
                kept.push(s);
            }
        }
        while let Some(s) = self.queue.peek() {
            if s.start > lo {
                break;
            }
            self.queue.pop();
            if self.valid(&s) && s.end > lo {
                kept.push(s);
            }
        }
        kept.sort_unstable();
        for s in kept {
            self.take(s);
        }
    }

    /// The cell `[lo, hi)` with the edges of the valid live spans that meet it.
    fn cell(&self, lo: f64, hi: f64) -> SweepCell {
        let edges = self
            .live
            .iter()
            .filter(|s| self.valid(s) && s.start < hi && s.end > lo)
            .map(|s| {
                let c = &self.constraints[s.constraint as usize];
                (c.behind, c.front)
            })
            .collect();
        SweepCell {
            lo,
            hi,
            edges,
            closing: Vec::new(),
        }
    }

    /// The `(behind, front)` edges of a cycle of live labels.
    fn cycle_edges(&self, cycle: &[u32]) -> Vec<(u32, u32)> {
        cycle
            .iter()
            .map(|&l| {
                let c = &self.constraints[self.live[l as usize].constraint as usize];
                (c.behind, c.front)
            })
            .collect()
    }

    /// The constraints of a cycle's labels that are not exact yet.
    fn loose(&self, cycle: &[u32]) -> Vec<u32> {
        let mut out: Vec<u32> = cycle
            .iter()
            .map(|&l| self.live[l as usize].constraint)
            .filter(|&k| !self.constraints[k as usize].exact)
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Replaces the arcs of constraints `ks` by their exact arcs (in parallel): their live
    /// edges leave the graph; their new spans that start at or before `now` and reach past
    /// `lo` are taken (returned, for insertion), the others queued.
    fn refine_all(&mut self, ks: &[u32], lo: f64, now: f64) -> Vec<u32> {
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
        let mut taken = Vec::new();
        for (&k, arcs) in ks.iter().zip(exact) {
            let ku = k as usize;
            let (behind, front) = (self.constraints[ku].behind, self.constraints[ku].front);
            for label in std::mem::take(&mut self.labels[ku]) {
                self.order.remove(behind, front, label);
            }
            let c = &mut self.constraints[ku];
            c.arcs = arcs;
            c.exact = true;
            self.version[ku] += 1;
            let mut spans = Vec::new();
            spans_of(c, k, self.version[ku], self.origin, &mut spans);
            for s in spans {
                if s.start <= now {
                    if s.end > lo {
                        taken.push(self.take(s));
                    }
                } else {
                    self.queue.push(s);
                }
            }
        }
        taken
    }
}

/// The greedy cells over one turn from `origin`: each cell takes the constraints active at
/// its start, then those that start later in order, and ends where one would close a cycle.
/// A cycle through constraints that are not exact refines them (`refine`, in place) first, so
/// that every cell ends at a cycle of exact constraints. The last cell ends at `2π`
/// (relative).
pub(crate) fn sweep(
    constraints: &mut [Constraint],
    origin: f64,
    n: usize,
    refine: Refine<'_>,
    guess: Guess<'_>,
) -> Result<Vec<SweepCell>, CycleAt> {
    let count = constraints.len();
    let mut state = Sweep {
        constraints,
        version: vec![0; count],
        origin,
        refine,
        guess,
        queue: Queue::default(),
        live: Vec::new(),
        labels: vec![Vec::new(); count],
        listed: Vec::new(),
        order: DynamicOrder::new(n),
    };
    for (k, c) in state.constraints.iter().enumerate() {
        spans_of(c, k as u32, 0, origin, &mut state.queue.sorted);
    }
    state.queue.sorted.par_sort_unstable();
    let mut cells = Vec::new();
    let mut lo = 0.0;
    'cells: loop {
        state.reset(lo);
        // The constraints active at `lo`: a cycle through loose ones refines every loose one
        // there at once.
        let mut k = 0;
        while k < state.live.len() {
            if let Err(cycle) = state.insert(k as u32) {
                if state.loose(&cycle).is_empty() {
                    // Constraints that end within a rounding gap of `lo` end with the event
                    // that starts the others (a fold turning edge-on ends two pairs' overlap
                    // as it starts a third's): they leave this cell.
                    let ending = |s: &Span| s.end <= lo + EVENT_GAP_RAD;
                    if !cycle.iter().any(|&l| ending(&state.live[l as usize])) {
                        let edges = state.cycle_edges(&cycle);
                        return Err(CycleAt { at: lo, edges });
                    }
                    let kept: Vec<Span> =
                        state.live.iter().copied().filter(|s| !ending(s)).collect();
                    state.live.clear();
                    state.order.clear();
                    for &k in &state.listed {
                        state.labels[k as usize].clear();
                    }
                    state.listed.clear();
                    for s in kept {
                        state.take(s);
                    }
                    k = 0;
                    continue;
                }
                let loose: Vec<u32> = state
                    .live
                    .iter()
                    .map(|s| s.constraint)
                    .filter(|&c| !state.constraints[c as usize].exact)
                    .collect::<std::collections::BTreeSet<u32>>()
                    .into_iter()
                    .collect();
                state.refine_all(&loose, lo, lo);
                state.reset(lo);
                k = 0;
                continue;
            }
            k += 1;
        }
        let mut now = lo;
        let mut pending: Vec<u32> = Vec::new();
        loop {
            let (label, from_queue) = if let Some(label) = pending.pop() {
                (label, false)
            } else {
                let Some(s) = state.queue.pop() else {
                    cells.push(state.cell(lo, TAU));
                    return Ok(cells);
                };
                if !state.valid(&s) {
                    continue;
                }
                now = s.start;
                (state.take(s), true)
            };
            if !state.valid(&state.live[label as usize]) {
                continue;
            }
            let Err(cycle) = state.insert(label) else {
                continue;
            };
            let loose = state.loose(&cycle);
            if loose.is_empty() {
                if from_queue && now > lo {
                    let mut cell = state.cell(lo, now);
                    cell.closing = state.cycle_edges(&cycle);
                    cells.push(cell);
                    lo = now;
                }
                // Otherwise a cycle closed out of order: redo the cell from its start.
                continue 'cells;
            }
            pending.extend(state.refine_all(&loose, lo, now));
            pending.push(label);
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
            within: ArcSet::empty(),
        }
    }

    #[test]
    fn a_cell_ends_where_a_cycle_would_close() {
        let exact = |c: &Constraint| c.arcs.clone();
        // 0 before 1 over [1, 2], 1 before 0 over [3, 4]: two cells.
        let mut constraints = vec![c(0, 1, 1.0, 1.0), c(1, 0, 3.0, 1.0)];
        let cells = sweep(&mut constraints, 0.0, 2, &exact, &|_| vec![0, 1]).unwrap();
        assert_eq!(cells.len(), 2);
        assert!((cells[0].hi - 3.0).abs() < 1e-12);
        // Without the conflict: one cell.
        let cells = sweep(&mut constraints[..1], 0.0, 2, &exact, &|_| vec![0, 1]).unwrap();
        assert_eq!(cells.len(), 1);
        // A cycle at one angle is reported.
        let mut both = vec![c(0, 1, 1.0, 1.0), c(1, 0, 1.5, 1.0)];
        assert!(sweep(&mut both, 1.6, 2, &exact, &|_| vec![0, 1]).is_err());
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
        let cells = sweep(&mut loose, 0.0, 2, &shrink, &|_| vec![1, 0]).unwrap();
        assert_eq!(cells.len(), 2);
        assert!(loose[1].exact);
        assert!((cells[0].hi - 3.0).abs() < 1e-12);
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
