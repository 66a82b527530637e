//! `cargo xtask fuzz --libfuzzer TARGET --time S`: the coverage-guided targets of `fuzz/`
//! under libFuzzer, through cargo-fuzz and the nightly toolchain.
//!
//! Each run starts from the committed corpus `fuzz/corpus/TARGET/` (read only) and keeps
//! what it adds under `target/fuzz-corpus/TARGET/`, with libFuzzer's log under
//! `target/fuzz-logs/`. Resource bounds are part of the contract: every execution runs under
//! `-rss_limit_mb=2048` and `-timeout=10`; a breach is a finding like a crash. libFuzzer runs
//! in fork mode (`-fork=JOBS`), so a run saves every finding under `fuzz/artifacts/TARGET/`
//! and goes on; the command fails when a run saved any. With `--runs N` a target runs exactly
//! N executions from seed 1 in one process instead, the same every time (CI). Fix a finding, then move its input to
//! `fuzz/regressions/TARGET/`, where `cargo test -p fuzz-checks` replays it.
//!
//! The targets are built without a sanitizer: the workspace denies unsafe code, so what
//! libFuzzer looks for is panics, broken checks, hangs and memory growth, and without
//! AddressSanitizer a target runs several times as many executions a second
//! (docs/ROBUSTNESS.md).
//!
//! Without the nightly toolchain or cargo-fuzz the command prints a notice and succeeds, so
//! that CI runs the targets where it can.

use std::path::Path;
use std::process::{Command, ExitCode, Stdio};
use std::time::Instant;

use anyhow::{Context, Result, bail};

use crate::{target_dir, workspace_root};

/// The target triple to build for: the host's (cargo-fuzz's default), on Linux and macOS.
fn host_triple() -> String {
    let vendor_os = if cfg!(target_os = "macos") {
        "apple-darwin"
    } else {
        "unknown-linux-gnu"
    };
    format!("{}-{vendor_os}", std::env::consts::ARCH)
}

/// Memory limit of one libFuzzer process, MB.
const RSS_LIMIT_MB: u32 = 2048;
/// Time limit of one execution, s.
const TIMEOUT_S: u32 = 10;

/// What libFuzzer reported at the end of a run.
#[derive(Debug, Default)]
struct Stats {
    executions: u64,
    coverage: u64,
    features: u64,
    peak_rss_mb: u64,
}

/// The targets: the files of `fuzz/fuzz_targets/`.
fn targets(fuzz: &Path) -> Result<Vec<String>> {
    let dir = fuzz.join("fuzz_targets");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .with_context(|| format!("reading {}", dir.display()))?
        .filter_map(Result::ok)
        .filter_map(|e| {
            let path = e.path();
            (path.extension()? == "rs").then(|| path.file_stem()?.to_str().map(str::to_owned))?
        })
        .collect();
    names.sort();
    Ok(names)
}

fn succeeds(command: &mut Command) -> bool {
    command
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// The crash, timeout and out-of-memory inputs saved in `dir`.
fn findings(dir: &Path) -> Vec<String> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut names: Vec<String> = entries
        .filter_map(Result::ok)
        .filter_map(|e| e.file_name().into_string().ok())
        .filter(|n| {
            ["crash-", "timeout-", "oom-"]
                .iter()
                .any(|p| n.starts_with(p))
        })
        .collect();
    names.sort();
    names
}

/// Runs `target` (or `all`) for `seconds` each with `jobs` processes, or for exactly `runs`
/// executions from seed 1 in one process; `dev` builds the targets unoptimised.
pub fn run(
    target: &str,
    seconds: u64,
    runs: Option<u64>,
    jobs: u32,
    dev: bool,
) -> Result<ExitCode> {
    if !succeeds(Command::new("cargo").args(["+nightly", "--version"])) {
        println!(
            "fuzz --libfuzzer: skipped, the nightly toolchain is not installed \
             (rustup toolchain install nightly)"
        );
        return Ok(ExitCode::SUCCESS);
    }
    if !succeeds(Command::new("cargo").args(["+nightly", "fuzz", "--version"])) {
        println!(
            "fuzz --libfuzzer: skipped, cargo-fuzz is not installed (cargo install cargo-fuzz)"
        );
        return Ok(ExitCode::SUCCESS);
    }
    let fuzz = workspace_root().join("fuzz");
    let all = targets(&fuzz)?;
    let chosen: Vec<String> = if target == "all" {
        all
    } else if all.iter().any(|t| t == target) {
        vec![target.to_owned()]
    } else {
        bail!(
            "no fuzz target `{target}`; the targets: all, {}",
            all.join(", ")
        );
    };
    let logs = target_dir().join("fuzz-logs");
    std::fs::create_dir_all(&logs)?;
    let mut failed = Vec::new();
    for name in &chosen {
        let work = target_dir().join("fuzz-corpus").join(name);
        std::fs::create_dir_all(&work)?;
        let log_path = logs.join(format!("{name}.log"));
        let log = std::fs::File::create(&log_path)?;
        let artifacts = fuzz.join("artifacts").join(name);
        let before = findings(&artifacts);
        // Build with cargo-fuzz, then run the binary itself: `cargo fuzz run` replays every
        // saved finding through `cargo run` afterwards, which fork mode makes slow.
        let mut build = Command::new("cargo");
        build
            .current_dir(&fuzz)
            .args([
                "+nightly",
                "fuzz",
                "build",
                "--sanitizer",
                "none",
                "--target",
            ])
            .arg(host_triple())
            .args(dev.then_some("--dev"))
            .arg(name);
        if !build
            .status()
            .context("running cargo fuzz build")?
            .success()
        {
            bail!("cargo fuzz build {name} failed");
        }
        let profile = if dev { "debug" } else { "release" };
        let binary = fuzz
            .join("target")
            .join(host_triple())
            .join(profile)
            .join(name);
        std::fs::create_dir_all(&artifacts)?;
        let mut command = Command::new(&binary);
        // Fork mode: a crash, timeout or memory breach is saved and the run goes on, so
        // one run finds every finding it can in its time.
        command
            .current_dir(&fuzz)
            .env("RAYON_NUM_THREADS", "1")
            .arg(&work)
            .arg(fuzz.join("corpus").join(name))
            .arg(format!("-artifact_prefix={}/", artifacts.display()))
            .arg(format!("-rss_limit_mb={RSS_LIMIT_MB}"))
            .arg(format!("-timeout={TIMEOUT_S}"))
            .arg("-print_final_stats=1");
        match runs {
            Some(runs) => command.args(["-seed=1".to_owned(), format!("-runs={runs}")]),
            None => command
                .arg(format!("-max_total_time={seconds}"))
                .arg(format!("-fork={jobs}"))
                .args(["-ignore_crashes=1", "-ignore_timeouts=1", "-ignore_ooms=1"]),
        };
        let start = Instant::now();
        let status = command
            .stdout(log.try_clone()?)
            .stderr(log)
            .status()
            .with_context(|| format!("running {}", binary.display()))?;
        let new: Vec<String> = findings(&artifacts)
            .into_iter()
            .filter(|f| !before.contains(f))
            .collect();
        let elapsed = start.elapsed().as_secs_f64();
        let text = String::from_utf8_lossy(&std::fs::read(&log_path)?).into_owned();
        let stats = parse(&text);
        println!(
            "{name:<8} {:>12} executions in {elapsed:>7.0} s ({:>7.0}/s, {} process(es)), \
             coverage {} edges, {} features, peak RSS {}: {}",
            stats.executions,
            stats.executions as f64 / elapsed.max(1e-9),
            if runs.is_some() { 1 } else { jobs },
            stats.coverage,
            stats.features,
            if stats.peak_rss_mb > 0 {
                format!("{} MB", stats.peak_rss_mb)
            } else {
                "not reported".to_owned()
            },
            if new.is_empty() && status.success() {
                "no crash".to_owned()
            } else if new.is_empty() {
                format!("libFuzzer failed (log {})", log_path.display())
            } else {
                format!(
                    "{} finding(s) under fuzz/artifacts/{name}/, the first {} (log {})",
                    new.len(),
                    new[0],
                    log_path.display()
                )
            }
        );
        if !new.is_empty() || !status.success() {
            failed.push(name.clone());
        }
    }
    if failed.is_empty() {
        Ok(ExitCode::SUCCESS)
    } else {
        println!("fuzz --libfuzzer: crashes in {}", failed.join(", "));
        Ok(ExitCode::FAILURE)
    }
}

/// The final statistics in libFuzzer's log: the last status line (`#N ... cov: C ft: F`, or
/// in fork mode `#N: cov: C ft: F`, N counting every worker's executions) and `stat::` lines
/// where the run printed them.
fn parse(log: &str) -> Stats {
    let mut stats = Stats::default();
    let field = |line: &str, key: &str| -> Option<u64> {
        let rest = line.split(key).nth(1)?;
        rest.split_whitespace()
            .next()?
            .trim_end_matches("Mb")
            .parse()
            .ok()
    };
    for line in log.lines() {
        if let Some(v) = line
            .strip_prefix("stat::number_of_executed_units:")
            .and_then(|v| v.trim().parse::<u64>().ok())
        {
            stats.executions = stats.executions.max(v);
        } else if let Some(v) = line
            .strip_prefix("stat::peak_rss_mb:")
            .and_then(|v| v.trim().parse::<u64>().ok())
        {
            stats.peak_rss_mb = stats.peak_rss_mb.max(v);
        } else if line.starts_with('#') {
            if let Some(v) = field(line, "cov: ") {
                stats.coverage = v;
            }
            if let Some(v) = field(line, "ft: ") {
                stats.features = v;
            }
            if let Some(v) = field(line, "rss: ") {
                stats.peak_rss_mb = stats.peak_rss_mb.max(v);
            }
            if let Some(v) = line
                .strip_prefix('#')
                .and_then(|l| l.split_whitespace().next())
                .and_then(|n| n.trim_end_matches(':').parse().ok())
            {
                stats.executions = stats.executions.max(v);
            }
        }
    }
    stats
}

#[cfg(test)]
mod tests {
    #[test]
    fn libfuzzer_statistics_are_read() {
        let log = "#2\tINITED cov: 10 ft: 12 corp: 1/1b exec/s: 0 rss: 40Mb\n\
                   #9000\tNEW    cov: 2393 ft: 8689 corp: 641/3457Kb lim: 16780 exec/s: 225 rss: 467Mb\n\
                   stat::number_of_executed_units: 9406\nstat::peak_rss_mb:              553\n";
        let stats = super::parse(log);
        assert_eq!(
            (
                stats.executions,
                stats.coverage,
                stats.features,
                stats.peak_rss_mb
            ),
            (9406, 2393, 8689, 553)
        );
    }
}
