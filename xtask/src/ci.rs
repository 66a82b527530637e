//! `cargo xtask ci`: what CI runs.

use std::process::{Command, ExitCode};

use anyhow::{Context, Result, bail};
use clap::Args;

use crate::workspace_root;

/// Options of `ci`.
#[derive(Debug, Args)]
pub struct CiArgs {
    /// Skip `cargo test` (format and lint only).
    #[arg(long)]
    no_test: bool,
}

/// Runs `cargo fmt --all -- --check`, `cargo clippy --workspace --all-targets -- -D warnings`
/// and `cargo test --workspace`, stopping at the first failure.
pub fn run(args: &CiArgs) -> Result<ExitCode> {
    let mut steps: Vec<&[&str]> = vec![
        &["fmt", "--all", "--", "--check"],
        &[
            "clippy",
            "--workspace",
            "--all-targets",
            "--",
            "-D",
            "warnings",
        ],
    ];
    if !args.no_test {
        steps.push(&["test", "--workspace"]);
    }
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let root = workspace_root();
    for step in steps {
        eprintln!("ci: cargo {}", step.join(" "));
        let status = Command::new(&cargo)
            .args(step)
            .current_dir(&root)
            .status()
            .with_context(|| format!("running cargo {}", step.join(" ")))?;
        if !status.success() {
            bail!("`cargo {}` failed ({status})", step.join(" "));
        }
    }
    eprintln!("ci: all steps passed");
    Ok(ExitCode::SUCCESS)
}
