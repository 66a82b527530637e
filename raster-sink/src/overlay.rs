//! Lines and points among faces, on a colour raster: the visible parts that
//! `sprite_compose::visible_overlay` computed, drawn after the faces.

use sprite_compose::DrawnOverlay;
use tiny_skia::{FillRule, LineCap, Paint, PathBuilder, Pixmap, Stroke, Transform};

/// Draws `overlay` on `pixmap` (typically [`render_colour`](crate::render_colour)'s output
/// of the same view): every visible line part stroked with butt ends, then every visible
/// point as a disc, anti-aliased or not.
pub fn draw_overlay(pixmap: &mut Pixmap, overlay: &DrawnOverlay, anti_alias: bool) {
    let paint = |c: [u8; 4]| {
        let mut paint = Paint::default();
        paint.set_color_rgba8(c[0], c[1], c[2], c[3]);
        paint.anti_alias = anti_alias;
        paint
    };
    for s in &overlay.strokes {
        let [a, b] = s.ends;
        let mut path = PathBuilder::new();
        path.move_to(a.x as f32, a.y as f32);
        path.line_to(b.x as f32, b.y as f32);
        let Some(path) = path.finish() else { continue };
        let stroke = Stroke {
            width: s.width_px as f32,
            line_cap: LineCap::Butt,
            ..Stroke::default()
        };
        pixmap.stroke_path(
            &path,
            &paint(s.colour),
            &stroke,
            Transform::identity(),
            None,
        );
    }
    for d in &overlay.dots {
        let Some(path) =
            PathBuilder::from_circle(d.centre.x as f32, d.centre.y as f32, d.radius_px as f32)
        else {
            continue;
        };
        pixmap.fill_path(
            &path,
            &paint(d.colour),
            FillRule::Winding,
            Transform::identity(),
            None,
        );
    }
}
