//! `cargo xtask bench`: every sorter and the plane-split peer, time against error.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use clap::Args;
use face_sort::{DrawList, FaceSorter, Geometry, SorterKind, View, oracle};
use serde::Serialize;

use crate::peer::PlaneSplitPeer;
use crate::progress;
use crate::raster;
use crate::scenes::{self, Scene};

/// Options of `bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// A fast run (about a minute): fewer views and frames, scaling up to 10k faces.
    #[arg(long, conflicts_with = "full")]
    quick: bool,
    /// A long run: more frames per view, scaling up to 1M faces.
    #[arg(long)]
    full: bool,
    /// Also write the JSON report to FILE.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Copy the chart and the table to docs/bench.svg and docs/bench.md.
    #[arg(long)]
    docs: bool,
    /// Image size (square) for the pixel error against the z-buffer truth.
    #[arg(long, default_value_t = 256, value_name = "PX")]
    resolution: u32,
    /// Output directory. Default: target/bench.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Tiny run for tests: one small scene, one view, no scaling series.
    #[arg(long, hide = true)]
    smoke: bool,
}

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
    /// Median per-frame cull+order time over every timed frame, microseconds.
    pub frame_us: f64,
    /// `frame_us` ÷ the centroid sorter's on the same scene and projection.
    pub frame_ratio_vs_centroid: f64,
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

/// The whole JSON report.
#[derive(Debug, Serialize)]
struct Report<'a> {
    command: &'a str,
    rows: &'a [Row],
    scaling: &'a [ScalingRow],
}

/// How long to measure.
#[derive(Clone, Copy, Debug)]
struct Budget {
    yaws: usize,
    pitches: &'static [f64],
    frames: usize,
    per_view: Duration,
    scaling: &'static [usize],
    /// Largest piece count for per-frame peers with quadratic cost (plane-split, Newell).
    peer_pieces: usize,
    /// Longest estimated single measurement in the scaling series.
    scaling_limit: Duration,
}

const PEER: &str = "plane-split";

/// Runs the bench.
pub fn run(args: &BenchArgs) -> Result<ExitCode> {
    let budget = if args.smoke {
        Budget {
            yaws: 1,
            pitches: &[25.0],
            frames: 3,
            per_view: Duration::from_millis(5),
            scaling: &[],
            peer_pieces: 1000,
            scaling_limit: Duration::from_secs(1),
        }
    } else if args.quick {
        Budget {
            yaws: 4,
            pitches: &[25.0, -30.0],
            frames: 15,
            per_view: Duration::from_millis(15),
            scaling: &[1_000, 10_000],
            peer_pieces: 8_000,
            scaling_limit: Duration::from_secs(3),
        }
    } else if args.full {
        Budget {
            yaws: 8,
            pitches: &[25.0, -30.0],
            frames: 200,
            per_view: Duration::from_millis(150),
            scaling: &[1_000, 10_000, 100_000, 1_000_000],
            peer_pieces: 20_000,
            scaling_limit: Duration::from_secs(60),
        }
    } else {
        Budget {
            yaws: 8,
            pitches: &[25.0, -30.0],
            frames: 60,
            per_view: Duration::from_millis(40),
            scaling: &[1_000, 10_000, 100_000],
            peer_pieces: 20_000,
            scaling_limit: Duration::from_secs(30),
        }
    };
    let command = if args.smoke {
        "cargo xtask bench --smoke"
    } else if args.quick {
        "cargo xtask bench --quick"
    } else if args.full {
        "cargo xtask bench --full"
    } else {
        "cargo xtask bench"
    };

    let scenes = load_scenes(args.smoke)?;
    let bar = progress::bar(scenes.len() as u64 + budget.scaling.len() as u64, "bench");
    let mut rows = Vec::new();
    for scene in &scenes {
        bar.set_message(scene.name.clone());
        rows.extend(bench_scene(scene, &budget, args.resolution)?);
        bar.inc(1);
    }
    let mut scaling = Vec::new();
    for &faces in budget.scaling {
        bar.set_message(format!("scaling {faces}"));
        scaling.extend(scaling_size(faces, &budget, &scaling)?);
        bar.inc(1);
    }
    bar.finish_and_clear();

    let out = args
        .out
        .clone()
        .unwrap_or_else(|| crate::target_dir().join("bench"));
    std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
    let json = serde_json::to_string_pretty(&Report {
        command,
        rows: &rows,
        scaling: &scaling,
    })?;
    let rows_json = serde_json::to_string_pretty(&rows)?;
    write(&out.join("report.json"), &rows_json)?;
    write(&out.join("report-full.json"), &json)?;
    if let Some(path) = &args.json {
        write(path, &json)?;
    }
    let table = markdown(command, &rows, &scaling, args.resolution);
    write(&out.join("report.md"), &table)?;
    let chart = chart_svg(&rows);
    write(&out.join("chart.svg"), &chart)?;
    if args.docs {
        let docs = crate::workspace_root().join("docs");
        std::fs::create_dir_all(&docs)?;
        write(&docs.join("bench.md"), &table)?;
        write(&docs.join("bench.svg"), &chart)?;
    }
    println!("{}", summary(&rows));
    println!(
        "wrote {}, {}, {}",
        out.join("report.md").display(),
        out.join("report.json").display(),
        out.join("chart.svg").display()
    );
    Ok(ExitCode::SUCCESS)
}

fn write(path: &std::path::Path, text: &str) -> Result<()> {
    std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))
}

fn load_scenes(smoke: bool) -> Result<Vec<Scene>> {
    if smoke {
        return Ok(vec![scenes::cycle()?]);
    }
    let mut out = Vec::new();
    for (name, path) in scenes::MODELS {
        out.push(scenes::model_scene(name, path)?);
    }
    out.push(scenes::cycle()?);
    out.push(scenes::interpenetrating()?);
    out.push(scenes::nested_boxes()?);
    out.push(scenes::random_quads(60, 7)?);
    Ok(out)
}

/// The bench's views of a scene: `yaws` yaws (offset from the axes) × pitches.
fn views(geometry: &Geometry, scene: &Scene, budget: &Budget, size: u32, persp: bool) -> Vec<View> {
    let mut out = Vec::new();
    for k in 0..budget.yaws {
        let yaw = 15.0 + 360.0 * k as f64 / budget.yaws as f64;
        for &pitch in budget.pitches {
            let mut view = View::fit(&geometry.bounds(), size, size)
                .with_yaw_pitch_roll(yaw, pitch, 0.0)
                .with_cull(scene.cull);
            if persp {
                view = view.with_perspective(f64::from(size));
            }
            out.push(view);
        }
    }
    out
}

/// Times `frame` until `budget.frames` frames or `budget.per_view` elapsed (at least 3).
fn time_frames(budget: &Budget, times: &mut Vec<f64>, mut frame: impl FnMut()) {
    frame(); // warm-up: first-frame allocations are not the steady state.
    let start = Instant::now();
    for i in 0..budget.frames {
        let t = Instant::now();
        frame();
        times.push(t.elapsed().as_secs_f64() * 1e6);
        if i >= 2 && start.elapsed() >= budget.per_view {
            break;
        }
    }
}

fn median(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

/// Accumulates one (sorter, projection) over views.
#[derive(Default)]
struct Acc {
    times: Vec<f64>,
    items: usize,
    wrong: u64,
    unambiguous: u64,
    error_measured: bool,
    violations: usize,
    views: usize,
}

impl Acc {
    fn check(&mut self, view: &View, list: &DrawList, truth: Option<&raster::Truth>) {
        self.views += 1;
        self.items += list.len();
        self.violations += oracle::count_violations(view, list);
        if let Some(truth) = truth {
            let error = raster::pixel_error(view, list, truth);
            self.wrong += error.wrong;
            self.unambiguous += error.pixels;
            self.error_measured = true;
        }
    }

    fn row(
        mut self,
        sorter: &str,
        scene: &Scene,
        geometry: &Geometry,
        projection: &str,
        build_ms: f64,
    ) -> Row {
        Row {
            sorter: sorter.to_owned(),
            scene: scene.name.clone(),
            projection: projection.to_owned(),
            faces: geometry.face_count(),
            pieces: geometry.pieces().len(),
            views: self.views,
            frame_us: median(&mut self.times),
            frame_ratio_vs_centroid: f64::NAN,
            build_ms,
            fragments: self.items as f64 / self.views.max(1) as f64,
            pixel_error: self
                .error_measured
                .then(|| self.wrong as f64 / self.unambiguous.max(1) as f64),
            violations: self.violations,
            note: String::new(),
        }
    }
}

fn bench_scene(scene: &Scene, budget: &Budget, resolution: u32) -> Result<Vec<Row>> {
    let geometry = Geometry::new(&scene.mesh).with_context(|| format!("scene {}", scene.name))?;
    let mut sorters: Vec<(Box<dyn FaceSorter>, f64)> = SorterKind::ALL
        .into_iter()
        .map(|kind| {
            let start = Instant::now();
            let sorter = kind.build(&geometry);
            let measured = start.elapsed().as_secs_f64() * 1e3;
            (sorter, measured)
        })
        .collect();
    let pieces = geometry.pieces().len();
    let run_peer = pieces <= budget.peer_pieces;
    let mut peer = PlaneSplitPeer::new(&geometry);
    let mut list = DrawList::new();
    let mut rows = Vec::new();
    for (projection, persp) in [("ortho", false), ("persp", true)] {
        let views = views(&geometry, scene, budget, resolution, persp);
        let mut accs: Vec<Acc> = sorters.iter().map(|_| Acc::default()).collect();
        let mut peer_acc = Acc::default();
        for view in &views {
            let truth = raster::truth(view, &geometry);
            for ((sorter, _), acc) in sorters.iter_mut().zip(accs.iter_mut()) {
                time_frames(budget, &mut acc.times, || sorter.sort(view, &mut list));
                acc.check(view, &list, truth.as_ref());
            }
            if run_peer {
                time_frames(budget, &mut peer_acc.times, || {
                    peer.frame(view);
                });
                peer.write_draw_list(view, &mut list);
                peer_acc.check(view, &list, truth.as_ref());
            }
        }
        let mut scene_rows: Vec<Row> = sorters
            .iter()
            .zip(accs)
            .map(|((sorter, measured), acc)| {
                let build_ms = match sorter.stats().build_ms {
                    b if b > 0.0 => b,
                    _ => *measured,
                };
                acc.row(sorter.name(), scene, &geometry, projection, build_ms)
            })
            .collect();
        if run_peer {
            let mut row = peer_acc.row(PEER, scene, &geometry, projection, 0.0);
            row.note = "rebuilt every frame".to_owned();
            scene_rows.push(row);
        } else {
            let mut row = Acc::default().row(PEER, scene, &geometry, projection, 0.0);
            row.note = format!(
                "skipped: {pieces} pieces > {} (per-frame rebuild)",
                budget.peer_pieces
            );
            scene_rows.push(row);
        }
        let base = scene_rows
            .iter()
            .find(|r| r.sorter == "centroid")
            .map_or(f64::NAN, |r| r.frame_us);
        for row in &mut scene_rows {
            row.frame_ratio_vs_centroid = row.frame_us / base;
        }
        rows.extend(scene_rows);
    }
    Ok(rows)
}

/// Scaling: build and per-frame time of every sorter on a planar torus of `faces` faces; skips a
/// measurement whose estimate from the previous sizes exceeds the budget.
fn scaling_size(faces: usize, budget: &Budget, previous: &[ScalingRow]) -> Result<Vec<ScalingRow>> {
    let scene = scenes::planar_torus(faces);
    let geometry = Geometry::new(&scene.mesh)?;
    let faces = geometry.face_count();
    let views: Vec<View> = [(30.0, 25.0), (200.0, -30.0)]
        .into_iter()
        .map(|(yaw, pitch)| {
            View::fit(&geometry.bounds(), 512, 512).with_yaw_pitch_roll(yaw, pitch, 0.0)
        })
        .collect();
    let limit_ms = budget.scaling_limit.as_secs_f64() * 1e3;
    // Extrapolates from the previous sizes with the growth exponent seen between the last
    // two (clamped to 1..=2; 2 when there is only one).
    let estimate = |sorter: &str, pick: fn(&ScalingRow) -> Option<f64>, scale_ms: f64| {
        let mut points: Vec<(usize, f64)> = previous
            .iter()
            .filter(|r| r.sorter == sorter)
            .filter_map(|r| pick(r).map(|v| (r.faces, v)))
            .collect();
        points.sort_by_key(|&(f, _)| f);
        let &(f1, v1) = points.last()?;
        let exponent = match points.len() {
            n if n >= 2 => {
                let (f0, v0) = points[n - 2];
                ((v1 / v0).ln() / (f1 as f64 / f0 as f64).ln()).clamp(1.0, 2.0)
            }
            _ => 2.0,
        };
        Some(v1 * scale_ms * (faces as f64 / f1 as f64).powf(exponent))
    };
    let skipped_before = |sorter: &str| {
        previous
            .iter()
            .any(|r| r.sorter == sorter && r.frame_us.is_none())
    };
    let frame_budget = Budget {
        frames: budget.frames.min(20),
        per_view: budget.per_view * 4,
        ..*budget
    };
    let mut out = Vec::new();
    let mut list = DrawList::new();
    for kind in SorterKind::ALL {
        let name = kind.name();
        let build_estimate = estimate(name, |r| r.build_ms, 1.0).unwrap_or(0.0);
        let frame_estimate = estimate(name, |r| r.frame_us, 1e-3).unwrap_or(0.0);
        if skipped_before(name) || build_estimate > limit_ms || frame_estimate * 4.0 > limit_ms {
            out.push(ScalingRow {
                sorter: name.to_owned(),
                faces,
                build_ms: None,
                frame_us: None,
                fragments: None,
                note: format!(
                    "skipped: estimated build {:.0} ms / frame {:.0} ms over the {:.0} s limit",
                    build_estimate,
                    frame_estimate,
                    limit_ms / 1e3
                ),
            });
            continue;
        }
        let start = Instant::now();
        let mut sorter = kind.build(&geometry);
        let measured = start.elapsed().as_secs_f64() * 1e3;
        let build_ms = match sorter.stats().build_ms {
            b if b > 0.0 => b,
            _ => measured,
        };
        let mut times = Vec::new();
        let mut items = 0;
        for view in &views {
            time_frames(&frame_budget, &mut times, || sorter.sort(view, &mut list));
            items += list.len();
        }
        out.push(ScalingRow {
            sorter: name.to_owned(),
            faces,
            build_ms: Some(build_ms),
            frame_us: Some(median(&mut times)),
            fragments: Some(items as f64 / views.len() as f64),
            note: String::new(),
        });
    }
    // The peer, per-frame only.
    let pieces = geometry.pieces().len();
    let frame_estimate = estimate(PEER, |r| r.frame_us, 1e-3).unwrap_or(0.0);
    if pieces > budget.peer_pieces || skipped_before(PEER) || frame_estimate * 4.0 > limit_ms {
        out.push(ScalingRow {
            sorter: PEER.to_owned(),
            faces,
            build_ms: None,
            frame_us: None,
            fragments: None,
            note: format!(
                "skipped: {pieces} pieces, rebuilt per frame (limit {})",
                budget.peer_pieces
            ),
        });
    } else {
        let mut peer = PlaneSplitPeer::new(&geometry);
        let mut times = Vec::new();
        let mut items = 0;
        for view in &views {
            time_frames(&frame_budget, &mut times, || {
                items = peer.frame(view);
            });
        }
        out.push(ScalingRow {
            sorter: PEER.to_owned(),
            faces,
            build_ms: Some(0.0),
            frame_us: Some(median(&mut times)),
            fragments: Some(items as f64),
            note: "rebuilt every frame".to_owned(),
        });
    }
    Ok(out)
}

fn fmt_error(e: Option<f64>) -> String {
    match e {
        None => "n/a".to_owned(),
        Some(0.0) => "0".to_owned(),
        Some(e) => format!("{:.3} %", e * 100.0),
    }
}

fn fmt_time(us: f64) -> String {
    if us.is_nan() {
        "—".to_owned()
    } else if us < 1000.0 {
        format!("{us:.1} µs")
    } else {
        format!("{:.2} ms", us / 1000.0)
    }
}

fn markdown(command: &str, rows: &[Row], scaling: &[ScalingRow], resolution: u32) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Bench: time against error\n");
    let _ = writeln!(
        s,
        "Command: `{command}` (release build). Per scene and projection, every view of the set \
         (yaws × pitches) is measured; **frame** is the median cull+order time over all timed \
         frames, **× centroid** its ratio to the centroid baseline in the same run, **build** \
         the one-time cost, **items** the mean polygons drawn per view (fragments included), \
         **pixel error** wrong ÷ unambiguous pixels against the z-buffer truth at \
         {resolution}×{resolution} (CONVENTIONS.md), **violations** the oracle's order \
         violations summed over views. plane-split is rebuilt every frame (as WebRender does).\n"
    );
    let _ = writeln!(
        s,
        "| scene | proj | faces | pieces | sorter | frame | × centroid | build | items | pixel error | violations | note |"
    );
    let _ = writeln!(
        s,
        "|---|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---|"
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {:.2} ms | {:.0} | {} | {} | {} |",
            r.scene,
            r.projection,
            r.faces,
            r.pieces,
            r.sorter,
            fmt_time(r.frame_us),
            if r.frame_ratio_vs_centroid.is_finite() {
                format!("{:.2}", r.frame_ratio_vs_centroid)
            } else {
                "—".to_owned()
            },
            r.build_ms,
            r.fragments,
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
            "\n## Scaling (generated planar torus, orthographic 512², two views)\n\n| faces | sorter | build | frame | items | note |\n|---:|---|---:|---:|---:|---|"
        );
        for r in scaling {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} |",
                r.faces,
                r.sorter,
                r.build_ms.map_or("—".to_owned(), |b| format!("{b:.1} ms")),
                r.frame_us.map_or("—".to_owned(), fmt_time),
                r.fragments.map_or("—".to_owned(), |f| format!("{f:.0}")),
                r.note
            );
        }
    }
    s
}

fn summary(rows: &[Row]) -> String {
    let mut s =
        String::from("sorter        ×centroid (geo-mean)  mean pixel error  violations  rows\n");
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
        let geo = (ratios.iter().map(|r| r.ln()).sum::<f64>() / ratios.len().max(1) as f64).exp();
        let errors: Vec<f64> = mine.iter().filter_map(|r| r.pixel_error).collect();
        let mean_error = errors.iter().sum::<f64>() / errors.len().max(1) as f64;
        let violations: usize = mine.iter().map(|r| r.violations).sum();
        let _ = writeln!(
            s,
            "{name:<13} {geo:>20.2} {:>17} {violations:>11} {:>5}",
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

const COLOURS: [&str; 6] = [
    "#7f7f7f", "#1f77b4", "#2ca02c", "#d62728", "#9467bd", "#ff7f0e",
];

/// A scatter chart of per-frame time (log x) against pixel error (y), one mark per row,
/// coloured by sorter; circles orthographic, squares perspective. Hand-written SVG.
fn chart_svg(rows: &[Row]) -> String {
    let (w, h) = (760.0, 460.0);
    let (left, right, top, bottom) = (70.0, 170.0, 30.0, 50.0);
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
    let (x0, x1) = (lo.log10().floor(), hi.log10().ceil());
    let max_error = points
        .iter()
        .filter_map(|r| r.pixel_error)
        .fold(0.0, f64::max)
        .max(1e-4)
        * 100.0;
    let y_max = nice_ceiling(max_error);
    let px = |us: f64| left + (us.log10() - x0) / (x1 - x0) * (w - left - right);
    let py = |e: f64| top + (1.0 - e / y_max) * (h - top - bottom);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="18" text-anchor="middle" font-size="14">Per-frame cull+order time against pixel error (every scene, view set, projection)</text>"#,
        w / 2.0
    );
    // Axes and grid.
    let (gx0, gx1, gy0, gy1) = (left, w - right, top, h - bottom);
    for d in (x0 as i32)..=(x1 as i32) {
        let x = px(10f64.powi(d));
        let label = match d {
            d if d < 3 => format!("{} µs", 10f64.powi(d)),
            d if d < 6 => format!("{} ms", 10f64.powi(d - 3)),
            d => format!("{} s", 10f64.powi(d - 6)),
        };
        let _ = writeln!(
            s,
            r##"<line x1="{x:.1}" y1="{gy0}" x2="{x:.1}" y2="{gy1}" stroke="#ddd"/><text x="{x:.1}" y="{}" text-anchor="middle">{label}</text>"##,
            gy1 + 16.0
        );
    }
    for k in 0..=4 {
        let e = y_max * f64::from(k) / 4.0;
        let y = py(e);
        let _ = writeln!(
            s,
            r##"<line x1="{gx0}" y1="{y:.1}" x2="{gx1}" y2="{y:.1}" stroke="#ddd"/><text x="{}" y="{:.1}" text-anchor="end">{} %</text>"##,
            gx0 - 6.0,
            y + 4.0,
            trim_number(e)
        );
    }
    let _ = writeln!(
        s,
        r##"<rect x="{gx0}" y="{gy0}" width="{}" height="{}" fill="none" stroke="#333"/>"##,
        gx1 - gx0,
        gy1 - gy0
    );
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">median frame time (log scale)</text>"#,
        (gx0 + gx1) / 2.0,
        h - 12.0
    );
    let _ = writeln!(
        s,
        r#"<text transform="translate(16 {}) rotate(-90)" text-anchor="middle">pixel error (wrong ÷ unambiguous pixels)</text>"#,
        (gy0 + gy1) / 2.0
    );
    for r in &points {
        let colour =
            COLOURS[sorters.iter().position(|&n| n == r.sorter).unwrap_or(0) % COLOURS.len()];
        let (x, y) = (px(r.frame_us), py(r.pixel_error.unwrap_or(0.0) * 100.0));
        let title = format!(
            "{} on {} ({}): {}, error {}, {} violations",
            r.sorter,
            r.scene,
            r.projection,
            fmt_time(r.frame_us),
            fmt_error(r.pixel_error),
            r.violations
        );
        if r.projection == "ortho" {
            let _ = writeln!(
                s,
                r#"<circle cx="{x:.1}" cy="{y:.1}" r="4" fill="{colour}" fill-opacity="0.75"><title>{title}</title></circle>"#
            );
        } else {
            let _ = writeln!(
                s,
                r#"<rect x="{:.1}" y="{:.1}" width="8" height="8" fill="none" stroke="{colour}" stroke-width="1.5"><title>{title}</title></rect>"#,
                x - 4.0,
                y - 4.0
            );
        }
    }
    for (i, name) in sorters.iter().enumerate() {
        let y = top + 10.0 + 20.0 * i as f64;
        let x = w - right + 20.0;
        let _ = writeln!(
            s,
            r#"<circle cx="{x}" cy="{y}" r="5" fill="{}"/><text x="{}" y="{}">{name}</text>"#,
            COLOURS[i % COLOURS.len()],
            x + 12.0,
            y + 4.0
        );
    }
    let y = top + 10.0 + 20.0 * sorters.len() as f64 + 10.0;
    let x = w - right + 20.0;
    let _ = writeln!(
        s,
        r##"<circle cx="{x}" cy="{y}" r="4" fill="#555"/><text x="{}" y="{}">orthographic</text><rect x="{}" y="{}" width="8" height="8" fill="none" stroke="#555" stroke-width="1.5"/><text x="{}" y="{}">perspective</text>"##,
        x + 12.0,
        y + 4.0,
        x - 4.0,
        y + 16.0,
        x + 12.0,
        y + 24.0
    );
    s.push_str("</svg>\n");
    s
}

fn nice_ceiling(v: f64) -> f64 {
    let p = 10f64.powf(v.log10().floor());
    for m in [1.0, 2.0, 5.0, 10.0] {
        if v <= m * p {
            return m * p;
        }
    }
    10.0 * p
}

fn trim_number(v: f64) -> String {
    let s = format!("{v:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_owned()
}
