//! Page elements of pieces: one CSS class per piece (or per triangle or convex quad of it)
//! holding its size, colour and `matrix3d`, shared by every copy of the piece on the page.

use std::fmt::Write as _;

use aspect_bake::{EventFn, Roots};
use face_sort::{Geometry, PolygonSet};
use glam::{DMat3, DMat4, DVec2, DVec3};

use crate::tolerance::HTML_SEAM_PX;
use sprite_compose::PieceMap;

/// Where the pieces go on the page: `place` maps a sprite transform's pixels to the page's
/// (origin at the container), `place_point` a centred model point times `scale` likewise;
/// `turning` says from where the page shows them.
pub(crate) struct Placement {
    pub(crate) place: DMat4,
    pub(crate) place_point: DMat3,
    pub(crate) scale: f64,
    pub(crate) turning: Turning,
}

/// From where a page shows its elements (page pixels about the container, y down, z toward
/// the viewer), which decides where each border triangle puts its right angle
/// ([`border_shape`]).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Turning {
    /// Every element turns about the unit `axis` through the container, seen from the eye
    /// `(0, 0, distance)`: the eye goes round a circle in each element's own coordinates.
    Spin { axis: DVec3, distance: f64 },
    /// Any rotation (a page turned by the pointer).
    Free,
}

/// A face's fill: its ID colour (CONVENTIONS.md) in ID mode, else `colour(face)`.
pub(crate) fn face_fill<'a>(
    ids: bool,
    colour: &'a dyn Fn(u32) -> [u8; 4],
) -> impl Fn(u32) -> String + 'a {
    move |face| {
        crate::numbers::hex(if ids {
            crate::id_colour(face)
        } else {
            colour(face)
        })
    }
}

/// Writes one class per element of every polygon of `set` into `page` and returns, per
/// polygon, its elements' class names and tags (`b`: a border triangle, `i`: a sprite quad).
/// A whole triangle is one border triangle; a part of a cut piece is a fan of triangles
/// grown by a seam's width along the edges the truth does not have; any other polygon is its
/// sprite (`maps`) in one or more convex quads.
pub(crate) fn piece_classes(
    page: &mut String,
    set: &PolygonSet,
    maps: &[Option<PieceMap>],
    geometry: &Geometry,
    placement: &Placement,
    fill: &dyn Fn(u32) -> String,
    oversize: f64,
) -> Vec<Vec<(String, char)>> {
    let whole: std::collections::HashSet<(u32, Vec<[u64; 3]>)> = {
        let pieces = geometry.pieces();
        (0..pieces.len())
            .map(|i| (pieces.face(i), bits(pieces.corners(i))))
            .collect()
    };
    let mut sources_of: std::collections::HashMap<u32, Vec<usize>> =
        std::collections::HashMap::new();
    for i in 0..geometry.pieces().len() {
        sources_of
            .entry(geometry.pieces().face(i))
            .or_default()
            .push(i);
    }
    let edge_tolerance = 1e-9 * geometry.bounds().diagonal();
    let mut elements_of: Vec<Vec<(String, char)>> = vec![Vec::new(); set.len()];
    let at = |c: DVec3| placement.place_point * (c * placement.scale);
    for (p, elements) in elements_of.iter_mut().enumerate() {
        let face = set.face(p);
        let fill = fill(face);
        let corners = set.corners(p);
        let is_whole = whole.contains(&(face, bits(corners)));
        let sources = sources_of.get(&face).map_or(&[][..], Vec::as_slice);
        let grow_unless_outline = |a: DVec3, b: DVec3| {
            seam_growth(
                a,
                b,
                sources.iter().map(|&i| geometry.pieces().corners(i)),
                edge_tolerance,
            )
        };
        if corners.len() == 3 && is_whole {
            let name = format!("p{p}");
            let [a, b, c] = [corners[0], corners[1], corners[2]];
            triangle_rule(
                page,
                &name,
                &fill,
                [at(a), at(b), at(c)],
                [
                    grow_unless_outline(a, b),
                    grow_unless_outline(b, c),
                    grow_unless_outline(c, a),
                ],
                oversize,
                placement.turning,
            );
            elements.push((name, 'b'));
            continue;
        }
        if !is_whole {
            // A part of a cut piece: its fan of triangles, each edge but the face's outline
            // grown.
            let n = corners.len();
            for k in 1..n - 1 {
                let name = format!("p{p}_{k}");
                let (a, b, c) = (corners[0], corners[k], corners[k + 1]);
                let grow_if = |x: DVec3, y: DVec3, boundary: bool| {
                    if boundary {
                        grow_unless_outline(x, y)
                    } else {
                        HTML_SEAM_PX
                    }
                };
                let grow = [
                    grow_if(a, b, k == 1),
                    grow_if(b, c, true),
                    grow_if(c, a, k + 1 == n - 1),
                ];
                triangle_rule(
                    page,
                    &name,
                    &fill,
                    [at(a), at(b), at(c)],
                    grow,
                    oversize,
                    placement.turning,
                );
                elements.push((name, 'b'));
            }
            continue;
        }
        let Some(PieceMap { transform, clip }) = &maps[p] else {
            continue;
        };
        let size = crate::spin::layout_size(transform, oversize);
        let unscale = DMat4::from_scale(DVec3::new(1.0 / size, 1.0 / size, 1.0));
        let quads = match clip {
            None => vec![DMat4::IDENTITY],
            Some(clip) => crate::html::clip_quads(clip),
        };
        for (q, quad) in quads.iter().enumerate() {
            let name = if quads.len() > 1 {
                format!("p{p}_{q}")
            } else {
                format!("p{p}")
            };
            let _ = writeln!(
                page,
                ".{name}{{width:{s}px;height:{s}px;background:{fill};transform:{}}}",
                matrix(&(placement.place * transform.matrix * *quad * unscale)),
                s = num(size),
            );
            elements.push((name, 'i'));
        }
    }
    elements_of
}

/// A number with about six significant digits, no trailing zeros (CSS accepts it).
pub(crate) fn num(v: f64) -> String {
    crate::numbers::significant(v, 6)
}

/// `matrix3d(…)` with compact numbers: five significant digits (a thousandth of a pixel
/// across a 512-pixel page), two for the third column, which multiplies the element's
/// local `z = 0` and so only has to keep the matrix invertible.
pub(crate) fn matrix(m: &DMat4) -> String {
    let cols: Vec<String> = m
        .to_cols_array()
        .iter()
        .enumerate()
        .map(|(k, &v)| crate::numbers::significant(v, if (8..12).contains(&k) { 2 } else { 5 }))
        .collect();
    format!("matrix3d({})", cols.join(","))
}

/// How far the edge `a`–`b` of an element of a face is grown: not at all when the truth has
/// that edge, an edge of the face's outline (on the boundary of exactly one of the face's
/// pieces `face_pieces`); [`HTML_SEAM_PX`] for any other edge (a cut, a fan's diagonal, the
/// diagonal between the triangles of a non-planar face), so that no crack opens there.
fn seam_growth<'a>(
    a: DVec3,
    b: DVec3,
    face_pieces: impl Iterator<Item = &'a [DVec3]>,
    tolerance: f64,
) -> f64 {
    let m = 0.5 * (a + b);
    let on = face_pieces
        .filter(|corners| on_boundary(corners, m, tolerance))
        .count();
    if on == 1 { 0.0 } else { HTML_SEAM_PX }
}

/// Whether point `m` lies on an edge of the polygon `corners` (within `tolerance`).
fn on_boundary(corners: &[DVec3], m: DVec3, tolerance: f64) -> bool {
    (0..corners.len()).any(|k| {
        let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
        let e = b - a;
        let t = ((m - a).dot(e) / e.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        (a + e * t).distance(m) <= tolerance
    })
}

/// Corners as bits, to recognise a piece that a bake left whole.
fn bits(corners: &[DVec3]) -> Vec<[u64; 3]> {
    corners
        .iter()
        .map(|c| [c.x.to_bits(), c.y.to_bits(), c.z.to_bits()])
        .collect()
}

/// The class `.name` of a CSS border triangle `(0, 0), (S, 0), (0, S)` under an affine map
/// onto `tri` (page pixels about the centre, y down), edge `k` (from corner `k` to `k + 1`)
/// first moved out by `grow[k]` pixels in the triangle's plane (a corner moves at most eight
/// times the larger growth). A triangle's edges are piece edges, so the border's
/// anti-aliased diagonal only touches pixels next to an edge. The triangle lies in its box as
/// [`border_shape`] picks for `turning`.
fn triangle_rule(
    page: &mut String,
    name: &str,
    fill: &str,
    tri: [DVec3; 3],
    grow: [f64; 3],
    oversize: f64,
    turning: Turning,
) {
    let mut v = tri;
    let normal = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
    if grow.iter().any(|&g| g > 0.0) && normal.length() > 0.0 {
        let n = normal.normalize();
        // Outward in-plane normal of edge k.
        let out = |k: usize| {
            let e = tri[(k + 1) % 3] - tri[k];
            let o = e.cross(n).normalize_or_zero();
            if o.dot(tri[(k + 2) % 3] - tri[k]) > 0.0 {
                -o
            } else {
                o
            }
        };
        let limit = 8.0 * grow.iter().copied().fold(0.0, f64::max);
        for k in 0..3 {
            // Corner k joins edge k − 1 and edge k: the point whose distances out of both
            // lines are their growths.
            let (i, j) = ((k + 2) % 3, k);
            let (a, b) = (out(i), out(j));
            let ab = a.dot(b);
            let det = 1.0 - ab * ab;
            let shift = if det > 1e-12 {
                let (ga, gb) = (grow[i], grow[j]);
                let x = (ga - ab * gb) / det;
                let y = (gb - ab * ga) / det;
                a * x + b * y
            } else {
                a * grow[i].max(grow[j])
            };
            v[k] = tri[k]
                + if shift.length() > limit {
                    shift.normalize() * limit
                } else {
                    shift
                };
        }
    }
    // The border triangle (0, 0), (S, 0), (λS, S) in a box S × S. Page coordinates have
    // y down, which mirrors the winding: (S, 0) goes to the third corner and (λS, S) to the
    // second, so that the element's front is the piece's. A cyclic shift keeps the winding.
    let shape = border_shape(v, grow.map(|g| g > 0.0), turning);
    let k = shape.first;
    let [v0, v1, v2] = [v[k], v[(k + 1) % 3], v[(k + 2) % 3]];
    let base = v2 - v0;
    let lean = |lean: f64| v1 - v0 - base * lean;
    let extent = base.length().max(lean(shape.lean).length()).max(1.0);
    let size = (extent * oversize).ceil().max(8.0);
    // Chromium lays borders out in whole pixels.
    let left = (shape.lean * size).round();
    let (x, y) = (base / size, lean(left / size) / size);
    let normal = x.cross(y).normalize_or(DVec3::Z);
    let m = DMat4::from_cols(
        x.extend(0.0),
        y.extend(0.0),
        normal.extend(0.0),
        v0.extend(1.0),
    );
    let widths = if left == 0.0 {
        format!("{s}px {s}px 0 0", s = num(size))
    } else {
        format!(
            "{s}px {r}px 0 {l}px",
            s = num(size),
            r = num(size - left),
            l = num(left)
        )
    };
    let _ = writeln!(
        page,
        ".{name}{{border-width:{widths};border-top-color:{fill};transform:{}}}",
        matrix(&m),
    );
}

/// How a border triangle lies in its element's box: corner `first` of the triangle at the
/// box's corner `(0, 0)`, the next corner (the apex) at `(lean · S, S)`, the last at
/// `(S, 0)`.
///
/// Chromium draws the box's sides sharp and the borders' joins anti-aliased: the base
/// (edge `first + 2`, from the last corner to the first) is always sharp, edge `first` (to
/// the apex) only when `lean` is 0, and edge `first + 1` never.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BorderShape {
    pub(crate) first: usize,
    pub(crate) lean: f64,
}

impl BorderShape {
    /// The right angle at corner 0: what pages drew before shapes were chosen.
    const PLAIN: BorderShape = BorderShape {
        first: 0,
        lean: 0.0,
    };

    /// The box's two corners beyond the triangle `v`: the apex moved back along the base by
    /// the lean, and forward by the rest.
    fn box_corners(self, v: [DVec3; 3]) -> [DVec3; 2] {
        let k = self.first;
        let (v0, apex, v2) = (v[k], v[(k + 1) % 3], v[(k + 2) % 3]);
        let base = v2 - v0;
        [apex - base * self.lean, apex + base * (1.0 - self.lean)]
    }

    /// Whether edge `k` (from corner `k` to `k + 1`) is a sharp side of the box.
    fn is_sharp(self, k: usize) -> bool {
        k == (self.first + 2) % 3 || (k == self.first && self.lean == 0.0)
    }
}

/// Steps in which [`border_shape`] tries leans in `[0, 1]`, before a finer search around the
/// best.
const LEAN_STEPS: u32 = 32;

/// How the border triangle of the triangle `v` (page pixels) lies in its element's box,
/// keeping every edge `k` with `seams[k]` sharp.
///
/// - **Seams.** A seam is an edge between two elements of one face (a cut, the diagonal
///   between the triangles of a non-planar face). An anti-aliased join there leaves a crack
///   in the face: both sides half covered. A sharp side of the box leaves none.
/// - **Edge-on views.** The box is a parallelogram twice the triangle: the base and its
///   translate through the apex. Where the page shows the triangle nearly edge-on, its
///   projection is a sliver along a line and so is the box's. Chromium's software compositor
///   has been seen to paint the triangle's colour on that line beyond the triangle, inside
///   the box (docs/CHROMIUM.md). Among the shapes that keep the seams sharp, the one chosen
///   keeps the box's projection on the triangle's at the views where the triangle is
///   edge-on, as far as one shape can:
///   - [`Turning::Spin`]: the triangle is edge-on twice a turn (or never), where the eye's
///     circle crosses its plane. The shape is the one whose box reaches least beyond the
///     triangle at the worse of those two views. Orthographic, both views look along one
///     line, and a right angle at the corner between the other two, or a lean that puts the
///     apex over its place on the base, reaches nowhere. In perspective the two views
///     differ.
///   - [`Turning::Free`]: every view in the triangle's plane can occur. The right angle goes
///     to the corner with the largest angle, which lies between the other two for the
///     largest share of those views (its angle over π).
///
/// Ties, a triangle never edge-on, and a triangle whose three edges are seams get
/// [`BorderShape::PLAIN`] or the first right angle allowed.
pub(crate) fn border_shape(v: [DVec3; 3], seams: [bool; 3], turning: Turning) -> BorderShape {
    let allowed = |shape: BorderShape| (0..3).all(|k| !seams[k] || shape.is_sharp(k));
    let right_angles = (0..3)
        .map(|first| BorderShape { first, lean: 0.0 })
        .filter(|&shape| allowed(shape));
    let edge = |k: usize| v[(k + 1) % 3] - v[k];
    match turning {
        Turning::Free => {
            let angle = |shape: &BorderShape| {
                let k = shape.first;
                (-edge((k + 2) % 3)).angle_between(edge(k))
            };
            right_angles
                .reduce(|best, shape| {
                    if angle(&shape) > angle(&best) {
                        shape
                    } else {
                        best
                    }
                })
                .unwrap_or(BorderShape::PLAIN)
        }
        Turning::Spin { axis, distance } => {
            let views = edge_on_views(v, axis, distance);
            let reach = |shape: BorderShape| {
                let corners = shape.box_corners(v);
                views
                    .iter()
                    .flatten()
                    .flat_map(|view| corners.map(|q| view.overshoot(q)))
                    .fold(0.0, f64::max)
            };
            let better = |best: Option<(BorderShape, f64)>, shape: BorderShape| {
                if !allowed(shape) {
                    return best;
                }
                let r = reach(shape);
                match best {
                    Some((_, b)) if b <= r => best,
                    _ => Some((shape, r)),
                }
            };
            // Right angles first: a tie keeps the shorter rule.
            let mut best = None;
            for j in 0..=LEAN_STEPS {
                for first in 0..3 {
                    let lean = f64::from(j) / f64::from(LEAN_STEPS);
                    best = better(best, BorderShape { first, lean });
                }
            }
            let Some((coarse, _)) = best else {
                return BorderShape::PLAIN;
            };
            let step = 1.0 / f64::from(LEAN_STEPS * LEAN_STEPS);
            for j in 1..=LEAN_STEPS {
                for lean in [
                    coarse.lean - step * f64::from(j),
                    coarse.lean + step * f64::from(j),
                ] {
                    if (0.0..=1.0).contains(&lean) {
                        best = better(best, BorderShape { lean, ..coarse });
                    }
                }
            }
            best.map_or(BorderShape::PLAIN, |(shape, _)| shape)
        }
    }
}

/// The views in which a page spinning about `axis` (with the eye at `(0, 0, distance)`)
/// shows the triangle `v` edge-on: where the eye's circle, `c + r₁ cos φ + r₂ sin φ` in the
/// triangle's coordinates, meets the triangle's plane, found as the roots of
/// `n · (e(φ) − v₀)` ([`EventFn::roots`]): two, one where the circle only touches the plane,
/// or none.
fn edge_on_views(v: [DVec3; 3], axis: DVec3, distance: f64) -> [Option<EdgeOnView>; 2] {
    let n = (v[1] - v[0]).cross(v[2] - v[0]);
    let eye = DVec3::new(0.0, 0.0, distance);
    let centre = axis * axis.dot(eye);
    let (r1, r2) = (eye - centre, axis.cross(eye));
    let facing = EventFn {
        a: n.dot(r1),
        b: n.dot(r2),
        c: n.dot(centre - v[0]),
        scale: n.length() * (distance.abs() + v[0].length()),
    };
    // The eye at r₁ cos φ + r₂ sin φ (about the axis) is the page turned by −φ.
    let view = |phi: f64| {
        Some(EdgeOnView::new(
            v,
            DMat3::from_axis_angle(axis, -phi),
            distance,
        ))
    };
    match facing.roots() {
        Roots::Two { down, up } => [view(up), view(down)],
        Roots::Tangent(phi) => [view(phi), None],
        Roots::None | Roots::Identically => [None, None],
    }
}

/// A view in which the page shows a triangle edge-on: the page turned by `turn` and seen
/// from `(0, 0, distance)`, where the triangle projects onto a line, from `origin` along
/// `along` over `[lo, hi]`.
struct EdgeOnView {
    turn: DMat3,
    distance: f64,
    origin: DVec2,
    along: DVec2,
    lo: f64,
    hi: f64,
}

impl EdgeOnView {
    /// The view of the triangle `v` turned by `turn`: the line of its longest projected edge.
    fn new(v: [DVec3; 3], turn: DMat3, distance: f64) -> Self {
        let mut view = EdgeOnView {
            turn,
            distance,
            origin: DVec2::ZERO,
            along: DVec2::ZERO,
            lo: 0.0,
            hi: 0.0,
        };
        let corners = v.map(|p| view.screen(p));
        let length = |(i, j): (usize, usize)| corners[i].distance(corners[j]);
        let (i, j) = [(0, 1), (1, 2), (2, 0)]
            .into_iter()
            .fold(
                (0, 1),
                |best, e| if length(e) > length(best) { e } else { best },
            );
        view.origin = corners[i];
        view.along = (corners[j] - corners[i]).normalize_or_zero();
        (view.lo, view.hi) = corners
            .iter()
            .map(|&p| view.along_line(p))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| {
                (lo.min(t), hi.max(t))
            });
        view
    }

    /// The page pixels of a point of the triangle's plane.
    fn screen(&self, p: DVec3) -> DVec2 {
        let p = self.turn * p;
        p.truncate() * (self.distance / (self.distance - p.z))
    }

    /// Where along the line a screen point lies.
    fn along_line(&self, p: DVec2) -> f64 {
        (p - self.origin).dot(self.along)
    }

    /// How far (page pixels) the point `q` of the triangle's plane projects beyond the
    /// triangle along the line.
    fn overshoot(&self, q: DVec3) -> f64 {
        let x = self.along_line(self.screen(q));
        (self.lo - x).max(x - self.hi).max(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_orthographic_spin_puts_the_right_angle_at_the_corner_seen_between_the_others() {
        // In the plane x = 0, spun about y: seen edge-on along ±z, onto the y axis, where
        // corner 2 (y = 5) lies between the others.
        let v = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.0, 10.0, 1.0),
            DVec3::new(0.0, 5.0, 5.0),
        ];
        let distance = 1e8;
        let turning = Turning::Spin {
            axis: DVec3::Y,
            distance,
        };
        let shape = border_shape(v, [false; 3], turning);
        assert_eq!(
            shape,
            BorderShape {
                first: 2,
                lean: 0.0
            }
        );
        let views = edge_on_views(v, DVec3::Y, distance);
        assert_eq!(views.iter().flatten().count(), 2);
        for view in views.iter().flatten() {
            for q in shape.box_corners(v) {
                assert!(view.overshoot(q) <= 1e-6);
            }
            // The right angle at corner 0 reaches 5 pixels beyond, to y = 15.
            let q = BorderShape::PLAIN.box_corners(v)[1];
            assert!((view.overshoot(q) - 5.0).abs() <= 1e-6);
        }
        // Never edge-on (spun about z, the eye stays on the axis, facing the plane z = 0): the
        // plain shape.
        let flat = [
            DVec3::ZERO,
            DVec3::new(10.0, 0.0, 0.0),
            DVec3::new(0.0, 10.0, 0.0),
        ];
        let around_z = Turning::Spin {
            axis: DVec3::Z,
            distance: 1e3,
        };
        assert_eq!(border_shape(flat, [false; 3], around_z), BorderShape::PLAIN);
    }

    #[test]
    fn seams_stay_sharp_sides_of_the_box() {
        // The orthographic test's triangle with a seam from corner 0 to 1: the right angle
        // cannot go to corner 2, so the seam is the base and the apex (corner 2) leans over
        // its place on it, halfway.
        let v = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.0, 10.0, 1.0),
            DVec3::new(0.0, 5.0, 5.0),
        ];
        let (axis, distance) = (DVec3::Y, 1e8);
        let shape = border_shape(v, [true, false, false], Turning::Spin { axis, distance });
        assert_eq!(
            shape,
            BorderShape {
                first: 1,
                lean: 0.5
            }
        );
        for view in edge_on_views(v, axis, distance).iter().flatten() {
            for q in shape.box_corners(v) {
                assert!(view.overshoot(q) <= 1e-6);
            }
        }
        // Every pattern of seams, on random triangles and turnings.
        let mut rng = test_support::Rng::new(30);
        for _ in 0..50 {
            let mut corner = || {
                DVec3::new(
                    rng.range(-50.0, 50.0),
                    rng.range(-50.0, 50.0),
                    rng.range(-50.0, 50.0),
                )
            };
            let v = [corner(), corner(), corner()];
            let axis = DVec3::new(rng.range(-0.3, 0.3), 1.0, 0.0).normalize();
            for turning in [
                Turning::Free,
                Turning::Spin {
                    axis,
                    distance: 1e8,
                },
                Turning::Spin {
                    axis,
                    distance: 800.0,
                },
            ] {
                for pattern in 0..8_u8 {
                    let seams = [0, 1, 2].map(|k| pattern & (1 << k) != 0);
                    let shape = border_shape(v, seams, turning);
                    if pattern == 7 {
                        assert_eq!(shape, BorderShape::PLAIN);
                        continue;
                    }
                    for k in 0..3 {
                        assert!(!seams[k] || shape.is_sharp(k), "{seams:?} {shape:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn in_perspective_the_chosen_box_reaches_least_beyond_its_edge_on_triangle() {
        let mut rng = test_support::Rng::new(26);
        let (mut worst_plain, mut worst_chosen) = (0.0_f64, 0.0_f64);
        for _ in 0..300 {
            let axis = DVec3::new(rng.range(-0.3, 0.3), 1.0, rng.range(-0.3, 0.3)).normalize();
            let distance = rng.range(500.0, 2000.0);
            let centre = DVec3::new(
                rng.range(-200.0, 200.0),
                rng.range(-200.0, 200.0),
                rng.range(-200.0, 200.0),
            );
            let mut corner = || {
                centre
                    + DVec3::new(
                        rng.range(-15.0, 15.0),
                        rng.range(-15.0, 15.0),
                        rng.range(-15.0, 15.0),
                    )
            };
            let v = [corner(), corner(), corner()];
            let shape = border_shape(v, [false; 3], Turning::Spin { axis, distance });
            // Where the turned page shows the triangle edge-on, found apart from
            // edge_on_views: the sign changes of its projected area over the turn.
            let area = |theta: f64| {
                let turn = DMat3::from_axis_angle(axis, theta);
                let p = v.map(|c| {
                    let c = turn * c;
                    c.truncate() * (distance / (distance - c.z))
                });
                (p[1] - p[0]).perp_dot(p[2] - p[0])
            };
            let steps = 720;
            let mut found = Vec::new();
            for k in 0..steps {
                let step = std::f64::consts::TAU / f64::from(steps);
                let (mut lo, mut hi) = (step * f64::from(k), step * f64::from(k + 1));
                if area(lo).signum() == area(hi).signum() {
                    continue;
                }
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if area(mid).signum() == area(lo).signum() {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                found.push(DMat3::from_axis_angle(axis, lo));
            }
            let turns: Vec<DMat3> = edge_on_views(v, axis, distance)
                .iter()
                .flatten()
                .map(|view| view.turn)
                .collect();
            assert_eq!(turns.len(), found.len());
            for turn in &found {
                let same = |other: &DMat3| {
                    v.iter()
                        .all(|&c| (*turn * c).distance(*other * c) <= 1e-6 * distance)
                };
                assert!(
                    turns.iter().any(same),
                    "edge-on turns {turns:?}, found {found:?}"
                );
                let view = EdgeOnView::new(v, *turn, distance);
                let reach = |shape: BorderShape| {
                    shape
                        .box_corners(v)
                        .map(|q| view.overshoot(q))
                        .into_iter()
                        .fold(0.0, f64::max)
                };
                worst_plain = worst_plain.max(reach(BorderShape::PLAIN));
                worst_chosen = worst_chosen.max(reach(shape));
            }
        }
        // 41 px against 3 px when written.
        assert!(
            worst_chosen < 0.1 * worst_plain,
            "the chosen shapes reach {worst_chosen} px beyond, the plain right angle {worst_plain}"
        );
    }

    #[test]
    fn a_freely_turned_page_puts_the_right_angle_at_the_largest_angle() {
        let v = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(10.0, 0.0, 0.0),
            DVec3::new(5.0, 1.0, 0.0),
        ];
        assert_eq!(
            border_shape(v, [false; 3], Turning::Free),
            BorderShape {
                first: 2,
                lean: 0.0
            }
        );
    }

    #[test]
    fn the_diagonal_between_a_non_planar_faces_triangles_is_grown_and_its_outline_is_not() {
        // A quad folded along its diagonal a–c, as the two triangles its pieces are.
        let [a, b, c, d] = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.3),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let pieces = [vec![a, b, c], vec![a, c, d]];
        let growth = |x, y| seam_growth(x, y, pieces.iter().map(Vec::as_slice), 1e-9);
        assert_eq!(growth(c, a), HTML_SEAM_PX);
        assert_eq!(growth(a, c), HTML_SEAM_PX);
        for (x, y) in [(a, b), (b, c), (c, d), (d, a)] {
            assert_eq!(growth(x, y), 0.0);
        }
        // A part of a cut piece: its cut (inside the first triangle) is grown too.
        assert_eq!(growth(a, 0.5 * (b + c)), HTML_SEAM_PX);
    }
}
