//! `cargo xtask fuzz`: every sorter against the oracle on generated scenes.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Context, Result};
use clap::Args;
use face_sort::strategies::{ViewSpec, any_scene, view_spec};
use face_sort::{CullMode, DrawList, Geometry, PolygonMesh, Projection, SorterKind, View, oracle};
use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

use crate::progress;
use crate::scenes;

/// Options of `fuzz`.
#[derive(Debug, Args)]
pub struct FuzzArgs {
    /// Number of generated cases (scene + view), each run through every sorter.
    #[arg(long, default_value_t = 20_000)]
    cases: u64,
    /// Seed of the generator (a run is reproducible from it).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Where failing cases go. Default: an exact sorter's (Newell, BSP) under
    /// tests/data/sorters/, where `cargo test` replays them (face-sort/tests/fuzz_cases.rs);
    /// the other sorters' under target/fuzz.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Largest number of failing cases saved per sorter.
    #[arg(long, default_value_t = 5)]
    save: usize,
    /// Fuzz the model loaders (OBJ, MTL, glTF, GLB) instead of the sorters: --cases mutated
    /// seed files, each failure shrunk and saved under tests/data/loaders/ (or --out).
    #[arg(long)]
    loaders: bool,
    /// Run a coverage-guided libFuzzer target of fuzz/ (or `all`, one after another) instead:
    /// cargo-fuzz on the nightly toolchain, each for --time seconds. Skips with a notice
    /// when nightly or cargo-fuzz is missing.
    #[arg(long, value_name = "TARGET")]
    libfuzzer: Option<String>,
    /// Seconds per libFuzzer target.
    #[arg(long, default_value_t = 60, requires = "libfuzzer")]
    time: u64,
    /// libFuzzer processes per target (`-fork`).
    #[arg(long, default_value_t = 1, requires = "libfuzzer")]
    jobs: u32,
    /// Instead of --time: exactly this many executions per target from seed 1, in one process
    /// (deterministic: CI's smoke run).
    #[arg(long, value_name = "N", requires = "libfuzzer")]
    runs: Option<u64>,
    /// Build the libFuzzer targets unoptimised: quicker to build, slower to run (CI's
    /// few-second smoke run).
    #[arg(long, requires = "libfuzzer")]
    dev: bool,
}

#[derive(Default)]
struct Tally {
    failing_cases: u64,
    violations: u64,
    saved: usize,
}

/// Runs the fuzzer. Fails when an exact sorter (Newell, BSP) has a violation.
pub fn run(args: &FuzzArgs) -> Result<ExitCode> {
    if let Some(target) = &args.libfuzzer {
        return crate::fuzz_libfuzzer::run(target, args.time, args.runs, args.jobs, args.dev);
    }
    if args.loaders {
        return crate::fuzz_loaders::run(args.cases, args.seed, args.out.clone());
    }
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| crate::target_dir().join("fuzz"));
    let regressions = args
        .out
        .clone()
        .unwrap_or_else(|| test_support::test_data_dir().join("sorters"));
    let mut seed = [0u8; 32];
    seed[..8].copy_from_slice(&args.seed.to_le_bytes());
    let mut runner = TestRunner::new_with_rng(
        Config {
            max_local_rejects: u32::MAX,
            max_global_rejects: u32::MAX,
            ..Config::default()
        },
        TestRng::from_seed(RngAlgorithm::ChaCha, &seed),
    );
    let strategy = (any_scene(), view_spec());
    let mut tallies: Vec<Tally> = SorterKind::ALL.iter().map(|_| Tally::default()).collect();
    let bar = progress::bar(args.cases, "fuzz");
    let start = Instant::now();
    let mut list = DrawList::new();
    let mut skipped = 0u64;
    for case in 0..args.cases {
        bar.inc(1);
        let mut tree = strategy
            .new_tree(&mut runner)
            .map_err(|e| anyhow::anyhow!("generating case {case}: {e}"))?;
        let (mut mesh, spec) = tree.current();
        // Every tenth case: a larger scene (10 to 80 random quads crossing freely), where
        // sorters meet many overlaps at once. Not shrunk.
        let large = case % 10 == 9;
        if large {
            let mut rng = scenes::Rng::new(args.seed ^ case.wrapping_mul(0x2545_F491_4F6C_DD1D));
            let count = 10 + (rng.next_u64() % 71) as usize;
            mesh = scenes::random_quads(count, rng.next_u64())?.mesh;
        }
        let Ok(geometry) = Geometry::new(&mesh) else {
            skipped += 1;
            continue;
        };
        let view = spec.view(&geometry);
        let mut shrunk = large;
        for (kind, tally) in SorterKind::ALL.into_iter().zip(tallies.iter_mut()) {
            let violations = violations_of(kind, &geometry, &view, &mut list);
            if violations == 0 {
                continue;
            }
            tally.failing_cases += 1;
            tally.violations += violations as u64;
            if tally.saved < args.save {
                tally.saved += 1;
                // Shrink exact sorters' failures to a small case worth a regression test.
                let (mesh, spec) = if SorterKind::EXACT.contains(&kind) && !shrunk {
                    shrunk = true;
                    shrink(&mut tree, kind, &mut list)
                } else {
                    (mesh.clone(), spec.clone())
                };
                let dir = if SorterKind::EXACT.contains(&kind) {
                    &regressions
                } else {
                    &out
                };
                let path = save_case(dir, kind, case, args.seed, &mesh, &spec)?;
                bar.println(format!(
                    "{}: {violations} violation(s) in case {case}; saved {}",
                    kind.name(),
                    path.display()
                ));
            }
        }
    }
    bar.finish_and_clear();
    println!(
        "fuzz: {} cases (seed {}, {} without area skipped) in {:.1} s",
        args.cases,
        args.seed,
        skipped,
        start.elapsed().as_secs_f64()
    );
    let mut failed = false;
    for (kind, tally) in SorterKind::ALL.into_iter().zip(&tallies) {
        let exact = SorterKind::EXACT.contains(&kind);
        println!(
            "{:<12} {:>6} failing cases, {:>7} violations{}",
            kind.name(),
            tally.failing_cases,
            tally.violations,
            if exact {
                "  (exact: must be 0)"
            } else {
                "  (not exact: reported only)"
            }
        );
        failed |= exact && tally.failing_cases > 0;
    }
    if failed {
        println!(
            "failing cases are under {} (exact sorters', replayed by cargo test) and {}",
            regressions.display(),
            out.display()
        );
        return Ok(ExitCode::FAILURE);
    }
    Ok(ExitCode::SUCCESS)
}

fn violations_of(kind: SorterKind, geometry: &Geometry, view: &View, list: &mut DrawList) -> usize {
    let mut sorter = kind.build(geometry);
    sorter.sort(view, list);
    oracle::count_violations(view, list)
}

/// proptest-style shrinking: simplify while the case still fails (bounded).
fn shrink(
    tree: &mut impl ValueTree<Value = (PolygonMesh, ViewSpec)>,
    kind: SorterKind,
    list: &mut DrawList,
) -> (PolygonMesh, ViewSpec) {
    let fails = |value: &(PolygonMesh, ViewSpec), list: &mut DrawList| {
        Geometry::new(&value.0).is_ok_and(|g| {
            let view = value.1.view(&g);
            violations_of(kind, &g, &view, list) > 0
        })
    };
    let mut best = tree.current();
    for _ in 0..500 {
        if !tree.simplify() {
            break;
        }
        let candidate = tree.current();
        if fails(&candidate, list) {
            best = candidate;
        } else if !tree.complicate() {
            break;
        }
    }
    best
}

fn cull_name(cull: CullMode) -> &'static str {
    match cull {
        CullMode::Back => "back",
        CullMode::Front => "front",
        CullMode::None => "none",
    }
}

/// The `cargo xtask render` arguments that replay a view of `geometry`.
fn replay_args(spec: &ViewSpec, view: &View) -> String {
    let mut s = format!(
        "--yaw {:?} --pitch {:?} --roll {:?} --cull {} --size {}x{}",
        spec.yaw,
        spec.pitch,
        spec.roll,
        cull_name(spec.cull),
        view.width(),
        view.height()
    );
    if let Projection::Perspective { distance } = view.projection() {
        let _ = write!(s, " --persp {distance:?}");
    }
    s
}

/// The comment line of a saved case that holds its view ([`ViewSpec`]'s text form), read back
/// by face-sort/tests/fuzz_cases.rs.
const VIEW_SPEC_PREFIX: &str = "view-spec: ";

fn save_case(
    dir: &Path,
    kind: SorterKind,
    case: u64,
    seed: u64,
    mesh: &PolygonMesh,
    spec: &ViewSpec,
) -> Result<PathBuf> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let stem = format!("{}-seed{seed}-case{case}", kind.name());
    let obj = dir.join(format!("{stem}.obj"));
    let geometry = Geometry::new(mesh)?;
    let view = spec.view(&geometry);
    let args = replay_args(spec, &view);
    // Paths inside the workspace are written relative to it: a committed case replays anywhere.
    let shown = |p: &Path| {
        p.strip_prefix(crate::workspace_root())
            .unwrap_or(p)
            .display()
            .to_string()
    };
    let command = format!(
        "cargo xtask render {} {args} --sorter {} --check -o {}",
        shown(&obj),
        kind.name(),
        shown(&dir.join(format!("{stem}.png")))
    );
    let mut list = DrawList::new();
    let violations = violations_of(kind, &geometry, &view, &mut list);
    let comment = vec![
        format!("{VIEW_SPEC_PREFIX}{spec}"),
        format!(
            "xtask fuzz: {} has {violations} order violation(s) in this view",
            kind.name()
        ),
        format!("view: {args}"),
        format!("replay: {command}"),
    ];
    std::fs::write(&obj, scenes::to_obj(mesh, &comment))
        .with_context(|| format!("writing {}", obj.display()))?;
    let txt = dir.join(format!("{stem}.txt"));
    std::fs::write(
        &txt,
        format!(
            "sorter: {}\nviolations: {violations}\nview: {spec:?}\n{command}\n",
            kind.name()
        ),
    )
    .with_context(|| format!("writing {}", txt.display()))?;
    Ok(obj)
}
