//! `cargo xtask`: the workspace's command line.
//!
//! - `render` draws a model (or the built-in demo scene) with any sorter to a PNG or an ID image.
//! - `bench` measures every sorter, and the `plane-split` crate as an outside peer, for time
//!   against error on real models and generated hard scenes, and writes a table, a JSON
//!   report and a chart under `target/bench/`.
//! - `fuzz` runs every sorter against the order-violation oracle on generated scenes and
//!   saves failing cases for replay with `render`: an exact sorter's under `tests/data/sorters/`,
//!   where `cargo test` replays them, the others' under `target/fuzz/`. `fuzz --loaders`
//!   mutates model and texture files; `fuzz --libfuzzer TARGET --time S` runs the
//!   coverage-guided targets of `fuzz/` (cargo-fuzz, nightly).
//! - `stress` runs the exact sorters on moved, scaled, coplanar, degenerate and edge-on cases
//!   and reports violations, pixel error, fragments and NaN counts (docs/ROBUSTNESS.md).
//! - `ci` runs what CI runs (`.ci/run`): fmt, clippy, tests, packaging.
//! - `oneshot` times one exact picture against the centroid's, whole process.
//!
//! See `xtask/README.md` for examples.

mod bake;
mod bench;
mod ci;
mod fuzz;
mod fuzz_libfuzzer;
mod fuzz_loaders;
mod oneshot;
mod peer;
mod presort_cache;
mod progress;
mod raster;
mod render;
mod scenes;
mod stress;
mod truth;
mod turn;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// The workspace's command line.
#[derive(Debug, Parser)]
#[command(name = "cargo xtask", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// Every subcommand.
#[derive(Debug, Subcommand)]
enum Command {
    /// Render a model (or the built-in demo scene) to a PNG or an ID image.
    Render(render::RenderArgs),
    /// Bake every painter order along an animation axis (exact breakpoints); write JSON
    /// and a spinning HTML page.
    Bake(bake::BakeArgs),
    /// Measure every sorter (and plane-split) for time against error; write
    /// target/bench/report.{md,json} and a chart.
    Bench(bench::BenchArgs),
    /// Run every sorter against the order-violation oracle on generated scenes; save an
    /// exact sorter's failures under tests/data/sorters/ (replayed by cargo test), the
    /// others' under target/fuzz/.
    Fuzz(fuzz::FuzzArgs),
    /// Run what CI runs (.ci/run): cargo fmt --check, clippy -D warnings, tests, packaging.
    Ci(ci::CiArgs),
    /// Time one exact picture (`render --sorter auto`) against the centroid's, whole process,
    /// median of alternating runs.
    Oneshot(oneshot::OneshotArgs),
    /// Numerical stress: every exact sorter on transformed models and degenerate scenes;
    /// violations, pixel error, fragments, NaN counts, time (docs/ROBUSTNESS.md).
    Stress(stress::StressArgs),
    /// Write a page that turns the model with the pointer, showing orders certified by
    /// face-sort's `Presorted` (the script only looks up the viewer's region).
    Turn(turn::TurnArgs),
    /// Write raster-sink's references (ID truth with its unambiguous pixels, exact
    /// compositing) for triangles seen by an engine's camera, given as JSON: for checks
    /// outside Rust, such as the npm package's browser tests.
    Truth(truth::TruthArgs),
}

fn main() -> ExitCode {
    // A panic is a bug, but the user still gets one plain line rather than a backtrace.
    std::panic::set_hook(Box::new(|info| {
        let message = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| (*s).to_owned())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown cause".to_owned());
        let location = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        eprintln!("error: internal failure{location}: {message}");
    }));
    let cli = Cli::parse();
    let result = std::panic::catch_unwind(|| match cli.command {
        Command::Render(args) => render::run(&args),
        Command::Bake(args) => bake::run(&args),
        Command::Turn(args) => turn::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Fuzz(args) => fuzz::run(&args),
        Command::Ci(args) => ci::run(&args),
        Command::Oneshot(args) => oneshot::run(&args),
        Command::Stress(args) => stress::run(&args),
        Command::Truth(args) => truth::run(&args),
    });
    match result {
        Ok(Ok(code)) => code,
        Ok(Err(error)) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
        Err(_) => ExitCode::from(101),
    }
}

/// The workspace root (the parent of this crate's directory).
fn workspace_root() -> PathBuf {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    manifest
        .parent()
        .map_or_else(|| manifest.clone(), PathBuf::from)
}

/// `target/` of the workspace (honours `CARGO_TARGET_DIR`).
fn target_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| workspace_root().join("target"))
}
