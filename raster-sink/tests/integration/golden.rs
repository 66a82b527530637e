//! Golden images: small PNGs under `tests/images/colour/`, compared with a tolerance.
//!
//! Equal means: every channel (straight RGBA) within [`MAX_CHANNEL_DIFF`] of the golden
//! image, except at most [`MAX_DIFFERING_FRACTION`] of the pixels. Regenerate with
//! `RASTER_SINK_BLESS=1 cargo test -p raster-sink --test integration golden`.

use std::path::PathBuf;

use raster_sink::face_sort::{Geometry, View};
use raster_sink::tiny_skia::Pixmap;
use raster_sink::{Brush, Light, RasterOptions, Style, render_colour, save_png};

use crate::common::{spot, spot_control};
use crate::scenes::{centroid_list, grid_first_list, textured_spot_style, with_grid};

/// Largest per-channel difference that counts as equal.
const MAX_CHANNEL_DIFF: u8 = 2;
/// Largest fraction of pixels allowed to differ by more than that.
const MAX_DIFFERING_FRACTION: f64 = 0.005;
const SIZE: u32 = 96;

fn golden_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/images/colour")
        .join(format!("{name}.png"))
}

fn compare(name: &str, image: &Pixmap) {
    let path = golden_path(name);
    if std::env::var_os("RASTER_SINK_BLESS").is_some_and(|v| v == "1") {
        std::fs::create_dir_all(path.parent().expect("dir")).expect("create dir");
        save_png(image, &path).expect("write golden");
        return;
    }
    let golden = Pixmap::load_png(&path).unwrap_or_else(|e| {
        panic!(
            "{}: {e}; create it with RASTER_SINK_BLESS=1 cargo test -p raster-sink --test integration golden",
            path.display()
        )
    });
    assert_eq!(
        (golden.width(), golden.height()),
        (image.width(), image.height()),
        "{name}: size"
    );
    let differing = golden
        .pixels()
        .iter()
        .zip(image.pixels())
        .filter(|(a, b)| {
            let (a, b) = (a.demultiply(), b.demultiply());
            [
                a.red().abs_diff(b.red()),
                a.green().abs_diff(b.green()),
                a.blue().abs_diff(b.blue()),
                a.alpha().abs_diff(b.alpha()),
            ]
            .into_iter()
            .any(|d| d > MAX_CHANNEL_DIFF)
        })
        .count();
    let fraction = differing as f64 / golden.pixels().len() as f64;
    if fraction > MAX_DIFFERING_FRACTION {
        let actual = std::env::temp_dir().join(format!("raster-sink-{name}.actual.png"));
        save_png(image, &actual).ok();
        panic!(
            "{name}: {differing} pixels ({:.2} %) differ from {}; actual image written to {}",
            fraction * 100.0,
            path.display(),
            actual.display()
        );
    }
}

fn spot_geometry() -> Geometry {
    Geometry::new(&test_support::polygon_mesh(&spot())).expect("spot")
}

#[test]
fn golden_solid() {
    let geometry = spot_geometry();
    let view = View::fit(&geometry.bounds(), SIZE, SIZE).with_yaw_pitch_roll(35.0, 15.0, 0.0);
    let image = render_colour(
        &view,
        &centroid_list(&view, &geometry),
        &Style::solid([230, 120, 40, 255]),
        &RasterOptions::DEFAULT,
    )
    .expect("render");
    compare("solid", &image);
}

#[test]
fn golden_palette() {
    let geometry = Geometry::new(&spot_control()).expect("spot");
    let view = View::fit(&geometry.bounds(), SIZE, SIZE).with_yaw_pitch_roll(-35.0, 15.0, 0.0);
    let image = render_colour(
        &view,
        &centroid_list(&view, &geometry),
        &Style::palette(),
        &RasterOptions::DEFAULT.with_background([30, 30, 30, 255]),
    )
    .expect("render");
    compare("palette", &image);
}

#[test]
fn golden_shaded() {
    let geometry = spot_geometry();
    let view = View::fit(&geometry.bounds(), SIZE, SIZE)
        .with_yaw_pitch_roll(35.0, 15.0, 0.0)
        .with_perspective(f64::from(SIZE) * 1.5);
    let image = render_colour(
        &view,
        &centroid_list(&view, &geometry),
        &Style::solid([240, 240, 235, 255]),
        &RasterOptions::DEFAULT
            .with_background([40, 70, 120, 255])
            .with_shading(Some(Light::DEFAULT)),
    )
    .expect("render");
    compare("shaded", &image);
}

#[test]
fn golden_textured() {
    let spot = spot();
    let geometry = Geometry::new(&test_support::polygon_mesh(&spot)).expect("spot");
    let style = textured_spot_style(&spot, &geometry);
    let view = View::fit(&geometry.bounds(), SIZE, SIZE).with_yaw_pitch_roll(35.0, 15.0, 0.0);
    let list = centroid_list(&view, &geometry);
    let image = render_colour(&view, &list, &style, &RasterOptions::DEFAULT).expect("render");
    compare("textured", &image);
    // Perspective, subdivided for a closer texture mapping, and shaded.
    let view = view.with_perspective(f64::from(SIZE));
    let list = centroid_list(&view, &geometry);
    let options = RasterOptions::DEFAULT
        .with_texture_subdivision(3)
        .with_shading(Some(Light::DEFAULT));
    let image = render_colour(&view, &list, &style, &options).expect("render");
    compare("textured_perspective_subdivided", &image);
}

#[test]
fn golden_grid() {
    let (mesh, grid, grid_face) = with_grid(&spot_control(), 2.0);
    let geometry = Geometry::new(&mesh).expect("geometry");
    let style = Style::solid([200, 200, 210, 255]).with_face(grid_face, Brush::Grid(grid));
    let view = View::fit(&geometry.bounds(), 160, 112)
        .with_yaw_pitch_roll(30.0, 25.0, 0.0)
        .with_perspective(f64::from(SIZE) * 1.2);
    let list = grid_first_list(&view, &geometry, grid_face);
    let options = RasterOptions::DEFAULT.with_shading(Some(Light::DEFAULT));
    let image = render_colour(&view, &list, &style, &options).expect("render");
    compare("grid", &image);
}

/// Writes larger renders to the temp dir for eyeballing (`RASTER_SINK_PREVIEW=1`).
#[test]
fn preview() {
    if std::env::var_os("RASTER_SINK_PREVIEW").is_none() {
        return;
    }
    let (mesh, grid, grid_face) = with_grid(&spot_control(), 2.0);
    let geometry = Geometry::new(&mesh).expect("geometry");
    let style = Style::solid([200, 200, 210, 255]).with_face(grid_face, Brush::Grid(grid));
    let view = View::fit(&geometry.bounds(), 768, 512)
        .with_yaw_pitch_roll(30.0, 25.0, 0.0)
        .with_perspective(600.0);
    let list = grid_first_list(&view, &geometry, grid_face);
    let options = RasterOptions::DEFAULT.with_shading(Some(Light::DEFAULT));
    let image = render_colour(&view, &list, &style, &options).expect("render");
    save_png(
        &image,
        std::env::temp_dir().join("raster-sink-preview-grid.png"),
    )
    .expect("save");
}
