//! Bakes exact for the picture: cells over which one order paints the right picture when the
//! sink hides back faces itself.
//!
//! # What a cell promises
//! A cell `[lo, hi)` holds one order of *all* pieces. At every angle inside it, every pair of
//! pieces that are both front-facing and whose projections overlap with positive area is in
//! occlusion order. A sink that culls back faces (CSS `backface-visibility: hidden`, a
//! compositor's back-face visibility, a raster that culls while painting) then paints the
//! right picture; pairs that do not overlap, or of which one is culled, may come in any order.
//!
//! # Why a cell is exact at every angle inside it (not only at sampled ones)
//! 1. **Pieces.** Pieces that pass through each other are cut along one's plane, repeatedly,
//!    before baking, so no two remaining pieces cross.
//! 2. **One relation per pair.** For two pieces that do not cross, wherever both are drawn and
//!    overlap, the one in front is fixed by their planes: a piece lying on the front side of
//!    the other's plane is in front of it (the viewer is on that side when the other is
//!    drawn). If each lies in front of the other, or each behind, they never overlap while
//!    both are drawn, and need no order. Only a pair that spans each other's planes without
//!    crossing is decided by depth, once per arc of overlap (the depth difference cannot
//!    change sign inside an arc: that would need a common point).
//! 3. **Arcs in closed form.** A piece is drawn where its facing value
//!    `a·cos θ + b·sin θ + c` is positive. Two drawn convex projections overlap with positive
//!    area unless some edge line of one has every corner of the other on its outer side or
//!    on it (the separating-axis theorem for convex polygons); the side of a corner `v`
//!    relative to edge `(a, b)` is the sign of `((b − a) × (v − a))·(eye − a)` (perspective)
//!    or `·d` (orthographic), again `a·cos θ + b·sin θ + c` along the turn (a corner whose
//!    side is zero within rounding all turn, the viewer level with it and the edge, keeps
//!    that line from separating). So the arcs where
//!    a pair needs an order are unions and intersections of arcs with closed-form ends. Every
//!    arc where a condition that creates a need holds is widened, and every arc that removes
//!    one is shrunk, by the rounding bound of its root plus a margin: the computed arcs
//!    contain the true ones.
//! 4. **Every pair that can overlap is tested.** Candidates come from angular bins; in each
//!    bin a piece's screen box bounds the piece at every angle of the bin (the box of its
//!    corners, each grown by how far it can move along each view axis within the bin,
//!    rounded outward to f32), so a pair whose boxes never meet never overlaps. A pair of
//!    fixed relation overlaps only where the viewer sees the front piece in front of the
//!    other, inside the closed-form sight cone of their corner differences
//!    (`Pieces::sight`); its arcs start as that superset and are narrowed to the exact ones
//!    (point 3) wherever a cell could end on them, or at once where the superset is long.
//! 5. **Cells.** A cell takes every constraint whose arc meets it; its order is a topological
//!    order of them. It ends where one more constraint would close a cycle, at that
//!    constraint's event (its widened start plus the margin). So every pair that needs an
//!    order anywhere in the cell has it. Constraints that end with the event that opens a
//!    cell (their widened ends reach past it) are left out of that cell; they have ended
//!    where it begins.
//!
//! [`verify_picture`] checks this independently of the construction, with the order-violation
//! oracle on the drawn pieces at random angles inside every cell and within `1e-6°` of both
//! of its ends.

mod cycles;
mod pairs;
mod pieces;
mod sweep;

use std::sync::Arc;
use web_time::Instant;

use face_sort::glam::DVec3;
use face_sort::{DrawList, Geometry, PolygonSet, Projection, oracle};
use rayon::prelude::*;

use crate::BakeError;
use crate::axis::Spin;
use crate::build::refuse_cull_margin;
use crate::cells::{AngleRange, Bake, BakeCell, Breakpoint, Method, cell_bytes, cell_list_where};
use crate::event::EventFn;
use crate::tolerance::{EVENT_GAP_RAD, NEAR_EYE, PICTURE_BOUNDARY_DEG};
use crate::verify::{INTERIOR_MARGIN, VerifyError, VerifyReport, cell_state, inside};

use pairs::{Constraint, Pieces};
use sweep::{Dag, SweepCell, moved};

/// Options of [`bake_picture`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PictureOptions {
    /// Angular bins of the candidate search (more bins: tighter boxes, more passes; 1 to
    /// 16,383).
    pub bins: usize,
    /// At most this many pieces after cutting the ones that cross ([`BakeError::Pieces`];
    /// never more than 2²⁴ − 1).
    pub max_pieces: usize,
    /// At most this many candidate pairs ([`BakeError::PairBudget`]). A pair and its
    /// constraint cost about 400 bytes while the bake runs, so the pairs bound its memory:
    /// the default stops a bake near 2 GB, checked before the pairs are built.
    pub max_pairs: usize,
    /// The cells' orders stop at this many bytes ([`BakeError::SizeBudget`]).
    pub budget_bytes: usize,
    /// Pieces overlapping cyclically at some view are cut (one piece by another's plane, or
    /// the largest across its longest edge, the bake then redone) at most this many times
    /// before [`BakeError::Cycle`]. Each cut redoes the bake, so this bounds its time too.
    pub max_cycle_cuts: usize,
    /// A bake with more than eight cells tries cutting a piece of a cycle that ended a cell
    /// (by another's plane, the bake then redone) at most this many times, keeping each cut
    /// that lowers the number of cells.
    pub max_boundary_cuts: usize,
}

impl PictureOptions {
    /// 32 bins, 4 million pieces, 5 million pairs, 1 GiB, 256 cycle cuts, 32 boundary cuts.
    pub const DEFAULT: PictureOptions = PictureOptions {
        bins: 32,
        max_pieces: 4_000_000,
        max_pairs: 5_000_000,
        budget_bytes: 1 << 30,
        max_cycle_cuts: 256,
        max_boundary_cuts: 32,
    };
}

impl Default for PictureOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// What a picture bake found on the way.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PictureStats {
    /// Pieces baked (the geometry's, plus the parts of those cut).
    pub pieces: usize,
    /// Cuts of pieces that passed through each other.
    pub cuts: usize,
    /// Pairs whose screen boxes met in some bin while their planes allowed an occlusion.
    pub candidate_pairs: usize,
    /// Pairs (or arcs of a depth-decided pair) that need an order somewhere in the turn.
    pub constraints: usize,
    /// Per boundary, how many pieces drawn on both sides change place (those outside a
    /// longest common subsequence of the two orders of such pieces); over a full turn the
    /// last entry is the wrap back to the first cell.
    pub moved: Vec<usize>,
}

/// A sweep that ends with more cells than this is run again from its first forced boundary.
const SECOND_SWEEP_FROM: usize = 8;

/// Which sign of the facing value the view draws: `+1` or `−1`.
fn drawn_sign(spin: &Spin) -> Result<f64, BakeError> {
    refuse_cull_margin(spin.template())?;
    match spin.template().cull_test().facing_rule() {
        Some((true, false)) => Ok(1.0),
        Some((false, true)) => Ok(-1.0),
        _ => Err(BakeError::Unsupported {
            sorter: "picture (without culling)",
        }),
    }
}

/// In perspective, every point must stay in front of the near plane at every angle: the eye
/// (which orbits the centre) outside the sphere holding the pieces.
fn check_eye(spin: &Spin, set: &PolygonSet) -> Result<(), BakeError> {
    if let Projection::Perspective { distance } = spin.template().projection() {
        let eye = distance / spin.template().scale();
        let reach = (0..set.len())
            .flat_map(|i| set.corners(i).iter().map(|c| c.length()))
            .fold(0.0, f64::max);
        if reach >= eye * (1.0 - NEAR_EYE) {
            return Err(BakeError::EyeInside { eye, reach });
        }
    }
    Ok(())
}

/// The pieces back to front by the depth of their centroids at `theta` (radians).
fn depth_order(spin: &Spin, set: &PolygonSet, theta: f64) -> Vec<u32> {
    let toward = spin.toward_viewer();
    let axis = toward[0] + toward[1] * theta.cos() + toward[2] * theta.sin();
    let depth: Vec<f64> = (0..set.len())
        .map(|i| {
            let c = set.corners(i);
            axis.dot(c.iter().copied().sum::<DVec3>() / c.len() as f64)
        })
        .collect();
    let mut order: Vec<u32> = (0..set.len() as u32).collect();
    order.sort_by(|&a, &b| depth[a as usize].total_cmp(&depth[b as usize]));
    order
}

/// Why a sweep stopped: a budget, or pieces overlapping cyclically at an angle (radians),
/// with the cycle's edges.
enum Interrupt {
    Error(BakeError),
    Cycle(f64, Vec<(u32, u32)>),
}

impl From<BakeError> for Interrupt {
    fn from(e: BakeError) -> Self {
        Interrupt::Error(e)
    }
}

/// Cuts one piece of a cycle: by the plane of another piece of the cycle that it spans (as
/// Newell's algorithm breaks a cycle), or, when every pair is separated by a plane (pieces
/// can overlap cyclically all the same), the largest piece across the middle of its longest
/// edge, so that repeated cuts shrink the pieces until the cycle opens. `None` when the
/// piece cannot be cut.
fn cut_cycle(set: &PolygonSet, edges: &[(u32, u32)], tolerance: f64) -> Option<PolygonSet> {
    let mut members: Vec<u32> = edges.iter().flat_map(|&(a, b)| [a, b]).collect();
    members.sort_unstable();
    members.dedup();
    let spanning = members.iter().find_map(|&x| {
        members.iter().find_map(|&y| {
            let spans = x != y
                && set
                    .plane(y as usize)
                    .side_of_polygon(set.corners(x as usize), tolerance)
                    == face_sort::Side::Spanning;
            spans.then(|| (x as usize, *set.plane(y as usize)))
        })
    });
    let (x, plane) = match spanning {
        Some(cut) => cut,
        None => {
            let area = |p: u32| face_sort::newell_normal(set.corners(p as usize)).length();
            let x = *members
                .iter()
                .max_by(|&&a, &&b| area(a).total_cmp(&area(b)))? as usize;
            let c = set.corners(x);
            let (a, b) = (0..c.len())
                .map(|k| (c[k], c[(k + 1) % c.len()]))
                .max_by(|p, q| p.0.distance(p.1).total_cmp(&q.0.distance(q.1)))?;
            (
                x,
                face_sort::Plane::try_from_point_normal(0.5 * (a + b), b - a)?,
            )
        }
    };
    let (mut front, mut back) = (Vec::new(), Vec::new());
    face_sort::split_polygon(set.corners(x), &plane, tolerance, &mut front, &mut back);
    if front.len() < 3 || back.len() < 3 {
        return None;
    }
    let mut out = PolygonSet::new();
    for i in 0..set.len() {
        if i == x {
            for part in [&front, &back] {
                out.push(part, set.face(i), *set.plane(i));
            }
        } else {
            out.push(set.corners(i), set.face(i), *set.plane(i));
        }
    }
    Some(out)
}

/// The cells of one sweep from `origin`, the last merged with the first when together
/// they stay acyclic.
fn cells_from(
    pieces: &Pieces,
    constraints: &mut [Constraint],
    origin: f64,
    dag: &mut Dag,
) -> Result<Vec<SweepCell>, Interrupt> {
    let refine = |c: &Constraint| pieces.refine(c);
    let mut cells = sweep::sweep(constraints, origin, pieces.set.len(), &refine)
        .map_err(|c| Interrupt::Cycle(origin + c.at, c.edges))?;
    // A cell no longer than EVENT_GAP_RAD (two events a rounding apart) is exact nowhere for
    // sure: the next cell starts where it started instead.
    let mut k = 0;
    while k < cells.len() && cells.len() > 1 {
        if cells[k].hi - cells[k].lo > EVENT_GAP_RAD {
            k += 1;
            continue;
        }
        let short = cells.remove(k);
        match cells.get_mut(k) {
            Some(next) => next.lo = short.lo,
            None => cells[k - 1].hi = short.hi,
        }
    }
    if cells.len() > 1 {
        let (first, last) = (&cells[0], &cells[cells.len() - 1]);
        let both = first.edges.iter().chain(&last.edges).copied();
        if dag.acyclic(both.clone()) {
            let merged = SweepCell {
                lo: last.lo,
                hi: first.hi + std::f64::consts::TAU,
                edges: both.collect(),
                closing: first.closing.clone(),
            };
            cells.remove(0);
            let n = cells.len();
            cells[n - 1] = merged;
        }
    }
    Ok(cells)
}

/// One bake's sweep over a set of pieces, before its cells get orders.
struct Baked {
    set: PolygonSet,
    cells: Vec<SweepCell>,
    constraints: Vec<Constraint>,
    candidate_pairs: usize,
    origin: f64,
}

/// Cuts of pieces a bake may still make.
struct CutBudget {
    /// Of pieces that overlap cyclically at one view ([`PictureOptions::max_cycle_cuts`]).
    cycle_cuts: usize,
    /// Of pieces whose cycles end cells ([`PictureOptions::max_boundary_cuts`]).
    boundary_cuts: usize,
}

/// The cells of `set` (from the better of two sweep origins when the first gives many),
/// cutting pieces that overlap cyclically at one view while `budget` allows; `cuts` counts
/// the cuts.
fn bake_set(
    mut set: PolygonSet,
    spin: &Spin,
    (sigma, diagonal): (f64, f64),
    options: &PictureOptions,
    budget: &mut CutBudget,
    cuts: &mut usize,
) -> Result<Baked, BakeError> {
    let tolerance = crate::tolerance::PICTURE_SIDE * diagonal;
    loop {
        let pieces = Pieces::new(spin, &set, sigma, diagonal);
        let (mut constraints, candidate_pairs) = pairs::constraints(
            &pieces,
            options.bins.clamp(1, pairs::MAX_BINS),
            options.max_pairs,
        )?;
        let mut dag = Dag::new(set.len());
        let (cells, origin) = match cells_from(&pieces, &mut constraints, 0.0, &mut dag) {
            Ok(cells) if cells.len() <= SECOND_SWEEP_FROM => (cells, 0.0),
            Ok(cells) => {
                // Many cells: sweep again from the first angle where a cell had to end (the
                // first sweep's start is arbitrary), and keep the shorter.
                let origin = cells[1].lo;
                match cells_from(&pieces, &mut constraints, origin, &mut dag) {
                    Ok(second) if second.len() < cells.len() => (second, origin),
                    _ => (cells, 0.0),
                }
            }
            Err(Interrupt::Error(e)) => return Err(e),
            Err(Interrupt::Cycle(at, edges)) => {
                let cut = (budget.cycle_cuts > 0)
                    .then(|| cut_cycle(&set, &edges, tolerance))
                    .flatten();
                let Some(next) = cut else {
                    return Err(BakeError::Cycle {
                        degrees: at.to_degrees(),
                    });
                };
                if next.len() > options.max_pieces.min(pairs::MAX_PIECES) {
                    return Err(BakeError::Pieces {
                        pieces: next.len(),
                        budget: options.max_pieces,
                    });
                }
                set = next;
                *cuts += 1;
                budget.cycle_cuts -= 1;
                continue;
            }
        };
        drop(pieces);
        return Ok(Baked {
            set,
            cells,
            constraints,
            candidate_pairs,
            origin,
        });
    }
}

/// Bakes `geometry` along a full turn of `spin` into the fewest cells this greedy sweep finds
/// that are exact for the picture when the sink culls back faces (see the module docs). The
/// bake's [`Method`] is [`Method::Picture`]; its cells hold every piece.
///
/// # Errors
/// [`BakeError::CullMargin`], [`BakeError::Unsupported`] without culling,
/// [`BakeError::EyeInside`], [`BakeError::Pieces`], [`BakeError::PairBudget`],
/// [`BakeError::Cycle`] (pieces that overlap cyclically at one view) and
/// [`BakeError::SizeBudget`].
pub fn bake_picture(
    geometry: &Geometry,
    spin: &Spin,
    options: &PictureOptions,
) -> Result<(Bake, PictureStats), BakeError> {
    let started = Instant::now();
    let sigma = drawn_sign(spin)?;
    let diagonal = geometry.bounds().diagonal();
    let (set, mut cuts) = pieces::split_crossing(
        geometry.pieces(),
        diagonal,
        options.max_pieces.min(pairs::MAX_PIECES),
    )?;
    check_eye(spin, &set)?;
    let mut budget = CutBudget {
        cycle_cuts: options.max_cycle_cuts,
        boundary_cuts: options.max_boundary_cuts,
    };
    let best = bake_set(
        set,
        spin,
        (sigma, diagonal),
        options,
        &mut budget,
        &mut cuts,
    )?;
    let best = with_boundary_cuts(
        best,
        spin,
        (sigma, diagonal),
        options,
        &mut budget,
        &mut cuts,
    );
    let Baked {
        set,
        cells,
        constraints,
        candidate_pairs,
        origin,
    } = best;
    let n = set.len();
    let needed = constraints.iter().filter(|c| !c.arcs.is_empty()).count();
    let bytes = cells.len() * cell_bytes(n);
    if bytes > options.budget_bytes {
        return Err(BakeError::SizeBudget {
            bytes_so_far: bytes,
            cells_so_far: cells.len(),
            done: cells.len(),
            total: cells.len(),
            estimated_bytes: bytes,
            budget: options.budget_bytes,
        });
    }
    let mut baked = cell_orders(&cells, &set, spin, origin)?;
    let drawn = drawn_in_cells(spin, &set, sigma, baked.iter().map(|c| c.range));
    let moved_per_boundary = if baked.len() > 1 {
        (0..baked.len())
            .map(|k| {
                let next = (k + 1) % baked.len();
                let both = |p: &&u32| drawn[k][**p as usize] && drawn[next][**p as usize];
                let a: Vec<u32> = baked[k].order.iter().filter(both).copied().collect();
                let b: Vec<u32> = baked[next].order.iter().filter(both).copied().collect();
                moved(&a, &b)
            })
            .collect()
    } else {
        Vec::new()
    };
    if baked.len() == 1 {
        baked[0].range.hi = baked[0].range.lo + 360.0;
    }
    if baked[0].range.lo >= 360.0 {
        for cell in &mut baked {
            cell.range.lo -= 360.0;
            cell.range.hi -= 360.0;
        }
    }
    let lo = baked[0].range.lo;
    let breakpoints = if baked.len() > 1 {
        baked
            .iter()
            .map(|c| Breakpoint {
                degrees: c.range.lo,
                event: None,
            })
            .collect()
    } else {
        Vec::new()
    };
    let stats = PictureStats {
        pieces: n,
        cuts,
        candidate_pairs,
        constraints: needed,
        moved: moved_per_boundary,
    };
    Ok((
        Bake {
            axis: spin.axis(),
            sorter: "picture".to_owned(),
            method: Method::Picture,
            domain: AngleRange {
                lo,
                hi: lo + 360.0,
                period: Some(360.0),
            },
            polygons: Arc::new(set),
            cells: baked,
            breakpoints,
            events: needed,
            bake_ms: started.elapsed().as_secs_f64() * 1e3,
        },
        stats,
    ))
}

/// Many cells: cuts a piece of a cycle that ended a cell (by another's plane) and keeps the
/// cut when the bake then has fewer cells, while the boundary-cut budget lasts.
fn with_boundary_cuts(
    mut best: Baked,
    spin: &Spin,
    sign_and_diagonal: (f64, f64),
    options: &PictureOptions,
    budget: &mut CutBudget,
    cuts: &mut usize,
) -> Baked {
    let tolerance = crate::tolerance::PICTURE_SIDE * sign_and_diagonal.1;
    'cut: while best.cells.len() > SECOND_SWEEP_FROM && budget.boundary_cuts > 0 {
        for closing in best.cells.iter().map(|c| &c.closing) {
            if budget.boundary_cuts == 0 {
                break 'cut;
            }
            let Some(next) = cut_cycle(&best.set, closing, tolerance) else {
                continue;
            };
            budget.boundary_cuts -= 1;
            let mut tried_cuts = *cuts + 1;
            let Ok(tried) = bake_set(
                next,
                spin,
                sign_and_diagonal,
                options,
                budget,
                &mut tried_cuts,
            ) else {
                continue;
            };
            if tried.cells.len() < best.cells.len() {
                best = tried;
                *cuts = tried_cuts;
                continue 'cut;
            }
        }
        break;
    }
    best
}

/// Each cell's order: one key for the whole turn, so that neighbouring cells differ in few
/// places (an order that breaks as few of all the cells' constraints together as it can,
/// ties by depth at the first cell's middle), then per cell the topological order nearest
/// the previous cell's, forward or backward, whichever moves fewer pieces.
fn cell_orders(
    cells: &[SweepCell],
    set: &PolygonSet,
    spin: &Spin,
    origin: f64,
) -> Result<Vec<BakeCell>, BakeError> {
    let n = set.len();
    let mut dag = Dag::new(n);
    let by_depth = depth_order(spin, set, origin + 0.5 * (cells[0].lo + cells[0].hi));
    let mut key = vec![0u32; n];
    for (rank, &p) in by_depth.iter().enumerate() {
        key[p as usize] = rank as u32;
    }
    let all_edges = cells.iter().flat_map(|c| c.edges.iter().copied());
    let global = dag.order_breaking_cycles(all_edges, &key);
    for (rank, &p) in global.iter().enumerate() {
        key[p as usize] = rank as u32;
    }
    let cycle = |cell: &SweepCell| BakeError::Cycle {
        degrees: (origin + cell.lo).to_degrees(),
    };
    let mut baked = Vec::with_capacity(cells.len());
    let mut global: Vec<u32> = (0..n as u32).collect();
    global.sort_unstable_by_key(|&p| key[p as usize]);
    let mut reversed_key: Vec<u32> = key.iter().map(|&k| n as u32 - 1 - k).collect();
    let mut back_dag = Dag::new(n);
    for cell in cells {
        if let Some(previous) = baked.last().map(|c: &BakeCell| &c.order) {
            for (rank, &p) in previous.iter().enumerate() {
                key[p as usize] = rank as u32;
                reversed_key[p as usize] = n as u32 - 1 - rank as u32;
            }
            global.clone_from(previous);
        }
        // Kahn's algorithm keeps the key order except where an edge forces a piece later;
        // run backwards it forces pieces earlier instead. Keep whichever moves fewer.
        let (forward, backward) = rayon::join(
            || dag.order(cell.edges.iter().copied(), &key),
            || back_dag.order(cell.edges.iter().map(|&(a, b)| (b, a)), &reversed_key),
        );
        let forward = forward.ok_or_else(|| cycle(cell))?;
        let mut backward = backward.ok_or_else(|| cycle(cell))?;
        backward.reverse();
        let order = if moved(&global, &backward) < moved(&global, &forward) {
            backward
        } else {
            forward
        };

        baked.push(BakeCell {
            range: AngleRange {
                lo: (origin + cell.lo).to_degrees(),
                hi: (origin + cell.hi).to_degrees(),
                period: Some(360.0),
            },
            order,
        });
    }
    Ok(baked)
}

/// Per range, per piece: whether the piece is drawn (front-facing, by the view's cull mode)
/// at some angle of the range, from the closed-form facing arcs (widened by their margin).
fn drawn_in_cells(
    spin: &Spin,
    set: &PolygonSet,
    sigma: f64,
    ranges: impl Iterator<Item = AngleRange>,
) -> Vec<Vec<bool>> {
    let pieces = Pieces::new(spin, set, sigma, 1.0);
    ranges
        .map(|r| {
            let arc = crate::arcs::ArcSet::arc(r.lo.to_radians(), (r.hi - r.lo).to_radians());
            pieces
                .drawn
                .iter()
                .map(|d| !d.intersect(&arc).is_empty())
                .collect()
        })
        .collect()
}

/// Per cell of a picture bake, the pieces drawn (front-facing by the view's cull mode) at
/// some angle of the cell, in the cell's order: what a sink that culls can show there.
/// Pieces absent from a cell's list may take any place in it.
///
/// # Errors
/// As [`bake_picture`] for views it cannot bake (a cull margin, no culling).
pub fn drawn_lists(bake: &Bake, spin: &Spin) -> Result<Vec<Vec<u32>>, BakeError> {
    let sigma = drawn_sign(spin)?;
    let drawn = drawn_in_cells(
        spin,
        &bake.polygons,
        sigma,
        bake.cells.iter().map(|c| c.range),
    );
    Ok(bake
        .cells
        .iter()
        .zip(&drawn)
        .map(|(c, d)| c.order.iter().copied().filter(|&p| d[p as usize]).collect())
        .collect())
}

/// Cell `cell`'s whole order as [`cell_list`](crate::cell_list) gives it, less the pieces edge-on within
/// rounding at `theta` (their facing `facings[p]` zero there): a sink culls or draws such a
/// piece as rounding falls, and it covers no pixel either way, so no order can be judged on
/// it. The bake gives a piece edge-on all turn (facing zero at every angle) no drawn arcs.
fn judged_list(bake: &Bake, cell: usize, facings: &[EventFn], theta: f64, list: &mut DrawList) {
    cell_list_where(bake, cell, list, |p| !facings[p as usize].is_zero_at(theta));
}

/// Checks a picture bake with the order-violation oracle: at `per_cell` random angles inside
/// every cell and at `1e-6°` inside both of its ends, the cell's list ([`cell_list`](crate::cell_list), the
/// oracle skipping what the sink culls and the pieces edge-on within rounding there) has no
/// violation.
///
/// # Errors
/// [`VerifyError::Picture`] at the first angle with violations.
pub fn verify_picture(
    bake: &Bake,
    spin: &Spin,
    per_cell: usize,
    seed: u64,
) -> Result<VerifyReport, VerifyError> {
    let facings: Vec<EventFn> = (0..bake.polygons.len())
        .map(|p| spin.polygon_facing(&bake.polygons, p))
        .collect();
    let results: Vec<Result<(usize, usize), VerifyError>> = bake
        .cells
        .par_iter()
        .enumerate()
        .map_init(DrawList::new, |list, (k, cell)| {
            let mut state = cell_state(seed, k);
            let (lo, hi) = (cell.range.lo, cell.range.hi);
            let mut angles: Vec<(f64, bool)> = (0..per_cell)
                .map(|_| (cell.range.lerp(inside(&mut state, INTERIOR_MARGIN)), false))
                .collect();
            if hi - lo > 2.0 * PICTURE_BOUNDARY_DEG {
                angles.push((lo + PICTURE_BOUNDARY_DEG, true));
                angles.push((hi - PICTURE_BOUNDARY_DEG, true));
            }
            let mut counts = (0, 0);
            for (degrees, boundary) in angles {
                let view = spin.view_at(degrees);
                judged_list(bake, k, &facings, degrees.to_radians(), list);
                let violations = oracle::count_violations(&view, list);
                if violations > 0 {
                    return Err(VerifyError::Picture {
                        cell: k,
                        degrees,
                        violations,
                    });
                }
                if boundary {
                    counts.1 += 1;
                } else {
                    counts.0 += 1;
                }
            }
            Ok(counts)
        })
        .collect();
    let mut report = VerifyReport::default();
    for r in results {
        let (interior, boundary) = r?;
        report.interior_checks += interior;
        report.breakpoint_checks += boundary;
    }
    Ok(report)
}
