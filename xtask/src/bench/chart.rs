//! The chart of per-frame time (log scale) against pixel error: one mark per report row,
//! coloured by sorter, filled circles orthographic, hollow squares perspective. Drawn with
//! plotters' SVG backend, which writes text as SVG `<text>` and needs no system fonts.

use anyhow::{Result, anyhow};
use plotters::prelude::*;

use face_sort::SorterKind;

use super::{PEER, Row, ScalingRow};

/// One colour per sorter: the workspace's sorters in `SorterKind::ALL`'s order, then the peer.
const COLOURS: [RGBColor; SorterKind::ALL.len() + 1] = [
    RGBColor(0x7f, 0x7f, 0x7f),
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0x17, 0xbe, 0xcf),
    RGBColor(0xff, 0x7f, 0x0e),
];

/// The sorters in order of first appearance (the legend's order).
fn sorter_order<'a>(names: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut sorters: Vec<&str> = Vec::new();
    for name in names {
        if !sorters.contains(&name) {
            sorters.push(name);
        }
    }
    sorters
}

/// A sorter's colour, the same in every chart whichever sorters it shows.
fn colour_of(sorter: &str) -> RGBColor {
    let place = SorterKind::ALL
        .iter()
        .map(|k| k.name())
        .chain([PEER])
        .position(|n| n == sorter)
        .unwrap_or(0);
    COLOURS[place]
}

/// Chart size in pixels.
const SIZE: (u32, u32) = (760, 460);

/// The power of ten at or below `v`, and at or above it.
fn decade_below(v: f64) -> f64 {
    10f64.powf(v.log10().floor())
}

fn decade_above(v: f64) -> f64 {
    10f64.powf(v.log10().ceil())
}

/// The chart as SVG text.
pub(super) fn chart_svg(rows: &[Row]) -> Result<String> {
    let points: Vec<&Row> = rows
        .iter()
        .filter(|r| r.views > 0 && r.frame_us.is_finite() && r.frame_us > 0.0)
        .collect();
    let sorters = sorter_order(rows.iter().map(|r| r.sorter.as_str()));
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
    let (x0, x1) = (decade_below(lo), decade_above(hi));
    let max_error = points
        .iter()
        .filter_map(|r| r.pixel_error)
        .fold(0.0, f64::max)
        .max(1e-4)
        * 100.0;
    let y_max = nice_ceiling(max_error);

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
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
            let c = colour_of(name);
            let mine: Vec<&&Row> = points.iter().filter(|r| r.sorter == name).collect();
            let at = |r: &Row| (r.frame_us, r.pixel_error.unwrap_or(0.0) * 100.0);
            chart
                .draw_series(
                    mine.iter()
                        .filter(|r| r.projection.starts_with("ortho"))
                        .map(|r| Circle::new(at(r), 4, c.mix(0.75).filled())),
                )
                .map_err(|e| err(&e))?
                .label(name)
                .legend(move |(x, y)| Circle::new((x, y), 5, c.filled()));
            chart
                .draw_series(
                    mine.iter()
                        .filter(|r| !r.projection.starts_with("ortho"))
                        .map(|r| {
                            EmptyElement::at(at(r))
                                + Rectangle::new([(-4, -4), (4, 4)], c.stroke_width(2))
                        }),
                )
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

/// The scaling series on log-log axes: build time per face (lines) and per-frame time
/// (crosses) against faces, one colour per sorter; skipped measurements are absent.
pub(super) fn scaling_svg(rows: &[ScalingRow]) -> Result<String> {
    let sorters = sorter_order(rows.iter().map(|r| r.sorter.as_str()));
    // Below a nanosecond per face a build is a constructor, not a build: not drawn.
    let build_us = |r: &ScalingRow| {
        r.build_ms
            .map(|b| (r.faces as f64, b * 1e3 / r.faces.max(1) as f64))
            .filter(|&(_, us)| us >= 1e-3)
    };
    let frame_us = |r: &ScalingRow| {
        r.frame_us
            .map(|f| (r.faces as f64, f / r.faces.max(1) as f64))
            .filter(|&(_, us)| us >= 1e-3)
    };
    let values: Vec<(f64, f64)> = rows
        .iter()
        .flat_map(|r| [build_us(r), frame_us(r)])
        .flatten()
        .collect();
    let (fx0, fx1) = values
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &(x, _)| {
            (a.min(x), b.max(x))
        });
    let (fy0, fy1) = values
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &(_, y)| {
            (a.min(y), b.max(y))
        });
    if values.is_empty() {
        return Err(anyhow!("scaling chart: no measurement"));
    }
    let (x0, x1) = (fx0 / 1.5, fx1 * 1.5);
    // Three empty decades on top for the legend.
    let (y0, y1) = (
        decade_below(fy0),
        decade_above(fy1).max(decade_below(fy0) * 10.0) * 1e3,
    );
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        let err = |e: &dyn std::fmt::Display| anyhow!("scaling chart: {e}");
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "Generated planar torus: build per face (lines) and frame per face (crosses)",
                ("sans-serif", 14),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("faces (log scale)")
            .y_desc("µs per face (log scale)")
            .x_label_formatter(&|v| trim_number(*v))
            .y_label_formatter(&|v| trim_number(*v))
            .draw()
            .map_err(|e| err(&e))?;
        for &name in &sorters {
            let c = colour_of(name);
            let mine: Vec<&ScalingRow> = rows.iter().filter(|r| r.sorter == name).collect();
            let builds: Vec<(f64, f64)> = mine.iter().filter_map(|r| build_us(r)).collect();
            if !builds.is_empty() {
                chart
                    .draw_series(LineSeries::new(builds.clone(), c.stroke_width(2)))
                    .map_err(|e| err(&e))?
                    .label(format!("{name} build"))
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], c));
                chart
                    .draw_series(builds.iter().map(|&p| Circle::new(p, 3, c.filled())))
                    .map_err(|e| err(&e))?;
            }
            let frames: Vec<(f64, f64)> = mine.iter().filter_map(|r| frame_us(r)).collect();
            if !frames.is_empty() {
                chart
                    .draw_series(frames.iter().map(|&p| Cross::new(p, 5, c.stroke_width(2))))
                    .map_err(|e| err(&e))?
                    .label(format!("{name} frame"))
                    .legend(move |(x, y)| Cross::new((x + 8, y), 4, c.stroke_width(2)));
            }
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
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
