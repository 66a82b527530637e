//! The scaling series: every sorter on generated planar tori of growing size, each
//! measurement skipped when its estimate from the previous sizes exceeds the budget.

use std::time::Instant;

use anyhow::Result;
use face_sort::{DrawList, Geometry, SorterKind, View};

use super::timing::{median, time_frames};
use super::{Budget, PEER, ScalingRow};
use crate::peer::PlaneSplitPeer;
use crate::scenes;

/// Scaling: build and per-frame time of every sorter on a planar torus of `faces` faces; skips a
/// measurement whose estimate from the previous sizes exceeds the budget.
pub(super) fn scaling_size(
    faces: usize,
    budget: &Budget,
    previous: &[ScalingRow],
) -> Result<Vec<ScalingRow>> {
    let scene = scenes::planar_torus(faces);
    let geometry = Geometry::new(&scene.mesh)?;
    let faces = geometry.face_count();
    let views: Vec<View> = [(30.0, 25.0), (200.0, -30.0)]
        .into_iter()
        .map(|(yaw, pitch)| {
            View::fit(&geometry.bounds(), 512, 512).with_yaw_pitch_roll(yaw, pitch, 0.0)
        })
        .collect();
    let limit_ms = budget.scaling_limit.as_secs_f64() * 1e3;
    // Extrapolates from the previous sizes with the growth exponent seen between the last
    // two (clamped to 1..=2; 2 when there is only one).
    let estimate = |sorter: &str, pick: fn(&ScalingRow) -> Option<f64>, scale_ms: f64| {
        let mut points: Vec<(usize, f64)> = previous
            .iter()
            .filter(|r| r.sorter == sorter)
            .filter_map(|r| pick(r).map(|v| (r.faces, v)))
            .collect();
        points.sort_by_key(|&(f, _)| f);
        let &(f1, v1) = points.last()?;
        let exponent = match points.len() {
            n if n >= 2 => {
                let (f0, v0) = points[n - 2];
                ((v1 / v0).ln() / (f1 as f64 / f0 as f64).ln()).clamp(1.0, 2.0)
            }
            _ => 2.0,
        };
        Some(v1 * scale_ms * (faces as f64 / f1 as f64).powf(exponent))
    };
    let skipped_before = |sorter: &str| {
        previous
            .iter()
            .any(|r| r.sorter == sorter && r.frame_us.is_none())
    };
    let frame_budget = Budget {
        frames: budget.frames.min(20),
        per_view: budget.per_view * 4,
        ..*budget
    };
    let mut out = Vec::new();
    let mut list = DrawList::new();
    // `bsp-merged` builds the same tree as `bsp`: the series measures the tree's growth once.
    for kind in SorterKind::ALL
        .into_iter()
        .filter(|&k| k != SorterKind::BspMerged)
    {
        let name = kind.name();
        let build_estimate = estimate(name, |r| r.build_ms, 1.0).unwrap_or(0.0);
        let frame_estimate = estimate(name, |r| r.frame_us, 1e-3).unwrap_or(0.0);
        if skipped_before(name) || build_estimate > limit_ms || frame_estimate * 4.0 > limit_ms {
            out.push(ScalingRow {
                sorter: name.to_owned(),
                faces,
                build_ms: None,
                frame_us: None,
                fragments: None,
                note: format!(
                    "skipped: estimated build {:.0} ms / frame {:.0} ms over the {:.0} s limit",
                    build_estimate,
                    frame_estimate,
                    limit_ms / 1e3
                ),
            });
            continue;
        }
        let start = Instant::now();
        let mut sorter = kind.build(&geometry);
        let measured = start.elapsed().as_secs_f64() * 1e3;
        let build_ms = match sorter.stats().build_ms {
            b if b > 0.0 => b,
            _ => measured,
        };
        let mut times = Vec::new();
        let mut items = 0;
        for view in &views {
            time_frames(&frame_budget, &mut times, |_| sorter.sort(view, &mut list));
            items += list.len();
        }
        out.push(ScalingRow {
            sorter: name.to_owned(),
            faces,
            build_ms: Some(build_ms),
            frame_us: Some(median(&mut times)),
            fragments: Some(items as f64 / views.len() as f64),
            note: String::new(),
        });
    }
    // The peer, per-frame only.
    let pieces = geometry.pieces().len();
    let frame_estimate = estimate(PEER, |r| r.frame_us, 1e-3).unwrap_or(0.0);
    if pieces > budget.peer_pieces || skipped_before(PEER) || frame_estimate * 4.0 > limit_ms {
        out.push(ScalingRow {
            sorter: PEER.to_owned(),
            faces,
            build_ms: None,
            frame_us: None,
            fragments: None,
            note: format!(
                "skipped: {pieces} pieces, rebuilt per frame (limit {})",
                budget.peer_pieces
            ),
        });
    } else {
        let mut peer = PlaneSplitPeer::new(&geometry);
        let mut times = Vec::new();
        let mut items = 0;
        for view in &views {
            time_frames(&frame_budget, &mut times, |_| {
                items = peer.frame(view);
            });
        }
        out.push(ScalingRow {
            sorter: PEER.to_owned(),
            faces,
            build_ms: Some(0.0),
            frame_us: Some(median(&mut times)),
            fragments: Some(items as f64),
            note: "rebuilt every frame".to_owned(),
        });
    }
    Ok(out)
}
