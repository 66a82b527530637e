//! The spinning page of a picture bake: one element per piece and place, turned by one
//! shared `rotate` animation on the compositor, back faces hidden by the browser.

use std::fmt::Write as _;

use aspect_bake::{Bake, Spin};
use face_sort::Geometry;
use glam::{DMat3, DMat4, DVec3};

use crate::page_pieces::num;
use crate::spin::SpinOptions;

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
/// Faces are filled from `options.materials` (ignored in ID mode).
#[must_use]
pub fn write_culled_spin_html(
    bake: &Bake,
    lists: &[Vec<u32>],
    spin: &Spin,
    geometry: &Geometry,
    options: &SpinOptions,
) -> String {
    let colour = |face| crate::page::face_colour(options.materials.as_deref(), face);
    let view = spin.view_at(0.0);
    let graph_maps = sprite_compose::polygon_maps(bake.polygons(), geometry, &view);
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
    let copies = sprite_compose::culled_copies(lists, bake.polygons().len());
    let background = crate::page::background(options.background, options.ids);
    let mut page = crate::page::head("aspect-bake spin", w, h, background);
    let _ = write!(
        page,
        "#s{{position:absolute;left:{cx}px;top:{cy}px;width:0;height:0;perspective:{d}px;perspective-origin:0 0}}\n\
         body:not(:has(#end)) #s{{display:none}}\n\
         #s>i,#s>b{{position:absolute;left:0;top:0;transform-origin:0 0;backface-visibility:hidden;animation:t {timing}}}\n\
         b{{width:0;height:0;border-style:solid;border-color:transparent}}\n\
         @keyframes t{{from{{rotate:{x} {y} {z} {a0}deg}}to{{rotate:{x} {y} {z} {a1}deg}}}}\n",
        cx = num(origin.x),
        cy = num(origin.y),
        d = num(distance),
        x = num(axis.x),
        y = num(axis.y),
        z = num(axis.z),
        a0 = num(start),
        a1 = num(start + 360.0),
    );
    let elements_of = crate::page_pieces::piece_classes(
        &mut page,
        bake.polygons(),
        &graph_maps,
        geometry,
        &crate::page_pieces::Placement {
            place,
            place_point,
            scale: view.scale(),
            turning: crate::page_pieces::Turning::Spin {
                axis: axis.normalize(),
                distance,
            },
        },
        &crate::page_pieces::face_fill(options.ids, &colour),
        options.oversize,
    );
    // Visibility of each element: shown in the cells that use it, hidden in the cells where
    // another copy of its piece is used, either way where its piece is never drawn.
    let shown = copies.visibility(lists);
    let mut patterns: Vec<Vec<bool>> = Vec::new();
    let mut pattern_of: Vec<Option<usize>> = vec![None; copies.pieces().len()];
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
    for (e, &p) in copies.pieces().iter().enumerate() {
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
    fn numbers_are_short() {
        assert_eq!(num(0.5), "0.5");
        assert_eq!(num(-256.0), "-256");
        assert_eq!(num(1.23456789e-7), "1.23457e-7"); // shorter with an exponent, as CSS allows
        assert_eq!(num(123456.789), "123457");
    }
}
