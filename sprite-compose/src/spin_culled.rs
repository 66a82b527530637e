//! The spinning page of a picture bake: one element per piece and place, turned by one
//! shared `rotate` animation on the compositor, back faces hidden by the browser.

use std::fmt::Write as _;

use aspect_bake::{Bake, Spin};
use face_sort::Geometry;
use glam::{DMat3, DMat4, DVec3};

use crate::spin::SpinOptions;
use crate::svg::hex;
use crate::tolerance::HTML_SEAM_PX;
use crate::{BakedSpriteTree, id_colour};

/// The elements of a culled realisation: a sequence of copies of pieces such that every
/// cell's list of drawn pieces is a subsequence of it (one copy per piece per cell).
pub(crate) struct Copies {
    /// Piece of each element, in paint order.
    pub(crate) pieces: Vec<u32>,
    /// Per cell, the element each drawn piece uses.
    used: Vec<Vec<usize>>,
}

impl Copies {
    /// Per element, per cell: whether it is shown. An element is shown in the cells that use
    /// it and hidden in the cells where another copy of its piece is used; where its piece is
    /// never drawn (culled throughout the cell) it is shown, so that a piece with one copy
    /// never switches.
    pub(crate) fn visibility(&self, lists: &[Vec<u32>]) -> Vec<Vec<bool>> {
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
pub(crate) fn copies(lists: &[Vec<u32>], pieces: usize) -> Copies {
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
    Copies {
        pieces: order.iter().map(|&e| element_piece[e]).collect(),
        used: used
            .into_iter()
            .map(|u| u.into_iter().map(|e| rank[e]).collect())
            .collect(),
    }
}

/// A number with about six significant digits, no trailing zeros (CSS accepts it).
fn num(v: f64) -> String {
    crate::numbers::significant(v, 6)
}

/// `matrix3d(…)` with compact numbers: five significant digits (a thousandth of a pixel
/// across a 512-pixel page), two for the third column, which multiplies the element's
/// local `z = 0` and so only has to keep the matrix invertible.
fn matrix(m: &DMat4) -> String {
    let cols: Vec<String> = m
        .to_cols_array()
        .iter()
        .enumerate()
        .map(|(k, &v)| crate::numbers::significant(v, if (8..12).contains(&k) { 2 } else { 5 }))
        .collect();
    format!("matrix3d({})", cols.join(","))
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

/// A picture bake ([`aspect_bake::bake_picture`]) as a self-contained page that turns once
/// per `period_s`, with no script.
///
/// - Every element is a piece (or one convex quad of it) under its fixed `matrix3d` for the
///   spin's base factors, `B` placed inside the sprite matrix and `A` folded into the axis:
///   `A·Rot(k, θ)·B = Rot(A k, θ)·A·B`. One shared `@keyframes` on the individual `rotate`
///   property turns every element about `A k` through the page's centre (on the compositor
///   thread), and the container's `perspective` projects (a huge one for orthographic
///   bakes).
/// - `backface-visibility: hidden` culls: a cell's order holds every piece, and only the
///   front-facing ones need their order.
/// - `lists[c]` are cell `c`'s drawn pieces in order ([`aspect_bake::drawn_lists`]); the
///   elements are copies of pieces such that each list is a subsequence of the page, and a
///   piece with copies shows each one (composited `opacity` keyframes, `step-end`) only in
///   the cells that use it. A piece with one copy has no visibility animation.
/// - The container stays hidden until the last element has been parsed, so that every
///   animation starts together.
///
/// `colour(face)` fills a face (ignored in ID mode).
#[must_use]
pub fn write_culled_spin_html(
    bake: &Bake,
    lists: &[Vec<u32>],
    spin: &Spin,
    geometry: &Geometry,
    colour: &dyn Fn(u32) -> [u8; 4],
    options: &SpinOptions,
) -> String {
    let view = spin.view_at(0.0);
    let graph = BakedSpriteTree::realise(bake, geometry, &view);
    let (w, h) = (view.width(), view.height());
    let (a, k, b) = spin.factors();
    let flip = DMat3::from_diagonal(DVec3::new(1.0, -1.0, 1.0));
    let distance = match view.projection() {
        face_sort::Projection::Orthographic => options.orthographic_distance,
        face_sort::Projection::Perspective { distance } => distance,
    };
    // Sprite matrices map to pixels with the origin at the page's centre.
    let origin = DVec3::new(f64::from(w) * 0.5, f64::from(h) * 0.5, 0.0);
    let place = DMat4::from_mat3(flip * a * b * flip) * DMat4::from_translation(-origin);
    // A centred model point (times the scale) to page pixels about the centre.
    let place_point = flip * a * b;
    let axis = -(flip * (a * k));
    let start = bake.domain().lo;
    let period = options.period_s;
    let (delay, state) = match options.paused_at_s {
        Some(t) => (format!("{}s", num(-t)), "paused"),
        None => ("0s".to_owned(), "running"),
    };
    let timing = format!("{period}s linear {delay} infinite {state}");
    let steps = format!("{period}s step-end {delay} infinite {state}");
    let copies = copies(lists, bake.polygons().len());
    let mut page = String::new();
    let _ = write!(
        page,
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>aspect-bake spin</title><style>\n\
         html,body{{margin:0;padding:0;overflow:hidden;width:{w}px;height:{h}px;background:{bg}}}\n\
         #s{{position:absolute;left:{cx}px;top:{cy}px;width:0;height:0;perspective:{d}px;perspective-origin:0 0}}\n\
         body:not(:has(#end)) #s{{display:none}}\n\
         #s>i,#s>b{{position:absolute;left:0;top:0;transform-origin:0 0;backface-visibility:hidden;animation:t {timing}}}\n\
         b{{width:0;height:0;border-style:solid;border-color:transparent}}\n\
         @keyframes t{{from{{rotate:{x} {y} {z} {a0}deg}}to{{rotate:{x} {y} {z} {a1}deg}}}}\n",
        bg = hex(options.background),
        cx = num(origin.x),
        cy = num(origin.y),
        d = num(distance),
        x = num(axis.x),
        y = num(axis.y),
        z = num(axis.z),
        a0 = num(start),
        a1 = num(start + 360.0),
    );
    // One class per piece element: size, colour, transform (shared by the piece's copies).
    let set = &bake.polygons();
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
    let sprite_scale = view.scale();
    let at = |c: DVec3| place_point * (c * sprite_scale);
    for (p, elements) in elements_of.iter_mut().enumerate() {
        let face = set.face(p);
        let fill = hex(if options.ids {
            id_colour(face)
        } else {
            colour(face)
        });
        let corners = set.corners(p);
        let is_whole = whole.contains(&(face, bits(corners)));
        if corners.len() == 3 && is_whole {
            let name = format!("p{p}");
            triangle_rule(
                &mut page,
                &name,
                &fill,
                [at(corners[0]), at(corners[1]), at(corners[2])],
                [0.0; 3],
                options.oversize,
            );
            elements.push((name, 'b'));
            continue;
        }
        if !is_whole {
            // A part of a cut piece: its fan of triangles, the edges where the truth has none
            // (the cut, the fan's diagonals) grown by a seam's width so that no crack opens
            // there; the piece's own edges stay.
            let sources = sources_of.get(&face).map_or(&[][..], Vec::as_slice);
            let original = |a: DVec3, b: DVec3| {
                let m = 0.5 * (a + b);
                sources
                    .iter()
                    .any(|&i| on_boundary(geometry.pieces().corners(i), m, edge_tolerance))
            };
            let n = corners.len();
            for k in 1..n - 1 {
                let name = format!("p{p}_{k}");
                let (a, b, c) = (corners[0], corners[k], corners[k + 1]);
                let grow_if = |x: DVec3, y: DVec3, boundary: bool| {
                    if boundary && original(x, y) {
                        0.0
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
                    &mut page,
                    &name,
                    &fill,
                    [at(a), at(b), at(c)],
                    grow,
                    options.oversize,
                );
                elements.push((name, 'b'));
            }
            continue;
        }
        let Some((transform, clip)) = graph.polygon_map(p as u32) else {
            continue;
        };
        let size = crate::spin::layout_size(transform, options.oversize);
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
                matrix(&(place * transform.matrix * *quad * unscale)),
                s = num(size),
            );
            elements.push((name, 'i'));
        }
    }
    // Visibility of each element: shown in the cells that use it, hidden in the cells where
    // another copy of its piece is used, either way where its piece is never drawn.
    let shown = copies.visibility(lists);
    let mut patterns: Vec<Vec<bool>> = Vec::new();
    let mut pattern_of: Vec<Option<usize>> = vec![None; copies.pieces.len()];
    for (e, visible) in shown.into_iter().enumerate() {
        if visible.iter().all(|&v| v) {
            continue;
        }
        let k = patterns
            .iter()
            .position(|q| *q == visible)
            .unwrap_or_else(|| {
                patterns.push(visible);
                patterns.len() - 1
            });
        pattern_of[e] = Some(k);
    }
    for (k, visible) in patterns.iter().enumerate() {
        // (offset %, visible), offsets from the page's start angle.
        let mut keys: Vec<(f64, bool)> = Vec::new();
        for (c, cell) in bake.cells().iter().enumerate() {
            let lo = (cell.range.lo - start).rem_euclid(360.0);
            keys.push((lo / 360.0 * 100.0, visible[c]));
        }
        keys.sort_by(|x, y| x.0.total_cmp(&y.0));
        // Before the first boundary the last cell (wrapping round) holds.
        let last = keys.last().is_none_or(|k| k.1);
        let _ = write!(page, "@keyframes v{k}{{0%{{opacity:{}}}", u8::from(last));
        for (offset, v) in keys {
            let _ = write!(page, "{}%{{opacity:{}}}", num(offset), u8::from(v));
        }
        let _ = writeln!(page, "}}\n#s>.v{k}{{animation:t {timing},v{k} {steps}}}");
    }
    page.push_str("</style></head><body><div id=\"s\">\n");
    for (e, &p) in copies.pieces.iter().enumerate() {
        let extra = pattern_of[e].map_or(String::new(), |k| format!(" v{k}"));
        for (name, tag) in &elements_of[p as usize] {
            let _ = write!(page, "<{tag} class=\"{name}{extra}\"></{tag}>");
        }
        if e % 16 == 15 {
            page.push('\n');
        }
    }
    page.push_str("\n</div><i id=\"end\"></i></body></html>\n");
    page
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
        let c = copies(&lists, 4);
        for (list, used) in lists.iter().zip(&c.used) {
            assert!(used.windows(2).all(|w| w[0] < w[1]));
            for (&p, &e) in list.iter().zip(used) {
                assert_eq!(c.pieces[e], p);
            }
        }
        assert!(c.pieces.len() <= 4 + 3);
        assert_eq!(num(0.5), "0.5");
        assert_eq!(num(-256.0), "-256");
        assert_eq!(num(1.23456789e-7), "1.23457e-7"); // shorter with an exponent, as CSS allows
        assert_eq!(num(123456.789), "123457");
    }
}
