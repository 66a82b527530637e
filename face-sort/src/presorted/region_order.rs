//! A region's order found testing few of its pairs, near `n log n` in the pieces.
//!
//! # The idea
//! Testing every pair that may ever need an order is quadratic, and most pairs need no test:
//! a pair whose edge would agree with an order of the pieces can be kept untested, since an
//! order that the kept pairs respect stays one when pairs agreeing with it are added. So the
//! pieces are ranked far to near along the region's middle direction `w`, and only pairs
//! against that rank are tested, found by a grid (the bound below says which can be kept).
//! The pairs kept (few: the rank is nearly right) then rank the pieces again ([`ranked`]):
//! their cycles in an order they respect, each cycle a run, ties kept in the previous rank.
//! The pairs that new rank turns ([`inversions`]) are tested in turn, until a rank turns
//! none that can be kept.
//!
//! # Which pairs against the first rank can be kept: the bound
//! Let every direction from a point of the geometry's bounding ball (radius `R` about the
//! centre) toward an eye of the region make at most an angle of cosine `γ > 0` with `w`
//! ([`lean`]: the eyes form a convex set spanned by points and rays, the directions from a
//! ball toward a point lie within `asin(R / d)` of the direction toward its centre, and a
//! sum of vectors within an angle below 90° of `w` stays within it). When `B` hides part of
//! `A`, a point `q` of `B` lies between a point `p` of `A` and an eye: `q = p + t·u` with
//! `t > 0`, `u` a unit direction toward the eye, `u · w ≥ γ`. If `A`'s centre `c_A` is no
//! farther along `w` than `B`'s (`c_A · w ≥ c_B · w`, the pair against the rank), then with
//! the pieces' radii `r_A`, `r_B` about their centres, `p · w ≥ c_A · w − r_A` and
//! `q · w ≤ c_B · w + r_B ≤ c_A · w + r_B`, so `t γ ≤ t (u · w) = (q − p) · w ≤ r_A + r_B`
//! (so the centres are at most `r_A + r_B` apart along `w`), and `|c_A − c_B| ≤ r_A + t + r_B
//! ≤ (r_A + r_B)(1 + 1 / γ)`: neighbours in a thin slab of depth. [`near_pairs`] finds every
//! such pair (with a sharper bound across `w`) by a grid; other pairs against the rank are
//! never kept.
//!
//! # Why the result is the one testing every pair gives
//! Every pair not tested either agrees with the final rank, or is against the first rank
//! beyond the bound (never kept), or was tested and not kept. The kept pairs agree with the
//! final rank but inside their cycles, each a run of the rank. A cycle of kept and untested
//! pairs that may be kept would have to step back outside a run, so the cycles of the pairs
//! that may be kept are those of the kept ones: cycles of the true pairs, and every cycle of
//! the true pairs lies in one of them. Inside each cycle every pair is tested
//! ([`RegionOrder::open_edges`], what the sub-regions refine). So the cycles, an order
//! respecting every pair outside them, and the pairs inside them are what testing every pair
//! would give.
//!
//! A region that does not see the geometry from one side (`γ` below [`MIN_LEAN`]: an eye near
//! the geometry, or directions too far apart) is not ordered here: its sub-regions are.

use std::collections::HashSet;
use std::hash::{BuildHasherDefault, Hasher};

use glam::{DVec2, DVec3, UVec2};

use super::PresortError;
use super::occlusion::{OcclusionTest, PieceBounds, may_ever_hide};
use super::partial::{Graph, Partial};
use super::region::{EyeHull, Region};
use crate::PolygonSet;

/// Regions whose [`lean`] is below this are split before they are ordered. The bound's reach
/// `1 + 1 / γ` grows as `γ` falls: 6 at this value. With the default `min_eye_distance` of
/// 1.5 the octants' quarters pass (about 0.22 for the middle one).
pub(super) const MIN_LEAN: f64 = 0.2;

/// A hasher for pairs of piece indices packed in a `u64` (the set of pairs a region tested):
/// one multiply, far cheaper than the default's, and enough for keys that are not chosen by
/// an adversary to collide (the pieces' indices).
#[derive(Default)]
struct PairHasher(u64);

impl Hasher for PairHasher {
    fn finish(&self) -> u64 {
        // The table picks buckets by the low bits: fold the product's high bits into them.
        self.0 ^ self.0 >> 32
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0.rotate_left(8) ^ u64::from(b)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        }
    }

    fn write_u64(&mut self, key: u64) {
        self.0 = (key ^ key >> 29).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

/// What the orders of a build share: the pieces, their bounds, and limits.
pub(super) struct Setting<'a> {
    pub pieces: &'a PolygonSet,
    pub bounds: &'a [PieceBounds],
    /// Radius of the ball about the origin that holds every piece.
    pub radius: f64,
    /// Absolute tolerance of the plane-side test ([`may_ever_hide`]).
    pub tolerance: f64,
    /// Most pairs a region may look at or keep ([`PresortError::PairBudget`] beyond).
    pub max_pairs: usize,
}

/// What [`region_order`] finds.
pub(super) struct RegionOrder {
    /// The order, its blocks the cycles.
    pub partial: Partial,
    /// Every pair kept inside a cycle.
    pub open_edges: Vec<(u32, u32)>,
    /// Pairs tested.
    pub tests: usize,
    /// Pairs looked at: those the grid put forward, those new ranks turned that may need
    /// a test, and those inside cycles.
    pub candidates: usize,
}

/// The least cosine between the middle direction of `region` (grown) and a direction from a
/// point of the ball of `radius` about the origin toward a viewer of the region; −1 when the
/// angle may reach 90°.
pub(super) fn lean(region: &Region, radius: f64) -> f64 {
    let w = region.centre();
    let mut least = 1.0f64;
    if region.far.is_infinite() {
        // Orthographic viewers and the hull's rays: the corner directions.
        for c in region.corners {
            least = least.min(w.dot(c));
        }
    }
    if !region.orthographic_only() {
        let mut hull = EyeHull::default();
        region.eye_hull(&mut hull);
        for &e in &hull.points {
            let d = e.length();
            if d.is_nan() || d <= radius {
                return -1.0;
            }
            let angle = (w.dot(e) / d).clamp(-1.0, 1.0).acos() + (radius / d).asin();
            least = least.min(if angle < std::f64::consts::FRAC_PI_2 {
                angle.cos()
            } else {
                -1.0
            });
        }
    }
    least
}

/// The order of the pieces `facing` the viewers of `region` (grown, its [`lean`] at least
/// [`MIN_LEAN`]), its cycles, and the pairs inside them, tested by `test` (made for the same
/// region). `check_time` stops the work on the build's budget.
pub(super) fn region_order(
    setting: &Setting<'_>,
    test: &mut OcclusionTest<'_>,
    facing: &[bool],
    region: &Region,
    check_time: &dyn Fn() -> Result<(), PresortError>,
) -> Result<RegionOrder, PresortError> {
    let (pieces, bounds) = (setting.pieces, setting.bounds);
    let budget = PresortError::PairBudget {
        limit: setting.max_pairs,
    };
    let n = facing.len();
    let w = region.centre();
    let gamma = lean(region, setting.radius);
    debug_assert!(gamma >= MIN_LEAN);
    let mut by_rank: Vec<u32> = (0..n as u32).filter(|&i| facing[i as usize]).collect();
    by_rank.sort_by(|&i, &j| {
        let depth = |k: u32| w.dot(bounds[k as usize].centre);
        depth(i).total_cmp(&depth(j)).then(i.cmp(&j))
    });
    let mut rank = vec![u32::MAX; n];
    for (k, &i) in by_rank.iter().enumerate() {
        rank[i as usize] = k as u32;
    }
    let first_rank = rank.clone();
    let (mut tests, mut candidates) = (0usize, 0usize);
    let mut kept: Vec<(u32, u32)> = Vec::new();
    // Against the first rank (`a` ranked after `b`), within the bound.
    let mut first = |a: u32, b: u32| -> Result<(), PresortError> {
        let (ai, bi) = (a as usize, b as usize);
        candidates += 1;
        if candidates > setting.max_pairs {
            return Err(budget.clone());
        }
        if may_ever_hide(pieces, ai, bi, setting.tolerance) {
            tests += 1;
            if test.may_hide(ai, bi) {
                kept.push((a, b));
            }
        }
        Ok(())
    };
    near_pairs(bounds, &by_rank, w, gamma, &mut first)?;
    let mut tested: HashSet<u64, BuildHasherDefault<PairHasher>> = HashSet::default();
    let mut cycle_of = vec![u32::MAX; n];
    let mut fresh = kept.len();
    while fresh > 0 {
        check_time()?;
        let next = ranked(n, &kept, &by_rank, &rank, &mut cycle_of);
        fresh = 0;
        let mut turned = 0usize;
        let mut check = |x: u32, y: u32| -> Result<(), PresortError> {
            // `x` now comes before `y`: the pair "`y` before `x`" may be broken.
            turned += 1;
            if turned.is_multiple_of(1 << 22) {
                check_time()?;
            }
            let (xi, yi) = (x as usize, y as usize);
            let same_cycle = cycle_of[xi] != u32::MAX && cycle_of[xi] == cycle_of[yi];
            // A pair against the first rank was tested then, or lies beyond the bound.
            if same_cycle || first_rank[yi] > first_rank[xi] {
                return Ok(());
            }
            if may_ever_hide(pieces, yi, xi, setting.tolerance)
                && tested.insert(u64::from(y) << 32 | u64::from(x))
            {
                candidates += 1;
                if candidates > setting.max_pairs {
                    return Err(budget.clone());
                }
                tests += 1;
                if test.may_hide(yi, xi) {
                    kept.push((y, x));
                    fresh += 1;
                }
            }
            Ok(())
        };
        inversions(&next, &rank, &mut check)?;
        for (k, &i) in next.iter().enumerate() {
            rank[i as usize] = k as u32;
        }
        by_rank = next;
    }
    let partial = Partial::with_runs(by_rank, &cycle_of);
    // Inside each cycle, every pair is tested: what the sub-regions refine.
    let inside: usize = partial.blocks.iter().map(|b| b.len() * b.len()).sum();
    if candidates + inside > setting.max_pairs {
        return Err(budget);
    }
    let mut open_edges = Vec::new();
    for block in &partial.blocks {
        let set = &partial.order[block.start as usize..block.end as usize];
        for &a in set {
            for &b in set {
                let (ai, bi) = (a as usize, b as usize);
                if a != b && may_ever_hide(pieces, ai, bi, setting.tolerance) {
                    tests += 1;
                    if test.may_hide(ai, bi) {
                        open_edges.push((a, b));
                    }
                }
            }
        }
    }
    Ok(RegionOrder {
        partial,
        open_edges,
        tests,
        candidates: candidates + inside,
    })
}

/// Calls `f(a, b)` once for every pair of `by_rank` (pieces sorted far to near along `w`)
/// with `b` ranked before `a` that the bound allows: `δ = (c_a − c_b) · w ≤ r_a + r_b`, and
/// the part of `c_a − c_b` across `w` at most `r_a + r_b + (r_a + r_b − δ) · tan θ` long
/// (`cos θ = γ`, the region's [`lean`]); since `q − p = t·u` with `t (u · w) ≤ r_a + r_b − δ`
/// and `u` within `θ` of `w`, its part across `w` is at most `(r_a + r_b − δ) · tan θ`. A grid
/// across `w` holds each piece in the cells its disc of radius `r · (1 + tan θ)` meets, in
/// rank order, so each query scans a window of depths.
fn near_pairs(
    bounds: &[PieceBounds],
    by_rank: &[u32],
    w: DVec3,
    gamma: f64,
    f: &mut dyn FnMut(u32, u32) -> Result<(), PresortError>,
) -> Result<(), PresortError> {
    if by_rank.is_empty() {
        return Ok(());
    }
    // Rounding: a little more than the bound.
    let tan = (1.0 - gamma * gamma).max(0.0).sqrt() / gamma * (1.0 + 1e-9) + 1e-9;
    let grow = 1.0 + tan;
    let e1 = w.any_orthonormal_vector();
    let e2 = w.cross(e1);
    let across = |c: DVec3| DVec2::new(c.dot(e1), c.dot(e2));
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    let mut radii = Vec::with_capacity(by_rank.len());
    for &i in by_rank {
        let b = &bounds[i as usize];
        let x = across(b.centre);
        lo = lo.min(x - b.radius * grow);
        hi = hi.max(x + b.radius * grow);
        radii.push(b.radius);
    }
    let at = (radii.len() * 9 / 10).min(radii.len() - 1);
    let typical = *radii.select_nth_unstable_by(at, f64::total_cmp).1;
    let extent = (hi - lo).max(DVec2::splat(f64::MIN_POSITIVE));
    let mut cell = (2.0 * grow * typical).max(extent.max_element() / 1024.0);
    if !(cell > 0.0 && cell.is_finite()) {
        cell = extent.max_element();
    }
    let span = |i: u32, cell: f64| {
        let b = &bounds[i as usize];
        let x = across(b.centre);
        let r = b.radius * grow;
        (
            ((x - r - lo) / cell).floor().max(DVec2::ZERO).as_uvec2(),
            ((x + r - lo) / cell).floor().max(DVec2::ZERO).as_uvec2(),
        )
    };
    // Coarser cells while the entries would be many more than the pieces.
    let count = |cell: f64| -> u64 {
        by_rank
            .iter()
            .map(|&i| {
                let (a, z) = span(i, cell);
                u64::from(z.x - a.x + 1) * u64::from(z.y - a.y + 1)
            })
            .sum()
    };
    while count(cell) > 16 * by_rank.len() as u64 + 4096 {
        cell *= 2.0;
    }
    let dims = ((extent / cell).floor().as_uvec2() + UVec2::ONE).min(UVec2::splat(1 << 11));
    let total = dims.x as usize * dims.y as usize;
    let cells = |i: u32, g: &mut dyn FnMut(usize)| {
        let (a, z) = span(i, cell);
        for x in a.x..=z.x.min(dims.x - 1) {
            for y in a.y..=z.y.min(dims.y - 1) {
                g(x as usize * dims.y as usize + y as usize);
            }
        }
    };
    let mut start = vec![0u32; total + 1];
    for &i in by_rank {
        cells(i, &mut |c| start[c + 1] += 1);
    }
    for c in 0..total {
        start[c + 1] += start[c];
    }
    // Each cell's pieces in rank order (far to near), with their depths, and the largest
    // radius among them.
    let mut fill = start.clone();
    let mut entries = vec![0u32; start[total] as usize];
    let mut largest = vec![0.0f64; total];
    for &i in by_rank {
        cells(i, &mut |c| {
            entries[fill[c] as usize] = i;
            fill[c] += 1;
            largest[c] = largest[c].max(bounds[i as usize].radius);
        });
    }
    drop(fill);
    let depth = |i: u32| w.dot(bounds[i as usize].centre);
    let depths: Vec<f64> = entries.iter().map(|&i| depth(i)).collect();
    let mut seen = vec![u32::MAX; bounds.len()];
    let mut found = Vec::new();
    for &a in by_rank {
        let ba = &bounds[a as usize];
        let da = depth(a);
        let xa = across(ba.centre);
        found.clear();
        cells(a, &mut |c| {
            let (s, e) = (start[c] as usize, start[c + 1] as usize);
            let from = s + depths[s..e].partition_point(|&d| d < da - ba.radius - largest[c]);
            for &b in &entries[from..e] {
                if b == a {
                    // The pieces after `a` in the cell are ranked after it.
                    break;
                }
                if seen[b as usize] != a {
                    seen[b as usize] = a;
                    found.push(b);
                }
            }
        });
        for &b in &found {
            let bb = &bounds[b as usize];
            let sum = ba.radius + bb.radius;
            let delta = da - depth(b);
            let side = (xa - across(bb.centre)).length();
            if delta <= sum * (1.0 + 1e-9)
                && side <= sum + (sum - delta).max(0.0) * tan + 1e-9 * sum
            {
                f(a, b)?;
            }
        }
    }
    Ok(())
}

/// Calls `f(x, y)` for every pair of pieces that `next` puts in the other order than `rank`
/// does, `x` before `y` in `next` (a merge sort of the ranks, listing what each step passes),
/// stopping at its first error.
fn inversions(
    next: &[u32],
    rank: &[u32],
    f: &mut dyn FnMut(u32, u32) -> Result<(), PresortError>,
) -> Result<(), PresortError> {
    let mut run: Vec<u32> = next.to_vec();
    let mut scratch = vec![0u32; run.len()];
    let mut width = 1;
    while width < run.len() {
        for lo in (0..run.len()).step_by(2 * width) {
            let mid = (lo + width).min(run.len());
            let hi = (lo + 2 * width).min(run.len());
            let (mut i, mut j, mut k) = (lo, mid, lo);
            while i < mid || j < hi {
                if j >= hi || (i < mid && rank[run[i] as usize] < rank[run[j] as usize]) {
                    scratch[k] = run[i];
                    i += 1;
                } else {
                    // `run[j]` comes after every piece left in `run[i..mid]` in `next` and
                    // before each of them in `rank`.
                    for &x in &run[i..mid] {
                        f(x, run[j])?;
                    }
                    scratch[k] = run[j];
                    j += 1;
                }
                k += 1;
            }
        }
        std::mem::swap(&mut run, &mut scratch);
        width *= 2;
    }
    Ok(())
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

    /// Suzanne (whose regions hold cycles) read with the loader.
    fn suzanne() -> Geometry {
        let path = test_base::model_path("suzanne/suzanne.obj");
        let (mesh, _) = obj_quads::load(&path, &obj_quads::LoadOptions::default()).unwrap();
        let mesh = crate::PolygonMesh::new(mesh.positions(), mesh.faces()).unwrap();
        Geometry::with_exact_corners(&mesh).unwrap()
    }

    /// On suzanne, whose regions hold cycles, and a bumpy torus, each region's order has the
    /// cycles that testing every pair finds, respects every pair that testing keeps outside
    /// them, and passes on every pair inside them; with fewer tests.
    #[test]
    fn the_order_is_the_one_testing_every_pair_gives() {
        let mut regions_with_cycles = 0;
        for geometry in [
            suzanne(),
            Geometry::new(&crate::generate::torus(600)).unwrap(),
        ] {
            regions_with_cycles += compare_with_every_pair(&geometry);
        }
        assert!(regions_with_cycles > 0, "no cycle to check");
    }

    /// Checks each quarter of an octant of `geometry` against testing every pair; returns
    /// how many held cycles.
    fn compare_with_every_pair(geometry: &Geometry) -> usize {
        let pieces = geometry.pieces();
        let n = pieces.len();
        let tolerance = PLANE_SIDE * geometry.bounds().diagonal();
        let (start, targets) = pairs_ever(pieces, tolerance, usize::MAX, 1).unwrap();
        let bounds = PieceBounds::of(pieces);
        let radius = 0.5 * geometry.bounds().diagonal();
        let setting = Setting {
            pieces,
            bounds: &bounds,
            radius,
            tolerance,
            max_pairs: usize::MAX,
        };
        let mut regions_with_cycles = 0;
        // Quarters of octants, with eyes from 1.5 radii or from 3 (and orthographic).
        let regions = Region::octants(1.5 * radius)
            .into_iter()
            .chain(Region::octants(3.0 * radius))
            .flat_map(|octant| octant.split_directions());
        for region in regions {
            let grown = region.grown();
            assert!(lean(&grown, radius) >= MIN_LEAN);
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
            let found = region_order(&setting, &mut test, &facing, &grown, &|| Ok(())).unwrap();
            let lazy = found.partial;
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
            let open: BTreeSet<(u32, u32)> = found.open_edges.into_iter().collect();
            let whole_open: BTreeSet<(u32, u32)> = whole_open.into_iter().collect();
            assert_eq!(open, whole_open);
            assert!(found.tests < candidates, "{} of {candidates}", found.tests);
            regions_with_cycles += usize::from(!whole.blocks.is_empty());
        }
        regions_with_cycles
    }

    /// The pairs two orders put differently, listed by the merge sort, are those a scan of
    /// every pair finds.
    #[test]
    fn inversions_are_the_pairs_two_orders_turn() {
        let mut rng = crate::generate::Rng::new(5);
        for len in [0usize, 1, 2, 7, 40] {
            let previous: Vec<u32> = (0..len as u32).collect();
            let mut next = previous.clone();
            for i in (1..len).rev() {
                let j = (rng.range(0.0, (i + 1) as f64) as usize).min(i);
                next.swap(i, j);
            }
            let rank: Vec<u32> = previous.clone();
            let mut found = Vec::new();
            inversions(&next, &rank, &mut |x, y| {
                found.push((x, y));
                Ok(())
            })
            .unwrap();
            found.sort_unstable();
            let mut every = Vec::new();
            for i in 0..len {
                for j in i + 1..len {
                    if rank[next[i] as usize] > rank[next[j] as usize] {
                        every.push((next[i], next[j]));
                    }
                }
            }
            every.sort_unstable();
            assert_eq!(found, every, "{next:?}");
        }
    }
}
