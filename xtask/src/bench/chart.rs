//! The chart of per-frame time (log scale) against pixel error: one mark per report row,
//! coloured by sorter, filled circles orthographic, hollow squares perspective. Drawn with
//! plotters' SVG backend, which writes text as SVG `<text>` and needs no system fonts.

use anyhow::{Result, anyhow};
use plotters::prelude::*;

use super::Row;

/// One colour per sorter, in order of first appearance.
const COLOURS: [RGBColor; 6] = [
    RGBColor(0x7f, 0x7f, 0x7f),
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0xff, 0x7f, 0x0e),
];

/// The chart as SVG text.
pub(super) fn chart_svg(rows: &[Row]) -> Result<String> {
    let points: Vec<&Row> = rows
        .iter()
        .filter(|r| r.views > 0 && r.frame_us.is_finite() && r.frame_us > 0.0)
        .collect();
    let mut sorters: Vec<&str> = Vec::new();
    for r in rows {
        if !sorters.contains(&r.sorter.as_str()) {
            sorters.push(&r.sorter);
        }
    }
    let lo = points
        .iter()
        .map(|r| r.frame_us)
        .fold(f64::INFINITY, f64::min)
        .max(0.01);
    let hi = points
        .iter()
        .map(|r| r.frame_us)
        .fold(0.0, f64::max)
        .max(lo * 10.0);
    let (x0, x1) = (
        10f64.powf(lo.log10().floor()),
        10f64.powf(hi.log10().ceil()),
    );
    let max_error = points
        .iter()
        .filter_map(|r| r.pixel_error)
        .fold(0.0, f64::max)
        .max(1e-4)
        * 100.0;
    let y_max = nice_ceiling(max_error);
    let colour = |sorter: &str| {
        COLOURS[sorters.iter().position(|&n| n == sorter).unwrap_or(0) % COLOURS.len()]
    };

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (760, 460)).into_drawing_area();
        let err = |e: &dyn std::fmt::Display| anyhow!("chart: {e}");
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "Per-frame cull+order time against pixel error (every scene, view set, projection)",
                ("sans-serif", 14),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d((x0..x1).log_scale(), 0.0..y_max)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("median frame time, µs (log scale)")
            .y_desc("pixel error, % (wrong ÷ unambiguous pixels)")
            .x_label_formatter(&|v| trim_number(*v))
            .y_label_formatter(&|v| format!("{} %", trim_number(*v)))
            .draw()
            .map_err(|e| err(&e))?;
        for &name in &sorters {
            let c = colour(name);
            let mine: Vec<&&Row> = points.iter().filter(|r| r.sorter == name).collect();
            let at = |r: &Row| (r.frame_us, r.pixel_error.unwrap_or(0.0) * 100.0);
            chart
                .draw_series(
                    mine.iter()
                        .filter(|r| r.projection == "ortho")
                        .map(|r| Circle::new(at(r), 4, c.mix(0.75).filled())),
                )
                .map_err(|e| err(&e))?
                .label(name)
                .legend(move |(x, y)| Circle::new((x, y), 5, c.filled()));
            chart
                .draw_series(mine.iter().filter(|r| r.projection != "ortho").map(|r| {
                    EmptyElement::at(at(r)) + Rectangle::new([(-4, -4), (4, 4)], c.stroke_width(2))
                }))
                .map_err(|e| err(&e))?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(&e))?;
        root.draw(&Text::new(
            "● orthographic   □ perspective",
            (80, 440),
            ("sans-serif", 12),
        ))
        .map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
    }
    Ok(svg)
}

/// The smallest of 1, 2, 5 × a power of ten at least `v`.
fn nice_ceiling(v: f64) -> f64 {
    let p = 10f64.powf(v.log10().floor());
    for m in [1.0, 2.0, 5.0, 10.0] {
        if v <= m * p {
            return m * p;
        }
    }
    10.0 * p
}

/// `v` with at most four decimals and no trailing zeros.
fn trim_number(v: f64) -> String {
    let s = format!("{v:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_owned()
}
