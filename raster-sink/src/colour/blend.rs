//! Filling and blending on the tiny-skia canvas: solid paints, polygon paths, and the
//! per-pixel "over" of shaders tiny-skia does not run (the ground grid).

use face_sort::glam::DVec2;
use tiny_skia::{FillRule, Paint, PathBuilder, Pixmap, PremultipliedColorU8, Transform};

/// A solid paint of a straight-alpha sRGB colour.
pub(super) fn paint_for(colour: [u8; 4], anti_alias: bool) -> Paint<'static> {
    let mut paint = Paint::default();
    let [r, g, b, a] = colour;
    paint.set_color_rgba8(r, g, b, a);
    paint.anti_alias = anti_alias;
    paint
}

/// A closed tiny-skia path through pixel-space points; `None` when tiny-skia finds it empty.
#[must_use]
pub fn polygon_path(points: &[DVec2]) -> Option<tiny_skia::Path> {
    let mut builder = PathBuilder::new();
    for (i, p) in points.iter().enumerate() {
        if i == 0 {
            builder.move_to(p.x as f32, p.y as f32);
        } else {
            builder.line_to(p.x as f32, p.y as f32);
        }
    }
    builder.close();
    builder.finish()
}

/// Fills a closed polygon (pixel-space points) with a paint, non-zero winding.
pub(super) fn fill(canvas: &mut Pixmap, points: &[DVec2], paint: &Paint<'_>) {
    if let Some(path) = polygon_path(points) {
        canvas.fill_path(&path, paint, FillRule::Winding, Transform::identity(), None);
    }
}

/// `src` (premultiplied, 0..1) over `dst`.
pub(super) fn blend_over(dst: PremultipliedColorU8, src: [f64; 4]) -> PremultipliedColorU8 {
    let inv = 1.0 - src[3];
    let c = |s: f64, d: u8| (s * 255.0 + f64::from(d) * inv).round().clamp(0.0, 255.0) as u8;
    let a = c(src[3], dst.alpha());
    let (r, g, b) = (
        c(src[0], dst.red()).min(a),
        c(src[1], dst.green()).min(a),
        c(src[2], dst.blue()).min(a),
    );
    PremultipliedColorU8::from_rgba(r, g, b, a).unwrap_or(dst)
}
