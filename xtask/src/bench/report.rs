//! The report: rows, the Markdown table (docs/bench.md), its format check, and the
//! console summary.

use std::fmt::Write as _;

use anyhow::{Result, bail};
use face_sort::SorterKind;
use serde::Serialize;

use super::timing::{TURN_PER_FRAME_DEG, WANDER_PER_FRAME_DEG};

/// One row of the report: a sorter on a scene under one projection, over every view.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// Sorter name (`plane-split` for the peer).
    pub sorter: String,
    /// Scene name.
    pub scene: String,
    /// `ortho` or `persp`.
    pub projection: String,
    /// Faces of the mesh.
    pub faces: usize,
    /// Pieces (planar faces plus fan triangles of non-planar ones).
    pub pieces: usize,
    /// Views measured.
    pub views: usize,
    /// Median per-frame cull+order time over every timed frame, microseconds; each timed
    /// frame turns the view a little (a new view every frame, as in an animation).
    pub frame_us: f64,
    /// `frame_us` ÷ the centroid sorter's on the same scene and projection.
    pub frame_ratio_vs_centroid: f64,
    /// The same, every timed frame repeating its view (which favours sorts: the CPU learns
    /// their branches).
    pub same_view_us: f64,
    /// `same_view_us` ÷ the centroid sorter's.
    pub same_view_ratio_vs_centroid: f64,
    /// Build time of cached state, milliseconds (0 for sorters without any).
    pub build_ms: f64,
    /// Mean number of items drawn per view (fragments included).
    pub fragments: f64,
    /// Wrong ÷ unambiguous pixels against the z-buffer truth, summed over views (a fraction,
    /// not a percentage); `null` when not measured.
    pub pixel_error: Option<f64>,
    /// Order violations from the oracle, summed over views.
    pub violations: usize,
    /// Anything skipped or unusual.
    pub note: String,
}

/// One row of the scaling series.
#[derive(Clone, Debug, Serialize)]
pub struct ScalingRow {
    /// Sorter name.
    pub sorter: String,
    /// Faces of the generated planar torus.
    pub faces: usize,
    /// Build time, milliseconds (`null` when skipped).
    pub build_ms: Option<f64>,
    /// Median per-frame time, microseconds (`null` when skipped).
    pub frame_us: Option<f64>,
    /// Mean items drawn.
    pub fragments: Option<f64>,
    /// Why a measurement was skipped.
    pub note: String,
}

pub(super) fn fmt_error(e: Option<f64>) -> String {
    match e {
        None => "n/a".to_owned(),
        Some(0.0) => "0".to_owned(),
        Some(e) => format!("{:.3} %", e * 100.0),
    }
}

fn fmt_ratio(ratio: f64) -> String {
    if ratio.is_finite() {
        format!("{ratio:.2}")
    } else {
        "—".to_owned()
    }
}

pub(super) fn fmt_time(us: f64) -> String {
    if us.is_nan() {
        "—".to_owned()
    } else if us < 1000.0 {
        format!("{us:.1} µs")
    } else {
        format!("{:.2} ms", us / 1000.0)
    }
}

/// The Markdown report (what `--docs` writes to docs/bench.md).
pub(super) fn markdown(
    command: &str,
    rows: &[Row],
    scaling: &[ScalingRow],
    resolution: u32,
) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Bench: time against error\n");
    // Reports from before the wandering camera have no such rows, and say nothing of it.
    let wander = if rows.iter().any(|r| r.projection.ends_with("wander")) {
        format!(
            "; rows *ortho wander* and *persp wander* turn it by {WANDER_PER_FRAME_DEG}° about a \
             random axis instead, and check their last view too"
        )
    } else {
        String::new()
    };
    let _ = writeln!(
        s,
        "Command: `{command}` (release build). Per scene and projection, every view of the set \
         (yaws × pitches) is measured; **frame** is the median cull+order time over all timed \
         frames, each of which turns the view by a further {TURN_PER_FRAME_DEG}° of yaw (a new view every \
         frame, as in an animation{wander}), **× centroid** its ratio to the centroid baseline in the \
         same run, **same view** and its **× centroid** the same with every timed frame \
         repeating its view (which favours sorts: the CPU learns their branches), **build** \
         the one-time cost, **items** the mean polygons drawn per view (fragments included), \
         **items × centroid** their ratio to the centroid's (both rounded as shown), \
         **pixel error** wrong ÷ unambiguous pixels against the z-buffer truth at \
         {resolution}×{resolution} (CONVENTIONS.md), **violations** the oracle's order \
         violations summed over views. plane-split is rebuilt every frame (as WebRender does).\n"
    );
    let _ = writeln!(
        s,
        "| scene | proj | faces | pieces | sorter | frame | × centroid | same view | × centroid | build | items | items × centroid | pixel error | violations | note |"
    );
    let _ = writeln!(
        s,
        "|---|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
    );
    // Items as the table shows them (formatting rounds half to even), so that the ratio
    // read back from the table is the one written.
    let shown = |v: f64| format!("{v:.0}").parse::<f64>().unwrap_or(f64::NAN);
    for r in rows {
        let items = shown(r.fragments);
        let centroid_items = centroid_of(rows, r).map(|c| shown(c.fragments));
        let items_ratio = fmt_ratio(
            centroid_items
                .filter(|&c| c > 0.0)
                .map_or(f64::NAN, |c| items / c),
        );
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.2} ms | {:.0} | {} | {} | {} | {} |",
            r.scene,
            r.projection,
            r.faces,
            r.pieces,
            r.sorter,
            fmt_time(r.frame_us),
            fmt_ratio(r.frame_ratio_vs_centroid),
            fmt_time(r.same_view_us),
            fmt_ratio(r.same_view_ratio_vs_centroid),
            r.build_ms,
            r.fragments,
            items_ratio,
            fmt_error(r.pixel_error),
            if r.views == 0 {
                "—".to_owned()
            } else {
                r.violations.to_string()
            },
            r.note
        );
    }
    if !scaling.is_empty() {
        let _ = writeln!(
            s,
            "\n## Scaling (generated planar torus, orthographic 512², two views)\n\n**build / face** is the build time shown divided by the faces (every face of the planar torus is one piece); **frame** repeats each view. Chart (log-log, written by the runs that measure the series): [bench-scaling.svg](bench-scaling.svg).\n\n| faces | sorter | build | build / face | frame | items | note |\n|---:|---|---:|---:|---:|---:|---|"
        );
        for r in scaling {
            let build = r.build_ms.map(|b| format!("{b:.1}"));
            let per_face = build.as_ref().map_or("—".to_owned(), |b| {
                let us = b.parse::<f64>().unwrap_or(f64::NAN) * 1e3 / r.faces.max(1) as f64;
                format!("{us:.2} µs")
            });
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} |",
                r.faces,
                r.sorter,
                build.map_or("—".to_owned(), |b| format!("{b} ms")),
                per_face,
                r.frame_us.map_or("—".to_owned(), fmt_time),
                r.fragments.map_or("—".to_owned(), |f| format!("{f:.0}")),
                r.note
            );
        }
    }
    s
}

/// The centroid baseline's row of the same scene and projection as `r`.
fn centroid_of<'a>(rows: &'a [Row], r: &Row) -> Option<&'a Row> {
    let centroid = SorterKind::Centroid.name();
    rows.iter()
        .find(|c| c.sorter == centroid && c.scene == r.scene && c.projection == r.projection)
}

/// The geometric mean (1 for none).
fn geo_mean(values: &[f64]) -> f64 {
    (values.iter().map(|v| v.ln()).sum::<f64>() / values.len().max(1) as f64).exp()
}

/// The console summary: per sorter, geometric-mean ratio to centroid, mean pixel error,
/// violations.
pub(super) fn summary(rows: &[Row]) -> String {
    let mut s = String::from(
        "sorter        ×centroid (geo-mean)  items ×centroid (geo-mean)  mean pixel error  violations  rows\n",
    );
    let mut seen: Vec<&str> = Vec::new();
    for r in rows {
        let name = r.sorter.as_str();
        if seen.contains(&name) {
            continue;
        }
        seen.push(name);
        let mine: Vec<&Row> = rows
            .iter()
            .filter(|r| r.sorter == name && r.views > 0)
            .collect();
        let ratios: Vec<f64> = mine
            .iter()
            .map(|r| r.frame_ratio_vs_centroid)
            .filter(|r| r.is_finite() && *r > 0.0)
            .collect();
        let geo = geo_mean(&ratios);
        let item_ratios: Vec<f64> = mine
            .iter()
            .filter_map(|r| {
                let c = centroid_of(rows, r)?;
                (c.fragments > 0.0).then(|| r.fragments / c.fragments)
            })
            .collect();
        let items_geo = geo_mean(&item_ratios);
        let errors: Vec<f64> = mine.iter().filter_map(|r| r.pixel_error).collect();
        let mean_error = errors.iter().sum::<f64>() / errors.len().max(1) as f64;
        let violations: usize = mine.iter().map(|r| r.violations).sum();
        let _ = writeln!(
            s,
            "{name:<13} {geo:>20.2} {items_geo:>27.2} {:>17} {violations:>11} {:>5}",
            if errors.is_empty() {
                "n/a".to_owned()
            } else {
                format!("{:.3} %", mean_error * 100.0)
            },
            mine.len()
        );
    }
    s.trim_end().to_owned()
}

/// The heading of docs/bench.md's hand-written notes: design measurements quoted by the
/// code's docs. Everything from it on is kept by `--docs` and not part of the report.
pub(super) const NOTES_HEADING: &str = "## Design measurements moved from rustdoc";

/// docs/bench.md split into the generated report and the hand-written notes after it
/// ([`NOTES_HEADING`], empty when there are none).
pub(super) fn split_notes(text: &str) -> (&str, &str) {
    match text.find(NOTES_HEADING) {
        Some(at) => (text[..at].trim_end(), &text[at..]),
        None => (text, ""),
    }
}

/// Checks that `text` (docs/bench.md) is in the format [`markdown`] writes: its command,
/// resolution, rows and scaling rows are parsed back and written again, and the result must
/// be the report part of `text` (before [`NOTES_HEADING`]) exactly. A changed column,
/// heading, explanation or number format fails.
pub(super) fn check_format(text: &str) -> Result<()> {
    let text = split_notes(text).0;
    let parsed = parse(text)?;
    let again = markdown(
        &parsed.command,
        &parsed.rows,
        &parsed.scaling,
        parsed.resolution,
    );
    if again.trim_end() == text.trim_end() {
        return Ok(());
    }
    let (line, (want, got)) = again
        .lines()
        .zip(text.lines())
        .enumerate()
        .find(|(_, (a, b))| a != b)
        .unwrap_or((
            again.lines().count().min(text.lines().count()),
            ("(end of text)", "(end of text)"),
        ));
    bail!(
        "line {}: the current format writes\n  {want}\nbut the file has\n  {got}",
        line + 1
    )
}

/// The rows of a report table (docs/bench.md), as [`markdown`] wrote them.
pub(super) fn parse_rows(text: &str) -> Result<Vec<Row>> {
    Ok(parse(text)?.rows)
}

/// The scaling rows of a report (docs/bench.md), as [`markdown`] wrote them.
pub(super) fn parse_scaling(text: &str) -> Result<Vec<ScalingRow>> {
    Ok(parse(text)?.scaling)
}

/// What a report table holds.
struct Parsed {
    command: String,
    resolution: u32,
    rows: Vec<Row>,
    scaling: Vec<ScalingRow>,
}

fn parse(text: &str) -> Result<Parsed> {
    let command = text
        .split_once("Command: `")
        .and_then(|(_, rest)| rest.split_once('`'))
        .map(|(c, _)| c.to_owned())
        .ok_or_else(|| anyhow::anyhow!("no \"Command: `…`\" line"))?;
    let resolution = text
        .split_once("z-buffer truth at ")
        .and_then(|(_, rest)| rest.split_once('×'))
        .and_then(|(r, _)| r.parse().ok())
        .ok_or_else(|| anyhow::anyhow!("no \"z-buffer truth at N×N\" resolution"))?;
    let mut rows = Vec::new();
    let mut scaling = Vec::new();
    let mut in_scaling = false;
    for line in text.lines() {
        if line.starts_with("## Scaling") {
            in_scaling = true;
            continue;
        }
        if !line.starts_with("| ") || line.starts_with("| scene ") || line.starts_with("| faces ") {
            continue;
        }
        let cells: Vec<&str> = line
            .strip_prefix("| ")
            .and_then(|l| l.strip_suffix(" |"))
            .unwrap_or(line)
            .split(" | ")
            .collect();
        if in_scaling {
            scaling.push(parse_scaling_row(&cells).map_err(|e| anyhow::anyhow!("{line}: {e}"))?);
        } else {
            rows.push(parse_row(&cells).map_err(|e| anyhow::anyhow!("{line}: {e}"))?);
        }
    }
    Ok(Parsed {
        command,
        resolution,
        rows,
        scaling,
    })
}

/// Inverse of [`fmt_time`].
fn parse_time(cell: &str) -> Result<f64> {
    if cell == "—" {
        return Ok(f64::NAN);
    }
    if let Some(us) = cell.strip_suffix(" µs") {
        return Ok(us.parse()?);
    }
    if let Some(ms) = cell.strip_suffix(" ms") {
        return Ok(ms.parse::<f64>()? * 1000.0);
    }
    bail!("not a time: {cell:?}")
}

/// Inverse of [`fmt_error`].
fn parse_error(cell: &str) -> Result<Option<f64>> {
    Ok(match cell {
        "n/a" => None,
        "0" => Some(0.0),
        _ => match cell.strip_suffix(" %") {
            Some(p) => Some(p.parse::<f64>()? / 100.0),
            None => bail!("not a pixel error: {cell:?}"),
        },
    })
}

fn parse_row(cells: &[&str]) -> Result<Row> {
    let [
        scene,
        projection,
        faces,
        pieces,
        sorter,
        frame,
        ratio,
        same_view,
        same_view_ratio,
        build,
        items,
        _items_ratio,
        error,
        violations,
        note,
    ] = cells
    else {
        bail!("{} cells, the table has 15", cells.len());
    };
    let parse_ratio = |cell: &str| -> Result<f64> {
        Ok(if cell == "—" {
            f64::NAN
        } else {
            cell.parse()?
        })
    };
    let build = build
        .strip_suffix(" ms")
        .ok_or_else(|| anyhow::anyhow!("build time without ms: {build:?}"))?;
    Ok(Row {
        sorter: (*sorter).to_owned(),
        scene: (*scene).to_owned(),
        projection: (*projection).to_owned(),
        faces: faces.parse()?,
        pieces: pieces.parse()?,
        views: usize::from(*violations != "—"),
        frame_us: parse_time(frame)?,
        frame_ratio_vs_centroid: parse_ratio(ratio)?,
        same_view_us: parse_time(same_view)?,
        same_view_ratio_vs_centroid: parse_ratio(same_view_ratio)?,
        build_ms: build.parse()?,
        fragments: items.parse()?,
        pixel_error: parse_error(error)?,
        violations: if *violations == "—" {
            0
        } else {
            violations.parse()?
        },
        note: note.trim_end().to_owned(),
    })
}

fn parse_scaling_row(cells: &[&str]) -> Result<ScalingRow> {
    let [faces, sorter, build, _per_face, frame, items, note] = cells else {
        bail!("{} cells, the scaling table has 7", cells.len());
    };
    let optional = |cell: &str| cell != "—";
    Ok(ScalingRow {
        sorter: (*sorter).to_owned(),
        faces: faces.parse()?,
        build_ms: match build.strip_suffix(" ms") {
            Some(b) if optional(build) => Some(b.parse()?),
            _ => None,
        },
        frame_us: if optional(frame) {
            Some(parse_time(frame)?)
        } else {
            None
        },
        fragments: if optional(items) {
            Some(items.parse()?)
        } else {
            None
        },
        note: note.trim_end().to_owned(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(sorter: &str, frame_us: f64, error: Option<f64>) -> Row {
        Row {
            sorter: sorter.to_owned(),
            scene: "spot".to_owned(),
            projection: "ortho".to_owned(),
            faces: 2928,
            pieces: 5854,
            views: 16,
            frame_us,
            frame_ratio_vs_centroid: frame_us / 75.7,
            same_view_us: frame_us * 0.8,
            same_view_ratio_vs_centroid: frame_us / 75.7,
            build_ms: 0.05,
            fragments: 2927.0,
            pixel_error: error,
            violations: 29,
            note: String::new(),
        }
    }

    fn sample() -> String {
        let rows = [
            row("centroid", 75.7, Some(0.0)),
            row("topological", 12010.0, Some(0.00059)),
            Row {
                views: 0,
                note: "skipped: 20000 pieces".to_owned(),
                ..row("plane-split", f64::NAN, None)
            },
        ];
        let scaling = [
            ScalingRow {
                sorter: "bsp".to_owned(),
                faces: 1014,
                build_ms: Some(3.2),
                frame_us: Some(25.0),
                fragments: Some(1500.0),
                note: String::new(),
            },
            ScalingRow {
                sorter: "plane-split".to_owned(),
                faces: 100_000,
                build_ms: None,
                frame_us: None,
                fragments: None,
                note: "skipped".to_owned(),
            },
        ];
        markdown("cargo xtask bench", &rows, &scaling, 256)
    }

    #[test]
    fn the_written_format_passes_its_check() {
        check_format(&sample()).unwrap();
    }

    #[test]
    fn items_are_compared_with_the_centroid_row_of_the_same_scene_and_projection() {
        let rows = [
            row("centroid", 75.7, Some(0.0)),
            Row {
                fragments: 5442.4,
                ..row("bsp", 92.0, Some(0.0))
            },
            Row {
                projection: "persp".to_owned(),
                ..row("bsp", 92.0, Some(0.0))
            },
        ];
        let text = markdown("cargo xtask bench", &rows, &[], 256);
        // 5442 / 2927 = 1.859…; no centroid row in perspective.
        assert!(text.contains("| 5442 | 1.86 |"), "{text}");
        assert!(text.contains("| 2927 | — |"), "{text}");
        check_format(&text).unwrap();
        // Halves: 638.5 is shown as 638 (formatting rounds half to even) and the ratio uses
        // what is shown, so that it reads back the same.
        let rows = [
            Row {
                fragments: 638.5,
                ..row("centroid", 7.0, Some(0.0))
            },
            Row {
                fragments: 4128.5,
                ..row("plane-split", 1150.0, Some(0.0))
            },
        ];
        let text = markdown("cargo xtask bench", &rows, &[], 256);
        assert!(text.contains("| 4128 | 6.47 |"), "{text}");
        check_format(&text).unwrap();
    }

    #[test]
    fn a_changed_format_fails_the_check() {
        let text = sample();
        // A column dropped from every row, a heading renamed, a number written differently.
        let dropped = text.replace(" | 0.05 ms |", " |");
        assert!(check_format(&dropped).is_err());
        let renamed = text.replace("## Scaling (generated planar torus", "## Scaling (torus");
        assert!(check_format(&renamed).is_err());
        let reformatted = text.replace("75.7 µs", "75.70 µs");
        assert!(check_format(&reformatted).is_err());
    }

    #[test]
    fn the_committed_docs_are_in_the_current_format() {
        let path = crate::workspace_root().join("docs/bench.md");
        let text = std::fs::read_to_string(&path).unwrap();
        check_format(&text).unwrap();
    }
}
