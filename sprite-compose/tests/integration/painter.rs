//! SpritePainter against the recording backend: the rebuild table, minimal diffs, rotation.

use std::time::Duration;

use sprite_compose::face_sort::{CullMode, Geometry, ProjectionScratch, SorterKind, View};
use sprite_compose::glam::{DMat3, DVec2, DVec3};
use sprite_compose::{
    Brush, FrameStats, OpCounts, RecordingCompositor, SpriteId, SpritePainter,
    rotation_from_yaw_pitch_roll,
};

use crate::support::{self, Rng};

fn painter(
    geometry: &Geometry,
    kind: SorterKind,
    view: View,
) -> SpritePainter<RecordingCompositor> {
    SpritePainter::new(
        geometry,
        kind.build(geometry),
        view,
        RecordingCompositor::new(),
    )
}

fn sphere() -> Geometry {
    support::geometry(&test_support::models::uv_sphere(12, 8))
}

/// Checks that the backend shows exactly the draw list, in order, at the right pixels.
fn assert_scene_matches(p: &SpritePainter<RecordingCompositor>) {
    let scene = p.compositor().scene();
    let list = p.draw_list();
    let shown: Vec<u32> = scene.visible().map(|(_, s)| s.face).collect();
    let want: Vec<u32> = list.items().iter().map(|i| i.face).collect();
    assert_eq!(shown, want, "visible sprites in paint order = draw list");
    // Every visible sprite lands on its polygon's projection.
    let view = p.view();
    let mut scratch = ProjectionScratch::default();
    let mut projected = Vec::new();
    for ((_, sprite), item) in scene.visible().zip(list.items()) {
        view.project_polygon(list.corners(*item), &mut projected, &mut scratch);
        let corners: Vec<DVec2> = match &sprite.clip {
            Some(c) => c.clone(),
            None => vec![DVec2::ZERO, DVec2::Y, DVec2::ONE, DVec2::X],
        };
        assert_eq!(corners.len(), projected.len());
        for (uv, want) in corners.iter().zip(&projected) {
            let h = *scene.root() * sprite.transform.apply_homogeneous(*uv);
            let got = DVec2::new(h.x / h.w, h.y / h.w);
            assert!((got - *want).length() < 1e-6, "{got} vs {want}");
        }
    }
}

fn only(ops: OpCounts, allowed: &[&str]) {
    let named = [
        ("create", ops.create),
        ("destroy", ops.destroy),
        ("transform", ops.transform),
        ("clip", ops.clip),
        ("brush", ops.brush),
        ("visible", ops.visible),
        ("reorder", ops.reorder),
        ("root", ops.root),
    ];
    for (name, count) in named {
        if !allowed.contains(&name) {
            assert_eq!(count, 0, "unexpected {name} operations in {ops:?}");
        }
    }
}

#[test]
fn first_frame_builds_the_scene_and_an_unchanged_frame_sends_nothing() {
    let g = sphere();
    let view = View::fit(&g.bounds(), 256, 256).with_yaw_pitch_roll(20.0, 30.0, 0.0);
    let mut p = painter(&g, SorterKind::Centroid, view);
    let first = p.frame();
    assert!(first.sorted);
    assert_eq!(first.ops.create, g.pieces().len());
    assert_eq!(first.ops.transform, g.pieces().len());
    assert_eq!(first.ops.root, 1);
    assert_scene_matches(&p);
    for _ in 0..3 {
        assert_eq!(
            p.frame(),
            FrameStats {
                ops: OpCounts::default(),
                sorted: false,
                drawn: first.drawn
            }
        );
    }
    // The same view set again, and the same rotation requested: still nothing.
    p.set_view(view);
    assert_eq!(p.frame().ops.total(), 0);
    p.rotation_handle().request_rotation(view.rotation());
    assert_eq!(p.tick(Duration::ZERO).ops.total(), 0);
}

#[test]
fn rotation_costs_root_visibility_and_moves_only() {
    let g = sphere();
    let view = View::fit(&g.bounds(), 256, 256).with_yaw_pitch_roll(0.0, 25.0, 0.0);
    let mut p = painter(&g, SorterKind::Centroid, view);
    p.frame();
    let mut total = OpCounts::default();
    let mut drawn = 0;
    for k in 1..=180 {
        p.set_rotation(rotation_from_yaw_pitch_roll(f64::from(k) * 2.0, 25.0, 0.0));
        let stats = p.frame();
        only(stats.ops, &["root", "visible", "reorder"]);
        assert_eq!(stats.ops.root, 1);
        assert_scene_matches(&p);
        total += stats.ops;
        drawn += stats.drawn;
    }
    assert!(total.visible > 0 && total.reorder > 0);
    // Far fewer moves than re-adding every drawn sprite each frame.
    assert!(total.reorder * 2 < drawn, "{total:?} for {drawn} drawn");
}

#[test]
fn culling_change_sends_only_visibility_flips() {
    let g = sphere();
    let view = View::fit(&g.bounds(), 256, 256).with_yaw_pitch_roll(30.0, 20.0, 0.0);
    let mut p = painter(&g, SorterKind::Centroid, view);
    p.frame();
    let before = p.draw_list().len();
    p.set_view(view.with_cull_margin(20.0));
    let s = p.frame();
    only(s.ops, &["visible"]);
    assert!(s.ops.visible > 0 && p.draw_list().len() > before);
    assert_scene_matches(&p);
    p.set_view(view.with_cull(CullMode::None));
    only(p.frame().ops, &["visible"]);
    assert_scene_matches(&p);
    p.set_view(view);
    let s = p.frame();
    only(s.ops, &["visible"]);
    assert_eq!(s.ops.visible, g.pieces().len() - before);
    assert_scene_matches(&p);
}

#[test]
fn scale_and_size_rebuild_transforms() {
    let g = sphere();
    let view = View::fit(&g.bounds(), 256, 256).with_yaw_pitch_roll(10.0, 20.0, 0.0);
    let mut p = painter(&g, SorterKind::Centroid, view);
    p.frame();
    let n = g.pieces().len();
    p.set_view(view.with_scale(view.scale() * 1.5));
    let s = p.frame();
    only(s.ops, &["transform", "root", "visible", "reorder"]);
    assert_eq!(s.ops.transform, n);
    assert_scene_matches(&p);
    p.set_view(p.view().with_size(320, 200));
    let s = p.frame();
    only(s.ops, &["transform", "root", "visible", "reorder"]);
    assert_eq!(s.ops.transform, n);
    assert_scene_matches(&p);
}

#[test]
fn perspective_costs_root_and_order_only() {
    let g = support::geometry(&support::boxes(&[
        (DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 1.0, 1.0)),
        (DVec3::new(1.5, 0.2, -0.5), DVec3::new(2.5, 1.0, 2.0)),
        (DVec3::new(-1.0, 1.2, 0.0), DVec3::new(2.0, 1.5, 0.6)),
    ]));
    let view = View::fit(&g.bounds(), 256, 256).with_yaw_pitch_roll(35.0, 20.0, 0.0);
    let mut p = painter(&g, SorterKind::Bsp, view);
    p.frame();
    assert_scene_matches(&p);
    p.set_view(view.with_perspective(256.0));
    let s = p.frame();
    only(s.ops, &["root", "visible", "reorder"]);
    assert_eq!(s.ops.root, 1);
    assert_scene_matches(&p);
    p.set_view(view.with_perspective(400.0));
    only(p.frame().ops, &["root", "visible", "reorder"]);
    assert_scene_matches(&p);
}

#[test]
fn sorter_change_costs_order_only_and_brushes_cost_brushes_only() {
    let g = sphere();
    let view = View::fit(&g.bounds(), 256, 256).with_yaw_pitch_roll(40.0, -30.0, 0.0);
    let mut p = painter(&g, SorterKind::Centroid, view);
    p.frame();
    p.set_sorter(SorterKind::Topological.build(&g));
    let s = p.frame();
    only(s.ops, &["visible", "reorder"]);
    assert_scene_matches(&p);
    // Recolour every third face.
    p.set_brushes(|f| {
        if f.is_multiple_of(3) {
            Brush::Solid([255, 0, 0, 255])
        } else {
            Brush::Palette
        }
    });
    let s = p.frame();
    only(s.ops, &["brush"]);
    let recoloured = (0..g.pieces().len())
        .filter(|&i| g.pieces().face(i).is_multiple_of(3))
        .count();
    assert_eq!(s.ops.brush, recoloured);
    p.set_brushes(|f| {
        if f.is_multiple_of(3) {
            Brush::Solid([255, 0, 0, 255])
        } else {
            Brush::Palette
        }
    });
    assert_eq!(p.frame().ops.total(), 0, "same brushes: nothing");
}

#[test]
fn model_change_rebuilds_every_sprite() {
    let g = sphere();
    let view = View::fit(&g.bounds(), 256, 256);
    let mut p = painter(&g, SorterKind::Centroid, view);
    p.frame();
    let g2 = support::geometry(&test_support::models::uv_sphere(7, 5));
    let v2 = View::fit(&g2.bounds(), 256, 256).with_yaw_pitch_roll(10.0, 10.0, 0.0);
    p.set_geometry(&g2, SorterKind::Centroid.build(&g2), v2);
    let destroyed = p.compositor().frame().destroy;
    let s = p.frame();
    assert_eq!(destroyed, g.pieces().len());
    assert_eq!(s.ops.create, g2.pieces().len());
    assert_eq!(p.compositor().scene().len(), g2.pieces().len());
    assert_scene_matches(&p);
}

#[test]
fn rotation_requests_coalesce_across_threads() {
    let g = sphere();
    let view = View::fit(&g.bounds(), 256, 256);
    let mut p = painter(&g, SorterKind::Centroid, view);
    p.frame();
    let handle = p.rotation_handle();
    let workers: Vec<_> = (0..4)
        .map(|t| {
            let h = handle.clone();
            std::thread::spawn(move || {
                for k in 0..50 {
                    h.request_rotation(rotation_from_yaw_pitch_roll(
                        f64::from(t * 50 + k),
                        0.0,
                        0.0,
                    ));
                }
            })
        })
        .collect();
    for w in workers {
        w.join().expect("worker");
    }
    let last = rotation_from_yaw_pitch_roll(77.0, 12.0, 0.0);
    handle.request_rotation(last);
    let s = p.tick(Duration::from_millis(16));
    assert_eq!(s.ops.root, 1, "one root update for many requests");
    assert_eq!(p.view().rotation(), last);
    assert_eq!(
        p.tick(Duration::from_millis(32)).ops.total(),
        0,
        "requests were consumed"
    );
    // A rotation source is sampled per tick.
    p.set_rotation_source(Some(Box::new(|t: Duration| {
        rotation_from_yaw_pitch_roll(t.as_secs_f64() * 90.0, 20.0, 0.0)
    })));
    p.tick(Duration::from_secs(1));
    let want = rotation_from_yaw_pitch_roll(90.0, 20.0, 0.0);
    assert!(
        (p.view().rotation() - want)
            .abs()
            .to_cols_array()
            .iter()
            .all(|e| *e < 1e-12)
    );
    assert_scene_matches(&p);
}

#[test]
fn cull_margin_covers_a_one_frame_lag() {
    // Faces drawn at the new angle were already shown at the old one when the margin covers
    // the step, so a compositor showing the previous frame for one more tick has no holes.
    let g = sphere();
    let step = 5.0;
    let mut rng = Rng::new(7);
    for _ in 0..20 {
        let (yaw, pitch) = (rng.range(0.0, 360.0), rng.range(-60.0, 60.0));
        let base = View::fit(&g.bounds(), 256, 256);
        let old = base
            .with_yaw_pitch_roll(yaw, pitch, 0.0)
            .with_cull_margin(step);
        let new = base.with_yaw_pitch_roll(yaw + step * 0.99, pitch, 0.0);
        let faces = |v: &View| {
            let mut s = SorterKind::Centroid.build(&g);
            let mut l = sprite_compose::face_sort::DrawList::new();
            s.sort(v, &mut l);
            l.items()
                .iter()
                .map(|i| i.polygon)
                .collect::<std::collections::HashSet<_>>()
        };
        assert!(faces(&new).is_subset(&faces(&old)));
    }
}

#[test]
fn random_walk_keeps_the_backend_in_sync() {
    let g = support::geometry(&support::load_obj(
        "keenan-crane/spot/spot_control_mesh.obj",
    ));
    let mut rng = Rng::new(99);
    let base = View::fit(&g.bounds(), 200, 200);
    let mut p = painter(&g, SorterKind::Bsp, base);
    p.frame();
    for _ in 0..40 {
        let mut view = base.with_rotation(DMat3::from_euler(
            sprite_compose::glam::EulerRot::YXZ,
            rng.range(-3.2, 3.2),
            rng.range(-1.5, 1.5),
            rng.range(-0.3, 0.3),
        ));
        if rng.range(0.0, 1.0) < 0.3 {
            view = view.with_perspective(rng.range(150.0, 600.0));
        }
        p.set_view(view);
        p.frame();
        assert_scene_matches(&p);
        let scene = p.compositor().scene();
        assert_eq!(scene.len(), p.sprite_count());
        assert!(scene.stack().iter().all(|id| scene.sprite(*id).is_some()));
        let _ = SpriteId(0);
    }
}
