//! Orders with open blocks, and graphs of pairs: what a region's certificate is built from.

/// A partial certificate: pieces in an order that every kept pair respects, except inside
/// `blocks` (ranges of `order`, ascending), sets of pieces whose order is still open.
#[derive(Clone, Debug, Default)]
pub(super) struct Partial {
    pub order: Vec<u32>,
    pub blocks: Vec<std::ops::Range<u32>>,
}

impl Partial {
    /// `order` with a block for each run of two or more pieces of one cycle (`cycle_of`
    /// numbers them, `u32::MAX` for a piece in none).
    pub fn with_runs(order: Vec<u32>, cycle_of: &[u32]) -> Partial {
        let mut blocks = Vec::new();
        let mut i = 0;
        while i < order.len() {
            let cycle = cycle_of[order[i] as usize];
            let mut end = i + 1;
            while cycle != u32::MAX && end < order.len() && cycle_of[order[end] as usize] == cycle {
                end += 1;
            }
            if end > i + 1 {
                blocks.push(i as u32..end as u32);
            }
            i = end;
        }
        Partial { order, blocks }
    }

    /// Pieces in open blocks.
    pub fn open_pieces(&self) -> usize {
        self.blocks.iter().map(|b| b.len()).sum()
    }

    /// This order for a sub-region: pieces that do not face it are dropped, and each open
    /// block is replaced by the strongly connected components of `edges` (pairs inside
    /// blocks) in topological order. Returns the refined order and the pairs inside its
    /// open blocks.
    pub fn refined(&self, facing: &[bool], edges: &[(u32, u32)]) -> (Partial, Vec<(u32, u32)>) {
        let n = facing.len();
        let mut in_block = vec![false; n];
        for block in &self.blocks {
            for &p in &self.order[block.start as usize..block.end as usize] {
                in_block[p as usize] = facing[p as usize];
            }
        }
        let graph = Graph::new(n, edges);
        let components = graph.components(&in_block);
        // Components of a block, in topological order, by the block's first... each
        // component lies in one block (pairs never cross blocks): group them by block.
        let mut block_of = vec![u32::MAX; n];
        for (k, block) in self.blocks.iter().enumerate() {
            for &p in &self.order[block.start as usize..block.end as usize] {
                block_of[p as usize] = k as u32;
            }
        }
        let mut by_block: Vec<Vec<usize>> = vec![Vec::new(); self.blocks.len()];
        for (c, component) in components.iter().enumerate() {
            by_block[block_of[component[0] as usize] as usize].push(c);
        }
        let mut out = Partial::default();
        let mut component_of = vec![u32::MAX; n];
        let mut blocks = self.blocks.iter().enumerate().peekable();
        let mut i = 0;
        while i < self.order.len() {
            if let Some((k, block)) = blocks.next_if(|(_, b)| b.start as usize == i) {
                for &c in &by_block[k] {
                    let component = &components[c];
                    let start = out.order.len() as u32;
                    out.order.extend_from_slice(component);
                    if component.len() > 1 {
                        out.blocks.push(start..out.order.len() as u32);
                        for &p in component {
                            component_of[p as usize] = c as u32;
                        }
                    }
                }
                i = block.end as usize;
                continue;
            }
            let piece = self.order[i];
            if facing[piece as usize] {
                out.order.push(piece);
            }
            i += 1;
        }
        let open = edges
            .iter()
            .copied()
            .filter(|&(a, b)| {
                let c = component_of[a as usize];
                c != u32::MAX && c == component_of[b as usize]
            })
            .collect();
        (out, open)
    }
}

/// Pairs "`a` before `b`" as adjacency lists.
pub(super) struct Graph {
    start: Vec<u32>,
    targets: Vec<u32>,
}

impl Graph {
    /// The graph of adjacency lists: where each piece's targets start (one more entry than
    /// pieces), and the targets.
    pub fn from_lists(start: Vec<u32>, targets: Vec<u32>) -> Self {
        Graph { start, targets }
    }

    pub fn new(n: usize, edges: &[(u32, u32)]) -> Self {
        let mut start = vec![0u32; n + 1];
        for &(a, _) in edges {
            start[a as usize + 1] += 1;
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut targets = vec![0u32; edges.len()];
        for &(a, b) in edges {
            targets[fill[a as usize] as usize] = b;
            fill[a as usize] += 1;
        }
        Graph { start, targets }
    }

    pub fn next(&self, v: usize) -> &[u32] {
        &self.targets[self.start[v] as usize..self.start[v + 1] as usize]
    }

    /// The strongly connected components of the `kept` pieces (Tarjan, iterative), in
    /// topological order (each component's pieces ascending).
    pub fn components(&self, kept: &[bool]) -> Vec<Vec<u32>> {
        let n = kept.len();
        let mut index = vec![u32::MAX; n];
        let mut low = vec![0u32; n];
        let mut on_stack = vec![false; n];
        let mut stack = Vec::new();
        let mut next_index = 0u32;
        // Tarjan completes a component after every component it reaches: reverse
        // topological order.
        let mut components: Vec<Vec<u32>> = Vec::new();
        for root in (0..n).filter(|&v| kept[v]) {
            if index[root] != u32::MAX {
                continue;
            }
            let mut calls: Vec<(usize, usize)> = vec![(root, 0)];
            index[root] = next_index;
            low[root] = next_index;
            next_index += 1;
            stack.push(root as u32);
            on_stack[root] = true;
            while let Some(&mut (v, ref mut i)) = calls.last_mut() {
                let next = self.next(v);
                if *i < next.len() {
                    let w = next[*i] as usize;
                    *i += 1;
                    if !kept[w] {
                        continue;
                    }
                    if index[w] == u32::MAX {
                        index[w] = next_index;
                        low[w] = next_index;
                        next_index += 1;
                        stack.push(w as u32);
                        on_stack[w] = true;
                        calls.push((w, 0));
                    } else if on_stack[w] {
                        low[v] = low[v].min(index[w]);
                    }
                } else {
                    calls.pop();
                    if let Some(&(u, _)) = calls.last() {
                        low[u] = low[u].min(low[v]);
                    }
                    if low[v] == index[v] {
                        let mut component = Vec::new();
                        loop {
                            let w = stack.pop().expect("v is on the stack");
                            on_stack[w as usize] = false;
                            component.push(w);
                            if w as usize == v {
                                break;
                            }
                        }
                        component.sort_unstable();
                        components.push(component);
                    }
                }
            }
        }
        components.reverse();
        components
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refining_orders_components_and_keeps_cycles_open() {
        // 0 → 1 → 2 → 1, 2 → 3: one block of all four.
        let edges = [(0, 1), (1, 2), (2, 1), (2, 3)];
        let (partial, open) =
            Partial::with_runs(vec![3, 2, 1, 0], &[0; 4]).refined(&[true; 4], &edges);
        assert_eq!(partial.order, [0, 1, 2, 3]);
        assert_eq!(partial.blocks, std::iter::once(1..3).collect::<Vec<_>>());
        assert_eq!(open, [(1, 2), (2, 1)]);
        // Without piece 2 (facing away) the block orders itself.
        let (partial, open) = partial.refined(&[true, true, false, true], &[]);
        assert_eq!(partial.order, [0, 1, 3]);
        assert!(partial.blocks.is_empty() && open.is_empty());
    }
}
