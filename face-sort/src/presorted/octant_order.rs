//! An octant's order found testing few of its pairs.
//!
//! Testing every pair that may ever need an order costs most of a build, and most pairs need
//! no test: a pair whose edge would agree with an order of the pieces can be kept untested,
//! since an order that the kept pairs respect stays one when pairs agreeing with it are
//! added. So the pieces are ranked far to near along the region's middle direction and only
//! the pairs against that rank are tested. The pairs kept so far (few: the rank is nearly
//! right) then rank the pieces again ([`ranked`]): their cycles in an order they respect,
//! each cycle a run, ties kept in the previous rank. Untested pairs against the new rank,
//! between different cycles, are tested in turn, until none is left.
//!
//! # Why the result is the one testing every pair gives
//! Every untested pair agrees with the final rank, and the kept pairs agree with it but
//! inside their cycles, each a run of the rank. A cycle of kept and untested pairs would have
//! to step back outside a run, so the cycles of all the pairs returned are those of the
//! tested ones. Those are cycles of the true pairs, and every cycle of the true pairs (which
//! are among the pairs returned) lies in one of them: the cycles, their order and the pairs
//! inside them (untested ones among those are tested by the sub-regions) are what testing
//! every pair would give.
//!
//! # Which pairs a new rank can turn
//! Only pairs with a piece outside a longest run of the new rank that keeps the previous one
//! ([`moved`]): two pieces of the run keep their order. So each round looks only at the
//! untested pairs of the pieces that moved, through an index of the untested pairs by either
//! piece.

use glam::DVec3;

use super::PresortError;
use super::build::{Graph, Partial};
use super::occlusion::{OcclusionTest, PieceBounds};

/// The pieces' pairs that may ever need an order (adjacency lists: where each piece's
/// targets start, and the targets).
pub(super) struct EverPairs<'p> {
    pub start: &'p [u32],
    pub targets: &'p [u32],
}

/// What [`octant_order`] finds.
pub(super) struct OctantOrder {
    /// The order, its blocks the cycles.
    pub partial: Partial,
    /// The pairs inside the cycles (some untested).
    pub open_edges: Vec<(u32, u32)>,
    /// Pairs tested.
    pub tests: usize,
}

/// An octant's order and the pairs inside its cycles. `check_time` stops the work on the
/// build's budget.
pub(super) fn octant_order(
    test: &mut OcclusionTest<'_>,
    bounds: &[PieceBounds],
    facing: &[bool],
    centre: DVec3,
    ever: &EverPairs<'_>,
    check_time: &dyn Fn() -> Result<(), PresortError>,
) -> Result<OctantOrder, PresortError> {
    let n = facing.len();
    let mut by_rank: Vec<u32> = (0..n as u32).filter(|&i| facing[i as usize]).collect();
    by_rank.sort_by(|&i, &j| {
        let depth = |k: u32| centre.dot(bounds[k as usize].centre);
        depth(i).total_cmp(&depth(j)).then(i.cmp(&j))
    });
    let mut rank = vec![u32::MAX; n];
    for (k, &i) in by_rank.iter().enumerate() {
        rank[i as usize] = k as u32;
    }
    let mut cycle_of = vec![u32::MAX; n];
    let mut tests = 0;
    // The first round: pairs against the first rank are tested, the others indexed.
    let mut kept: Vec<(u32, u32)> = Vec::new();
    let mut untested: Vec<(u32, u32)> = Vec::new();
    let mut out_start = vec![0u32; n + 1];
    for a in 0..n {
        if facing[a] {
            for &b in &ever.targets[ever.start[a] as usize..ever.start[a + 1] as usize] {
                if !facing[b as usize] {
                    continue;
                }
                if rank[a] < rank[b as usize] {
                    untested.push((a as u32, b));
                } else {
                    tests += 1;
                    if test.may_hide(a, b as usize) {
                        kept.push((a as u32, b));
                    }
                }
            }
        }
        out_start[a + 1] = untested.len() as u32;
    }
    let (in_start, in_index) = index_by_target(n, &untested);
    let mut done = vec![false; untested.len()];
    let mut fresh = kept.len();
    while fresh > 0 {
        check_time()?;
        by_rank = ranked(n, &kept, &by_rank, &rank, &mut cycle_of);
        let pieces = moved(&by_rank, &rank);
        for (k, &i) in by_rank.iter().enumerate() {
            rank[i as usize] = k as u32;
        }
        fresh = 0;
        let mut check = |i: usize, kept: &mut Vec<(u32, u32)>| {
            let (a, b) = untested[i];
            let (a, b) = (a as usize, b as usize);
            if done[i]
                || rank[a] < rank[b]
                || (cycle_of[a] != u32::MAX && cycle_of[a] == cycle_of[b])
            {
                return 0;
            }
            done[i] = true;
            tests += 1;
            if test.may_hide(a, b) {
                kept.push((a as u32, b as u32));
                return 1;
            }
            0
        };
        for &v in &pieces {
            let v = v as usize;
            for i in out_start[v]..out_start[v + 1] {
                fresh += check(i as usize, &mut kept);
            }
            for &i in &in_index[in_start[v] as usize..in_start[v + 1] as usize] {
                fresh += check(i as usize, &mut kept);
            }
        }
    }
    let partial = Partial::with_runs(by_rank, &cycle_of);
    let inside = |&(a, b): &(u32, u32)| {
        let c = cycle_of[a as usize];
        c != u32::MAX && c == cycle_of[b as usize]
    };
    let open_edges = kept
        .iter()
        .copied()
        .chain(
            untested
                .iter()
                .zip(&done)
                .filter(|(_, done)| !**done)
                .map(|(pair, _)| *pair),
        )
        .filter(inside)
        .collect();
    Ok(OctantOrder {
        partial,
        open_edges,
        tests,
    })
}

/// The pairs by their second piece: where each piece's entries start, and indices into
/// `pairs`.
fn index_by_target(n: usize, pairs: &[(u32, u32)]) -> (Vec<u32>, Vec<u32>) {
    let mut start = vec![0u32; n + 1];
    for &(_, b) in pairs {
        start[b as usize + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut index = vec![0u32; pairs.len()];
    for (i, &(_, b)) in pairs.iter().enumerate() {
        index[fill[b as usize] as usize] = i as u32;
        fill[b as usize] += 1;
    }
    (start, index)
}

/// Pieces of `order` outside a longest run that keeps the order of `rank` (a longest
/// increasing subsequence, by patience sorting): every pair whose order `order` turns has
/// one of them.
fn moved(order: &[u32], rank: &[u32]) -> Vec<u32> {
    // `tails[k]`: position in `order` of the least rank ending an increasing run of k + 1.
    let mut tails: Vec<u32> = Vec::new();
    let mut before = vec![u32::MAX; order.len()];
    for (i, &p) in order.iter().enumerate() {
        let r = rank[p as usize];
        let k = tails.partition_point(|&t| rank[order[t as usize] as usize] < r);
        if k > 0 {
            before[i] = tails[k - 1];
        }
        if k == tails.len() {
            tails.push(i as u32);
        } else {
            tails[k] = i as u32;
        }
    }
    let mut in_run = vec![false; order.len()];
    let mut at = tails.last().copied().unwrap_or(u32::MAX);
    while at != u32::MAX {
        in_run[at as usize] = true;
        at = before[at as usize];
    }
    order
        .iter()
        .zip(&in_run)
        .filter(|(_, kept)| !**kept)
        .map(|(&p, _)| p)
        .collect()
}

/// The pieces of `previous` (ascending `rank`) in an order that `edges` respect but inside
/// their cycles, each cycle a run (its pieces numbered in `cycle_of`, others `u32::MAX`):
/// Kahn's order of the cycles, the one first ranked first among those ready.
fn ranked(
    n: usize,
    edges: &[(u32, u32)],
    previous: &[u32],
    rank: &[u32],
    cycle_of: &mut [u32],
) -> Vec<u32> {
    let mut member = vec![false; n];
    for &i in previous {
        member[i as usize] = true;
    }
    let components = Graph::new(n, edges).components(&member);
    let mut component_of = vec![0u32; n];
    for (c, component) in components.iter().enumerate() {
        for &p in component {
            component_of[p as usize] = c as u32;
            cycle_of[p as usize] = if component.len() > 1 {
                c as u32
            } else {
                u32::MAX
            };
        }
    }
    let m = components.len();
    let mut waiting = vec![0u32; m];
    let mut next: Vec<(u32, u32)> = Vec::with_capacity(edges.len());
    for &(a, b) in edges {
        let (ca, cb) = (component_of[a as usize], component_of[b as usize]);
        if ca != cb {
            waiting[cb as usize] += 1;
            next.push((ca, cb));
        }
    }
    let graph = Graph::new(m, &next);
    let first = |c: usize| {
        components[c]
            .iter()
            .map(|&p| rank[p as usize])
            .min()
            .unwrap_or(0)
    };
    let mut ready: std::collections::BinaryHeap<std::cmp::Reverse<(u32, u32)>> = (0..m)
        .filter(|&c| waiting[c] == 0)
        .map(|c| std::cmp::Reverse((first(c), c as u32)))
        .collect();
    let mut out = Vec::with_capacity(previous.len());
    while let Some(std::cmp::Reverse((_, c))) = ready.pop() {
        let mut pieces = components[c as usize].clone();
        pieces.sort_by_key(|&p| rank[p as usize]);
        out.extend(pieces);
        for &d in graph.next(c as usize) {
            waiting[d as usize] -= 1;
            if waiting[d as usize] == 0 {
                ready.push(std::cmp::Reverse((first(d as usize), d)));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use super::*;
    use crate::Geometry;
    use crate::presorted::build::pairs_ever;
    use crate::presorted::occlusion::may_face;
    use crate::presorted::region::Region;
    use crate::tolerance::PLANE_SIDE;

    /// The cycles of an order, each as its sorted pieces.
    fn cycles(partial: &Partial) -> BTreeSet<Vec<u32>> {
        partial
            .blocks
            .iter()
            .map(|b| {
                let mut set = partial.order[b.start as usize..b.end as usize].to_vec();
                set.sort_unstable();
                set
            })
            .collect()
    }

    /// On a bumpy torus, whose octants hold cycles, each octant's order has the cycles that
    /// testing every pair finds, respects every pair that testing keeps outside them, and
    /// passes on every pair inside them; with fewer tests.
    #[test]
    fn the_order_is_the_one_testing_every_pair_gives() {
        let geometry = Geometry::new(&crate::generate::torus(600)).unwrap();
        let pieces = geometry.pieces();
        let n = pieces.len();
        let tolerance = PLANE_SIDE * geometry.bounds().diagonal();
        let (start, targets) = pairs_ever(pieces, tolerance, usize::MAX, 1).unwrap();
        let ever = EverPairs {
            start: &start,
            targets: &targets,
        };
        let bounds = PieceBounds::of(pieces);
        let mut octants_with_cycles = 0;
        for region in Region::octants(0.75 * geometry.bounds().diagonal()) {
            let grown = region.grown();
            let mut test = OcclusionTest::new(pieces, &bounds, grown);
            let facing: Vec<bool> = (0..n)
                .map(|i| may_face(pieces, i, &grown, test.hull(), tolerance))
                .collect();
            let mut candidates = 0;
            let mut every = Vec::new();
            for a in (0..n).filter(|&a| facing[a]) {
                for &b in &targets[start[a] as usize..start[a + 1] as usize] {
                    if facing[b as usize] {
                        candidates += 1;
                        if test.may_hide(a, b as usize) {
                            every.push((a as u32, b));
                        }
                    }
                }
            }
            let all: Vec<u32> = (0..n as u32).filter(|&i| facing[i as usize]).collect();
            let (whole, whole_open) = Partial::with_runs(all, &vec![0; n]).refined(&facing, &every);
            let mut test = OcclusionTest::new(pieces, &bounds, grown);
            let OctantOrder {
                partial: lazy,
                open_edges: lazy_open,
                tests,
            } = octant_order(&mut test, &bounds, &facing, region.centre(), &ever, &|| {
                Ok(())
            })
            .unwrap();
            assert_eq!(cycles(&lazy), cycles(&whole));
            assert_eq!(lazy.order.len(), whole.order.len());
            let mut position = vec![usize::MAX; n];
            let mut block = vec![usize::MAX; n];
            for (k, &p) in lazy.order.iter().enumerate() {
                position[p as usize] = k;
            }
            for (k, b) in lazy.blocks.iter().enumerate() {
                for &p in &lazy.order[b.start as usize..b.end as usize] {
                    block[p as usize] = k;
                }
            }
            for &(a, b) in &every {
                let (a, b) = (a as usize, b as usize);
                let inside = block[a] != usize::MAX && block[a] == block[b];
                assert!(inside || position[a] < position[b], "{a} before {b}");
            }
            let lazy_open: BTreeSet<(u32, u32)> = lazy_open.into_iter().collect();
            assert!(whole_open.iter().all(|e| lazy_open.contains(e)));
            assert!(tests < candidates, "{tests} of {candidates}");
            octants_with_cycles += usize::from(!whole.blocks.is_empty());
        }
        assert!(octants_with_cycles > 0, "the torus has no cycle to check");
    }
}
