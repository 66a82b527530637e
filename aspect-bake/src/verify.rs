//! Checking a bake against the live sorter.

use face_sort::DrawList;
use rayon::prelude::*;

use crate::axis::Spin;
use crate::cells::Bake;
use crate::event::EventFn;
use crate::rows::Row;
use crate::source::EventSource;
use crate::tolerance::VERIFY_SIDE_RAD;

/// What [`verify`] checked.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct VerifyReport {
    /// Interior angles compared with the live sorter.
    pub interior_checks: usize,
    /// Breakpoints checked (sign change of their event and the lists on both sides).
    pub breakpoint_checks: usize,
    /// A two-axis bake's cell-bounding curves checked for a real sign change with the
    /// neighbouring lists ([`verify_two_axes`](crate::verify_two_axes)).
    pub curve_checks: usize,
}

/// A place where a bake disagrees with the live sorter.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum VerifyError {
    /// The live sorter's draw list at an angle inside a cell is not the cell's.
    #[error("cell {cell} [{lo}°, {hi}°): the live sorter's list at {degrees}° differs")]
    Interior {
        /// Cell index.
        cell: usize,
        /// Cell start, degrees.
        lo: f64,
        /// Cell end, degrees.
        hi: f64,
        /// Where, degrees.
        degrees: f64,
    },
    /// A picture bake's order, culled by the view, has order violations at an angle.
    #[error("cell {cell}: {violations} order violations at {degrees}°")]
    Picture {
        /// Cell index.
        cell: usize,
        /// Where, degrees.
        degrees: f64,
        /// Violations the oracle found.
        violations: usize,
    },
    /// At a breakpoint, no recorded event function changes sign, or the lists just before
    /// and after are not those of the two cells.
    #[error("breakpoint {index} at {degrees}°: {what}")]
    Breakpoint {
        /// Breakpoint index.
        index: usize,
        /// Where, degrees.
        degrees: f64,
        /// What failed.
        what: String,
    },
    /// Inside a two-axis bake's cell the live list differs, or `cell_at` names another
    /// cell.
    #[error("cell {cell} at yaw {yaw}°, pitch {pitch}°: {what}")]
    InteriorPoint {
        /// Cell index.
        cell: usize,
        /// Where, degrees.
        yaw: f64,
        /// Where, degrees.
        pitch: f64,
        /// What failed.
        what: String,
    },
    /// A curve between two cells of a two-axis bake is not a sign change of its circle, or
    /// the lists on its two sides are not the cells'.
    #[error("curve {index} of slab {slab} at pitch {pitch}°: {what}")]
    Curve {
        /// Slab index.
        slab: usize,
        /// Curve index in the slab.
        index: usize,
        /// Where, degrees.
        pitch: f64,
        /// What failed.
        what: String,
    },
}

/// The random state for cell `k` of a check seeded with `seed`.
pub(crate) fn cell_state(seed: u64, k: usize) -> u64 {
    seed ^ (k as u64).wrapping_mul(0x2545_F491_4F6C_DD1D)
}

/// A random fraction strictly inside `(0, 1)`, away from both ends by `margin` (a fraction).
pub(crate) fn inside(state: &mut u64, margin: f64) -> f64 {
    margin + (1.0 - 2.0 * margin) * unit(state)
}

/// The margin of [`inside`] for the verifiers' interior points (0.1 %).
pub(crate) const INTERIOR_MARGIN: f64 = 0.001;

/// The margin of [`inside`] for the pitch of a two-axis verifier's probe within its slab (1 %:
/// away from the slab's boundaries, where the cells of two slabs meet).
pub(crate) const SLAB_PITCH_MARGIN: f64 = 0.01;

/// How far on each side of a boundary to evaluate: [`VERIFY_SIDE_RAD`], or a quarter of the
/// narrower of the two widths beside it (radians).
pub(crate) fn side_of(left: f64, right: f64) -> f64 {
    VERIFY_SIDE_RAD.min(0.25 * left.min(right))
}

/// Whether an event function's values just before and just after a boundary have opposite
/// strict signs (a real sign change, not a tangency).
pub(crate) fn changes_sign(before: f64, after: f64) -> bool {
    before * after < 0.0
}

/// The polygons of a draw list, in order (what a cell stores).
pub(crate) fn polygons_of(list: &DrawList) -> Vec<u32> {
    list.items().iter().map(|i| i.polygon).collect()
}

/// Whether a draw list holds exactly the polygons `order`, in order (no list built).
pub(crate) fn same_order(list: &DrawList, order: &[u32]) -> bool {
    list.items()
        .iter()
        .map(|i| i.polygon)
        .eq(order.iter().copied())
}

/// Whether the live list and a cell's order agree once the pieces `skip` names are left out
/// of both.
fn same_order_but(list: &DrawList, order: &[u32], skip: &impl Fn(u32) -> bool) -> bool {
    list.items()
        .iter()
        .map(|i| i.polygon)
        .filter(|&p| !skip(p))
        .eq(order.iter().copied().filter(|&p| !skip(p)))
}

/// Whether the two lists hold the same polygons once those `skip` names are left out, in
/// any order.
fn same_items_but(list: &DrawList, order: &[u32], skip: &impl Fn(u32) -> bool) -> bool {
    let mut a: Vec<u32> = list
        .items()
        .iter()
        .map(|i| i.polygon)
        .filter(|&p| !skip(p))
        .collect();
    let mut b: Vec<u32> = order.iter().copied().filter(|&p| !skip(p)).collect();
    a.sort_unstable();
    b.sort_unstable();
    a == b
}

/// The plane conditions of `source` along `spin` (for a BSP, its splitting planes and its
/// pieces' facings), when it lists them within a small budget; none otherwise.
fn plane_conditions(source: &dyn EventSource, spin: &Spin) -> Vec<EventFn> {
    let mut rows = Vec::new();
    let budget = 4 * source.polygons().len() + 64;
    if source.rows(budget, &mut rows).is_err() {
        return Vec::new();
    }
    rows.iter()
        .filter_map(|row| match row {
            Row::Facing(r) => Some(spin.facing_fn(r)),
            Row::Depth(_) => None,
        })
        .collect()
}

/// Whether a plane condition is zero within rounding at `theta`, or at every angle (for a
/// BSP, a splitting plane the viewer lies in). The live sorter then takes either side as
/// rounding falls: the two orders paint the same picture (the viewer in a plane sees
/// nothing on one side of it overlap anything on the other), but the lists differ.
fn rounding_decides_at(conditions: &[EventFn], theta: f64) -> bool {
    conditions.iter().any(|f| f.is_zero_at(theta))
}

/// Per polygon of `polygons`: its facing along `spin`.
fn facings(polygons: &face_sort::PolygonSet, spin: &Spin) -> Vec<EventFn> {
    (0..polygons.len())
        .map(|i| spin.polygon_facing(polygons, i))
        .collect()
}

/// Whether polygon `p` is edge-on at `theta` within rounding: its facing zero at every
/// angle (the test that gives it no facing event), or zero at this one (a tangency that
/// rounding dips below zero, or a root that the angle falls on). The live sorter draws or
/// culls such a polygon as rounding falls; it covers no pixel either way.
fn edge_on_at(facings: &[EventFn], p: u32, theta: f64) -> bool {
    facings.get(p as usize).is_some_and(|f| f.is_zero_at(theta))
}

/// SplitMix64: a few random interior angles per cell, reproducible from a seed.
pub(crate) fn unit(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
}

/// Checks `bake` against `source`'s live sorter along `spin`: at `per_cell` random angles
/// strictly inside every cell the live draw list equals the cell's; at every breakpoint of an
/// exact bake, its event function has opposite strict signs just before and just after
/// (a real sign change, not a tangency), and the live lists there are the two cells' lists.
/// "Just" is [`VERIFY_SIDE_RAD`], or a quarter of the narrower neighbouring cell.
///
/// A piece edge-on at every angle of the turn (its facing zero within rounding, e.g. a face
/// whose normal lies along the turning axis while the viewer stays in its plane) has no
/// facing event; the live sorter keeps or culls it as rounding falls, angle by angle, and it
/// covers no pixel either way. The same holds for a piece whose facing is zero within
/// rounding at the angle checked (a tangency that rounding dips below zero). Lists are
/// compared without such pieces. Likewise, where some other condition of the sorter (a
/// BSP's splitting plane) is zero within rounding at the angle checked or at every angle,
/// the live list there follows rounding between orders that paint the same picture; there
/// a list that differs from the live one still passes when it holds the same pieces and the
/// oracle finds no more order violations in it than in the live list (none, unless the live
/// sorter itself is off there).
///
/// # Errors
/// The first disagreement found.
pub fn verify(
    bake: &Bake,
    source: &dyn EventSource,
    spin: &Spin,
    per_cell: usize,
    seed: u64,
) -> Result<VerifyReport, VerifyError> {
    let n = bake.cells.len();
    let facings = facings(source.polygons(), spin);
    let conditions = plane_conditions(source, spin);
    // Whether the live list at `view` (angle `theta`, radians) agrees with cell `k`'s.
    let agrees =
        |live: &DrawList, view: &face_sort::View, theta: f64, k: usize, list: &mut DrawList| {
            let order = &bake.cells[k].order;
            let skip = |p: u32| edge_on_at(&facings, p, theta);
            if same_order_but(live, order, &skip) {
                return true;
            }
            if !(rounding_decides_at(&conditions, theta) && same_items_but(live, order, &skip)) {
                return false;
            }
            let live_violations = face_sort::oracle::count_violations(view, live);
            crate::cells::cell_list(bake, k, list);
            face_sort::oracle::count_violations(view, list) <= live_violations
        };
    let results: Vec<Result<usize, VerifyError>> = (0..n)
        .into_par_iter()
        .map_init(
            || (source.sorter(), DrawList::new(), DrawList::new()),
            |(sorter, list, scratch), k| {
                let cell = &bake.cells[k];
                let mut state = cell_state(seed, k);
                let mut live_is = |degrees: f64| {
                    let view = spin.view_at(degrees);
                    sorter.sort(&view, list);
                    agrees(list, &view, degrees.to_radians(), k, scratch)
                };
                for _ in 0..per_cell {
                    let degrees = cell.range.lerp(inside(&mut state, INTERIOR_MARGIN));
                    if !live_is(degrees) {
                        return Err(VerifyError::Interior {
                            cell: k,
                            lo: cell.range.lo,
                            hi: cell.range.hi,
                            degrees,
                        });
                    }
                }
                Ok(per_cell)
            },
        )
        .collect();
    let mut report = VerifyReport::default();
    for r in results {
        report.interior_checks += r?;
    }
    if bake.breakpoints.iter().any(|b| b.event.is_none()) {
        return Ok(report);
    }
    let checks: Vec<Result<(), VerifyError>> = bake
        .breakpoints
        .par_iter()
        .enumerate()
        .map_init(
            || (source.sorter(), DrawList::new(), DrawList::new()),
            |(sorter, list, scratch), (index, b)| {
                let fail = |what: String| VerifyError::Breakpoint {
                    index,
                    degrees: b.degrees,
                    what,
                };
                let Some(event) = b.event else {
                    return Ok(());
                };
                // Breakpoint i starts cell i over a full period, cell i + 1 on a range.
                let right = index + usize::from(bake.domain.period.is_none());
                if right >= n || bake.cells[right].range.lo != b.degrees {
                    return Err(fail("it does not start a cell".into()));
                }
                let left = if right == 0 { n - 1 } else { right - 1 };
                let width = |c: usize| {
                    let r = bake.cells[c].range;
                    (r.hi - r.lo).to_radians()
                };
                let side = side_of(width(left), width(right));
                let t = b.degrees.to_radians();
                let (before, after) = (event.value(t - side), event.value(t + side));
                if !changes_sign(before, after) {
                    return Err(fail(format!(
                        "its event does not change sign ({before:e} before, {after:e} after)"
                    )));
                }
                let mut live_is = |theta: f64, k: usize| {
                    let view = spin.view_at_rad(theta);
                    sorter.sort(&view, list);
                    agrees(list, &view, theta, k, scratch)
                };
                if !live_is(t - side, left) {
                    return Err(fail(
                        "the live list just before is not the left cell's".into(),
                    ));
                }
                if !live_is(t + side, right) {
                    return Err(fail(
                        "the live list just after is not the right cell's".into(),
                    ));
                }
                Ok(())
            },
        )
        .collect();
    for c in checks {
        c?;
        report.breakpoint_checks += 1;
    }
    Ok(report)
}
