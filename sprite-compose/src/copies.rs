//! The elements that realise a picture bake with the back faces culled by the sink: copies
//! of pieces such that every cell's drawn list is a subsequence of them. The bake player and
//! the spinning pages use the same elements.

/// The elements of a culled realisation: a sequence of copies of pieces such that every
/// cell's list of drawn pieces is a subsequence of it (one copy per piece per cell).
pub struct CulledCopies {
    /// Piece of each element, in paint order.
    pieces: Vec<u32>,
    /// Per cell, the element each drawn piece uses.
    used: Vec<Vec<usize>>,
}

impl CulledCopies {
    /// The piece of each element, in paint order.
    #[must_use]
    pub fn pieces(&self) -> &[u32] {
        &self.pieces
    }

    /// Per element, per cell: whether it is shown. An element is shown in the cells that use
    /// it and hidden in the cells where another copy of its piece is used; where its piece is
    /// never drawn (culled throughout the cell) it is shown, so that a piece with one copy
    /// never switches.
    #[must_use]
    pub fn visibility(&self, lists: &[Vec<u32>]) -> Vec<Vec<bool>> {
        let cells = self.used.len();
        let mut shown: Vec<Vec<bool>> = vec![vec![true; cells]; self.pieces.len()];
        let size = self.pieces.iter().max().map_or(0, |&m| m as usize + 1);
        let mut copies_of: Vec<Vec<usize>> = vec![Vec::new(); size];
        for (e, &p) in self.pieces.iter().enumerate() {
            copies_of[p as usize].push(e);
        }
        for (c, used) in self.used.iter().enumerate() {
            for (i, &e) in used.iter().enumerate() {
                for &other in &copies_of[lists[c][i] as usize] {
                    shown[other][c] = other == e;
                }
            }
        }
        shown
    }
}

/// Elements built cell by cell: a cell reuses the longest run of existing elements that is
/// in its order (a longest common subsequence, Hunt and Szymanski's way: patience sorting
/// over each piece's existing copies), and inserts a new copy for each other piece just
/// before the next element it reuses.
#[must_use]
pub fn culled_copies(lists: &[Vec<u32>], pieces: usize) -> CulledCopies {
    // `order` holds element ids in paint order; ids are stable as elements are inserted.
    let mut element_piece: Vec<u32> = Vec::new();
    let mut order: Vec<usize> = Vec::new();
    let mut used = Vec::with_capacity(lists.len());
    for list in lists {
        let mut position = vec![0usize; element_piece.len()];
        for (k, &e) in order.iter().enumerate() {
            position[e] = k;
        }
        let mut copies_of: Vec<Vec<usize>> = vec![Vec::new(); pieces];
        for &e in &order {
            copies_of[element_piece[e] as usize].push(e);
        }
        // Patience sorting over (position, item) entries, each item's copies from the latest
        // position down, so that no chain uses one item twice.
        let mut entries: Vec<(usize, usize, Option<usize>)> = Vec::new();
        let mut tails: Vec<usize> = Vec::new();
        for (i, &p) in list.iter().enumerate() {
            for &e in copies_of[p as usize].iter().rev() {
                let x = position[e];
                let at = tails.partition_point(|&t| entries[t].0 < x);
                let previous = at.checked_sub(1).map(|k| tails[k]);
                entries.push((x, i, previous));
                let entry = entries.len() - 1;
                if at == tails.len() {
                    tails.push(entry);
                } else {
                    tails[at] = entry;
                }
            }
        }
        // The chain's items keep their copies.
        let mut keep = vec![usize::MAX; list.len()];
        let mut cursor = tails.last().copied();
        while let Some(entry) = cursor {
            let (x, i, previous) = entries[entry];
            keep[i] = order[x];
            cursor = previous;
        }
        // Insert a copy for every other item before the next kept one.
        let mut insert_before: Vec<Vec<usize>> = vec![Vec::new(); order.len() + 1];
        let mut cell_used = vec![0usize; list.len()];
        let mut pending: Vec<usize> = Vec::new();
        for (i, &p) in list.iter().enumerate() {
            if keep[i] == usize::MAX {
                let e = element_piece.len();
                element_piece.push(p);
                cell_used[i] = e;
                pending.push(e);
            } else {
                cell_used[i] = keep[i];
                insert_before[position[keep[i]]].append(&mut pending);
            }
        }
        insert_before[order.len()].append(&mut pending);
        let mut next = Vec::with_capacity(element_piece.len());
        for (k, &e) in order.iter().enumerate() {
            next.extend_from_slice(&insert_before[k]);
            next.push(e);
        }
        next.extend_from_slice(&insert_before[order.len()]);
        order = next;
        used.push(cell_used);
    }
    // Renumber elements by paint order.
    let mut rank = vec![0usize; element_piece.len()];
    for (k, &e) in order.iter().enumerate() {
        rank[e] = k;
    }
    CulledCopies {
        pieces: order.iter().map(|&e| element_piece[e]).collect(),
        used: used
            .into_iter()
            .map(|u| u.into_iter().map(|e| rank[e]).collect())
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_list_is_a_subsequence_of_the_copies() {
        let lists = vec![
            vec![0, 1, 2, 3],
            vec![1, 0, 2, 3],
            vec![3, 2, 1],
            vec![0, 1, 2, 3],
        ];
        let c = culled_copies(&lists, 4);
        for (list, used) in lists.iter().zip(&c.used) {
            assert!(used.windows(2).all(|w| w[0] < w[1]));
            for (&p, &e) in list.iter().zip(used) {
                assert_eq!(c.pieces[e], p);
            }
        }
        assert!(c.pieces.len() <= 4 + 3);
    }
}
