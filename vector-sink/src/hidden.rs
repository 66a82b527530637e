//! Hidden-part removal for vector outputs: what of each polygon no viewer can see.
//!
//! A vector file is resolution-free, so nothing may be dropped for being small: a part is
//! removed only because opaque polygons drawn after it (nearer, in an exact painter order)
//! cover it. Walking the polygons front to back, each polygon's visible part is the polygon
//! minus the union of the opaque polygons in front of it whose boxes overlap its box (found
//! through a uniform grid of buckets): the same set as minus everything in front, at the cost
//! of a few neighbours instead of the whole picture.
//!
//! The boolean operations are `i_overlay`'s, in 64-bit integers on **one grid for the whole
//! picture** (`2⁵²` steps across the largest coordinate: the resolution of an f64 there).
//! Every corner is rounded once, so corners and edges that polygons share stay shared
//! exactly, the cut edges lie on the covering polygons' edges, and "whole" and "hidden" are
//! decided by exact integer areas, with no tolerance.
//!
//! Translucent polygons keep what lies behind them visible: they are cut by what covers
//! them but cover nothing.

use glam::DVec2;

use crate::project_sprite;
use crate::tolerance::{HIDDEN_GRID_BITS, MIN_PART_AREA_PX2};
use crate::{Scene, SceneSprite};
use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::{IntOverlayOptions, Overlay};
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::i_float::int::point::IntPoint;

type Contour = Vec<IntPoint<i64>>;
type Shapes = Vec<Vec<Contour>>;

/// What of one polygon can be seen.
#[derive(Clone, Debug, PartialEq)]
pub enum Visibility {
    /// All of it: nothing opaque in front overlaps it.
    Whole,
    /// Nothing: opaque polygons in front cover it.
    Hidden,
    /// Part of it: shapes, each an outer contour followed by its holes (pixels; draw with the
    /// even-odd fill rule).
    Parts(Vec<Vec<Vec<DVec2>>>),
}

/// Whether the caller's vector output keeps hidden parts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum HiddenParts {
    /// Write every polygon whole, in paint order (the painter's algorithm as is).
    #[default]
    Keep,
    /// Leave out every polygon, or part of one, that opaque polygons in front cover.
    Remove,
}

/// The picture's integer grid: `round((p − origin) · scale)`.
struct Grid {
    origin: DVec2,
    scale: f64,
}

impl Grid {
    fn new(polygons: &[Vec<DVec2>]) -> Self {
        let (lo, hi) = polygons.iter().flatten().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        let origin = (lo + hi) * 0.5;
        let reach = (hi - lo).max_element() * 0.5;
        let scale = if reach.is_finite() && reach > 0.0 {
            2f64.powi(HIDDEN_GRID_BITS) / reach
        } else {
            1.0
        };
        Grid { origin, scale }
    }

    fn to_int(&self, p: DVec2) -> IntPoint<i64> {
        let q = ((p - self.origin) * self.scale).round();
        IntPoint::new(q.x as i64, q.y as i64)
    }

    fn to_float(&self, p: IntPoint<i64>) -> DVec2 {
        DVec2::new(p.x as f64, p.y as f64) / self.scale + self.origin
    }
}

/// One sprite as the vector writers draw it: its projected polygon (pixels, near-plane
/// clipped) and what of it is seen ([`Visibility::Whole`] or [`Visibility::Parts`]).
pub(crate) struct VectorShape<'a> {
    pub(crate) sprite: &'a SceneSprite,
    pub(crate) polygon: Vec<DVec2>,
    pub(crate) visible: Visibility,
}

/// The scene's visible sprites in paint order as the vector writers draw them, leaving out
/// what projects to nothing and, under [`HiddenParts::Remove`], what is covered. In ID mode
/// every sprite is opaque; otherwise a sprite is opaque when its solid colour is.
pub(crate) fn vector_shapes(scene: &Scene, ids: bool, hidden: HiddenParts) -> Vec<VectorShape<'_>> {
    let sprites: Vec<&SceneSprite> = scene.visible().map(|(_, sprite)| sprite).collect();
    let polygons: Vec<Vec<DVec2>> = sprites
        .iter()
        .map(|sprite| project_sprite(scene.root(), sprite))
        .collect();
    let visibility = match hidden {
        HiddenParts::Keep => vec![Visibility::Whole; polygons.len()],
        HiddenParts::Remove => {
            let opaque: Vec<bool> = sprites
                .iter()
                .map(|sprite| ids || sprite.brush.solid_colour(sprite.face)[3] == 255)
                .collect();
            visible_parts(&polygons, &opaque)
        }
    };
    sprites
        .into_iter()
        .zip(polygons)
        .zip(visibility)
        .filter(|((_, polygon), visible)| polygon.len() >= 3 && *visible != Visibility::Hidden)
        .map(|((sprite, polygon), visible)| VectorShape {
            sprite,
            polygon,
            visible,
        })
        .collect()
}

/// The visible part of each polygon, given the polygons in paint order (back to front, in
/// pixels) and whether each is opaque. Degenerate polygons (fewer than 3 corners, or no
/// area on the grid) are [`Visibility::Hidden`].
#[must_use]
pub fn visible_parts(polygons: &[Vec<DVec2>], opaque: &[bool]) -> Vec<Visibility> {
    assert_eq!(polygons.len(), opaque.len(), "one opacity per polygon");
    let grid = Grid::new(polygons);
    let options = IntOverlayOptions {
        min_output_area: (MIN_PART_AREA_PX2 * grid.scale * grid.scale) as u128,
        ..IntOverlayOptions::default()
    };
    // Every contour counter-clockwise, so that overlapping covers add up under non-zero.
    let contours: Vec<Contour> = polygons
        .iter()
        .map(|polygon| {
            let mut contour: Contour = polygon.iter().map(|&p| grid.to_int(p)).collect();
            if signed_twice_area(&contour) < 0 {
                contour.reverse();
            }
            contour
        })
        .collect();
    let boxes: Vec<(IntPoint<i64>, IntPoint<i64>)> =
        contours.iter().map(|c| int_bounds(c)).collect();
    let mut covers = CoverIndex::new(&boxes);
    let mut result = vec![Visibility::Hidden; polygons.len()];
    let mut clip: Vec<Contour> = Vec::new();
    for i in (0..polygons.len()).rev() {
        let contour = &contours[i];
        if contour.len() < 3 {
            continue;
        }
        let whole_area = twice_area(contour);
        if whole_area == 0 {
            continue;
        }
        // The opaque polygons in front whose boxes overlap this one's.
        clip.clear();
        covers.for_each_overlapping(boxes[i], |j| clip.push(contours[j].clone()));
        result[i] = if clip.is_empty() {
            Visibility::Whole
        } else {
            let visible =
                Overlay::from_subj_and_clip_custom(contour, &clip, options, Default::default())
                    .overlay(OverlayRule::Difference, FillRule::NonZero);
            classify(visible, whole_area, &grid)
        };
        if opaque[i] && !matches!(result[i], Visibility::Hidden) {
            covers.insert(i);
        }
    }
    result
}

/// The opaque polygons processed so far (all in front of the current one), bucketed by a
/// uniform grid over their boxes, for "which of them overlap this box" queries.
struct CoverIndex<'a> {
    boxes: &'a [(IntPoint<i64>, IntPoint<i64>)],
    origin: IntPoint<i64>,
    cell: i64,
    side: usize,
    buckets: Vec<Vec<u32>>,
    /// Query stamp per polygon, so that one query reports a polygon once.
    seen: Vec<u32>,
    stamp: u32,
}

impl<'a> CoverIndex<'a> {
    fn new(boxes: &'a [(IntPoint<i64>, IntPoint<i64>)]) -> Self {
        let valid = boxes.iter().filter(|(lo, hi)| lo.x <= hi.x && lo.y <= hi.y);
        let (lo, hi) = valid.fold(
            (
                IntPoint::new(i64::MAX, i64::MAX),
                IntPoint::new(i64::MIN, i64::MIN),
            ),
            |(a, b), (lo, hi)| {
                (
                    IntPoint::new(a.x.min(lo.x), a.y.min(lo.y)),
                    IntPoint::new(b.x.max(hi.x), b.y.max(hi.y)),
                )
            },
        );
        // About two polygons per cell side: side² ≈ n / 2 cells.
        let side = ((boxes.len() as f64 / 2.0).sqrt().ceil() as usize).clamp(1, 512);
        let extent = if lo.x <= hi.x {
            (hi.x - lo.x).max(hi.y - lo.y)
        } else {
            0
        };
        let cell = (extent / side as i64).max(1) + 1;
        CoverIndex {
            boxes,
            origin: lo,
            cell,
            side,
            buckets: vec![Vec::new(); side * side],
            seen: vec![0; boxes.len()],
            stamp: 0,
        }
    }

    /// Cells `[x0, x1] × [y0, y1]` under a box.
    fn cells(&self, (lo, hi): (IntPoint<i64>, IntPoint<i64>)) -> (usize, usize, usize, usize) {
        let at = |v: i64, o: i64| (((v - o) / self.cell).max(0) as usize).min(self.side - 1);
        (
            at(lo.x, self.origin.x),
            at(hi.x, self.origin.x),
            at(lo.y, self.origin.y),
            at(hi.y, self.origin.y),
        )
    }

    fn insert(&mut self, i: usize) {
        let (x0, x1, y0, y1) = self.cells(self.boxes[i]);
        for y in y0..=y1 {
            for x in x0..=x1 {
                self.buckets[y * self.side + x].push(i as u32);
            }
        }
    }

    /// Calls `f` once for each inserted polygon whose box overlaps `query` with positive area.
    fn for_each_overlapping(
        &mut self,
        query: (IntPoint<i64>, IntPoint<i64>),
        mut f: impl FnMut(usize),
    ) {
        self.stamp += 1;
        let (x0, x1, y0, y1) = self.cells(query);
        let (qlo, qhi) = query;
        for y in y0..=y1 {
            for x in x0..=x1 {
                for &j in &self.buckets[y * self.side + x] {
                    let j = j as usize;
                    if self.seen[j] == self.stamp {
                        continue;
                    }
                    self.seen[j] = self.stamp;
                    let (lo, hi) = self.boxes[j];
                    if lo.x < qhi.x && qlo.x < hi.x && lo.y < qhi.y && qlo.y < hi.y {
                        f(j);
                    }
                }
            }
        }
    }
}

/// `Whole` when the difference left the polygon's exact area in one contour without holes,
/// `Hidden` when nothing is left.
fn classify(visible: Shapes, whole_area: u128, grid: &Grid) -> Visibility {
    if visible.is_empty() {
        return Visibility::Hidden;
    }
    if visible.len() == 1 && visible[0].len() == 1 && twice_area(&visible[0][0]) == whole_area {
        return Visibility::Whole;
    }
    Visibility::Parts(
        visible
            .into_iter()
            .map(|shape| {
                shape
                    .into_iter()
                    .map(|c| c.into_iter().map(|p| grid.to_float(p)).collect())
                    .collect()
            })
            .collect(),
    )
}

fn int_bounds(contour: &[IntPoint<i64>]) -> (IntPoint<i64>, IntPoint<i64>) {
    contour.iter().fold(
        (
            IntPoint::new(i64::MAX, i64::MAX),
            IntPoint::new(i64::MIN, i64::MIN),
        ),
        |(lo, hi), p| {
            (
                IntPoint::new(lo.x.min(p.x), lo.y.min(p.y)),
                IntPoint::new(hi.x.max(p.x), hi.y.max(p.y)),
            )
        },
    )
}

/// Twice the unsigned area of a closed contour, exactly.
fn twice_area(contour: &[IntPoint<i64>]) -> u128 {
    signed_twice_area(contour).unsigned_abs()
}

/// Twice the signed area (counter-clockwise positive), exactly: the shoelace in 128 bits.
fn signed_twice_area(contour: &[IntPoint<i64>]) -> i128 {
    let n = contour.len();
    let mut sum: i128 = 0;
    for k in 0..n {
        let (a, b) = (contour[k], contour[(k + 1) % n]);
        sum += i128::from(a.x) * i128::from(b.y) - i128::from(b.x) * i128::from(a.y);
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, size: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(x, y),
            DVec2::new(x + size, y),
            DVec2::new(x + size, y + size),
            DVec2::new(x, y + size),
        ]
    }

    #[test]
    fn front_polygons_cut_what_lies_behind() {
        // Paint order: big back square, small front square inside it, far-away square.
        let polygons = vec![
            square(0.0, 0.0, 10.0),
            square(2.0, 2.0, 3.0),
            square(20.0, 0.0, 1.0),
        ];
        let parts = visible_parts(&polygons, &[true, true, true]);
        assert_eq!(parts[1], Visibility::Whole);
        assert_eq!(parts[2], Visibility::Whole);
        let Visibility::Parts(shapes) = &parts[0] else {
            panic!("expected a square with a hole, got {:?}", parts[0]);
        };
        assert_eq!(shapes.len(), 1);
        assert_eq!(shapes[0].len(), 2, "outer contour and one hole");
        let area = |c: &[DVec2]| {
            (0..c.len())
                .map(|k| c[k].perp_dot(c[(k + 1) % c.len()]))
                .sum::<f64>()
                .abs()
                * 0.5
        };
        let (outer, hole) = (area(&shapes[0][0]), area(&shapes[0][1]));
        assert!((outer - 100.0).abs() < 1e-9 && (hole - 9.0).abs() < 1e-9);
    }

    #[test]
    fn covered_polygons_are_hidden_and_translucent_ones_cover_nothing() {
        let polygons = vec![square(1.0, 1.0, 2.0), square(0.0, 0.0, 5.0)];
        assert_eq!(
            visible_parts(&polygons, &[true, true]),
            [Visibility::Hidden, Visibility::Whole]
        );
        assert_eq!(
            visible_parts(&polygons, &[true, false]),
            [Visibility::Whole, Visibility::Whole]
        );
    }

    #[test]
    fn two_neighbours_together_hide_what_neither_hides_alone() {
        let rect = |x0: f64, y0: f64, x1: f64, y1: f64| {
            vec![
                DVec2::new(x0, y0),
                DVec2::new(x1, y0),
                DVec2::new(x1, y1),
                DVec2::new(x0, y1),
            ]
        };
        // A square behind the shared edge of two rectangles in front.
        let polygons = vec![
            rect(1.0, 1.0, 3.0, 3.0),
            rect(0.0, 0.0, 2.0, 4.0),
            rect(2.0, 0.0, 4.0, 4.0),
        ];
        let parts = visible_parts(&polygons, &[true; 3]);
        assert_eq!(parts[0], Visibility::Hidden, "{:?}", parts[0]);
        assert_eq!(parts[1], Visibility::Whole);
        assert_eq!(parts[2], Visibility::Whole);
    }
}
