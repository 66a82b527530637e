//! Whether a set of order constraints can all hold at once, and where they cannot, which of
//! them lie on cycles: Kahn's algorithm peels every node no cycle holds up, and Tarjan's
//! strongly connected components of what is left are exactly the constraints on cycles.

/// A label that no edge has, and the component of a node on no cycle.
pub(crate) const UNSET: u32 = u32::MAX;

/// What [`CycleFinder::check`] found.
pub(crate) enum Acyclicity {
    /// Some order keeps every edge.
    Acyclic,
    /// Some cycle: `on_cycles` labels every edge that lies on some cycle (inside a strongly
    /// connected component); `cycle` labels the edges of one cycle, in order.
    Cyclic {
        on_cycles: Vec<u32>,
        cycle: Vec<u32>,
    },
}

/// Reusable buffers for cycle checks over `n` nodes.
pub(crate) struct CycleFinder {
    offsets: Vec<u32>,
    /// `(target, label)` per edge, grouped by source.
    targets: Vec<(u32, u32)>,
    indegree: Vec<u32>,
    ready: Vec<u32>,
    index: Vec<u32>,
    low: Vec<u32>,
    on_stack: Vec<bool>,
    component: Vec<u32>,
    stack: Vec<u32>,
    calls: Vec<(u32, u32)>,
    popped: Vec<u32>,
}

impl CycleFinder {
    pub(crate) fn new(n: usize) -> Self {
        CycleFinder {
            offsets: vec![0; n + 1],
            targets: Vec::new(),
            indegree: vec![0; n],
            ready: Vec::new(),
            index: vec![UNSET; n],
            low: vec![0; n],
            on_stack: vec![false; n],
            component: vec![UNSET; n],
            stack: Vec::new(),
            calls: Vec::new(),
            popped: Vec::new(),
        }
    }

    /// Checks the edges `(from, to, label)`.
    pub(crate) fn check(
        &mut self,
        edges: impl Iterator<Item = (u32, u32, u32)> + Clone,
    ) -> Acyclicity {
        let n = self.indegree.len();
        self.offsets.fill(0);
        self.indegree.fill(0);
        for (a, b, _) in edges.clone() {
            self.offsets[a as usize + 1] += 1;
            self.indegree[b as usize] += 1;
        }
        for k in 1..=n {
            self.offsets[k] += self.offsets[k - 1];
        }
        // Every slot below `offsets[n]` is written before it is read: only grow the buffer
        // (zeroing it wrote the whole buffer once more per check).
        let total = self.offsets[n] as usize;
        if self.targets.len() < total {
            self.targets.resize(total, (0, 0));
        }
        // Fill from the back of each group, so that `offsets` ends where it began.
        let mut end = self.offsets[1..].to_vec();
        for (a, b, label) in edges {
            let slot = &mut end[a as usize];
            *slot -= 1;
            self.targets[*slot as usize] = (b, label);
        }
        // Kahn: peel every node that no cycle holds up.
        self.ready.clear();
        self.ready
            .extend((0..n as u32).filter(|&v| self.indegree[v as usize] == 0));
        let mut peeled = 0;
        while let Some(v) = self.ready.pop() {
            peeled += 1;
            for k in self.offsets[v as usize]..self.offsets[v as usize + 1] {
                let w = self.targets[k as usize].0 as usize;
                self.indegree[w] -= 1;
                if self.indegree[w] == 0 {
                    self.ready.push(w as u32);
                }
            }
        }
        if peeled == n {
            return Acyclicity::Acyclic;
        }
        self.components();
        let mut on_cycles = Vec::new();
        let mut start = None;
        for v in 0..n {
            let c = self.component[v];
            if c == UNSET {
                continue;
            }
            for k in self.offsets[v]..self.offsets[v + 1] {
                let (w, label) = self.targets[k as usize];
                if self.component[w as usize] == c {
                    on_cycles.push(label);
                    start.get_or_insert(v as u32);
                }
            }
        }
        let start = start.expect("a node left by Kahn's algorithm lies on or after a cycle");
        Acyclicity::Cyclic {
            on_cycles,
            cycle: self.cycle_from(start),
        }
    }

    /// After a check that found cycles: per node, its strongly connected component (a label
    /// shared by its members), or [`UNSET`] for a node on no cycle.
    pub(crate) fn components_found(&self) -> &[u32] {
        &self.component
    }

    /// Tarjan's components of the nodes Kahn's algorithm left (`indegree > 0`); a node's
    /// `component` stays [`UNSET`] unless its component has more than one node. Only nodes
    /// that are left can follow a node that is left, so the search stays among them.
    fn components(&mut self) {
        let n = self.indegree.len();
        self.index.fill(UNSET);
        self.on_stack.fill(false);
        self.component.fill(UNSET);
        self.stack.clear();
        let mut counter = 0u32;
        for root in 0..n as u32 {
            if self.indegree[root as usize] == 0 || self.index[root as usize] != UNSET {
                continue;
            }
            self.open(root, &mut counter);
            while let Some(&(v, k)) = self.calls.last() {
                let vu = v as usize;
                if k < self.offsets[vu + 1] {
                    self.calls.last_mut().expect("a call").1 += 1;
                    let w = self.targets[k as usize].0;
                    if self.index[w as usize] == UNSET {
                        self.open(w, &mut counter);
                    } else if self.on_stack[w as usize] {
                        self.low[vu] = self.low[vu].min(self.index[w as usize]);
                    }
                    continue;
                }
                self.calls.pop();
                if let Some(&(parent, _)) = self.calls.last() {
                    let p = parent as usize;
                    self.low[p] = self.low[p].min(self.low[vu]);
                }
                if self.low[vu] == self.index[vu] {
                    self.popped.clear();
                    loop {
                        let w = self.stack.pop().expect("v is on the stack");
                        self.on_stack[w as usize] = false;
                        self.popped.push(w);
                        if w == v {
                            break;
                        }
                    }
                    if self.popped.len() > 1 {
                        for &w in &self.popped {
                            self.component[w as usize] = v;
                        }
                    }
                }
            }
        }
    }

    /// Tarjan's first visit of `v`.
    fn open(&mut self, v: u32, counter: &mut u32) {
        self.index[v as usize] = *counter;
        self.low[v as usize] = *counter;
        *counter += 1;
        self.stack.push(v);
        self.on_stack[v as usize] = true;
        self.calls.push((v, self.offsets[v as usize]));
    }

    /// One cycle through `start`'s component, as edge labels in order.
    fn cycle_from(&self, start: u32) -> Vec<u32> {
        let c = self.component[start as usize];
        // Where on the path each node was reached.
        let mut step = vec![UNSET; self.indegree.len()];
        let mut path: Vec<(u32, u32)> = Vec::new();
        let mut v = start;
        loop {
            let p = step[v as usize];
            if p != UNSET {
                return path[p as usize..].iter().map(|&(_, label)| label).collect();
            }
            step[v as usize] = path.len() as u32;
            let (w, label) = (self.offsets[v as usize]..self.offsets[v as usize + 1])
                .map(|k| self.targets[k as usize])
                .find(|&(w, _)| self.component[w as usize] == c)
                .expect("every node of a component has an edge inside it");
            path.push((v, label));
            v = w;
        }
    }
}
