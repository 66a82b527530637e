//! Line drawings as files: a [`Plot`]'s visible edges as SVG strokes or HP-GL pen moves, and
//! a [`DrawnOverlay`] or a selection outline as SVG markup over the faces.

use std::fmt::Write as _;

use glam::DVec2;
use sprite_compose::{DrawnOverlay, Plot};

use crate::numbers::{hex, pixel};

/// An SVG of strokes only (no fills), one `<path>` per polyline, black, `stroke_px` wide.
#[must_use]
pub fn plot_svg(plot: &Plot, stroke_px: f64) -> String {
    let (w, h) = plot.size;
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n<g fill=\"none\" stroke=\"black\" stroke-width=\"{}\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n",
        pixel(stroke_px)
    );
    for line in &plot.polylines {
        s.push_str("<path d=\"");
        for (k, p) in line.iter().enumerate() {
            let _ = write!(
                s,
                "{}{} {}",
                if k == 0 { "M" } else { " L" },
                pixel(p.x),
                pixel(p.y)
            );
        }
        s.push_str("\"/>\n");
    }
    s.push_str("</g>\n</svg>\n");
    s
}

/// HP-GL for plotters that take it: `IN;SP1;`, then per polyline `PU x,y;PD x,y,…;`,
/// then `PU;SP0;`. `units_per_px` plotter units per pixel (40 units are 1 mm); y grows
/// upward, so the picture is flipped into the plotter's frame.
#[must_use]
pub fn plot_hpgl(plot: &Plot, units_per_px: f64) -> String {
    let h = f64::from(plot.size.1);
    let unit = |p: DVec2| {
        (
            (p.x * units_per_px).round() as i64,
            ((h - p.y) * units_per_px).round() as i64,
        )
    };
    let mut s = String::from("IN;SP1;\n");
    for line in &plot.polylines {
        let (x, y) = unit(line[0]);
        let _ = write!(s, "PU{x},{y};PD");
        for (k, &p) in line[1..].iter().enumerate() {
            let (x, y) = unit(p);
            let _ = write!(s, "{}{x},{y}", if k == 0 { "" } else { "," });
        }
        s.push_str(";\n");
    }
    s.push_str("PU;SP0;\n");
    s
}

/// SVG markup of the strokes (butt ends) then the dots, for
/// [`SvgOptions::with_overlay`](crate::SvgOptions::with_overlay): drawn after the faces.
#[must_use]
pub fn overlay_svg(overlay: &DrawnOverlay) -> String {
    let mut s = String::from("<g fill=\"none\" stroke-linecap=\"butt\">\n");
    for stroke in &overlay.strokes {
        let [a, b] = stroke.ends;
        let _ = writeln!(
            s,
            "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{}\" stroke-width=\"{}\"{}/>",
            pixel(a.x),
            pixel(a.y),
            pixel(b.x),
            pixel(b.y),
            hex(stroke.colour),
            pixel(stroke.width_px),
            alpha("stroke-opacity", stroke.colour)
        );
    }
    for dot in &overlay.dots {
        let _ = writeln!(
            s,
            "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"{}\"{}/>",
            pixel(dot.centre.x),
            pixel(dot.centre.y),
            pixel(dot.radius_px),
            hex(dot.colour),
            alpha("fill-opacity", dot.colour)
        );
    }
    s.push_str("</g>\n");
    s
}

/// ` name="a"` for a translucent colour, nothing for an opaque one.
fn alpha(name: &str, colour: [u8; 4]) -> String {
    if colour[3] == 255 {
        String::new()
    } else {
        format!(" {name}=\"{}\"", pixel(f64::from(colour[3]) / 255.0))
    }
}

/// An SVG `<path>` drawing outline segments (e.g. a selection highlight overlay).
#[must_use]
pub fn outline_svg_path(segments: &[[DVec2; 2]], stroke: [u8; 4], width: f64) -> String {
    let mut d = String::new();
    for [a, b] in segments {
        let _ = write!(d, "M{:.3} {:.3}L{:.3} {:.3}", a.x, a.y, b.x, b.y);
    }
    format!(
        "<path d=\"{d}\" fill=\"none\" stroke=\"{}\" stroke-opacity=\"{:.3}\" stroke-width=\"{width}\" stroke-linecap=\"round\"/>",
        hex(stroke),
        f64::from(stroke[3]) / 255.0
    )
}
