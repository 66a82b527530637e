//! The spinning page of a picture bake: one element per piece and place, turned by one
//! shared `rotate` animation on the compositor, back faces hidden by the browser.

use std::fmt::Write as _;

use aspect_bake::{Bake, Spin};
use face_sort::Geometry;
use glam::{DMat3, DMat4, DVec2, DVec3};

use crate::spin::SpinOptions;
use crate::svg::hex;
use crate::{BakedGraph, id_colour};

/// The page's elements: a sequence of copies of pieces such that every cell's list of drawn
/// pieces is a subsequence of it (one copy per piece per cell).
struct Copies {
    /// Piece of each element, in paint (document) order.
    pieces: Vec<u32>,
    /// Per cell, the element each drawn piece uses.
    used: Vec<Vec<usize>>,
}

/// Elements built cell by cell: a cell reuses the longest run of existing elements that is
/// in its order (a longest common subsequence, Hunt and Szymanski's way: patience sorting
/// over each piece's existing copies), and inserts a new copy for each other piece just
/// before the next element it reuses.
fn copies(lists: &[Vec<u32>], pieces: usize) -> Copies {
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
    if v == 0.0 || !v.is_finite() {
        return "0".to_owned();
    }
    let digits = (5 - v.abs().log10().floor() as i32).clamp(0, 12) as usize;
    let s = format!("{v:.digits$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    };
    if s == "-0" { "0".to_owned() } else { s }
}

/// `matrix3d(…)` with compact numbers.
fn matrix(m: &DMat4) -> String {
    let cols: Vec<String> = m.to_cols_array().iter().map(|&v| num(v)).collect();
    format!("matrix3d({})", cols.join(","))
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
    let graph = BakedGraph::realise(bake, geometry, &view);
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
    let start = bake.domain.lo;
    let period = options.period_s;
    let (delay, state) = match options.paused_at_s {
        Some(t) => (format!("{}s", num(-t)), "paused"),
        None => ("0s".to_owned(), "running"),
    };
    let timing = format!("{period}s linear {delay} infinite {state}");
    let steps = format!("{period}s step-end {delay} infinite {state}");
    let copies = copies(lists, bake.polygons.len());
    let mut page = String::new();
    let _ = write!(
        page,
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>aspect-bake spin</title><style>\n\
         html,body{{margin:0;padding:0;overflow:hidden;width:{w}px;height:{h}px;background:{bg}}}\n\
         #s{{position:absolute;left:{cx}px;top:{cy}px;width:0;height:0;perspective:{d}px;perspective-origin:0 0}}\n\
         body:not(:has(#end)) #s{{display:none}}\n\
         #s>i{{position:absolute;left:0;top:0;transform-origin:0 0;backface-visibility:hidden;animation:t {timing}}}\n\
         .t{{width:0;height:0;border-style:solid;border-color:transparent}}\n\
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
    // One class per piece: size, colour, transform (shared by its copies and quads).
    let set = &bake.polygons;
    let mut quads_of: Vec<usize> = vec![0; set.len()];
    let mut triangle = vec![false; set.len()];
    let sprite_scale = view.scale();
    for p in 0..set.len() {
        let face = set.face(p);
        let fill = hex(if options.ids {
            id_colour(face)
        } else {
            colour(face)
        });
        let corners = set.corners(p);
        if corners.len() == 3 {
            // A triangle is one element: a CSS border triangle (0, 0), (S, 0), (0, S) under an
            // affine map onto its corners (its long edge is a piece edge, so the border's
            // anti-aliased diagonal only touches pixels next to an edge).
            let at = |c: DVec3| place_point * (c * sprite_scale);
            let (v0, v1, v2) = (at(corners[0]), at(corners[1]), at(corners[2]));
            let extent = (v1 - v0).length().max((v2 - v0).length()).max(1.0);
            let size = (extent * options.oversize).ceil().max(8.0);
            // Page coordinates have y down, which mirrors the winding: (S, 0) goes to the third
            // corner and (0, S) to the second, so that the element's front is the piece's.
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
                ".p{p}{{border-width:{s}px {s}px 0 0;border-top-color:{fill};transform:{}}}",
                matrix(&m),
                s = num(size),
            );
            quads_of[p] = 1;
            triangle[p] = true;
            continue;
        }
        let Some((transform, clip)) = graph.polygon_map(p as u32) else {
            continue;
        };
        let (mut lo, mut hi) = (DVec2::splat(f64::MAX), DVec2::splat(f64::MIN));
        for uv in [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y] {
            let q = transform.apply(uv).truncate();
            lo = lo.min(q);
            hi = hi.max(q);
        }
        let size = ((hi - lo).max_element().max(1.0) * options.oversize)
            .ceil()
            .max(8.0);
        let unscale = DMat4::from_scale(DVec3::new(1.0 / size, 1.0 / size, 1.0));
        let quads = match clip {
            None => vec![DMat4::IDENTITY],
            Some(clip) => crate::html::clip_quads(clip),
        };
        quads_of[p] = quads.len();
        for (q, quad) in quads.iter().enumerate() {
            let _ = writeln!(
                page,
                ".p{p}{}{{width:{s}px;height:{s}px;background:{fill};transform:{}}}",
                if quads.len() > 1 {
                    format!("_{q}")
                } else {
                    String::new()
                },
                matrix(&(place * transform.matrix * *quad * unscale)),
                s = num(size),
            );
        }
    }
    // Visibility of each element: shown in the cells that use it, hidden in the cells where
    // another copy of its piece is used, either way where its piece is never drawn.
    let cells = bake.cells.len();
    let mut shown: Vec<Vec<Option<bool>>> = vec![vec![None; cells]; copies.pieces.len()];
    let mut first_copy: Vec<Vec<usize>> = vec![Vec::new(); set.len()];
    for (e, &p) in copies.pieces.iter().enumerate() {
        first_copy[p as usize].push(e);
    }
    for (c, used) in copies.used.iter().enumerate() {
        for (i, &e) in used.iter().enumerate() {
            let p = lists[c][i] as usize;
            for &other in &first_copy[p] {
                shown[other][c] = Some(other == e);
            }
        }
    }
    let mut patterns: Vec<Vec<bool>> = Vec::new();
    let mut pattern_of: Vec<Option<usize>> = vec![None; copies.pieces.len()];
    for (e, s) in shown.iter().enumerate() {
        let visible: Vec<bool> = s.iter().map(|v| v.unwrap_or(true)).collect();
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
        for (c, cell) in bake.cells.iter().enumerate() {
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
        let quads = quads_of[p as usize];
        let mut extra = pattern_of[e].map_or(String::new(), |k| format!(" v{k}"));
        if triangle[p as usize] {
            extra.push_str(" t");
        }
        for q in 0..quads {
            let name = if quads > 1 {
                format!("p{p}_{q}")
            } else {
                format!("p{p}")
            };
            let _ = write!(page, "<i class=\"{name}{extra}\"></i>");
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
        assert_eq!(num(1.23456789e-7), "0.000000123457");
        assert_eq!(num(123456.789), "123457");
    }
}
