//! The bench's and the fuzzer's view of `raster-sink`: truth and pixel error.

use face_sort::{DrawList, Geometry, View};
pub use raster_sink::Truth;

/// Wrong and unambiguous pixel counts of one draw list.
#[derive(Clone, Copy, Debug, Default)]
pub struct ErrorCounts {
    /// Unambiguous pixels.
    pub pixels: u64,
    /// Of those, painted with the wrong face.
    pub wrong: u64,
}

/// The z-buffer truth of a view (`None` if the image would be empty).
pub fn truth(view: &View, geometry: &Geometry) -> Option<Truth> {
    Some(raster_sink::truth(view, geometry))
}

/// The pixel error of `list` painted under `view`, against `truth`.
pub fn pixel_error(view: &View, list: &DrawList, truth: &Truth) -> ErrorCounts {
    let painted = raster_sink::render_ids(view, list);
    let e = raster_sink::pixel_error(&painted, truth);
    ErrorCounts {
        pixels: e.pixels as u64,
        wrong: e.wrong as u64,
    }
}

/// Colour options of `render`.
#[derive(Clone, Copy, Debug)]
pub struct ColourOptions {
    /// Anti-aliased edges.
    pub anti_alias: bool,
    /// Flat Lambert shading.
    pub shade: bool,
    /// A ground grid under the model (drawn once raster-sink's grid lands).
    #[expect(dead_code, reason = "raster-sink's ground grid has not landed yet")]
    pub grid: bool,
}

/// A colour image ready to save.
pub struct ColourImage(raster_sink::tiny_skia::Pixmap);

impl ColourImage {
    /// Writes a PNG.
    pub fn save(&self, path: &std::path::Path) -> anyhow::Result<()> {
        self.0
            .save_png(path)
            .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
    }
}

/// Paints `list` in order with flat colours (material diffuse, else a golden-angle palette).
pub fn render_colour(
    view: &View,
    list: &DrawList,
    mesh: &obj_quads::Mesh,
    _model: &std::path::Path,
    options: &ColourOptions,
) -> anyhow::Result<ColourImage> {
    use raster_sink::tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Transform};
    let mut pixmap = Pixmap::new(view.width(), view.height()).ok_or_else(|| {
        anyhow::anyhow!("cannot allocate a {}x{} image", view.width(), view.height())
    })?;
    pixmap.fill(Color::from_rgba8(250, 250, 250, 255));
    let mut scratch = face_sort::ProjectionScratch::default();
    let mut points = Vec::new();
    let light = face_sort::glam::DVec3::new(0.3, 0.5, 1.0).normalize();
    for &item in list.items() {
        view.project_polygon(list.corners(item), &mut points, &mut scratch);
        if points.len() < 3 {
            continue;
        }
        let face = item.face as usize;
        let base = mesh
            .face_material(face)
            .and_then(|m| mesh.materials().get(m as usize))
            .map(|m| {
                [
                    m.diffuse[0] as f64,
                    m.diffuse[1] as f64,
                    m.diffuse[2] as f64,
                ]
            })
            .unwrap_or_else(|| golden(face));
        let k = if options.shade {
            let n = view.to_view(list.plane(item).normal());
            0.35 + 0.65 * n.dot(light).abs()
        } else {
            1.0
        };
        let c = |v: f64| ((v * k).clamp(0.0, 1.0) * 255.0).round() as u8;
        let mut pb = PathBuilder::new();
        pb.move_to(points[0].x as f32, points[0].y as f32);
        for p in &points[1..] {
            pb.line_to(p.x as f32, p.y as f32);
        }
        pb.close();
        let Some(path) = pb.finish() else { continue };
        let mut paint = Paint::default();
        paint.set_color_rgba8(c(base[0]), c(base[1]), c(base[2]), 255);
        paint.anti_alias = options.anti_alias;
        pixmap.fill_path(
            &path,
            &paint,
            FillRule::Winding,
            Transform::identity(),
            None,
        );
    }
    Ok(ColourImage(pixmap))
}

/// Golden-angle hue per face index.
fn golden(face: usize) -> [f64; 3] {
    let h = (face as f64 * 137.507_764) % 360.0 / 60.0;
    let (s, v) = (0.55, 0.9);
    let c = v * s;
    let x = c * (1.0 - (h % 2.0 - 1.0).abs());
    let (r, g, b) = match h as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = v - c;
    [r + m, g + m, b + m]
}
