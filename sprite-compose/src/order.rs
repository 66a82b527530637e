//! Few reorders: keep the longest increasing subsequence in place, move the rest.

use crate::{Compositor, SpriteId};

/// A mirror of a backend's stacking order with reusable buffers for planning moves.
#[derive(Clone, Debug, Default)]
pub(crate) struct StackMirror {
    /// Sprites bottom first (every sprite, shown or hidden).
    stack: Vec<SpriteId>,
    /// Position of each sprite in `stack` (`None`: not in the stack).
    position: Vec<Option<u32>>,
    // Reused buffers.
    ranks: Vec<u32>,
    tails: Vec<u32>,
    previous: Vec<Option<u32>>,
    keep: Vec<bool>,
    moved: Vec<bool>,
    in_sequence: Vec<Option<u32>>,
    next_stack: Vec<SpriteId>,
}

impl StackMirror {
    /// Adds a sprite on top (what `create_sprite` does).
    pub fn push(&mut self, id: SpriteId) {
        if self.position.len() <= id.index() {
            self.position.resize(id.index() + 1, None);
        }
        self.position[id.index()] = Some(self.stack.len() as u32);
        self.stack.push(id);
    }

    /// Reserves room for `n` sprites in every buffer (so that later frames do not allocate).
    pub fn reserve(&mut self, n: usize) {
        for v in [&mut self.ranks, &mut self.tails] {
            v.reserve(n.saturating_sub(v.len()));
        }
        self.previous.reserve(n.saturating_sub(self.previous.len()));
        self.keep.reserve(n.saturating_sub(self.keep.len()));
        self.moved.reserve(n.saturating_sub(self.moved.len()));
        self.in_sequence
            .reserve(n.saturating_sub(self.in_sequence.len()));
        self.next_stack
            .reserve(n.saturating_sub(self.next_stack.len()));
    }

    /// Removes a sprite (what `destroy_sprite` does).
    pub fn remove(&mut self, id: SpriteId) {
        if let Some(&Some(p)) = self.position.get(id.index()) {
            self.stack.remove(p as usize);
            self.position[id.index()] = None;
            self.reindex();
        }
    }

    fn reindex(&mut self) {
        for (i, id) in self.stack.iter().enumerate() {
            self.position[id.index()] = Some(i as u32);
        }
    }

    /// Bottom-first stack.
    #[cfg(test)]
    pub fn stack(&self) -> &[SpriteId] {
        &self.stack
    }

    /// Sends the fewest moves this planner finds so that `sequence` (every shown sprite, in
    /// paint order, each once) appears in that order in the stack; returns the number of moves.
    /// Sprites in the longest increasing subsequence of current positions stay; every other one
    /// is moved directly below its successor (or to the top), from the top down.
    pub fn reorder(&mut self, sequence: &[SpriteId], compositor: &mut dyn Compositor) -> usize {
        let n = sequence.len();
        self.ranks.clear();
        // Every shown sprite is in the stack; one that were not would rank last.
        let rank = |id: &SpriteId| self.position[id.index()].unwrap_or(u32::MAX);
        self.ranks.extend(sequence.iter().map(rank));
        longest_increasing(
            &self.ranks,
            &mut self.tails,
            &mut self.previous,
            &mut self.keep,
        );
        let moves = self.keep.iter().filter(|&&k| !k).count();
        if moves == 0 {
            return 0;
        }
        for i in (0..n).rev() {
            if !self.keep[i] {
                if i + 1 == n {
                    compositor.move_to_top(sequence[i]);
                } else {
                    compositor.move_before(sequence[i], sequence[i + 1]);
                }
            }
        }
        // Mirror the moves: a moved run ends directly below the next kept sprite (or on top).
        let len = self.position.len();
        self.moved.clear();
        self.moved.resize(len, false);
        self.in_sequence.clear();
        self.in_sequence.resize(len, None);
        for (i, id) in sequence.iter().enumerate() {
            self.in_sequence[id.index()] = Some(i as u32);
            self.moved[id.index()] = !self.keep[i];
        }
        self.next_stack.clear();
        for &id in &self.stack {
            if self.moved[id.index()] {
                continue;
            }
            if let Some(k) = self.in_sequence[id.index()] {
                let k = k as usize;
                let mut j = k;
                while j > 0 && !self.keep[j - 1] {
                    j -= 1;
                }
                self.next_stack.extend_from_slice(&sequence[j..k]);
            }
            self.next_stack.push(id);
        }
        let mut j = n;
        while j > 0 && !self.keep[j - 1] {
            j -= 1;
        }
        self.next_stack.extend_from_slice(&sequence[j..n]);
        std::mem::swap(&mut self.stack, &mut self.next_stack);
        self.reindex();
        moves
    }
}

/// Marks in `keep` one longest strictly increasing subsequence of `values` (O(n log n)).
fn longest_increasing(
    values: &[u32],
    tails: &mut Vec<u32>,
    previous: &mut Vec<Option<u32>>,
    keep: &mut Vec<bool>,
) {
    tails.clear();
    previous.clear();
    previous.resize(values.len(), None);
    keep.clear();
    keep.resize(values.len(), false);
    for (i, &v) in values.iter().enumerate() {
        // First tail whose value is ≥ v.
        let at = tails.partition_point(|&t| values[t as usize] < v);
        if at > 0 {
            previous[i] = Some(tails[at - 1]);
        }
        if at == tails.len() {
            tails.push(i as u32);
        } else {
            tails[at] = i as u32;
        }
    }
    let mut i = tails.last().copied();
    while let Some(k) = i {
        keep[k as usize] = true;
        i = previous[k as usize];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::RecordingCompositor;

    fn check(start: &[u32], target: &[u32]) -> usize {
        let mut rec = RecordingCompositor::new();
        let mut mirror = StackMirror::default();
        for &s in start {
            rec.create_sprite(SpriteId(s), s);
            mirror.push(SpriteId(s));
        }
        let seq: Vec<SpriteId> = target.iter().map(|&s| SpriteId(s)).collect();
        let moves = mirror.reorder(&seq, &mut rec);
        assert_eq!(
            mirror.stack(),
            rec.scene().stack(),
            "mirror matches backend"
        );
        let shown: Vec<SpriteId> = rec
            .scene()
            .stack()
            .iter()
            .copied()
            .filter(|s| seq.contains(s))
            .collect();
        assert_eq!(shown, seq);
        moves
    }

    #[test]
    fn keeps_the_longest_increasing_run() {
        assert_eq!(check(&[0, 1, 2, 3, 4], &[0, 1, 2, 3, 4]), 0);
        assert_eq!(check(&[0, 1, 2, 3, 4], &[4, 0, 1, 2, 3]), 1);
        assert_eq!(check(&[0, 1, 2, 3, 4], &[1, 2, 3, 4, 0]), 1);
        assert_eq!(check(&[0, 1, 2, 3, 4], &[4, 3, 2, 1, 0]), 4);
        assert_eq!(check(&[0, 1, 2, 3, 4, 5, 6], &[5, 1, 3, 0]), 2);
        assert_eq!(check(&[3, 1, 4, 0, 5, 2, 6], &[0, 1, 2, 3, 4, 5, 6]), 3);
    }

    #[test]
    fn random_permutations_match_the_backend() {
        let mut seed = 12345u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for _ in 0..200 {
            let n = (next() % 30) as u32 + 1;
            let start: Vec<u32> = (0..n).collect();
            let mut target: Vec<u32> = (0..n).filter(|_| next() % 3 != 0).collect();
            for i in (1..target.len()).rev() {
                if next() % 4 == 0 {
                    let j = (next() % (i as u64 + 1)) as usize;
                    target.swap(i, j);
                }
            }
            check(&start, &target);
        }
    }
}
