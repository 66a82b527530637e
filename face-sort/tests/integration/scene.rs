//! Scenes of instances: every frame exact under the oracle, the same faces drawn as the
//! flattened scene under culling, mirrored instances culled by their own front, and moving
//! instances rebuilding only their own clusters.

use crate::common;
use std::collections::BTreeSet;

use face_sort::glam::{DAffine3, DVec3};
use face_sort::{CullMode, DrawList, FaceSorter, Geometry, Instance, SceneSorter, View, oracle};

fn views(scene: &SceneSorter) -> Vec<View> {
    let base = View::fit(&scene.bounds(), 256, 256);
    let ld = base.diagonal() * base.scale();
    vec![
        base.with_yaw_pitch_roll(30.0, 35.0, 0.0),
        base.with_yaw_pitch_roll(200.0, -20.0, 10.0),
        base.with_yaw_pitch_roll(95.0, 60.0, 0.0)
            .with_cull(CullMode::None),
        base.with_yaw_pitch_roll(140.0, 25.0, 0.0)
            .with_perspective(1.2 * ld),
        base.with_yaw_pitch_roll(-40.0, 15.0, 0.0)
            .with_perspective(0.6 * ld),
    ]
}

/// The faces the flattened scene draws in `view` (any piece passing the cull test).
fn flattened_faces(geometry: &Geometry, view: &View) -> BTreeSet<u32> {
    let set = geometry.pieces();
    let cull = view.cull_test();
    (0..set.len())
        .filter(|&i| cull.is_drawn(set.plane(i), set.corners(i)[0]))
        .map(|i| set.face(i))
        .collect()
}

fn assert_same_faces(list: &DrawList, geometry: &Geometry, view: &View, what: &str) {
    let (got, want) = (faces_of(list), flattened_faces(geometry, view));
    if got != want {
        let set = geometry.pieces();
        let cull = view.cull_test();
        for face in got.symmetric_difference(&want) {
            for i in (0..set.len()).filter(|&i| set.face(i) == *face) {
                let plane = set.plane(i);
                println!(
                    "face {face} (scene draws it: {}): piece {i} facing {:e}",
                    got.contains(face),
                    cull.viewer.facing(plane)
                );
            }
        }
        panic!(
            "{what}: {} faces differ",
            got.symmetric_difference(&want).count()
        );
    }
}

fn faces_of(list: &DrawList) -> BTreeSet<u32> {
    list.items().iter().map(|i| i.face).collect()
}

#[test]
fn instanced_scenes_are_exact_and_draw_what_the_flattened_scene_draws() {
    let (meshes, instances) = common::instanced_scene(24, 7);
    let mut scene = SceneSorter::new(meshes, instances).unwrap();
    let flat = Geometry::new(&scene.flattened()).unwrap();
    let mut list = DrawList::new();
    let mut clusters = 0;
    for view in views(&scene) {
        scene.sort(&view, &mut list);
        assert_eq!(oracle::count_violations(&view, &list), 0, "{view:?}");
        assert_same_faces(&list, &flat, &view, &format!("{view:?}"));
        clusters += scene.stats().clusters;
        assert_eq!(scene.stats().objects_culled, 0);
    }
    // Interlocking instances were ordered as clusters (Newell while new), gathered once
    // each; drawn unchanged for more frames, they get their BSP, still exact.
    assert!(clusters > 0);
    assert_eq!(scene.stats().cluster_trees, 0);
    let view = views(&scene)[3];
    for _ in 0..10 {
        scene.sort(&view, &mut list);
        assert_eq!(oracle::count_violations(&view, &list), 0);
    }
    assert!(scene.stats().cluster_trees > 0, "{:?}", scene.stats());
    assert_same_faces(&list, &flat, &view, "settled");
    let builds = scene.stats().cluster_builds;
    assert!(
        builds > 0 && builds <= clusters,
        "{builds} builds for {clusters} cluster frames"
    );
    assert_eq!(scene.stats().tree_builds, 1);
}

#[test]
fn instances_share_their_meshs_presorted_orders_exactly() {
    let (meshes, instances) = common::instanced_scene(24, 7);
    let mut scene = SceneSorter::new(meshes, instances).unwrap();
    let flat = Geometry::new(&scene.flattened()).unwrap();
    scene
        .presort_meshes(&face_sort::PresortOptions::default())
        .unwrap();
    let mut list = DrawList::new();
    for view in views(&scene) {
        scene.sort(&view, &mut list);
        assert_eq!(oracle::count_violations(&view, &list), 0, "{view:?}");
        assert_same_faces(&list, &flat, &view, &format!("{view:?}"));
    }
}

#[test]
fn moving_instances_stay_exact_and_rebuild_only_their_clusters() {
    let (meshes, instances) = common::instanced_scene(16, 3);
    let mut scene = SceneSorter::new(meshes, instances.clone()).unwrap();
    // A frame of reference that holds instance 5 wherever it goes.
    let b = scene.bounds();
    scene.set_bounds(face_sort::Bounds {
        min: b.min - DVec3::splat(2.0),
        max: b.max + DVec3::splat(2.0),
    });
    let view = views(&scene)[3];
    let mut list = DrawList::new();
    scene.sort(&view, &mut list);
    let first_builds = scene.stats().cluster_builds;
    for frame in 1..=12 {
        // Instance 5 circles through its neighbours; the others stay.
        let angle = f64::from(frame) * 0.5;
        let mut t = instances[5].transform;
        t.translation += DVec3::new(angle.cos() * 1.5, 0.0, angle.sin() * 1.5);
        scene.set_transform(5, t).unwrap();
        scene.sort(&view, &mut list);
        assert_eq!(oracle::count_violations(&view, &list), 0, "frame {frame}");
        let flat = Geometry::new(&scene.flattened()).unwrap();
        assert_eq!(
            faces_of(&list),
            flattened_faces(&flat, &view),
            "frame {frame}"
        );
    }
    // Only clusters holding instance 5 were rebuilt: at most one per frame.
    let rebuilt = scene.stats().cluster_builds - first_builds;
    assert!(rebuilt <= 12, "{rebuilt} cluster builds in 12 frames");
    assert_eq!(scene.stats().tree_builds, 13);
}

#[test]
fn a_mirrored_instance_keeps_its_own_front() {
    let cube = face_sort::generate::boxes(&[(DVec3::splat(-0.5), DVec3::splat(0.5))]);
    let mirror = DAffine3::from_scale(DVec3::new(-1.0, 1.0, 1.0));
    let shifted = DAffine3::from_translation(DVec3::new(3.0, 0.0, 0.0)) * mirror;
    let mut scene = SceneSorter::new(
        vec![cube],
        vec![
            Instance::new(0, DAffine3::IDENTITY),
            Instance::new(0, shifted),
        ],
    )
    .unwrap();
    let view = View::fit(&scene.bounds(), 200, 100).with_yaw_pitch_roll(30.0, 25.0, 0.0);
    let mut list = DrawList::new();
    scene.sort(&view, &mut list);
    let faces = faces_of(&list);
    // Three faces of each cube face the viewer; the mirrored cube draws three, not its
    // three back faces.
    assert_eq!(faces.iter().filter(|&&f| f < 6).count(), 3, "{faces:?}");
    assert_eq!(faces.iter().filter(|&&f| f >= 6).count(), 3, "{faces:?}");
    assert_eq!(oracle::count_violations(&view, &list), 0);
}

#[test]
fn instances_outside_the_image_are_culled_by_their_box() {
    let (meshes, instances) = common::instanced_scene(16, 11);
    let mut scene = SceneSorter::new(meshes, instances).unwrap();
    // Four times closer: most instances fall outside the image.
    let view = View::fit(&scene.bounds(), 256, 256)
        .with_yaw_pitch_roll(0.0, 89.0, 0.0)
        .with_scale(4.0 * View::fit(&scene.bounds(), 256, 256).scale());
    let mut list = DrawList::new();
    scene.sort(&view, &mut list);
    let stats = scene.stats();
    assert!(stats.objects_culled > 4, "{stats:?}");
    assert_eq!(stats.objects_culled + stats.objects_drawn, 16);
    assert_eq!(oracle::count_violations(&view, &list), 0);
}

#[test]
fn an_instance_moved_outside_the_frame_of_reference_stays_exact() {
    let cube = face_sort::generate::boxes(&[(DVec3::splat(-0.5), DVec3::splat(0.5))]);
    let at = |x: f64| DAffine3::from_translation(DVec3::new(x, 0.0, 0.0));
    let mut scene = SceneSorter::new(
        vec![cube],
        vec![Instance::new(0, at(0.0)), Instance::new(0, at(0.6))],
    )
    .unwrap();
    // Zoomed out, so that the cubes stay in the image where they go.
    let fit = View::fit(&scene.bounds(), 200, 200);
    let view = fit
        .with_yaw_pitch_roll(30.0, 25.0, 0.0)
        .with_scale(fit.scale() / 10.0);
    let mut list = DrawList::new();
    for x in [0.6, 3.0, 5.0] {
        // Both cubes move out of the scene's bounds, still interlocking.
        scene.set_transform(0, at(x - 0.6)).unwrap();
        scene.set_transform(1, at(x)).unwrap();
        scene.sort(&view, &mut list);
        assert_eq!(oracle::count_violations(&view, &list), 0, "x = {x}");
        assert_eq!(scene.stats().clusters, 1, "{:?}", scene.stats());
        assert_eq!(faces_of(&list).len(), 6, "x = {x}");
    }
}

#[test]
fn bad_scenes_are_typed_errors() {
    let cube = face_sort::generate::boxes(&[(DVec3::ZERO, DVec3::ONE)]);
    let e = SceneSorter::new(
        vec![cube.clone()],
        vec![Instance::new(1, DAffine3::IDENTITY)],
    )
    .err()
    .unwrap();
    assert!(e.to_string().contains("mesh 1"), "{e}");
    let e = SceneSorter::new(
        vec![cube],
        vec![Instance::new(
            0,
            DAffine3::from_scale(DVec3::new(1.0, 0.0, 1.0)),
        )],
    )
    .err()
    .unwrap();
    assert!(e.to_string().contains("singular"), "{e}");
    assert!(SceneSorter::new(Vec::new(), Vec::new()).is_err());
}

#[test]
fn levels_of_detail_follow_the_projected_size() {
    use face_sort::glam::DQuat;
    let suzanne = common::load_model("suzanne/suzanne.obj");
    let cube =
        face_sort::generate::boxes(&[(DVec3::new(-1.3, -1.0, -0.9), DVec3::new(1.3, 1.0, 0.9))]);
    let instances: Vec<Instance> = (0..9)
        .map(|k| {
            let at = DVec3::new(f64::from(k % 3) * 3.5, 0.0, f64::from(k / 3) * 3.5);
            Instance::new(
                0,
                DAffine3::from_rotation_translation(DQuat::from_rotation_y(f64::from(k)), at),
            )
            .with_lod(1, 40.0)
        })
        .collect();
    let mut scene = SceneSorter::new(vec![suzanne, cube], instances).unwrap();
    let fit = View::fit(&scene.bounds(), 512, 512).with_yaw_pitch_roll(20.0, 30.0, 0.0);
    let mut list = DrawList::new();
    // (view, whether the coarse mesh is drawn)
    for (view, coarse) in [
        (fit, false),
        (fit.with_scale(fit.scale() / 8.0), true),
        (fit, false),
    ] {
        scene.sort(&view, &mut list);
        assert_eq!(oracle::count_violations(&view, &list), 0);
        let flat = Geometry::new_in_frame(&scene.flattened(), scene.bounds()).unwrap();
        assert_same_faces(&list, &flat, &view, "lod");
        for k in 0..9u32 {
            let faces = faces_of(&list)
                .into_iter()
                .filter(|&f| (k * 500..(k + 1) * 500).contains(&f))
                .collect::<Vec<_>>();
            if coarse {
                assert!(
                    faces.iter().all(|&f| f < k * 500 + 6),
                    "instance {k}: {faces:?}"
                );
                assert!(!faces.is_empty());
            } else {
                assert!(faces.len() > 6, "instance {k}: {} faces", faces.len());
            }
        }
    }
}

#[test]
fn material_overrides_and_layers_are_found_from_a_face() {
    let cube = face_sort::generate::boxes(&[(DVec3::splat(-0.5), DVec3::splat(0.5))]);
    let at = |x: f64| DAffine3::from_translation(DVec3::new(x, 0.0, 0.0));
    let scene = SceneSorter::new(
        vec![cube],
        vec![
            Instance::new(0, at(0.0)),
            Instance::new(0, at(2.0))
                .with_material(7)
                .with_layer(face_sort::Layer::Overlay),
        ],
    )
    .unwrap();
    assert_eq!(scene.material_of_face(3), None);
    assert_eq!(scene.material_of_face(6), Some(7));
    assert_eq!(scene.instance_of_face(11), Some(1));
    assert_eq!(scene.instance_of_face(12), None);
    assert_eq!(scene.instances()[1].layer, face_sort::Layer::Overlay);
}
