//! Page elements of pieces: one CSS class per piece (or per triangle or convex quad of it)
//! holding its size, colour and `matrix3d`, shared by every copy of the piece on the page.

use std::fmt::Write as _;

use face_sort::{Geometry, PolygonSet};
use glam::{DMat3, DMat4, DVec3};

use crate::bake::PolygonMap;
use crate::tolerance::HTML_SEAM_PX;

/// Where the pieces go on the page: `place` maps a sprite transform's pixels to the page's
/// (origin at the container), `place_point` a centred model point times `scale` likewise.
pub(crate) struct Placement {
    pub(crate) place: DMat4,
    pub(crate) place_point: DMat3,
    pub(crate) scale: f64,
}

/// A face's fill: its ID colour (CONVENTIONS.md) in ID mode, else `colour(face)`.
pub(crate) fn face_fill<'a>(
    ids: bool,
    colour: &'a dyn Fn(u32) -> [u8; 4],
) -> impl Fn(u32) -> String + 'a {
    move |face| {
        crate::svg::hex(if ids {
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
    maps: &[PolygonMap],
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
                triangle_rule(page, &name, &fill, [at(a), at(b), at(c)], grow, oversize);
                elements.push((name, 'b'));
            }
            continue;
        }
        let Some((transform, clip)) = &maps[p] else {
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
/// anti-aliased diagonal only touches pixels next to an edge.
fn triangle_rule(
    page: &mut String,
    name: &str,
    fill: &str,
    tri: [DVec3; 3],
    grow: [f64; 3],
    oversize: f64,
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
    let [v0, v1, v2] = v;
    let extent = (v1 - v0).length().max((v2 - v0).length()).max(1.0);
    let size = (extent * oversize).ceil().max(8.0);
    // Page coordinates have y down, which mirrors the winding: (S, 0) goes to the third corner
    // and (0, S) to the second, so that the element's front is the piece's.
    let (x, y) = ((v2 - v0) / size, (v1 - v0) / size);
    let normal = x.cross(y).normalize_or(DVec3::Z);
    let m = DMat4::from_cols(
        x.extend(0.0),
        y.extend(0.0),
        normal.extend(0.0),
        v0.extend(1.0),
    );
    let _ = writeln!(
        page,
        ".{name}{{border-width:{s}px {s}px 0 0;border-top-color:{fill};transform:{}}}",
        matrix(&m),
        s = num(size),
    );
}

#[cfg(test)]
mod tests {
    use super::*;

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
