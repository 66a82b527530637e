//! Exact sorters on the repository's real models, judged by the oracle.

mod common;

use common::{asset, read_obj};
use face_sort::{CullMode, DrawList, Geometry, SorterKind, View, oracle};

const MODELS: [&str; 9] = [
    "keenan-crane/spot/spot_quadrangulated.obj",
    "keenan-crane/spot/spot_control_mesh.obj",
    "suzanne/suzanne.obj",
    "fandisk-quads/fandisk_quads.converted.obj",
    "cornell-box/cornell_box.obj",
    "compas/boxes.obj",
    "compas/tubemesh.obj",
    "compas/hypar.obj",
    "opensubdiv-torus/catmark_torus_creases0.obj",
];

fn views(geometry: &Geometry) -> Vec<View> {
    let base = View::fit(&geometry.bounds(), 512, 512);
    let mut views = Vec::new();
    for (yaw, pitch) in [(30.0, 20.0), (135.0, -35.0), (250.0, 60.0)] {
        let v = base.with_yaw_pitch_roll(yaw, pitch, 10.0);
        views.push(v);
        views.push(v.with_perspective(512.0));
        views.push(
            v.with_perspective(0.8 * v.scale() * v.diagonal())
                .with_cull(CullMode::None),
        );
    }
    views
}

#[test]
fn exact_sorters_leave_no_violation_on_real_models() {
    let mut list = DrawList::new();
    for model in MODELS {
        let geometry = Geometry::new(&read_obj(&asset(model))).unwrap();
        for kind in SorterKind::EXACT {
            let mut sorter = kind.build(&geometry);
            for view in views(&geometry) {
                sorter.sort(&view, &mut list);
                let found = oracle::find_violations(&view, &list, 3);
                assert!(
                    found.is_empty(),
                    "{} on {model} at {view:?}: {found:?}",
                    kind.name()
                );
            }
        }
    }
}

#[test]
fn centroid_leaves_violations_on_spot() {
    // The judge must be able to fail on a real model.
    let geometry = Geometry::new(&read_obj(&asset(MODELS[0]))).unwrap();
    let mut sorter = SorterKind::Centroid.build(&geometry);
    let mut list = DrawList::new();
    let total: usize = views(&geometry)
        .iter()
        .map(|view| {
            sorter.sort(view, &mut list);
            oracle::count_violations(view, &list)
        })
        .sum();
    assert!(total > 0);
}

#[test]
fn bsp_fragments_and_build_are_reported() {
    let geometry = Geometry::new(&read_obj(&asset(MODELS[0]))).unwrap();
    let pieces = geometry.pieces().len();
    // Spot: 2928 quads, all but two non-planar → 5854 pieces.
    assert_eq!(pieces, 5854);
    let sorter = SorterKind::Bsp.build(&geometry);
    let stats = sorter.stats();
    assert!(stats.polygons >= pieces);
    assert!(stats.depth > 0);
    eprintln!(
        "spot: {} pieces, {} fragments ({:.2}x), depth {}, build {:.1} ms",
        pieces,
        stats.polygons,
        stats.polygons as f64 / pieces as f64,
        stats.depth,
        stats.build_ms
    );
}
