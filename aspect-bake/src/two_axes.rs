//! Two animated parameters: cells over a yaw × pitch domain (roll fixed).
//!
//! # Event curves
//! With `R = Ry(yaw)·Rx(pitch)·Rz(roll)` (CONVENTIONS.md), the unit vector toward the viewer
//! in centred model space is `d = Rᵀ·ẑ`, and every quantity whose sign decides a draw list is
//! `n·d − c` for a fixed `(n, c)` ([`EventCircle`]): a facing or a BSP node side (`c = 0`
//! orthographic; perspective, where the eye `(D/s)·d` orbits, `c = offset·s/D`) or a pair's
//! centroid depth (`c = 0`). On the sphere of directions each event set `{d : n·d = c}` is a
//! circle — a great circle when `c = 0` — and the draw list is constant on each face of
//! their arrangement.
//!
//! Writing `m = Rz(roll)ᵀ`-rotated `n` (`m.x = n.x cos r − n.y sin r`,
//! `m.y = n.x sin r + n.y cos r`): `n·d = −m.x·sin y + (m.y·sin p + n.z·cos p)·cos y`. At a
//! fixed pitch `p` that is `A(p)·cos y + B·sin y − c`, the one-axis event form, with
//! `A(p) = m.y·sin p + n.z·cos p` itself of that form in `p`. So, in closed form:
//! - the yaw roots of a circle at pitch `p` (one-axis [`EventFn::roots`]);
//! - the pitches where a circle's two yaw roots meet (`A(p) = ±sqrt(c² − B²)`);
//! - the pitches where a circle crosses a yaw boundary `y₀` (`A(p)·cos y₀ + B·sin y₀ = c`);
//! - the crossings of two circles (`d = α·n₁ + β·n₂ ± γ·n₁×n₂`), mapped back to `(y, p)`.
//!
//! # Cells
//! Those pitches cut the pitch range into slabs. Inside a slab no two curves cross and none
//! appears, vanishes or leaves through a yaw boundary, so every curve is a continuous
//! function `yaw(p)` and their order in yaw is fixed: the cells of the slab are the gaps
//! between consecutive curves, each with one draw list (the live sorter at the gap's middle at
//! the slab's middle pitch). This is the vertical (slab) decomposition of the arrangement of
//! event curves in the `(yaw, pitch)` chart: each face of the arrangement on the sphere is
//! cut into trapezoid-like pieces by the slab boundaries through the arrangement's vertices
//! and the curves' turning points; neighbouring pieces of one slab with equal lists are
//! merged. Every point of the domain lies in exactly one cell (slabs `[lo, hi)` in pitch,
//! gaps `[curve, next curve)` in yaw), found by [`TwoAxisBake::cell_at`] with two binary searches.
//!
//! Crossings are found between every pair of circles (a budget bounds them): a sweep over the
//! pitch with a kinetic list of adjacent curves would find only the crossings inside the
//! domain; not done.

use std::f64::consts::TAU;
use std::sync::Arc;
use web_time::Instant;

use face_sort::{DrawList, PolygonSet, View};
use glam::DVec3;
use rayon::prelude::*;

use crate::BakeError;
use crate::build::{BLOCK, check_range, lists_at, refuse_cull_margin};
use crate::cells::cell_bytes;
use crate::event::{EventFn, Roots, reduce};
use crate::rows::EventCircle;
use crate::source::EventSource;
use crate::tolerance::{
    CHART_POLE, CONTINUE_GAP_RAD, IDENTICALLY_ZERO, PARALLEL_SIN, ROOT_NOISE, SAME_ROOT_RAD,
    VERIFY_MIN_GAP_RAD, VERIFY_MIN_SIDE_RAD,
};
use crate::verify::{
    INTERIOR_MARGIN, SLAB_PITCH_MARGIN, VerifyError, VerifyReport, cell_state, changes_sign,
    inside, same_order, side_of, unit,
};

/// The domain of a two-axis bake: yaw and pitch in degrees, roll fixed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct YawPitch {
    /// Everything but the rotation (projection, scale, centre, culling).
    pub template: View,
    /// `[lo, hi)` of yaw, degrees; `None` is the full turn from 0.
    pub yaw: Option<(f64, f64)>,
    /// `[lo, hi)` of pitch, degrees.
    pub pitch: (f64, f64),
    /// The fixed roll, degrees.
    pub roll: f64,
}

impl YawPitch {
    /// The view at `(yaw, pitch)` in degrees.
    #[must_use]
    pub fn view_at(&self, yaw: f64, pitch: f64) -> View {
        self.template.with_yaw_pitch_roll(yaw, pitch, self.roll)
    }

    fn yaw_window(&self) -> (f64, f64, bool) {
        match self.yaw {
            None => (0.0, TAU, true),
            Some((lo, hi)) => (lo.to_radians(), hi.to_radians(), false),
        }
    }

    fn check(&self) -> Result<(), BakeError> {
        refuse_cull_margin(&self.template)?;
        check_range(self.pitch)?;
        if let Some(yaw) = self.yaw {
            check_range(yaw)?;
        }
        if !self.roll.is_finite() {
            return Err(BakeError::Range {
                lo: self.roll,
                hi: self.roll,
            });
        }
        Ok(())
    }
}

/// A circle in the chart's terms: `A(p)·cos y + B·sin y − c` with `A(p) = ay·sin p + az·cos p`.
#[derive(Clone, Copy, Debug)]
struct Chart {
    ay: f64,
    az: f64,
    b: f64,
    c: f64,
    scale: f64,
}

impl Chart {
    fn of(circle: &EventCircle, roll: f64) -> Self {
        let (sr, cr) = roll.sin_cos();
        let n = circle.normal;
        Chart {
            ay: n.x * sr + n.y * cr,
            az: n.z,
            b: -(n.x * cr - n.y * sr),
            c: circle.offset,
            scale: n.length() + circle.offset.abs(),
        }
    }

    /// The event function in yaw at pitch `p` (radians).
    fn at_pitch(&self, p: f64) -> EventFn {
        let (sp, cp) = p.sin_cos();
        EventFn {
            a: self.ay * sp + self.az * cp,
            b: self.b,
            c: -self.c,
            scale: self.scale,
        }
    }

    /// `A(p) − k` as an event function in pitch.
    fn a_minus(&self, k: f64, factor: f64) -> EventFn {
        EventFn {
            a: self.az * factor,
            b: self.ay * factor,
            c: -k,
            scale: self.scale,
        }
    }
}

/// One event curve inside a slab: the `down` (value falling with yaw) or up root of a circle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Curve {
    /// Index into [`TwoAxisBake::circles`].
    pub circle: u32,
    /// The root where the value falls (else where it rises).
    pub down: bool,
}

/// A pitch slab `[lo, hi)` (degrees) and its curves in yaw order.
#[derive(Clone, Debug, PartialEq)]
pub struct Slab {
    /// Start, degrees (inclusive).
    pub lo: f64,
    /// End, degrees (exclusive).
    pub hi: f64,
    /// The curves that bound cells, in increasing yaw from the window's start.
    pub curves: Vec<Curve>,
    /// Each curve's yaw (degrees) at the slab's middle pitch: which turn of the circle a root
    /// found at another pitch of the slab belongs to (near the window's start, rounding can
    /// put it a period away).
    pub mid_yaws: Vec<f64>,
    /// The cell of each gap: `cells[k]` lies between `curves[k − 1]` and `curves[k]` (the
    /// window's ends for the first and last). A cell spans gaps of several slabs.
    pub cells: Vec<u32>,
}

/// A two-axis bake: cells over yaw × pitch (the [`YawPitch`] domain), each with one draw
/// list that is exact over the whole cell, found in closed form ([`bake_two_axes`]).
#[derive(Clone, Debug)]
pub struct TwoAxisBake {
    /// The domain.
    pub(crate) domain: YawPitch,
    /// The sorter's name.
    pub(crate) sorter: String,
    /// The polygons the lists refer to.
    pub(crate) polygons: Arc<PolygonSet>,
    /// The event circles.
    pub(crate) circles: Vec<EventCircle>,
    /// Pitch slabs in increasing pitch.
    pub(crate) slabs: Vec<Slab>,
    /// Draw lists, back to front, per cell. A cell is a union of gaps between two curves
    /// in consecutive slabs (see [`Slab::cells`]); cells partition the domain.
    pub(crate) cells: Vec<Vec<u32>>,
    /// Pitches that bound slabs, found in closed form (before merging the close ones).
    pub(crate) critical_pitches: usize,
    /// Milliseconds the bake took.
    pub(crate) bake_ms: f64,
}

/// Options of [`bake_two_axes`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TwoAxisOptions {
    /// Stop with [`BakeError::EventBudget`] beyond this many critical pitches (curve
    /// crossings, turning points, boundary crossings) or circle pairs examined / 64.
    pub max_events: usize,
    /// Stop with [`BakeError::SizeBudget`] beyond this many bytes of per-cell lists, counted
    /// as they are sorted (before equal neighbours in a slab merge, so the finished bake's
    /// `full_bytes` is smaller).
    pub budget_bytes: usize,
}

impl Default for TwoAxisOptions {
    fn default() -> Self {
        TwoAxisOptions {
            max_events: 2_000_000,
            budget_bytes: 1 << 30,
        }
    }
}

impl TwoAxisBake {
    /// The domain.
    #[must_use]
    pub fn domain(&self) -> &YawPitch {
        &self.domain
    }
    /// The sorter's name.
    #[must_use]
    pub fn sorter(&self) -> &str {
        &self.sorter
    }
    /// The polygons the lists refer to.
    #[must_use]
    pub fn polygons(&self) -> &Arc<PolygonSet> {
        &self.polygons
    }
    /// The event circles.
    #[must_use]
    pub fn circles(&self) -> &[EventCircle] {
        &self.circles
    }
    /// Pitch slabs in increasing pitch.
    #[must_use]
    pub fn slabs(&self) -> &[Slab] {
        &self.slabs
    }
    /// Draw lists, back to front, per cell; cells partition the domain.
    #[must_use]
    pub fn cells(&self) -> &[Vec<u32>] {
        &self.cells
    }
    /// Pitches that bound slabs, found in closed form (before merging the close ones).
    #[must_use]
    pub fn critical_pitches(&self) -> usize {
        self.critical_pitches
    }
    /// Milliseconds the bake took.
    #[must_use]
    pub fn bake_ms(&self) -> f64 {
        self.bake_ms
    }
    /// The yaw (radians) of curve `k` of slab `s` at `pitch` (radians).
    fn yaw_of(&self, s: usize, k: usize, pitch: f64, window: (f64, f64, bool)) -> f64 {
        let slab = &self.slabs[s];
        let curve = slab.curves[k];
        let chart = Chart::of(
            &self.circles[curve.circle as usize],
            self.domain.roll.to_radians(),
        );
        curve_yaw_near(
            &chart,
            curve.down,
            pitch,
            window.0,
            slab.mid_yaws[k].to_radians(),
        )
    }

    /// The yaw bounds (radians) of cell `k` of slab `s` at pitch `p` (radians).
    fn gap(&self, s: usize, k: usize, p: f64) -> (f64, f64) {
        let window = self.domain.yaw_window();
        let slab = &self.slabs[s];
        let lo = if k == 0 {
            window.0
        } else {
            self.yaw_of(s, k - 1, p, window)
        };
        let hi = if k == slab.curves.len() {
            window.1
        } else {
            self.yaw_of(s, k, p, window)
        };
        (lo, hi)
    }

    /// The cell holding `(yaw, pitch)` (degrees), if it lies in the domain.
    #[must_use]
    pub fn cell_at(&self, yaw: f64, pitch: f64) -> Option<usize> {
        let (plo, phi) = self.domain.pitch;
        if !(pitch >= plo && pitch < phi) {
            return None;
        }
        let window = self.domain.yaw_window();
        let y = if window.2 {
            reduce(yaw.to_radians(), window.0)
        } else {
            let y = yaw.to_radians();
            if !(y >= window.0 && y < window.1) {
                return None;
            }
            y
        };
        let s = self.slabs.partition_point(|slab| slab.lo <= pitch) - 1;
        let slab = &self.slabs[s];
        let p = pitch.to_radians();
        // The first curve past `y` (curves are in yaw order across the slab).
        let (mut k, mut end) = (0, slab.curves.len());
        while k < end {
            let m = usize::midpoint(k, end);
            if self.yaw_of(s, m, p, window) <= y {
                k = m + 1;
            } else {
                end = m;
            }
        }
        Some(slab.cells[k] as usize)
    }

    /// Bytes of the full per-cell lists.
    #[must_use]
    pub fn full_bytes(&self) -> usize {
        self.cells.iter().map(|c| cell_bytes(c.len())).sum()
    }

    /// How many cells no sample of a `columns × rows` grid over the domain (sample centres)
    /// falls in: the draw lists that a sampled bake would never see.
    #[must_use]
    pub fn missed_by_grid(&self, columns: usize, rows: usize) -> usize {
        let (ylo, yhi) = self.domain.yaw.unwrap_or((0.0, 360.0));
        let (plo, phi) = self.domain.pitch;
        let mut seen = vec![false; self.cells.len()];
        for r in 0..rows {
            let pitch = plo + (phi - plo) * (r as f64 + 0.5) / rows as f64;
            for c in 0..columns {
                let yaw = ylo + (yhi - ylo) * (c as f64 + 0.5) / columns as f64;
                if let Some(k) = self.cell_at(yaw, pitch) {
                    seen[k] = true;
                }
            }
        }
        seen.iter().filter(|&&s| !s).count()
    }
}

/// The yaw (radians, in `[start, start + 2π)`) of a circle's down or up root at pitch `p`;
/// at a turning point, where the roots meet, their common value.
fn curve_yaw(chart: &Chart, down: bool, p: f64, start: f64) -> f64 {
    let f = chart.at_pitch(p);
    let t = match f.roots() {
        Roots::Two { down: d, up: u } => {
            if down {
                d
            } else {
                u
            }
        }
        Roots::Tangent(t) => t,
        // Past a turning point by rounding: the nearest approach.
        Roots::None | Roots::Identically => {
            let phi = f.b.atan2(f.a);
            if f.c > 0.0 { phi + TAU / 2.0 } else { phi }
        }
    };
    reduce(t, start)
}

/// [`curve_yaw`] on the turn nearest `near` (the curve's yaw at its slab's middle), kept in
/// the window `[start, start + 2π]`: inside a slab a curve never crosses the window's start,
/// but near it rounding can put a root a period away.
fn curve_yaw_near(chart: &Chart, down: bool, p: f64, start: f64, near: f64) -> f64 {
    let y = curve_yaw(chart, down, p, start);
    let y = y + TAU * ((near - y) / TAU).round();
    y.clamp(start, start + TAU)
}

/// The pitches (radians) where the structure of the yaw curves changes, in `[lo, hi)`, each
/// with whether a circle is zero along the whole pitch line there (then no cell continues
/// across it: a horizontal line of the chart is part of that circle's event set).
fn critical_pitches(
    charts: &[Chart],
    circles: &[EventCircle],
    domain: &YawPitch,
    max_events: usize,
) -> Result<Vec<(f64, bool)>, BakeError> {
    let (plo, phi) = (domain.pitch.0.to_radians(), domain.pitch.1.to_radians());
    let (ylo, yhi, periodic) = domain.yaw_window();
    let mut out = Vec::new();
    let push = |p: f64, whole: bool, out: &mut Vec<(f64, bool)>| {
        let p = reduce(p, plo);
        if p > plo && p < phi {
            out.push((p, whole));
        }
    };
    let pitch_roots = |f: EventFn, whole: bool, out: &mut Vec<(f64, bool)>| match f.roots() {
        Roots::Two { down, up } => {
            push(down, whole, out);
            push(up, whole, out);
        }
        Roots::Tangent(t) => push(t, whole, out),
        Roots::None | Roots::Identically => {}
    };
    let boundaries: &[f64] = if periodic { &[ylo] } else { &[ylo, yhi] };
    for ch in charts {
        // Turning points: A(p)² + B² = c².
        // With B = c = 0 the value is A(p)·cos y: zero along the whole line where A(p) = 0.
        let zero = IDENTICALLY_ZERO * ch.scale;
        let whole = ch.b.abs() <= zero && ch.c.abs() <= zero;
        let gap = ch.c * ch.c - ch.b * ch.b;
        if whole {
            pitch_roots(ch.a_minus(0.0, 1.0), true, &mut out);
        } else if gap >= 0.0 {
            let s = gap.sqrt();
            pitch_roots(ch.a_minus(s, 1.0), false, &mut out);
            pitch_roots(ch.a_minus(-s, 1.0), false, &mut out);
        }
        // Crossing a yaw boundary: A(p)·cos y₀ + B·sin y₀ − c = 0.
        for &y0 in boundaries {
            let (sy, cy) = y0.sin_cos();
            pitch_roots(ch.a_minus(ch.c - ch.b * sy, cy), false, &mut out);
        }
    }
    let roll = domain.roll.to_radians();
    let (sr, cr) = roll.sin_cos();
    let pairs = circles.len() * circles.len().saturating_sub(1) / 2;
    if pairs / 64 > max_events {
        return Err(BakeError::EventBudget {
            events: pairs / 64,
            budget: max_events,
        });
    }
    for (i, ci) in circles.iter().enumerate() {
        for cj in &circles[i + 1..] {
            for d in circle_crossings(ci, cj).into_iter().flatten() {
                // sin y = d.y sin r − d.x cos r; cos y·sin p = d.x sin r + d.y cos r;
                // cos y·cos p = d.z. Two charts of each direction: y and π − y.
                let sy = (d.y * sr - d.x * cr).clamp(-1.0, 1.0);
                let (u, v) = (d.x * sr + d.y * cr, d.z);
                let y = sy.asin();
                let cy = y.cos();
                if cy <= CHART_POLE {
                    // Looking along the yaw axis: every pitch is the same view.
                    continue;
                }
                for (yaw, sign) in [(y, 1.0), (TAU / 2.0 - y, -1.0)] {
                    let in_yaw = periodic || {
                        let t = reduce(yaw, ylo);
                        t >= ylo && t < yhi
                    };
                    if in_yaw {
                        push((sign * u).atan2(sign * v), false, &mut out);
                    }
                }
            }
            if out.len() > max_events {
                return Err(BakeError::EventBudget {
                    events: out.len(),
                    budget: max_events,
                });
            }
        }
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(out)
}

/// The directions `d` (unit) with `n₁·d = c₁` and `n₂·d = c₂`: none, or two (equal at a
/// tangency). Parallel normals give none (equal circles have no isolated crossing). No
/// allocation: it runs for every pair of circles.
fn circle_crossings(a: &EventCircle, b: &EventCircle) -> Option<[DVec3; 2]> {
    let (n1, n2) = (a.normal, b.normal);
    let cross = n1.cross(n2);
    let cc = cross.length_squared();
    let scale = n1.length_squared() * n2.length_squared();
    if cc <= PARALLEL_SIN * PARALLEL_SIN * scale {
        return None;
    }
    // d = α n₁ + β n₂ + γ n₁×n₂ with the Gram system for α, β.
    let (g11, g12, g22) = (n1.length_squared(), n1.dot(n2), n2.length_squared());
    let det = g11 * g22 - g12 * g12;
    let alpha = (a.offset * g22 - b.offset * g12) / det;
    let beta = (b.offset * g11 - a.offset * g12) / det;
    let base = n1 * alpha + n2 * beta;
    let rest = 1.0 - base.length_squared();
    if rest < 0.0 {
        return None;
    }
    let gamma = (rest / cc).sqrt();
    Some([base + cross * gamma, base - cross * gamma])
}

/// The exact two-axis bake of `source` over `domain`: slabs between consecutive critical
/// pitches (closed form, see the module docs), cells between consecutive curves inside each,
/// one live sort per cell (on all cores), equal neighbours in a slab merged.
///
/// # Errors
/// [`BakeError::CullMargin`], [`BakeError::Range`], [`BakeError::EventBudget`],
/// [`BakeError::SizeBudget`], and [`BakeError::Unsupported`] for a source without
/// [`EventSource::rows`].
pub fn bake_two_axes(
    source: &dyn EventSource,
    domain: &YawPitch,
    options: &TwoAxisOptions,
) -> Result<TwoAxisBake, BakeError> {
    let started = Instant::now();
    domain.check()?;
    let mut rows = Vec::new();
    source.rows(options.max_events, &mut rows)?;
    let circles: Vec<EventCircle> = rows.iter().map(|r| r.circle(&domain.template)).collect();
    let roll = domain.roll.to_radians();
    let charts: Vec<Chart> = circles.iter().map(|c| Chart::of(c, roll)).collect();
    let critical = critical_pitches(&charts, &circles, domain, options.max_events)?;
    let (plo, phi) = (domain.pitch.0.to_radians(), domain.pitch.1.to_radians());
    let (ylo, yhi, _) = domain.yaw_window();
    let bounds = slab_bounds(&critical, plo, phi);
    // Curves of each slab at its middle pitch, and the cells' middle points.
    // (low pitch, high pitch, curves with their yaw at the middle, continues from below)
    type SlabCurves = (f64, f64, Vec<(f64, Curve)>, bool);
    let mut slabs: Vec<SlabCurves> = Vec::new();
    for w in bounds.windows(2) {
        let mid = 0.5 * (w[0].0 + w[1].0);
        let mut curves: Vec<(f64, Curve)> = Vec::new();
        for (i, ch) in charts.iter().enumerate() {
            if let Roots::Two { .. } = ch.at_pitch(mid).roots() {
                for down in [true, false] {
                    let y = curve_yaw(ch, down, mid, ylo);
                    if y < yhi {
                        let curve = Curve {
                            circle: i as u32,
                            down,
                        };
                        curves.push((y, curve));
                    }
                }
            }
        }
        curves.sort_by(|a, b| a.0.total_cmp(&b.0));
        // Equal circles (a coplanar piece and its node) give one curve.
        curves.dedup_by(|b, a| b.0 - a.0 <= SAME_ROOT_RAD);
        slabs.push((w[0].0, w[1].0, curves, w[0].1));
    }
    // Cells: the region between two curves that stay neighbours across a slab boundary
    // continues into the next slab (nothing crosses its inside there), so it keeps its cell;
    // every other gap opens a cell, whose list is the live sorter's at the gap's middle.
    type Key = (Option<Curve>, Option<Curve>);
    let mut previous: std::collections::HashMap<Key, u32> = std::collections::HashMap::new();
    let mut current: std::collections::HashMap<Key, u32> = std::collections::HashMap::new();
    let mut gap_cells: Vec<Vec<u32>> = Vec::with_capacity(slabs.len());
    let mut points: Vec<(f64, f64)> = Vec::new();
    for (lo, hi, curves, continues) in &slabs {
        let mid = 0.5 * (lo + hi);
        current.clear();
        if !continues {
            previous.clear();
        }
        let mut ids = Vec::with_capacity(curves.len() + 1);
        for k in 0..=curves.len() {
            let left = k.checked_sub(1).map(|j| curves[j]);
            let right = curves.get(k).copied();
            let key = (left.map(|c| c.1), right.map(|c| c.1));
            // Continued only where the gap is open at the boundary: a gap that pinches to a
            // point there may have a third curve pass through the point (a crossing of three).
            let open = || {
                let at = |c: Option<(f64, Curve)>, end: f64| {
                    c.map_or(end, |(mid, c)| {
                        curve_yaw_near(&charts[c.circle as usize], c.down, *lo, ylo, mid)
                    })
                };
                at(right, yhi) - at(left, ylo) > CONTINUE_GAP_RAD
            };
            let id = if let Some(&id) = previous.get(&key)
                && open()
            {
                id
            } else {
                let (y0, y1) = (left.map_or(ylo, |c| c.0), right.map_or(yhi, |c| c.0));
                points.push((0.5 * (y0 + y1), mid));
                (points.len() - 1) as u32
            };
            current.insert(key, id);
            ids.push(id);
        }
        std::mem::swap(&mut previous, &mut current);
        gap_cells.push(ids);
    }
    let total_cells = points.len();
    let mut lists: Vec<Vec<u32>> = Vec::with_capacity(total_cells);
    let mut bytes = 0;
    for block in points.chunks(BLOCK) {
        let view = |&(y, p): &(f64, f64)| domain.view_at(y.to_degrees(), p.to_degrees());
        for list in lists_at(source, block, view) {
            bytes += cell_bytes(list.len());
            lists.push(list);
        }
        if bytes > options.budget_bytes {
            return Err(BakeError::SizeBudget {
                bytes_so_far: bytes,
                cells_so_far: lists.len(),
                done: lists.len(),
                total: total_cells,
                estimated_bytes: bytes / lists.len() * total_cells,
                budget: options.budget_bytes,
            });
        }
    }
    let (dense, cells) = merge_equal_neighbours(&gap_cells, lists);
    let mut out_slabs = Vec::with_capacity(slabs.len());
    for ((lo, hi, curves, _), ids) in slabs.into_iter().zip(gap_cells) {
        // Curves between two gaps of one cell bound nothing: dropped.
        let mut kept = Vec::new();
        let mut mid_yaws = Vec::new();
        let mut cell_of_gap = vec![dense[ids[0] as usize]];
        for (k, &(yaw, curve)) in curves.iter().enumerate() {
            let next = dense[ids[k + 1] as usize];
            if next != cell_of_gap[cell_of_gap.len() - 1] {
                kept.push(curve);
                mid_yaws.push(yaw.to_degrees());
                cell_of_gap.push(next);
            }
        }
        out_slabs.push(Slab {
            lo: lo.to_degrees(),
            hi: hi.to_degrees(),
            curves: kept,
            mid_yaws,
            cells: cell_of_gap,
        });
    }
    Ok(TwoAxisBake {
        domain: *domain,
        sorter: source.name().to_owned(),
        polygons: Arc::clone(source.polygons()),
        circles,
        slabs: out_slabs,
        cells,
        critical_pitches: critical.len(),
        bake_ms: started.elapsed().as_secs_f64() * 1e3,
    })
}

/// Slab bounds from `plo` to `phi`: critical pitches apart by more than their rounding, each
/// with whether cells may continue across it.
fn slab_bounds(critical: &[(f64, bool)], plo: f64, phi: f64) -> Vec<(f64, bool)> {
    let mut bounds = vec![(plo, false)];
    for &(p, whole) in critical {
        let last = bounds.len() - 1;
        if p - bounds[last].0 > SAME_ROOT_RAD.max(ROOT_NOISE * p.abs().max(1.0)) {
            bounds.push((p, !whole));
        } else if whole {
            bounds[last].1 = false;
        }
    }
    if bounds.len() > 1 && phi - bounds[bounds.len() - 1].0 <= SAME_ROOT_RAD {
        bounds.pop();
    }
    bounds.push((phi, false));
    bounds
}

/// Equal neighbours in a slab (gaps `gap_cells`, lists `lists` by gap cell) become one cell:
/// per gap cell its dense cell id, and each dense cell's list.
fn merge_equal_neighbours(
    gap_cells: &[Vec<u32>],
    mut lists: Vec<Vec<u32>>,
) -> (Vec<u32>, Vec<Vec<u32>>) {
    let total_cells = lists.len();
    let mut parent: Vec<u32> = (0..total_cells as u32).collect();
    fn root(parent: &mut [u32], mut i: u32) -> u32 {
        while parent[i as usize] != i {
            parent[i as usize] = parent[parent[i as usize] as usize];
            i = parent[i as usize];
        }
        i
    }
    for ids in gap_cells {
        for w in ids.windows(2) {
            let (a, b) = (root(&mut parent, w[0]), root(&mut parent, w[1]));
            if a != b && lists[a as usize] == lists[b as usize] {
                parent[b.max(a) as usize] = a.min(b);
            }
        }
    }
    let mut dense = vec![u32::MAX; total_cells];
    let mut cells: Vec<Vec<u32>> = Vec::new();
    for i in 0..total_cells as u32 {
        let r = root(&mut parent, i);
        if dense[r as usize] == u32::MAX {
            dense[r as usize] = cells.len() as u32;
            cells.push(std::mem::take(&mut lists[r as usize]));
        }
        dense[i as usize] = dense[r as usize];
    }
    (dense, cells)
}

/// Checks a two-axis bake against the live sorter, cell by cell: at `per_cell` random points
/// strictly inside each cell (a random gap of the cell, a random pitch of its slab, then a
/// random yaw between the gap's curves at that pitch) the live list is the cell's and
/// [`TwoAxisBake::cell_at`] finds the cell; and across one bounding curve of each cell (a random
/// one), at a random pitch of its slab, the circle's value has opposite strict signs just
/// before and after in yaw, and the live lists there are the two cells'.
///
/// # Errors
/// The first disagreement found.
pub fn verify_two_axes(
    bake: &TwoAxisBake,
    source: &dyn EventSource,
    per_cell: usize,
    seed: u64,
) -> Result<VerifyReport, VerifyError> {
    let domain = bake.domain;
    let roll = domain.roll.to_radians();
    let mut gaps: Vec<Vec<(u32, u32)>> = vec![Vec::new(); bake.cells.len()];
    for (s, slab) in bake.slabs.iter().enumerate() {
        for (k, &cell) in slab.cells.iter().enumerate() {
            gaps[cell as usize].push((s as u32, k as u32));
        }
    }
    let results: Vec<Result<VerifyReport, VerifyError>> = (0..bake.cells.len())
        .into_par_iter()
        .map_init(
            || (source.sorter(), DrawList::new()),
            |(sorter, list), cell| {
                let mut live_is = |y: f64, p: f64, order: &[u32]| {
                    sorter.sort(&domain.view_at(y.to_degrees(), p.to_degrees()), list);
                    same_order(list, order)
                };
                let mut state = cell_state(seed, cell);
                let mut report = VerifyReport::default();
                let mine = &gaps[cell];
                let pick = |state: &mut u64| {
                    let (s, k) =
                        mine[((unit(state) * mine.len() as f64) as usize).min(mine.len() - 1)];
                    let slab = &bake.slabs[s as usize];
                    let (plo, phi) = (slab.lo.to_radians(), slab.hi.to_radians());
                    let p = plo + (phi - plo) * inside(state, SLAB_PITCH_MARGIN);
                    (s as usize, k as usize, p)
                };
                for _ in 0..per_cell {
                    let (s, k, p) = pick(&mut state);
                    let (lo, hi) = bake.gap(s, k, p);
                    if hi - lo <= VERIFY_MIN_GAP_RAD {
                        continue;
                    }
                    let y = lo + (hi - lo) * inside(&mut state, INTERIOR_MARGIN);
                    let fail = |what: &str| VerifyError::InteriorPoint {
                        cell,
                        yaw: y.to_degrees(),
                        pitch: p.to_degrees(),
                        what: what.to_owned(),
                    };
                    if !live_is(y, p, &bake.cells[cell]) {
                        return Err(fail("the live list differs"));
                    }
                    if bake.cell_at(y.to_degrees(), p.to_degrees()) != Some(cell) {
                        return Err(fail("cell_at names another cell"));
                    }
                    report.interior_checks += 1;
                }
                // One bounding curve: the right-hand one of a random gap that has one.
                let (s, k, p) = pick(&mut state);
                let slab = &bake.slabs[s];
                let Some(&curve) = slab.curves.get(k) else {
                    return Ok(report);
                };
                let (lo, y) = bake.gap(s, k, p);
                let (_, hi) = bake.gap(s, k + 1, p);
                let side = side_of(y - lo, hi - y);
                if side <= VERIFY_MIN_SIDE_RAD {
                    return Ok(report);
                }
                let chart = Chart::of(&bake.circles[curve.circle as usize], roll);
                let f = chart.at_pitch(p);
                let fail = |what: String| VerifyError::Curve {
                    slab: s,
                    index: k,
                    pitch: p.to_degrees(),
                    what,
                };
                let (before, after) = (f.value(y - side), f.value(y + side));
                if !changes_sign(before, after) {
                    return Err(fail(format!(
                        "its circle does not change sign ({before:e}, {after:e})"
                    )));
                }
                if !live_is(y - side, p, &bake.cells[slab.cells[k] as usize]) {
                    return Err(fail("the live list just before is not the cell's".into()));
                }
                if !live_is(y + side, p, &bake.cells[slab.cells[k + 1] as usize]) {
                    return Err(fail("the live list just after is not the cell's".into()));
                }
                report.curve_checks += 1;
                Ok(report)
            },
        )
        .collect();
    let mut total = VerifyReport::default();
    for r in results {
        let r = r?;
        total.interior_checks += r.interior_checks;
        total.curve_checks += r.curve_checks;
    }
    Ok(total)
}

#[cfg(test)]
mod tests {
    use super::*;
    use face_sort::Bounds;

    #[test]
    fn the_chart_formula_is_the_conventions_rotation() {
        let b = Bounds {
            min: DVec3::splat(-1.0),
            max: DVec3::splat(1.0),
        };
        let template = View::fit(&b, 64, 64);
        let n = DVec3::new(0.3, -0.8, 0.5);
        for (y, p, r) in [
            (10.0, 20.0, 30.0),
            (-100.0, 75.0, -40.0),
            (200.0, -10.0, 5.0),
        ] {
            let view = template.with_yaw_pitch_roll(y, p, r);
            let d = view.rotation().row(2);
            let chart = Chart::of(
                &EventCircle {
                    normal: n,
                    offset: 0.1,
                },
                f64::to_radians(r),
            );
            let got = chart.at_pitch(f64::to_radians(p)).value(f64::to_radians(y));
            assert!(
                (got - (n.dot(d) - 0.1)).abs() < 1e-14,
                "{got} vs {}",
                n.dot(d) - 0.1
            );
        }
    }

    #[test]
    fn circle_crossings_lie_on_both_circles() {
        let a = EventCircle {
            normal: DVec3::new(1.0, 2.0, 0.5),
            offset: 0.4,
        };
        let b = EventCircle {
            normal: DVec3::new(-0.5, 0.3, 1.0),
            offset: -0.2,
        };
        let found = circle_crossings(&a, &b).expect("two crossings");
        for d in found {
            assert!((d.length() - 1.0).abs() < 1e-14);
            assert!((a.normal.dot(d) - a.offset).abs() < 1e-14);
            assert!((b.normal.dot(d) - b.offset).abs() < 1e-14);
        }
    }
}
