//! `cargo xtask ci`: what CI runs, which is `.ci/run` itself (one list of steps, not two).

use std::process::{Command, ExitCode};

use anyhow::{Context, Result, bail};
use clap::Args;

use crate::workspace_root;

/// Options of `ci`.
#[derive(Debug, Args)]
pub struct CiArgs {
    /// Skip `cargo test` and the packaging check (format, lints and docs only).
    #[arg(long)]
    no_test: bool,
}

/// Runs `.ci/run`: installs Chromium and poppler when missing, then `cargo fmt --check`,
/// `cargo clippy -D warnings`, `cargo doc` with warnings as errors, `cargo test --workspace`
/// and `cargo package` of the library crates, stopping at the first failure. `--no-test`
/// sets `CI_NO_TEST=1`, which stops it after the docs.
pub fn run(args: &CiArgs) -> Result<ExitCode> {
    let root = workspace_root();
    let mut command = Command::new("bash");
    command.arg(root.join(".ci/run")).current_dir(&root);
    if args.no_test {
        command.env("CI_NO_TEST", "1");
    }
    let status = command.status().context("running .ci/run")?;
    if !status.success() {
        bail!(".ci/run failed ({status})");
    }
    eprintln!("ci: all steps passed");
    Ok(ExitCode::SUCCESS)
}
