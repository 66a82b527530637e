//! `cargo xtask oneshot`: one exact picture against the centroid's, whole process.

use std::path::PathBuf;
use std::process::{Command, ExitCode, Stdio};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::Args;

use crate::bench::median;

/// Untimed runs of each sorter before the timed ones (disk cache, first-run costs).
const WARM_UP: usize = 2;

/// Options of `oneshot`.
#[derive(Debug, Args)]
pub struct OneshotArgs {
    /// Model to render.
    model: PathBuf,
    /// Timed runs of each sorter (after two warm-up runs each), alternating.
    #[arg(long, default_value_t = 10)]
    runs: usize,
    /// Image size.
    #[arg(long, value_name = "WxH", default_value = "1024x1024", value_parser = crate::render::parse_size)]
    size: (u32, u32),
}

/// Runs `render MODEL --sorter auto` and `--sorter centroid` alternately as separate
/// processes (load, order, raster, PNG: what a user waits for) and prints the median wall
/// times and their ratio.
pub fn run(args: &OneshotArgs) -> Result<ExitCode> {
    if args.runs == 0 {
        bail!("--runs must be at least 1");
    }
    let exe = std::env::current_exe().context("locating xtask")?;
    let out = crate::target_dir().join("oneshot.png");
    let mut times: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    let sorters = ["auto", "centroid"];
    let size = format!("{}x{}", args.size.0, args.size.1);
    for round in 0..args.runs + WARM_UP {
        for (k, sorter) in sorters.iter().enumerate() {
            let start = Instant::now();
            let status = Command::new(&exe)
                .arg("render")
                .arg(&args.model)
                .args(["--sorter", sorter, "--size", &size, "-o"])
                .arg(&out)
                .stdout(Stdio::null())
                .status()
                .context("running render")?;
            if !status.success() {
                bail!("render --sorter {sorter} failed ({status})");
            }
            if round >= WARM_UP {
                times[k].push(start.elapsed().as_secs_f64() * 1e3);
            }
        }
    }
    let [auto, centroid] = &mut times;
    let (auto, centroid) = (median(auto), median(centroid));
    println!(
        "{}: auto {auto:.1} ms, centroid {centroid:.1} ms, ratio {:.3} (medians of {} alternating runs after {WARM_UP} warm-up runs, {size})",
        args.model.display(),
        auto / centroid,
        args.runs,
    );
    Ok(ExitCode::SUCCESS)
}
