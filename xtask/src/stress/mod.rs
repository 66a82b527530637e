//! `cargo xtask stress`: numerical stability of every exact sorter (issue 10).
//!
//! Every case is a mesh (a transformed copy of a repository model, or a generated scene)
//! seen from a few views. The sorters are `Bsp`, `Newell` and the planner `Auto` (which may
//! pick culling alone on a mesh in convex position), all exact. Per case and sorter the run reports the oracle's order violations,
//! the pixel error against raster-sink's z-buffer truth, fragments, NaN or infinite
//! coordinates in the draw list, fallbacks (exactness given up), time, and any panic (each
//! case runs under `catch_unwind` on its own thread, with a time limit, so one failure does
//! not hide the others). `Centroid` is run as the reference that shows a case is hard.
//!
//! The run fails (exit code 1) when an exact sorter (`Bsp`, `Newell`) has a violation, a
//! wrong unambiguous pixel, a non-finite output or a fallback on a judged case, or when
//! anything panics or runs out of time.

use std::fmt::Write as _;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use anyhow::{Context, Result, bail};
use clap::Args;
use face_sort::glam::{DMat3, DVec3, EulerRot};
use face_sort::{
    Auto, CullMode, DrawList, FaceSorter, Geometry, PlanHint, PolygonMesh, SorterKind, View, oracle,
};
use serde::Serialize;

use crate::scenes::{self, Rng};

mod cases;
mod report;

use cases::{all_cases, quick_cases};
use report::{markdown, write_docs};

/// Options of `stress`.
#[derive(Debug, Args)]
pub struct StressArgs {
    /// Image side (pixels) of the truth and the painter's ID image.
    #[arg(long, default_value_t = 256)]
    size: u32,
    /// Run only the fast subset (what `cargo test` runs).
    #[arg(long)]
    quick: bool,
    /// Run only cases whose name contains this text.
    #[arg(long, value_name = "TEXT")]
    only: Option<String>,
    /// Also write the report as JSON to this file.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Write the table into docs/stress.md between its markers.
    #[arg(long)]
    docs: bool,
    /// Seconds one case may take (all sorters and views) before it counts as hung.
    #[arg(long, default_value_t = 300)]
    timeout: u64,
}

/// One stress case: a mesh, the views it is seen from, and whether its truth is judged.
pub struct Case {
    /// Group of the list ("position", "scale", "coplanar", …).
    pub group: &'static str,
    /// Unique name.
    pub name: String,
    /// The mesh, or the typed error building it gave (expected for some degenerate cases).
    pub mesh: Result<PolygonMesh, String>,
    /// Views.
    pub shots: Vec<Shot>,
    /// Whether failures of exact sorters here fail the run (the truth is unambiguous up to
    /// the conventions' tolerances, which the metrics already exclude).
    pub judged: bool,
    /// Whether the right outcome is a typed error (`MeshError`) rather than an order.
    pub expect_error: bool,
}

/// A view of a case, independent of the model's size.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Shot {
    /// Yaw, pitch, roll in degrees.
    pub angles: [f64; 3],
    /// Perspective eye distance from the centre, in units of the diagonal `L`.
    pub eye: Option<f64>,
    /// Cull mode.
    #[serde(skip)]
    pub cull: CullMode,
}

impl Shot {
    const fn ortho(yaw: f64, pitch: f64, roll: f64, cull: CullMode) -> Self {
        Shot {
            angles: [yaw, pitch, roll],
            eye: None,
            cull,
        }
    }

    const fn persp(yaw: f64, pitch: f64, eye: f64, cull: CullMode) -> Self {
        Shot {
            angles: [yaw, pitch, 0.0],
            eye: Some(eye),
            cull,
        }
    }

    fn view(&self, geometry: &Geometry, size: u32) -> View {
        let [yaw, pitch, roll] = self.angles;
        let mut view = View::fit(&geometry.bounds(), size, size)
            .with_yaw_pitch_roll(yaw, pitch, roll)
            .with_cull(self.cull);
        if let Some(k) = self.eye {
            view = view.with_perspective(k * view.diagonal() * view.scale());
        }
        view
    }

    fn label(&self) -> String {
        let [yaw, pitch, roll] = self.angles;
        let cull = match self.cull {
            CullMode::Back => "back",
            CullMode::Front => "front",
            CullMode::None => "none",
        };
        match self.eye {
            Some(k) => format!("persp {k}L y{yaw} p{pitch} cull {cull}"),
            None => format!("ortho y{yaw} p{pitch} r{roll} cull {cull}"),
        }
    }
}

/// Five general views: three orthographic, two perspective (one with the eye 0.7 `L` from
/// the centre, just outside the bounding sphere).
fn general_shots(cull: CullMode) -> Vec<Shot> {
    vec![
        Shot::ortho(30.0, 20.0, 0.0, cull),
        Shot::ortho(213.0, -37.0, 11.0, cull),
        Shot::ortho(301.0, 63.0, -27.0, cull),
        Shot::persp(121.0, 14.0, 1.5, cull),
        Shot::persp(47.0, -22.0, 0.7, cull),
    ]
}

/// One sorter's figures on one case, summed over its views.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Outcome {
    /// Sorter name.
    pub sorter: String,
    /// Order violations (oracle), summed over views.
    pub violations: usize,
    /// Wrong unambiguous pixels, summed over views.
    pub wrong_pixels: usize,
    /// Unambiguous pixels, summed over views.
    pub unambiguous_pixels: usize,
    /// Largest number of polygons drawn in one view (fragments included).
    pub drawn_max: usize,
    /// Fragments beyond the pieces: BSP tree fragments − pieces; Newell's largest per-frame
    /// count of cut polygons.
    pub fragments: usize,
    /// NaN or infinite coordinates in the draw lists (corners and planes).
    pub non_finite: usize,
    /// Frames in which the sorter gave up exactness (its own step budget).
    pub fallbacks: usize,
    /// Build plus every view's sort, milliseconds.
    pub ms: f64,
    /// Panic message, if the sorter panicked.
    pub panic: Option<String>,
    /// For `auto`: the strategy its plan picked (`cull-only`, `newell`, `bsp`).
    pub plan: Option<String>,
}

/// A case's figures.
#[derive(Clone, Debug, Serialize)]
pub struct CaseReport {
    /// Group.
    pub group: String,
    /// Case name.
    pub name: String,
    /// Faces of the mesh.
    pub faces: usize,
    /// Pieces after planarity handling (0 when the mesh was refused).
    pub pieces: usize,
    /// Views, as labels.
    pub views: Vec<String>,
    /// Whether exact sorters' failures here fail the run.
    pub judged: bool,
    /// Whether a typed error is the expected outcome.
    pub expect_error: bool,
    /// A typed error instead of a geometry (e.g. a mesh with no area), if any.
    pub error: Option<String>,
    /// Panic in the case's setup or truth, or a time-out.
    pub failure: Option<String>,
    /// One outcome per sorter.
    pub outcomes: Vec<Outcome>,
}

impl CaseReport {
    /// Why this case fails the run, if it does.
    pub fn problems(&self) -> Vec<String> {
        let mut out = Vec::new();
        if let Some(f) = &self.failure {
            out.push(format!("{}: {f}", self.name));
        }
        match (&self.error, self.expect_error) {
            (Some(e), false) => out.push(format!("{}: unexpected error: {e}", self.name)),
            (None, true) if self.failure.is_none() => {
                out.push(format!("{}: a typed error was expected", self.name));
            }
            _ => {}
        }
        for o in &self.outcomes {
            if let Some(p) = &o.panic {
                out.push(format!("{} / {}: panic: {p}", self.name, o.sorter));
            }
            if !is_exact(&o.sorter) || !self.judged {
                continue;
            }
            // The BSP tree stays within the budget its fallible constructors enforce.
            let budget = face_sort::BspOptions::DEFAULT.fragment_budget(self.pieces);
            if o.sorter == "bsp" && self.pieces + o.fragments > budget {
                out.push(format!(
                    "{} / bsp: {} fragments exceed the default budget of {budget}",
                    self.name,
                    self.pieces + o.fragments
                ));
            }
            if o.violations > 0 || o.wrong_pixels > 0 || o.non_finite > 0 || o.fallbacks > 0 {
                out.push(format!(
                    "{} / {}: {} violations, {} wrong pixels, {} non-finite, {} fallbacks",
                    self.name, o.sorter, o.violations, o.wrong_pixels, o.non_finite, o.fallbacks
                ));
            }
        }
        out
    }
}

/// The sorters run on every case (and the report's columns): the exact ones, then the
/// inexact reference.
const SORTERS: [&str; 6] = [
    "bsp",
    "bsp-merged",
    "newell",
    "presorted",
    "auto",
    REFERENCE,
];

/// The inexact reference among [`SORTERS`]: its violations are reported, not failures.
const REFERENCE: &str = "centroid";

/// The sorters whose failures fail the run.
fn is_exact(name: &str) -> bool {
    name != REFERENCE && SORTERS.contains(&name)
}

/// Builds a sorter by its name in [`SORTERS`].
fn build_sorter(name: &str, geometry: &Geometry) -> Box<dyn FaceSorter> {
    match SorterKind::from_name(name) {
        Some(kind) => kind.build(geometry),
        // The planner as an animation would use it (it may pick any of its strategies).
        None => Box::new(Auto::new(geometry, PlanHint::ANIMATION)),
    }
}

/// Runs the stress suite.
pub fn run(args: &StressArgs) -> Result<ExitCode> {
    let start = Instant::now();
    let cases = if args.quick {
        quick_cases()?
    } else {
        all_cases()?
    };
    let cases: Vec<Case> = cases
        .into_iter()
        .filter(|c| {
            args.only
                .as_ref()
                .is_none_or(|o| c.name.contains(o.as_str()))
        })
        .collect();
    if cases.is_empty() {
        bail!("no stress case matches");
    }
    let mut reports = Vec::with_capacity(cases.len());
    let total = cases.len();
    for (i, case) in cases.into_iter().enumerate() {
        let name = case.name.clone();
        let report = run_isolated(case, args.size, Duration::from_secs(args.timeout));
        let status = if report.problems().is_empty() {
            "ok"
        } else {
            "FAIL"
        };
        eprintln!("[{}/{total}] {name}: {status}", i + 1);
        reports.push(report);
    }
    let table = markdown(&reports, args.size);
    println!("{table}");
    let problems: Vec<String> = reports.iter().flat_map(CaseReport::problems).collect();
    println!(
        "stress: {} cases in {:.1} s; {} problem(s)",
        reports.len(),
        start.elapsed().as_secs_f64(),
        problems.len()
    );
    for p in &problems {
        println!("  {p}");
    }
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&reports)?;
        std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))?;
    }
    if args.docs {
        write_docs(&table, args)?;
    }
    Ok(if problems.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// Runs one case on its own thread under `catch_unwind`, waiting at most `limit`.
/// A case that does not finish in time is reported as hung (its thread is left running).
pub fn run_isolated(case: Case, size: u32, limit: Duration) -> CaseReport {
    let (group, name, judged, expect_error) = (
        case.group,
        case.name.clone(),
        case.judged,
        case.expect_error,
    );
    let views: Vec<String> = case.shots.iter().map(Shot::label).collect();
    isolated(&name, limit, move || run_case(&case, size)).unwrap_or_else(|failure| CaseReport {
        group: group.to_owned(),
        name: name.clone(),
        faces: 0,
        pieces: 0,
        views,
        judged,
        expect_error,
        error: None,
        failure: Some(failure),
        outcomes: Vec::new(),
    })
}

/// Runs `work` on its own thread under `catch_unwind`, waiting at most `limit`: its result,
/// or why there is none (a panic and its message, or the time-out; a hung thread is left
/// running, the caller goes on).
fn isolated<T: Send + 'static>(
    name: &str,
    limit: Duration,
    work: impl FnOnce() -> T + Send + 'static,
) -> Result<T, String> {
    let (send, receive) = mpsc::channel();
    std::thread::Builder::new()
        .name(format!("stress {name}"))
        .spawn(move || {
            let result = catch_unwind(AssertUnwindSafe(work));
            // The receiver may have given up (time-out): nothing to do then.
            let _ = send.send(result);
        })
        .map_err(|e| format!("could not start a thread: {e}"))?;
    match receive.recv_timeout(limit) {
        Ok(Ok(value)) => Ok(value),
        Ok(Err(payload)) => Err(format!("panic: {}", panic_message(payload.as_ref()))),
        Err(_) => Err(format!(
            "no result within {:.1} s (hung?)",
            limit.as_secs_f64()
        )),
    }
}

fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown cause".to_owned())
}

/// Runs every sorter over every view of one case.
fn run_case(case: &Case, size: u32) -> CaseReport {
    let mut report = CaseReport {
        group: case.group.to_owned(),
        name: case.name.clone(),
        faces: 0,
        pieces: 0,
        views: case.shots.iter().map(Shot::label).collect(),
        judged: case.judged,
        expect_error: case.expect_error,
        error: None,
        failure: None,
        outcomes: Vec::new(),
    };
    let mesh = match &case.mesh {
        Ok(mesh) => mesh,
        Err(e) => {
            report.error = Some(e.clone());
            return report;
        }
    };
    report.faces = mesh.face_count();
    let geometry = match Geometry::new(mesh) {
        Ok(g) => g,
        Err(e) => {
            report.error = Some(format!("MeshError: {e}"));
            return report;
        }
    };
    report.pieces = geometry.pieces().len();
    let views: Vec<View> = case.shots.iter().map(|s| s.view(&geometry, size)).collect();
    let truths = match catch_unwind(AssertUnwindSafe(|| {
        views
            .iter()
            .map(|v| raster_sink::truth(v, &geometry))
            .collect::<Vec<_>>()
    })) {
        Ok(t) => t,
        Err(payload) => {
            report.failure = Some(format!(
                "truth panicked: {}",
                panic_message(payload.as_ref())
            ));
            return report;
        }
    };
    for name in SORTERS {
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            run_sorter(name, &geometry, &views, &truths)
        }))
        .unwrap_or_else(|payload| Outcome {
            sorter: name.to_owned(),
            panic: Some(panic_message(payload.as_ref())),
            ..Outcome::default()
        });
        report.outcomes.push(outcome);
    }
    report
}

fn run_sorter(
    name: &str,
    geometry: &Geometry,
    views: &[View],
    truths: &[raster_sink::Truth],
) -> Outcome {
    let mut outcome = Outcome {
        sorter: name.to_owned(),
        ..Outcome::default()
    };
    let mut elapsed = Duration::ZERO;
    let start = Instant::now();
    let mut sorter = build_sorter(name, geometry);
    elapsed += start.elapsed();
    // `Auto` names itself after the strategy it runs.
    let runs = sorter.name();
    if name == "auto" {
        outcome.plan = Some(runs.to_owned());
    }
    if runs == "bsp" {
        outcome.fragments = sorter
            .stats()
            .polygons
            .saturating_sub(geometry.pieces().len());
    }
    let mut list = DrawList::new();
    for (view, truth) in views.iter().zip(truths) {
        let start = Instant::now();
        sorter.sort(view, &mut list);
        elapsed += start.elapsed();
        outcome.fallbacks += sorter.stats().fallbacks;
        if runs == "newell" {
            outcome.fragments = outcome.fragments.max(list.frame_fragments());
        }
        outcome.drawn_max = outcome.drawn_max.max(list.len());
        outcome.non_finite += non_finite(&list);
        outcome.violations += oracle::count_violations(view, &list);
        let ids = raster_sink::render_ids(view, &list);
        let error = raster_sink::pixel_error(&ids, truth);
        outcome.wrong_pixels += error.wrong;
        outcome.unambiguous_pixels += error.pixels;
    }
    outcome.ms = elapsed.as_secs_f64() * 1e3;
    outcome
}

/// NaN or infinite coordinates in a draw list's corners and planes.
fn non_finite(list: &DrawList) -> usize {
    let bad = |v: DVec3| usize::from(!v.is_finite());
    list.items()
        .iter()
        .map(|&item| {
            let plane = list.plane(item);
            list.corners(item).iter().map(|&c| bad(c)).sum::<usize>()
                + bad(plane.normal())
                + usize::from(!plane.offset().is_finite())
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::cases::separated;
    use super::*;
    use face_sort::sorter_api::DrawListWriter;

    /// The fast subset: every class of the issue once, at 64 × 64 pixels. Exact sorters must
    /// have no violation, no wrong pixel, no non-finite output and no fallback, and nothing
    /// may panic.
    #[test]
    fn quick_stress_subset_passes() {
        let cases = quick_cases().unwrap();
        let groups: std::collections::BTreeSet<&str> = cases.iter().map(|c| c.group).collect();
        assert_eq!(
            groups.into_iter().collect::<Vec<_>>(),
            [
                "coplanar",
                "degenerate",
                "generated",
                "position",
                "scale",
                "views"
            ]
        );
        let mut problems = Vec::new();
        let mut judged_pixels = 0;
        for case in cases {
            let report = run_isolated(case, 64, Duration::from_secs(600));
            problems.extend(report.problems());
            judged_pixels += report
                .outcomes
                .iter()
                .map(|o| o.unambiguous_pixels)
                .sum::<usize>();
        }
        assert!(problems.is_empty(), "{problems:#?}");
        // The pixel check saw pixels (it is not vacuous).
        assert!(judged_pixels > 10_000, "{judged_pixels}");
    }

    /// The checks can fail: a reversed draw order of an exact sorter shows up as violations
    /// and wrong pixels, and a panic inside a case is caught and reported.
    #[test]
    fn the_checks_can_fail() {
        let report = run_isolated(
            Case {
                group: "test",
                name: "typed error".to_owned(),
                mesh: Err("unused".to_owned()),
                shots: vec![],
                judged: true,
                expect_error: true,
            },
            64,
            Duration::from_secs(60),
        );
        // An expected mesh error is a typed outcome, not a failure; an unexpected one is.
        assert!(report.problems().is_empty());
        let mut unexpected = report.clone();
        unexpected.expect_error = false;
        assert_eq!(unexpected.problems().len(), 1);
        let mut bad = CaseReport {
            group: "test".to_owned(),
            name: "x".to_owned(),
            faces: 1,
            pieces: 1,
            views: vec![],
            judged: true,
            expect_error: false,
            error: None,
            failure: None,
            outcomes: vec![Outcome {
                sorter: "bsp".to_owned(),
                violations: 1,
                ..Outcome::default()
            }],
        };
        assert_eq!(bad.problems().len(), 1);
        bad.outcomes[0].sorter = REFERENCE.to_owned();
        assert!(bad.problems().is_empty(), "the reference is not judged");
        // A BSP tree beyond the default fragment budget (max(16 · pieces, 4096)) is a problem.
        bad.outcomes[0] = Outcome {
            sorter: "bsp".to_owned(),
            fragments: 4096,
            ..Outcome::default()
        };
        assert_eq!(bad.problems().len(), 1, "{:?}", bad.problems());
        bad.outcomes[0].fragments = 4095;
        assert!(bad.problems().is_empty());
        // The oracle and the truth see a reversed order on overlapping squares.
        let mesh = separated(1e-3).unwrap();
        let geometry = Geometry::new(&mesh).unwrap();
        let view = Shot::ortho(30.0, 20.0, 0.0, CullMode::None).view(&geometry, 64);
        let truth = raster_sink::truth(&view, &geometry);
        let mut sorter = SorterKind::Bsp.build(&geometry);
        let mut list = DrawList::new();
        sorter.sort(&view, &mut list);
        list.items_mut().reverse();
        assert!(oracle::count_violations(&view, &list) > 0);
        let ids = raster_sink::render_ids(&view, &list);
        assert!(raster_sink::pixel_error(&ids, &truth).wrong > 0);
    }

    #[test]
    fn panics_and_hangs_are_reported_not_hidden() {
        assert_eq!(isolated("ok", Duration::from_secs(60), || 7), Ok(7));
        assert_eq!(
            isolated("panics", Duration::from_secs(60), || -> u32 {
                panic!("boom {}", 1)
            }),
            Err("panic: boom 1".to_owned())
        );
        // Never returns: the time-out is the only way out, whatever the machine's load.
        let hung = isolated("hangs", Duration::from_millis(100), || {
            loop {
                std::thread::park();
            }
        });
        assert_eq!(hung, Err("no result within 0.1 s (hung?)".to_owned()));
    }
}
