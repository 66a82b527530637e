//! The planner's convex cases, per frame, in the same run: `Auto` (cull only) beside culling
//! alone, `Centroid` and `Bsp` on a closed convex UV sphere of 8,192 faces; and `Auto`
//! (convex parts) beside `Centroid`, `Bsp` and `Newell` on 64 separate spheres of 512 faces.
//!
//! `cargo bench -p face-sort --bench plan -- --warm-up-time 0.5 --measurement-time 1 --sample-size 20`

use face_sort::sorter_api::DrawListWriter;
use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use face_sort::{
    Auto, DrawList, FaceSorter, Geometry, PlanHint, SorterKind, Strategy, View, generate,
};

/// Eight views around the geometry, 512², pitch 20°.
fn views(geometry: &Geometry) -> Vec<View> {
    let base = View::fit(&geometry.bounds(), 512, 512);
    (0..8)
        .map(|k| base.with_yaw_pitch_roll(f64::from(k) * 45.0 + 10.0, 20.0, 0.0))
        .collect()
}

/// `auto` and the sorters of `kinds`, each with its name.
fn with_auto(
    auto: Auto,
    kinds: &[SorterKind],
    geometry: &Geometry,
) -> Vec<(&'static str, Box<dyn FaceSorter>)> {
    let built = kinds.iter().map(|k| (k.name(), k.build(geometry)));
    std::iter::once(("auto", Box::new(auto) as Box<dyn FaceSorter>))
        .chain(built)
        .collect()
}

/// One benchmark per sorter, cycling through `views`.
fn time_sorters(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    sorters: &mut [(&str, Box<dyn FaceSorter>)],
    views: &[View],
) {
    for (name, sorter) in sorters {
        let mut list = DrawList::new();
        let mut k = 0;
        group.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| {
                k = (k + 1) % views.len();
                sorter.sort(&views[k], &mut list);
                black_box(list.len())
            })
        });
    }
}

fn convex(c: &mut Criterion) {
    let geometry = Geometry::new(&generate::uv_sphere(128, 64)).unwrap();
    let views = views(&geometry);
    let mut group = c.benchmark_group("convex/sphere-8k");
    let auto = Auto::new(&geometry, PlanHint::ANIMATION);
    assert_eq!(auto.plan().strategy, Strategy::CullOnly);
    let mut sorters = with_auto(auto, &[SorterKind::Centroid, SorterKind::Bsp], &geometry);
    time_sorters(&mut group, &mut sorters, &views);
    // Culling alone: the floor any order costs.
    let pieces = geometry.pieces();
    let mut list = DrawList::new();
    let mut k = 0;
    group.bench_function(BenchmarkId::from_parameter("cull alone"), |b| {
        b.iter(|| {
            k = (k + 1) % views.len();
            let cull = views[k].cull_test();
            list.begin(pieces);
            for (i, plane) in pieces.planes().iter().enumerate() {
                if cull.is_drawn(plane, pieces.corners(i)[0]) {
                    list.push(i as u32, pieces.face(i));
                }
            }
            black_box(list.len())
        })
    });
    group.finish();
}

/// 64 spheres of 512 faces on a 4 × 4 × 4 grid: separate convex parts.
fn parts(c: &mut Criterion) {
    let sphere = generate::uv_sphere(32, 16);
    let mut positions = Vec::new();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for k in 0..64 {
        let offset = face_sort::glam::DVec3::new(
            f64::from(k % 4) * 3.0,
            f64::from((k / 4) % 4) * 3.0,
            f64::from(k / 16) * 3.0,
        );
        let base = positions.len() as u32;
        positions.extend(sphere.positions().iter().map(|p| *p + offset));
        faces.extend(
            sphere
                .faces()
                .map(|f| f.iter().map(|i| i + base).collect::<Vec<_>>()),
        );
    }
    let mesh = face_sort::PolygonMesh::new(positions, faces).unwrap();
    let geometry = Geometry::new(&mesh).unwrap();
    let views = views(&geometry);
    let mut group = c.benchmark_group("parts/64-spheres");
    let auto = Auto::new(&geometry, PlanHint::ANIMATION);
    assert_eq!(auto.plan().strategy, Strategy::ConvexParts);
    let kinds = [SorterKind::Centroid, SorterKind::Bsp, SorterKind::Newell];
    let mut sorters = with_auto(auto, &kinds, &geometry);
    time_sorters(&mut group, &mut sorters, &views);
    group.finish();
}

criterion_group!(benches, convex, parts);
criterion_main!(benches);
