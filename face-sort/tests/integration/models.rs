//! Exact sorters on the repository's real models, judged by the oracle.

use crate::common::{asset, read_obj};
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
        let mesh = read_obj(&asset(model));
        for kind in SorterKind::EXACT {
            let geometry = kind.geometry_for(&mesh).unwrap();
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

/// Split pieces drawn whole: on spot (fans of triangles sharing their edges bit for bit) the
/// merged BSP draws at most 1.2 times the centroid sort's items (the target; 1.15
/// measured over these views, some with back faces drawn and the eye close) where the plain
/// BSP draws about 1.9 times, and stays exact (the oracle above covers `bsp-merged` on every
/// model).
#[test]
fn merged_bsp_draws_about_as_many_items_as_the_centroid_sort_on_spot() {
    let geometry = Geometry::new(&read_obj(&asset(MODELS[0]))).unwrap();
    let mut counts = [0usize; 3];
    let mut list = DrawList::new();
    for view in views(&geometry) {
        for (count, kind) in
            counts
                .iter_mut()
                .zip([SorterKind::Centroid, SorterKind::Bsp, SorterKind::BspMerged])
        {
            kind.build(&geometry).sort(&view, &mut list);
            *count += list.len();
        }
    }
    let [centroid, plain, merged] = counts.map(|c| c as f64);
    eprintln!(
        "spot, 9 views: centroid {centroid}, bsp {plain} ({:.2}x), bsp-merged {merged} ({:.2}x)",
        plain / centroid,
        merged / centroid
    );
    assert!(plain > 1.5 * centroid);
    assert!(merged <= 1.2 * centroid);
}
