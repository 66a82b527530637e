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
    /// Write the table into docs/ROBUSTNESS.md between its markers.
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

/// The sorters run on every case: the exact ones, then the reference.
const SORTERS: [&str; 4] = ["bsp", "newell", "auto", "centroid"];

/// The sorters whose failures fail the run.
fn is_exact(name: &str) -> bool {
    matches!(name, "bsp" | "newell" | "auto")
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

// ---------------------------------------------------------------------------------------
// Cases.

/// Positions of `mesh` mapped by `f` (computed in f64, then stored: the rounding a file at
/// that position or scale would carry).
fn mapped(mesh: &PolygonMesh, f: impl Fn(DVec3) -> DVec3) -> Result<PolygonMesh, String> {
    let positions = mesh.positions().iter().map(|&p| f(p)).collect();
    PolygonMesh::new(positions, mesh.faces()).map_err(|e| format!("MeshError: {e}"))
}

/// A polygon mesh from loose polygons (every polygon its own vertices).
fn soup(polygons: &[Vec<DVec3>]) -> Result<PolygonMesh, String> {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for poly in polygons {
        let start = positions.len() as u32;
        positions.extend_from_slice(poly);
        faces.push((start..start + poly.len() as u32).collect::<Vec<u32>>());
    }
    PolygonMesh::new(positions, &faces).map_err(|e| format!("MeshError: {e}"))
}

/// A rectangle centred at `centre` spanned by the half axes `u`, `v` (counter-clockwise
/// seen from `u × v`).
fn rect(centre: DVec3, u: DVec3, v: DVec3) -> Vec<DVec3> {
    vec![
        centre - u - v,
        centre + u - v,
        centre + u + v,
        centre - u + v,
    ]
}

/// A generic rotation (no axis alignment), so that planes are not exact in f64.
fn tilt() -> DMat3 {
    DMat3::from_euler(EulerRot::YXZ, 0.61, 0.37, 0.23)
}

/// The repository models the position and scale cases transform, with their cull mode.
fn base_models() -> Result<Vec<(String, PolygonMesh, CullMode)>> {
    let mut out = Vec::new();
    for (name, path) in [
        ("suzanne", "assets/models/suzanne/suzanne.obj"),
        ("cornell-box", "assets/models/cornell-box/cornell_box.obj"),
        (
            "spot-control",
            "assets/models/keenan-crane/spot/spot_control_mesh.obj",
        ),
    ] {
        let scene = scenes::model_scene(name, path)?;
        out.push((name.to_owned(), scene.mesh, scene.cull));
    }
    // spot's quadrangulated mesh: most of its quads are not planar (fans of triangles).
    let spot = scenes::model_scene(
        "spot",
        "assets/models/keenan-crane/spot/spot_quadrangulated.obj",
    )?;
    out.push(("spot".to_owned(), spot.mesh, spot.cull));
    // fandisk: a CAD model, flat regions split into many coplanar quads.
    let fandisk = scenes::model_scene(
        "fandisk",
        "assets/models/fandisk-quads/fandisk_quads.converted.obj",
    )?;
    out.push(("fandisk".to_owned(), fandisk.mesh, fandisk.cull));
    // Meshes in convex position, where the planner orders by culling alone.
    let cube = scenes::model_scene("box", "assets/models/assimp-obj/box.obj")?;
    out.push(("box".to_owned(), cube.mesh, CullMode::Back));
    out.push((
        "uv-sphere-512".to_owned(),
        face_sort::generate::uv_sphere(32, 16),
        CullMode::Back,
    ));
    out.push((
        "uv-sphere-8k".to_owned(),
        face_sort::generate::uv_sphere(128, 64),
        CullMode::Back,
    ));
    let quads = scenes::random_quads(40, 11)?;
    out.push(("random-quads-40".to_owned(), quads.mesh, CullMode::None));
    out.push((
        "bumpy-torus-1k".to_owned(),
        face_sort::generate::torus(1_000),
        CullMode::Back,
    ));
    Ok(out)
}

/// Position and scale: every base model translated and scaled.
fn transform_cases(models: &[(String, PolygonMesh, CullMode)], quick: bool) -> Vec<Case> {
    let mut out = Vec::new();
    let translations: &[f64] = if quick {
        &[1e7]
    } else {
        &[1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9]
    };
    // 1e±100 are outside what face-sort accepts: the typed error is the expected outcome.
    let scales: &[f64] = if quick {
        &[1e-6, 1e6, 1e100]
    } else {
        &[1e-6, 1e-4, 1e-2, 1e2, 1e4, 1e6, 1e-50, 1e50, 1e-100, 1e100]
    };
    let direction = DVec3::new(1.0, -0.6, 0.35);
    for (name, mesh, cull) in models {
        let shots = if quick {
            vec![Shot::ortho(30.0, 20.0, 0.0, *cull)]
        } else {
            general_shots(*cull)
        };
        for &t in translations {
            out.push(Case {
                group: "position",
                name: format!("{name} moved {t:e}"),
                mesh: mapped(mesh, |p| p + direction * t),
                shots: shots.clone(),
                judged: true,
                expect_error: false,
            });
        }
        for &s in scales {
            out.push(Case {
                group: "scale",
                name: format!("{name} scaled {s:e}"),
                mesh: mapped(mesh, |p| p * s),
                shots: shots.clone(),
                judged: true,
                // Outside face-sort's range (1e-60 to 1e60): refused.
                expect_error: !(1e-60..=1e60).contains(&s),
            });
        }
        if !quick {
            // Small and far: the stored positions keep about 1e-7 (1e6) and 1e-6 (1e7) of
            // the model's size.
            for t in [1e6, 1e7] {
                out.push(Case {
                    group: "position",
                    name: format!("{name} scaled 1e-3 moved {t:e}"),
                    mesh: mapped(mesh, |p| p * 1e-3 + direction * t),
                    shots: shots.clone(),
                    judged: true,
                    expect_error: false,
                });
            }
        }
    }
    out
}

/// Three overlapping parallel squares `gap · L` apart (tilted), seen from general views.
fn separated(gap_rel: f64) -> Result<PolygonMesh, String> {
    let r = tilt();
    let (u, v, n) = (r * DVec3::X, r * DVec3::Y, r * DVec3::Z);
    // L of three unit squares shifted by 0.4: about 2.6; the gap is relative to it.
    let gap = gap_rel * 2.6;
    let polygons: Vec<Vec<DVec3>> = (0..3)
        .map(|k| {
            let k = f64::from(k);
            rect(u * (0.4 * k) + v * (0.25 * k) + n * (gap * k), u, v)
        })
        .collect();
    soup(&polygons)
}

/// Exactly coplanar overlapping polygons (axis-aligned, so exact in f64; and tilted,
/// coplanar up to round-off), some with opposite winding.
fn coplanar(tilted: bool) -> Result<PolygonMesh, String> {
    let r = if tilted { tilt() } else { DMat3::IDENTITY };
    let (u, v) = (r * DVec3::X, r * DVec3::Y);
    let mut polygons = Vec::new();
    let mut rng = Rng::new(5);
    for k in 0..12 {
        let c = u * rng.range(-1.0, 1.0) + v * rng.range(-1.0, 1.0);
        let mut p = rect(c, u * rng.range(0.2, 0.9), v * rng.range(0.2, 0.9));
        if k % 3 == 0 {
            p.reverse();
        }
        polygons.push(p);
    }
    // A crossing quad, so the coplanar set is not alone in the scene.
    let n = r * DVec3::Z;
    polygons.push(rect(DVec3::ZERO, u * 1.2, n * 0.8));
    soup(&polygons)
}

/// Every face of `mesh` twice: as is, and reversed (opposite winding, same place).
fn doubled(mesh: &PolygonMesh) -> Result<PolygonMesh, String> {
    let mut faces: Vec<Vec<u32>> = mesh.faces().map(<[u32]>::to_vec).collect();
    let reversed: Vec<Vec<u32>> = faces
        .iter()
        .map(|f| f.iter().rev().copied().collect())
        .collect();
    faces.extend(reversed);
    PolygonMesh::new(mesh.positions().to_vec(), &faces).map_err(|e| format!("MeshError: {e}"))
}

/// Slivers of aspect ratio `aspect` crossing each other over a background square.
fn slivers(aspect: f64) -> Result<PolygonMesh, String> {
    let mut rng = Rng::new(17);
    let mut polygons = vec![rect(
        DVec3::new(0.0, 0.0, -0.6),
        DVec3::X * 1.2,
        DVec3::Y * 1.2,
    )];
    for _ in 0..24 {
        let along = rng.direction() * 0.5;
        let side = along.any_orthonormal_vector() * (1.0 / aspect);
        let centre = DVec3::new(
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
        );
        polygons.push(rect(centre, along, side));
    }
    soup(&polygons)
}

/// Random quads plus near-degenerate faces: triangles whose apex is `1e-10 · D` off the base
/// line, and quads with two corners `1e-12 · D` apart.
fn near_degenerate() -> Result<PolygonMesh, String> {
    let mut rng = Rng::new(23);
    let mut polygons = Vec::new();
    for _ in 0..30 {
        let a = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let d = rng.direction() * 0.8;
        let off = d.any_orthonormal_vector();
        if rng.unit() < 0.5 {
            polygons.push(vec![a, a + d, a + d * 0.5 + off * (0.8e-10)]);
        } else {
            let b = a + d;
            polygons.push(vec![a, b, b + off * 1e-12, a + off * 0.6]);
        }
        polygons.push(rect(a, d * 0.5, off * 0.4));
    }
    soup(&polygons)
}

/// A sheet of quads with exactly degenerate faces mixed in: collinear corners, a repeated
/// index, all corners at one point.
fn degenerate() -> Result<PolygonMesh, String> {
    let mut positions = Vec::new();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    let r = tilt();
    for k in 0..6 {
        let z = f64::from(k) * 0.15;
        let start = positions.len() as u32;
        for p in rect(DVec3::new(0.1 * f64::from(k), 0.0, z), DVec3::X, DVec3::Y) {
            positions.push(r * p);
        }
        faces.push((start..start + 4).collect());
        // Collinear: three points on one edge.
        let e = positions.len() as u32;
        let (a, b) = (positions[start as usize], positions[start as usize + 1]);
        positions.extend([a, (a + b) * 0.5, b]);
        faces.push(vec![e, e + 1, e + 2]);
        // A repeated index.
        faces.push(vec![start, start + 1, start + 1]);
        // One point.
        faces.push(vec![start + 2, start + 2, start + 2, start + 2]);
    }
    PolygonMesh::new(positions, &faces).map_err(|e| format!("MeshError: {e}"))
}

/// A NaN and an infinite position: the typed error `MeshError::NonFinitePosition` is the
/// right outcome.
fn non_finite_positions() -> Result<PolygonMesh, String> {
    let mut positions = rect(DVec3::ZERO, DVec3::X, DVec3::Y);
    positions.push(DVec3::new(f64::NAN, 0.0, 0.0));
    positions.push(DVec3::new(0.0, f64::INFINITY, 0.0));
    PolygonMesh::new(
        positions,
        [vec![0u32, 1, 2, 3], vec![0, 1, 4], vec![1, 2, 5]],
    )
    .map_err(|e| format!("MeshError: {e}"))
}

/// Only degenerate faces: the typed error `MeshError::Empty` is the right outcome.
fn all_degenerate() -> Result<PolygonMesh, String> {
    let positions = vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::X * 2.0,
        DVec3::new(1.0, 1.0, 1.0),
    ];
    PolygonMesh::new(positions, [[0u32, 1, 2], [3, 3, 3]]).map_err(|e| format!("MeshError: {e}"))
}

/// Two crossing sheets of `n × n` quads, every quad's corners lifted by up to
/// `angle · size` off its plane (non-planar by about `angle` radians).
fn twisted(angle: f64) -> Result<PolygonMesh, String> {
    let n = 8;
    let mut rng = Rng::new(31);
    let mut polygons = Vec::new();
    for sheet in 0..2 {
        let r = if sheet == 0 {
            tilt()
        } else {
            tilt() * DMat3::from_rotation_x(1.1)
        };
        let cell = 2.0 / f64::from(n);
        for i in 0..n {
            for j in 0..n {
                let c = DVec3::new(
                    -1.0 + cell * (f64::from(i) + 0.5),
                    -1.0 + cell * (f64::from(j) + 0.5),
                    0.0,
                );
                let h = cell * 0.5;
                // The second sheet is shifted by a third of a cell, so that the line where
                // the sheets cross runs through cells, not along their edges.
                let shift = DVec3::Y * (cell / 3.0) * f64::from(sheet);
                let mut q = rect(c + shift, DVec3::X * h, DVec3::Y * h);
                // Opposite corners up and down: a twist of about `angle`.
                let lift = angle * cell * rng.range(0.5, 1.0);
                q[0].z += lift;
                q[2].z += lift;
                q[1].z -= lift;
                q[3].z -= lift;
                polygons.push(q.into_iter().map(|p| r * p).collect());
            }
        }
    }
    soup(&polygons)
}

/// A box whose faces are split unevenly (2 × 2, 1 × 3, …), so that edges end in the middle
/// of neighbours' edges (T-junctions); and a second, smaller box inside it.
fn t_junctions() -> Result<PolygonMesh, String> {
    let mut positions: Vec<DVec3> = Vec::new();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    let mut push = |quad: [DVec3; 4]| {
        let start = positions.len() as u32;
        positions.extend(quad);
        faces.push((start..start + 4).collect());
    };
    for (scale, offset) in [(1.0, DVec3::ZERO), (0.35, DVec3::new(0.1, -0.2, 0.15))] {
        // Each face of the cube [-1, 1]³ as (normal axis, sign), split into a × b cells.
        for (axis, sign, a, b) in [
            (0usize, 1.0, 2usize, 2usize),
            (0, -1.0, 1, 3),
            (1, 1.0, 3, 1),
            (1, -1.0, 2, 1),
            (2, 1.0, 1, 2),
            (2, -1.0, 3, 3),
        ] {
            let n = DVec3::AXES[axis] * sign;
            let u = DVec3::AXES[(axis + 1) % 3];
            let v = n.cross(u);
            for i in 0..a {
                for j in 0..b {
                    let (u0, u1) = (
                        -1.0 + 2.0 * i as f64 / a as f64,
                        -1.0 + 2.0 * (i + 1) as f64 / a as f64,
                    );
                    let (v0, v1) = (
                        -1.0 + 2.0 * j as f64 / b as f64,
                        -1.0 + 2.0 * (j + 1) as f64 / b as f64,
                    );
                    let p = |s: f64, t: f64| (n + u * s + v * t) * scale + offset;
                    push([p(u0, v0), p(u1, v0), p(u1, v1), p(u0, v1)]);
                }
            }
        }
    }
    PolygonMesh::new(positions, &faces).map_err(|e| format!("MeshError: {e}"))
}

/// `mesh` unwelded (every face its own copies of its vertices) and every position listed
/// twice; plus each quad's first corner repeated (a zero-length edge).
fn duplicate_vertices(mesh: &PolygonMesh) -> Result<PolygonMesh, String> {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for face in mesh.faces() {
        let start = positions.len() as u32;
        for &i in face {
            let p = mesh.positions()[i as usize];
            positions.push(p);
            positions.push(p);
        }
        let mut f: Vec<u32> = (0..face.len() as u32).map(|k| start + 2 * k).collect();
        if face.len() == 4 {
            f.insert(1, start + 1);
        }
        faces.push(f);
    }
    PolygonMesh::new(positions, &faces).map_err(|e| format!("MeshError: {e}"))
}

/// Pages of a book opened all the way round the z axis: quads in planes through the axis, so
/// that a view down the axis (orthographic, or perspective with the eye on it) sees every
/// page exactly edge-on; a closing square at each end.
fn pages() -> Result<PolygonMesh, String> {
    let mut polygons = Vec::new();
    for k in 0..8 {
        let a = f64::from(k) * std::f64::consts::TAU / 8.0 + 0.1;
        let d = DVec3::new(a.cos(), a.sin(), 0.0);
        polygons.push(vec![
            d * 0.2 + DVec3::Z * -1.0,
            d + DVec3::Z * -1.0,
            d + DVec3::Z,
            d * 0.2 + DVec3::Z,
        ]);
    }
    polygons.push(rect(DVec3::Z * -1.3, DVec3::X * 0.9, DVec3::Y * 0.9));
    polygons.push(rect(DVec3::Z * 1.3, DVec3::X * 0.5, DVec3::Y * 0.5));
    soup(&polygons)
}

/// Views along the axes (edge-on to every axis-aligned face), and perspective with the eye
/// close to, at the surface of, and inside the model (down to `0.01 · L` from its centre;
/// closer, the oracle's own pixel-space round-off decides: docs/ROBUSTNESS.md).
fn view_shots(cull: CullMode) -> Vec<Shot> {
    vec![
        Shot::ortho(0.0, 0.0, 0.0, cull),
        Shot::ortho(90.0, 0.0, 0.0, cull),
        Shot::ortho(180.0, 0.0, 0.0, cull),
        Shot::ortho(0.0, 90.0, 0.0, cull),
        Shot::ortho(0.0, -90.0, 0.0, cull),
        Shot::persp(0.0, 0.0, 0.55, cull),
        Shot::persp(90.0, 0.0, 0.3, cull),
        Shot::persp(35.0, 20.0, 0.1, CullMode::None),
        Shot::persp(200.0, -30.0, 0.01, CullMode::None),
    ]
}

/// Every case of the list.
fn all_cases() -> Result<Vec<Case>> {
    let models = base_models()?;
    let mut out = transform_cases(&models, false);
    out.extend(generated_cases(&models, false)?);
    Ok(out)
}

/// The fast subset `cargo test` runs: small models, one or two instances per class.
pub fn quick_cases() -> Result<Vec<Case>> {
    let box_scene =
        scenes::model_scene("cornell-box", "assets/models/cornell-box/cornell_box.obj")?;
    let quads = scenes::random_quads(16, 11)?;
    let models = vec![
        ("cornell-box".to_owned(), box_scene.mesh, CullMode::None),
        ("random-quads-16".to_owned(), quads.mesh, CullMode::None),
        (
            "uv-sphere-128".to_owned(),
            face_sort::generate::uv_sphere(16, 8),
            CullMode::Back,
        ),
    ];
    let mut out = transform_cases(&models, true);
    out.extend(generated_cases(&models, true)?);
    Ok(out)
}

/// Scenes of `face_sort::strategies::any_scene` (non-intersecting, interpenetrating, cyclic,
/// crossing; tiny and huge coordinates), drawn with a fixed seed.
fn strategy_scenes(count: usize) -> Result<Vec<PolygonMesh>> {
    use proptest::strategy::{Strategy as _, ValueTree as _};
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let mut runner = TestRunner::new_with_rng(
        Config::default(),
        TestRng::from_seed(RngAlgorithm::ChaCha, &[7; 32]),
    );
    let strategy = face_sort::strategies::any_scene();
    (0..count)
        .map(|i| {
            strategy
                .new_tree(&mut runner)
                .map(|tree| tree.current())
                .map_err(|e| anyhow::anyhow!("generating strategy scene {i}: {e}"))
        })
        .collect()
}

fn generated_cases(models: &[(String, PolygonMesh, CullMode)], quick: bool) -> Result<Vec<Case>> {
    let mut out = Vec::new();
    let direction = DVec3::new(-0.3, 1.0, 0.8);
    for (i, scene) in strategy_scenes(if quick { 2 } else { 12 })?
        .iter()
        .enumerate()
    {
        let shots = general_shots(CullMode::None);
        let shots: Vec<Shot> = shots.into_iter().take(if quick { 1 } else { 5 }).collect();
        out.push(Case {
            group: "generated",
            name: format!("strategies scene {i}"),
            mesh: Ok(scene.clone()),
            shots: shots.clone(),
            judged: true,
            expect_error: false,
        });
        out.push(Case {
            group: "generated",
            name: format!("strategies scene {i} moved 1e7"),
            mesh: mapped(scene, |p| p + direction * 1e7),
            shots,
            judged: true,
            expect_error: false,
        });
    }
    let general = general_shots(CullMode::None);
    let two =
        |s: &[Shot]| -> Vec<Shot> { s.iter().take(if quick { 1 } else { 5 }).copied().collect() };
    let gaps: &[i32] = if quick { &[3, 9] } else { &[3, 5, 7, 8, 9] };
    for &k in gaps {
        let gap = 10f64.powi(-k);
        out.push(Case {
            group: "coplanar",
            name: format!("squares 1e-{k} L apart"),
            mesh: separated(gap),
            shots: two(&general),
            judged: true,
            expect_error: false,
        });
    }
    for tilted in [false, true] {
        out.push(Case {
            group: "coplanar",
            name: format!(
                "coplanar overlapping ({})",
                if tilted { "tilted" } else { "axis-aligned" }
            ),
            mesh: coplanar(tilted),
            shots: two(&general),
            judged: true,
            expect_error: false,
        });
    }
    let closed = &models[0];
    for cull in [CullMode::Back, CullMode::None] {
        let label = if cull == CullMode::Back {
            "back"
        } else {
            "none"
        };
        out.push(Case {
            group: "coplanar",
            name: format!("{} doubled, opposite winding, cull {label}", closed.0),
            mesh: doubled(&closed.1),
            shots: two(&general_shots(cull)),
            judged: true,
            expect_error: false,
        });
    }
    let aspects: &[f64] = if quick { &[1e6] } else { &[1e3, 1e6] };
    for &a in aspects {
        out.push(Case {
            group: "degenerate",
            name: format!("slivers aspect {a:e}"),
            mesh: slivers(a),
            shots: two(&general),
            judged: true,
            expect_error: false,
        });
    }
    out.push(Case {
        group: "degenerate",
        name: "near-degenerate faces".to_owned(),
        mesh: near_degenerate(),
        shots: two(&general),
        judged: true,
        expect_error: false,
    });
    out.push(Case {
        group: "degenerate",
        name: "degenerate faces mixed in".to_owned(),
        mesh: degenerate(),
        shots: two(&general),
        judged: true,
        expect_error: false,
    });
    out.push(Case {
        group: "degenerate",
        name: "only degenerate faces (typed error expected)".to_owned(),
        mesh: all_degenerate(),
        shots: two(&general),
        judged: true,
        expect_error: true,
    });
    out.push(Case {
        group: "degenerate",
        name: "NaN and infinite positions (typed error expected)".to_owned(),
        mesh: non_finite_positions(),
        shots: two(&general),
        judged: true,
        expect_error: true,
    });
    let angles: &[f64] = if quick {
        &[1e-6]
    } else {
        &[1e-9, 1e-7, 1e-6, 1e-5, 1e-3]
    };
    for &a in angles {
        out.push(Case {
            group: "degenerate",
            name: format!("quads twisted {a:e} rad"),
            mesh: twisted(a),
            shots: two(&general),
            judged: true,
            expect_error: false,
        });
    }
    out.push(Case {
        group: "degenerate",
        name: "T-junctions (split box faces)".to_owned(),
        mesh: t_junctions(),
        shots: two(&general_shots(CullMode::Back)),
        judged: true,
        expect_error: false,
    });
    for (name, mesh, cull) in models.iter().take(if quick { 1 } else { 2 }) {
        out.push(Case {
            group: "degenerate",
            name: format!("{name} duplicate vertices"),
            mesh: duplicate_vertices(mesh),
            shots: two(&general_shots(*cull)),
            judged: true,
            expect_error: false,
        });
    }
    let view_models: Vec<(String, Result<PolygonMesh, String>, CullMode)> = if quick {
        vec![(models[0].0.clone(), Ok(models[0].1.clone()), CullMode::None)]
    } else {
        let mut v: Vec<_> = models
            .iter()
            .take(3)
            .map(|(n, m, c)| (n.clone(), Ok(m.clone()), *c))
            .collect();
        v.push(("T-junction boxes".to_owned(), t_junctions(), CullMode::Back));
        v.push((
            "book pages round the view axis".to_owned(),
            pages(),
            CullMode::None,
        ));
        let nested = scenes::nested_boxes()?;
        v.push(("nested-boxes".to_owned(), Ok(nested.mesh), CullMode::None));
        // Exactly edge-on views of faces whose stored positions are rounded far from the
        // origin.
        let far = DVec3::new(1.0, -0.6, 0.35) * 1e7;
        for (name, mesh, cull) in models.iter().take(3) {
            v.push((
                format!("{name} moved 1e7"),
                mapped(mesh, |p| p + far),
                *cull,
            ));
        }
        v
    };
    for (name, mesh, cull) in view_models {
        let shots = view_shots(cull);
        let shots = if quick {
            vec![shots[0], shots[3], shots[6], shots[8]]
        } else {
            shots
        };
        out.push(Case {
            group: "views",
            name: format!("{name}: axes, edge-on, eye close and inside"),
            mesh,
            shots,
            judged: true,
            expect_error: false,
        });
    }
    Ok(out)
}

// ---------------------------------------------------------------------------------------
// Report.

/// The markdown table of a run: one row per case, one column group per sorter.
pub fn markdown(reports: &[CaseReport], size: u32) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "One row per case, figures summed over its views ({size}×{size} px). Per sorter: \
         order violations (oracle) / wrong unambiguous pixels against the z-buffer truth / \
         fragments beyond the pieces (BSP: the tree's; Newell: most cut in one frame) / \
         milliseconds (build + sorts). **px** unambiguous pixels judged per sorter; \
         **NaN, fb** non-finite coordinates in the exact sorters' draw lists and frames \
         where they gave up exactness. `auto` is the planner (in brackets what it ran: \
         `cull-only` on meshes in convex position); `centroid` is the inexact reference.\n"
    );
    let _ = writeln!(
        s,
        "| group | case | pieces | views | px | bsp | newell | auto | centroid | NaN, fb | status |"
    );
    let _ = writeln!(
        s,
        "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"
    );
    for r in reports {
        let head = format!(
            "| {} | {} | {} | {} |",
            r.group,
            r.name,
            r.pieces,
            r.views.len()
        );
        if let Some(f) = &r.failure {
            let _ = writeln!(s, "{head} | | | | | | **FAIL**: {f} |");
            continue;
        }
        if let Some(e) = &r.error {
            let _ = writeln!(s, "{head} | | | | | | typed error: {e} |");
            continue;
        }
        let pixels = r.outcomes.first().map_or(0, |o| o.unambiguous_pixels);
        let cell = |name: &str| {
            r.outcomes
                .iter()
                .find(|o| o.sorter == name)
                .map_or_else(String::new, |o| match &o.panic {
                    Some(_) => "panic".to_owned(),
                    None if name == "centroid" => format!("{} / {}", o.violations, o.wrong_pixels),
                    None if name == "auto" => format!(
                        "{} / {} ({})",
                        o.violations,
                        o.wrong_pixels,
                        o.plan.as_deref().unwrap_or("?")
                    ),
                    None => format!(
                        "{} / {} / {} / {:.1}",
                        o.violations, o.wrong_pixels, o.fragments, o.ms
                    ),
                })
        };
        let exact = r.outcomes.iter().filter(|o| is_exact(&o.sorter));
        let (nan, fb) = exact.fold((0, 0), |(n, f), o| (n + o.non_finite, f + o.fallbacks));
        let problems = r.problems();
        let status = if problems.is_empty() {
            "ok".to_owned()
        } else if r.outcomes.iter().any(|o| o.panic.is_some()) {
            "**PANIC**".to_owned()
        } else {
            "**FAIL**".to_owned()
        };
        let _ = writeln!(
            s,
            "{head} {pixels} | {} | {} | {} | {} | {nan}, {fb} | {status} |",
            cell("bsp"),
            cell("newell"),
            cell("auto"),
            cell("centroid"),
        );
    }
    s
}

const BEGIN: &str = "<!-- stress:begin (cargo xtask stress --docs) -->";
const END: &str = "<!-- stress:end -->";

fn write_docs(table: &str, args: &StressArgs) -> Result<()> {
    let path = crate::workspace_root().join("docs/ROBUSTNESS.md");
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let (Some(b), Some(e)) = (text.find(BEGIN), text.find(END)) else {
        bail!("{} has no markers {BEGIN} … {END}", path.display());
    };
    if e < b {
        bail!(
            "{}: the end marker comes before the begin marker",
            path.display()
        );
    }
    let mut command = "cargo xtask stress".to_owned();
    if args.quick {
        command.push_str(" --quick");
    }
    if args.size != 256 {
        let _ = write!(command, " --size {}", args.size);
    }
    let out = format!(
        "{}{BEGIN}\nCommand: `{command} --docs`.\n\n{table}\n{}",
        &text[..b],
        &text[e..]
    );
    std::fs::write(&path, out).with_context(|| format!("writing {}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

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
        bad.outcomes[0].sorter = "centroid".to_owned();
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
