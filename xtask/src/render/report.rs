//! What `render` reports: the summary line and its `--json` form.

use std::time::Instant;

use serde::Serialize;

/// What `render --json` prints.
#[derive(Debug, Serialize)]
pub(super) struct Summary {
    pub(super) model: String,
    pub(super) output: String,
    pub(super) faces: usize,
    pub(super) drawn: usize,
    pub(super) fragments: usize,
    pub(super) sorter: &'static str,
    pub(super) plan: String,
    pub(super) load_ms: f64,
    pub(super) build_ms: f64,
    pub(super) sort_ms: f64,
    pub(super) raster_ms: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) pixel_error: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) violations: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) svg: Option<VectorSummary>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) pdf: Option<VectorSummary>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) plot: Option<PlotSummary>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) presorted: Option<PresortSummary>,
}

/// What `--plot` (and `--hpgl`) wrote.
#[derive(Debug, Serialize)]
pub(super) struct PlotSummary {
    /// Edges drawn (boundary, silhouette, crease, non-manifold), visible or not.
    pub(super) edges: usize,
    /// Of those, the ones with a visible part.
    pub(super) visible_edges: usize,
    pub(super) polylines: usize,
    /// Length drawn with the pen down, pixels.
    pub(super) pen_down_px: f64,
    /// Travel with the pen up between polylines, pixels.
    pub(super) pen_up_px: f64,
    pub(super) bytes: usize,
    /// Edge classification, hidden-line removal, joining and ordering.
    pub(super) plot_ms: f64,
}

/// What `--svg` or `--pdf` wrote.
#[derive(Debug, Serialize)]
pub(super) struct VectorSummary {
    /// SVG: `<polygon>` and `<path>` elements.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) shapes: Option<usize>,
    pub(super) bytes: usize,
    /// Hidden-part removal and writing.
    pub(super) write_ms: f64,
    pub(super) keep_hidden: bool,
}

/// What `--sorter presorted` built and did: the certificate's size, and whether this view
/// fell back to the BSP, and why (a refused build names its budget).
#[derive(Debug, Default, Serialize)]
pub(super) struct PresortSummary {
    pub(super) regions: usize,
    pub(super) orders: usize,
    /// Cycles left to per-frame BSP trees, and the pieces in them.
    pub(super) cores: usize,
    pub(super) core_pieces: usize,
    /// Threads the build used.
    pub(super) threads: usize,
    pub(super) fallback_frames: usize,
    /// Why the build stopped, when it did (every view is then drawn by the BSP).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) refused: Option<String>,
    /// Why this view fell back to the whole BSP, when the build finished and it did.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) fell_back: Option<String>,
    /// What drew the picture: "presorted" or "bsp".
    pub(super) drawn_by: &'static str,
    /// Where the certificate came from: built, built and saved, or loaded (`--presort-cache`).
    pub(super) certificate: String,
}

impl PresortSummary {
    /// The summary line's words.
    fn words(&self) -> String {
        if let Some(refused) = &self.refused {
            return format!("presorted build refused ({refused}); drawn by the BSP instead");
        }
        let base = format!(
            "presorted: {} regions, {} orders, {} cores of {} pieces, {} threads, certificate {}",
            self.regions, self.orders, self.cores, self.core_pieces, self.threads, self.certificate
        );
        match &self.fell_back {
            Some(why) => format!("{base}; this view fell back to the BSP ({why})"),
            None => base,
        }
    }
}

pub(super) fn line(s: &Summary) -> String {
    let mut out = format!(
        "{}: {} faces, {} drawn, {} fragments ({}); load {:.1} ms, build {:.1} ms, sort {:.2} ms, raster {:.1} ms",
        s.model,
        s.faces,
        s.drawn,
        s.fragments,
        s.sorter,
        s.load_ms,
        s.build_ms,
        s.sort_ms,
        s.raster_ms
    );
    if let (Some(e), Some(v)) = (s.pixel_error, s.violations) {
        out.push_str(&format!(
            "; pixel error {:.4} %, {v} order violations",
            e * 100.0
        ));
    }
    for (name, written) in [("svg", &s.svg), ("pdf", &s.pdf)] {
        if let Some(v) = written {
            let shapes = v
                .shapes
                .map(|n| format!("{n} shapes, "))
                .unwrap_or_default();
            let kept = if v.keep_hidden { " (hidden kept)" } else { "" };
            out.push_str(&format!(
                "; {name} {shapes}{} bytes, {:.1} ms{kept}",
                v.bytes, v.write_ms
            ));
        }
    }
    if let Some(p) = &s.presorted {
        out.push_str(&format!("; {}", p.words()));
    }
    if let Some(p) = &s.plot {
        out.push_str(&format!(
            "; plot {} of {} edges visible, {} polylines, pen down {:.0} px, pen up {:.0} px, {:.1} ms",
            p.visible_edges, p.edges, p.polylines, p.pen_down_px, p.pen_up_px, p.plot_ms
        ));
    }
    out.push_str(&format!(" -> {}", s.output));
    out
}

pub(super) fn ms(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}
