//! The ground grid brush: thick lines every tenth, fades, no moiré far away.

use raster_sink::face_sort::View;
use raster_sink::tiny_skia::Pixmap;
use raster_sink::{Brush, RasterOptions, Style, render_colour};

use crate::scenes::{centroid_list, grid_only};

fn luminance(image: &Pixmap, x: u32, y: u32) -> f64 {
    let p = image.pixel(x, y).expect("in image").demultiply();
    (f64::from(p.red()) + f64::from(p.green()) + f64::from(p.blue())) / 3.0
}

fn render(view: &View, size: f64, cell: f64) -> Pixmap {
    let (geometry, grid) = grid_only(size, cell);
    let style = Style::palette().with_face(0, Brush::Grid(grid));
    render_colour(
        view,
        &centroid_list(view, &geometry),
        &style,
        &RasterOptions::DEFAULT,
    )
    .expect("render")
}

#[test]
fn thick_lines_every_tenth_and_fade_toward_extent() {
    // Top view (pitch 90° shows the top), orthographic: ground x maps to screen x.
    let (geometry, _) = grid_only(4.0, 0.1);
    let view = View::fit(&geometry.bounds(), 400, 400)
        .with_yaw_pitch_roll(0.0, 90.0, 0.0)
        .with_scale(100.0);
    let image = render(&view, 4.0, 0.1);
    // Columns (sum of darkness over rows near the centre) at x = 0 (a tenth line), x = 0.3
    // (a thin line) and x = 0.35 (between lines). 100 px per unit, centre at 200.
    let darkness = |x: u32| -> f64 { (150..250).map(|y| 255.0 - luminance(&image, x, y)).sum() };
    let band = |centre: u32| -> f64 { (centre - 2..=centre + 2).map(darkness).sum() };
    let (thick, thin) = (band(200), band(230));
    assert!(thick > 1.6 * thin, "thick {thick} thin {thin}");
    // Between lines only the crossing horizontal lines darken a column.
    let (line, gap) = (darkness(230), darkness(235));
    assert!(line > 3.0 * gap, "line {line} gap {gap}");
    // Opacity falls toward the extent: the same thick line at the centre and near the edge
    // (ground |z| up to 2; fade starts at 0.6 · 2 = 1.2).
    let centre_line: f64 = (190..210).map(|y| 255.0 - luminance(&image, 200, y)).sum();
    let edge_line: f64 = (385..395)
        .map(|y| 255.0 - luminance(&image, 200, y))
        .sum::<f64>()
        * 2.0;
    assert!(
        edge_line < 0.2 * centre_line,
        "edge {edge_line} centre {centre_line}"
    );
}

#[test]
fn no_moire_far_away_and_fade_at_grazing_angles() {
    // A huge, fine grid seen at a low angle in perspective: cells far away are far below a
    // pixel. The level of detail must turn them into a smooth tone, not a pattern.
    let (geometry, _) = grid_only(400.0, 0.05);
    let view = View::fit(&geometry.bounds(), 320, 200)
        .with_yaw_pitch_roll(17.0, 20.0, 0.0)
        .with_scale(60.0)
        .with_perspective(320.0);
    let image = render(&view, 400.0, 0.05);
    // Rows above the near field but below the horizon: local variance (3×3 window around
    // each pixel) must stay small, unlike near the viewer where lines are resolved.
    let local_variance = |y0: u32, y1: u32| -> f64 {
        let mut total = 0.0;
        let mut n = 0.0;
        for y in y0..y1 {
            for x in 20..300 {
                let values: Vec<f64> = (0..3)
                    .flat_map(|dy| (0..3).map(move |dx| (x + dx, y + dy)))
                    .map(|(x, y)| luminance(&image, x, y))
                    .collect();
                let mean = values.iter().sum::<f64>() / 9.0;
                total += values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 9.0;
                n += 1.0;
            }
        }
        total / n
    };
    let horizon = (0..200)
        .find(|&y| (0..320).any(|x| luminance(&image, x, y) < 250.0))
        .expect("grid visible");
    let far = local_variance(horizon, horizon + 15);
    let near = local_variance(185, 197);
    assert!(near > 50.0, "near field shows lines: {near}");
    assert!(far < 0.05 * near, "far {far} near {near}");
    // Grazing: viewed almost edge-on the grid nearly vanishes.
    let graze = View::fit(&geometry.bounds(), 320, 200)
        .with_yaw_pitch_roll(0.0, 2.0, 0.0)
        .with_scale(60.0);
    let image = render(&graze, 400.0, 0.05);
    let darkest = (0..200)
        .flat_map(|y| (0..320).map(move |x| (x, y)))
        .map(|(x, y)| luminance(&image, x, y))
        .fold(255.0f64, f64::min);
    assert!(darkest > 200.0, "grazing grid too strong: {darkest}");
}
