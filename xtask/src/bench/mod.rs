//! `cargo xtask bench`: every sorter and the plane-split peer, time against error.
//!
//! One concern per module: this one is the command line and the run; [`timing`] measures
//! frames and checks orders on the repository's scenes, [`scaling`] runs the generated
//! series with its extrapolated budget, [`report`] writes (and checks) the table and the
//! summary, [`chart`] draws time against error with plotters.

mod chart;
mod presort_scaling;
mod report;
mod scaling;
mod timing;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use anyhow::{Context, Result};
use clap::Args;
use serde::Serialize;

use crate::progress;
use crate::scenes::{self, Scene};
pub use report::{Row, ScalingRow};
pub(crate) use timing::median;

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
    /// With --docs: run nothing, only check that docs/bench.md is in the report format this
    /// code writes (its table parsed and written again gives the same text); fails otherwise.
    #[arg(long, requires = "docs")]
    check: bool,
    /// With --docs: run nothing, redraw docs/bench.svg from the rows of docs/bench.md (after
    /// a change to the chart only).
    #[arg(long, requires = "docs", conflicts_with = "check")]
    redraw_chart: bool,
    /// Image size (square) for the pixel error against the z-buffer truth.
    #[arg(long, default_value_t = 256, value_name = "PX")]
    resolution: u32,
    /// Output directory. Default: target/bench.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Tiny run for tests: one small scene, one view, no scaling series.
    #[arg(long, hide = true)]
    smoke: bool,
    /// Keep each scene's `Presorted` certificate in DIR (`SCENE.presort`): load it when it
    /// holds one for the scene, else build it and save it there. The row's build time is then
    /// the load time, and its note says so.
    #[arg(long, value_name = "DIR")]
    presort_cache: Option<PathBuf>,
    /// Run only the `Presorted` scaling series (bumpy tori of 10³ to 10⁶ faces, with
    /// --quick 10³ and 10⁴; then the 69,168-triangle scan-like blob): build time, peak memory, certificate bytes, per-frame time and
    /// items against the centroid sort. Writes OUT/presort-scaling.md (with --docs also
    /// docs/bench-presort.md).
    #[arg(long)]
    presort_scaling: bool,
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
pub(crate) struct Budget {
    pub yaws: usize,
    pub pitches: &'static [f64],
    pub frames: usize,
    pub per_view: Duration,
    pub scaling: &'static [usize],
    /// Largest piece count for per-frame peers with quadratic cost (plane-split, Newell).
    pub peer_pieces: usize,
    /// Longest estimated single measurement in the scaling series.
    pub scaling_limit: Duration,
}

/// The peer's name in tables.
const PEER: &str = "plane-split";

/// Runs the bench.
pub fn run(args: &BenchArgs) -> Result<ExitCode> {
    if args.check {
        return check_report();
    }
    if args.redraw_chart {
        return redraw_charts();
    }
    let budget = Budget::of(args);
    let command = if args.smoke {
        "cargo xtask bench --smoke"
    } else if args.quick {
        "cargo xtask bench --quick"
    } else if args.full {
        "cargo xtask bench --full"
    } else {
        "cargo xtask bench"
    };

    if args.presort_scaling {
        let sizes: &[usize] = if args.smoke {
            &[200]
        } else if args.quick {
            &[1_000, 10_000]
        } else {
            &[1_000, 10_000, 100_000, 1_000_000]
        };
        let command = format!("{command} --presort-scaling");
        let out = args
            .out
            .clone()
            .unwrap_or_else(|| crate::target_dir().join("bench"));
        let table = presort_scaling::run(
            sizes,
            !args.smoke,
            &budget,
            &command,
            &out.join("presort-scaling.md"),
        )?;
        if args.docs {
            write(
                &crate::workspace_root().join("docs/bench-presort.md"),
                &table,
            )?;
        }
        println!("{table}");
        return Ok(ExitCode::SUCCESS);
    }
    let scenes = load_scenes(args.smoke)?;
    let bar = progress::bar(scenes.len() as u64 + budget.scaling.len() as u64, "bench");
    let mut rows = Vec::new();
    for scene in &scenes {
        bar.set_message(scene.name.clone());
        rows.extend(timing::bench_scene(
            scene,
            &budget,
            args.resolution,
            args.presort_cache.as_deref(),
        )?);
        bar.inc(1);
    }
    let mut scaling = Vec::new();
    for &faces in budget.scaling {
        bar.set_message(format!("scaling {faces}"));
        scaling.extend(scaling::scaling_size(faces, &budget, &scaling)?);
        bar.inc(1);
    }
    bar.finish_and_clear();

    let out = write_reports(args, command, &rows, &scaling)?;
    println!("{}", report::summary(&rows));
    println!(
        "wrote {}, {}, {}",
        out.join("report.md").display(),
        out.join("report.json").display(),
        out.join("chart.svg").display()
    );
    Ok(ExitCode::SUCCESS)
}

/// `--check`: docs/bench.md is in the current report format.
fn check_report() -> Result<ExitCode> {
    let path = crate::workspace_root().join("docs/bench.md");
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    report::check_format(&text).with_context(|| {
        format!(
            "{} is not in the current report format; regenerate it with `cargo xtask bench --docs`",
            path.display()
        )
    })?;
    println!("{}: in the current report format", path.display());
    Ok(ExitCode::SUCCESS)
}

/// `--redraw-chart`: the charts of docs/ drawn again from docs/bench.md's rows.
fn redraw_charts() -> Result<ExitCode> {
    let docs = crate::workspace_root().join("docs");
    let text = std::fs::read_to_string(docs.join("bench.md"))
        .with_context(|| format!("reading {}", docs.join("bench.md").display()))?;
    let text = report::split_notes(&text).0;
    let rows = report::parse_rows(text)?;
    write(&docs.join("bench.svg"), &chart::chart_svg(&rows)?)?;
    println!(
        "redrew {} from {} rows",
        docs.join("bench.svg").display(),
        rows.len()
    );
    let scaling = report::parse_scaling(text)?;
    if !scaling.is_empty() {
        write(
            &docs.join("bench-scaling.svg"),
            &chart::scaling_svg(&scaling)?,
        )?;
        println!(
            "redrew {} from {} scaling rows",
            docs.join("bench-scaling.svg").display(),
            scaling.len()
        );
    }
    Ok(ExitCode::SUCCESS)
}

impl Budget {
    /// The budget `--smoke`, `--quick`, `--full` or the default asks for.
    fn of(args: &BenchArgs) -> Budget {
        if args.smoke {
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
                // Long enough for the BSP build of the million-face torus (minutes): the point of
                // the full run is the growth curve to 1M faces.
                scaling_limit: Duration::from_secs(600),
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
        }
    }
}

/// The report in `--out` (markdown, JSON, charts), `--json`, and with `--docs` docs/bench.md
/// (keeping the hand-written notes that follow the generated report) and its charts.
fn write_reports(
    args: &BenchArgs,
    command: &str,
    rows: &[Row],
    scaling: &[ScalingRow],
) -> Result<std::path::PathBuf> {
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| crate::target_dir().join("bench"));
    std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
    let json = serde_json::to_string_pretty(&Report {
        command,
        rows,
        scaling,
    })?;
    let rows_json = serde_json::to_string_pretty(rows)?;
    write(&out.join("report.json"), &rows_json)?;
    write(&out.join("report-full.json"), &json)?;
    if let Some(path) = &args.json {
        write(path, &json)?;
    }
    let table = report::markdown(command, rows, scaling, args.resolution);
    write(&out.join("report.md"), &table)?;
    let chart = chart::chart_svg(rows)?;
    write(&out.join("chart.svg"), &chart)?;
    let scaling_chart = if scaling.is_empty() {
        None
    } else {
        Some(chart::scaling_svg(scaling)?)
    };
    if let Some(svg) = &scaling_chart {
        write(&out.join("scaling.svg"), svg)?;
    }
    if args.docs {
        let docs = crate::workspace_root().join("docs");
        std::fs::create_dir_all(&docs)?;
        // Keep the hand-written notes that follow the generated report.
        let old = std::fs::read_to_string(docs.join("bench.md")).unwrap_or_default();
        let notes = report::split_notes(&old).1;
        let text = if notes.is_empty() {
            table.clone()
        } else {
            format!("{}\n\n{notes}", table.trim_end())
        };
        write(&docs.join("bench.md"), &text)?;
        write(&docs.join("bench.svg"), &chart)?;
        if let Some(svg) = &scaling_chart {
            write(&docs.join("bench-scaling.svg"), svg)?;
        }
    }
    Ok(out)
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
    out.push(scenes::scan());
    Ok(out)
}
