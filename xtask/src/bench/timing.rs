//! Timing and checking on the repository's scenes: views, timed frames, medians, and the
//! per-(sorter, projection) accumulation of fragments, pixel error and oracle violations.

use std::time::Instant;

use anyhow::{Context, Result};
use face_sort::{DrawList, FaceSorter, Geometry, SorterKind, View, oracle};

use super::{Budget, PEER, Row};
use crate::peer::PlaneSplitPeer;
use crate::raster;
use crate::scenes::Scene;

/// Yaw turned between two timed frames, degrees: each timed frame orders a view no frame
/// ordered just before, as an animation does (a slow orbit: 1.2° per second at 60 frames per
/// second). Timing one view over and over instead lets the CPU's branch predictors learn a
/// sort's comparisons: before the centroid sort became a radix sort, it ran markedly faster
/// on a repeated view than on turning views, while the BSP's time did not move (figures in
/// docs/bench.md).
pub(super) const TURN_PER_FRAME_DEG: f64 = 0.02;

/// Turn of the wandering camera between two timed frames, degrees: each frame turns the
/// view by this about an axis drawn at random (seeded), so that the views drift over the
/// sphere instead of following one turn. A sorter that only handles turns about one axis
/// meets new views every frame there.
pub(super) const WANDER_PER_FRAME_DEG: f64 = 2.0;

/// How the timed frames of a view set move the camera.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Motion {
    /// [`TURN_PER_FRAME_DEG`] of yaw per frame.
    Turn,
    /// [`WANDER_PER_FRAME_DEG`] about a random axis per frame.
    Wander,
}

/// The bench's views of a scene: `yaws` yaws (offset from the axes) × pitches, each with the
/// views its timed frames move through (the first is the view itself).
fn views(
    geometry: &Geometry,
    scene: &Scene,
    budget: &Budget,
    size: u32,
    persp: bool,
    motion: Motion,
) -> Vec<Vec<View>> {
    let view = |yaw: f64, pitch: f64| {
        let view = View::fit(&geometry.bounds(), size, size)
            .with_yaw_pitch_roll(yaw, pitch, 0.0)
            .with_cull(scene.cull);
        if persp {
            view.with_perspective(f64::from(size))
        } else {
            view
        }
    };
    let mut out = Vec::new();
    let mut rng = test_support::Rng::new(0x57a9_de12);
    for k in 0..budget.yaws {
        let yaw = 15.0 + 360.0 * k as f64 / budget.yaws as f64;
        for &pitch in budget.pitches {
            out.push(match motion {
                Motion::Turn => (0..=budget.frames)
                    .map(|i| view(yaw + TURN_PER_FRAME_DEG * i as f64, pitch))
                    .collect(),
                Motion::Wander => {
                    let mut current = view(yaw, pitch);
                    let mut set = vec![current];
                    for _ in 0..budget.frames {
                        let turn = glam::DQuat::from_axis_angle(
                            rng.direction(),
                            WANDER_PER_FRAME_DEG.to_radians(),
                        );
                        current = current
                            .with_rotation(glam::DMat3::from_quat(turn) * current.rotation());
                        set.push(current);
                    }
                    set
                }
            });
        }
    }
    out
}

/// Times `frame(i)` for `i` = 1, 2, … until `budget.frames` frames or `budget.per_view`
/// elapsed (at least 3), after one untimed `frame(0)`.
pub(super) fn time_frames(budget: &Budget, times: &mut Vec<f64>, mut frame: impl FnMut(usize)) {
    frame(0); // warm-up: first-frame allocations are not the steady state.
    let start = Instant::now();
    for i in 1..=budget.frames {
        let t = Instant::now();
        frame(i);
        times.push(t.elapsed().as_secs_f64() * 1e6);
        if i >= 3 && start.elapsed() >= budget.per_view {
            break;
        }
    }
}

/// The median (NaN for none); sorts `values`.
pub(crate) fn median(values: &mut [f64]) -> f64 {
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
    /// Frames turning the view ([`TURN_PER_FRAME_DEG`]), and frames repeating it.
    times: Vec<f64>,
    same_view_times: Vec<f64>,
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
            same_view_us: median(&mut self.same_view_times),
            same_view_ratio_vs_centroid: f64::NAN,
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

/// Every sorter and the peer on one scene, orthographic and perspective.
pub(super) fn bench_scene(
    scene: &Scene,
    budget: &Budget,
    resolution: u32,
    presort_cache: Option<&std::path::Path>,
) -> Result<Vec<Row>> {
    let geometry = Geometry::new(&scene.mesh).with_context(|| format!("scene {}", scene.name))?;
    // Where the presorted certificate came from, when a cache directory is given.
    let mut certificate = None;
    let mut sorters: Vec<(Box<dyn FaceSorter>, f64)> = SorterKind::ALL
        .into_iter()
        .map(|kind| {
            let start = Instant::now();
            let own = kind.geometry_for(&scene.mesh)?;
            let cached = match presort_cache {
                Some(dir) if kind == SorterKind::Presorted => {
                    std::fs::create_dir_all(dir)
                        .with_context(|| format!("creating {}", dir.display()))?;
                    let file = dir.join(format!("{}.presort", scene.name.replace('/', "_")));
                    match crate::presort_cache::load_or_build(&own, Some(&file))? {
                        Ok((sorter, had, _)) => {
                            certificate = Some(had.words(Some(&file)));
                            Some(Box::new(sorter) as Box<dyn FaceSorter>)
                        }
                        Err(_) => None,
                    }
                }
                _ => None,
            };
            let sorter = cached.unwrap_or_else(|| kind.build(&own));
            let measured = start.elapsed().as_secs_f64() * 1e3;
            Ok((sorter, measured))
        })
        .collect::<Result<_>>()?;
    let pieces = geometry.pieces().len();
    let run_peer = pieces <= budget.peer_pieces;
    let mut peer = PlaneSplitPeer::new(&geometry);
    let mut list = DrawList::new();
    let mut rows = Vec::new();
    for (projection, persp, motion) in [
        ("ortho", false, Motion::Turn),
        ("persp", true, Motion::Turn),
        ("ortho wander", false, Motion::Wander),
        ("persp wander", true, Motion::Wander),
    ] {
        let views = views(&geometry, scene, budget, resolution, persp, motion);
        let mut accs: Vec<Acc> = sorters.iter().map(|_| Acc::default()).collect();
        let mut peer_acc = Acc::default();
        for turning in &views {
            let view = &turning[0];
            let truth = raster::truth(view, &geometry);
            for ((sorter, _), acc) in sorters.iter_mut().zip(accs.iter_mut()) {
                time_frames(budget, &mut acc.times, |i| {
                    sorter.sort(&turning[i], &mut list)
                });
                time_frames(budget, &mut acc.same_view_times, |_| {
                    sorter.sort(view, &mut list);
                });
                acc.check(view, &list, truth.as_ref());
            }
            if motion == Motion::Wander {
                let last = turning.last().expect("a view set has views");
                let truth = raster::truth(last, &geometry);
                for ((sorter, _), acc) in sorters.iter_mut().zip(accs.iter_mut()) {
                    sorter.sort(last, &mut list);
                    acc.check(last, &list, truth.as_ref());
                }
            }
            if run_peer {
                time_frames(budget, &mut peer_acc.times, |i| {
                    peer.frame(&turning[i]);
                });
                time_frames(budget, &mut peer_acc.same_view_times, |_| {
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
                let mut row = acc.row(sorter.name(), scene, &geometry, projection, build_ms);
                let stats = sorter.stats();
                if stats.fallback == Some(face_sort::FallbackReason::Refused) {
                    row.note = format!(
                        "build refused (a budget of PresortOptions): all {} frames drawn by the BSP",
                        stats.fallback_frames
                    );
                } else if stats.orders > 0 {
                    row.note = format!(
                        "{} orders, {} small cycles; {} fallback frames",
                        stats.orders, stats.cycles, stats.fallback_frames
                    );
                    if let Some(had) = &certificate {
                        row.note.push_str(&format!("; certificate {had}"));
                    }
                }
                row
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
        let centroid = (scene_rows.iter()).find(|r| r.sorter == SorterKind::Centroid.name());
        let (base, same_view_base) =
            centroid.map_or((f64::NAN, f64::NAN), |r| (r.frame_us, r.same_view_us));
        for row in &mut scene_rows {
            row.frame_ratio_vs_centroid = row.frame_us / base;
            row.same_view_ratio_vs_centroid = row.same_view_us / same_view_base;
        }
        rows.extend(scene_rows);
    }
    Ok(rows)
}
