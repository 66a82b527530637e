//! Per-frame cull + order of every sorter beside the centroid baseline, on real models and
//! generated bumpy tori (`face_sort::generate::torus`, the tables' "bumpy-torus") of 1k, 10k and 100k quads;
//! plus BSP build time.
//!
//! `cargo bench -p face-sort --bench sorters -- --warm-up-time 0.5 --measurement-time 1 --sample-size 10`

#[path = "../tests/common/mod.rs"]
mod common;

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use face_sort::generate::torus as bumpy_torus;
use face_sort::{DrawList, Geometry, PolygonMesh, SorterKind, View};
use test_base::model_name;

fn scenes() -> Vec<(String, PolygonMesh)> {
    vec![
        (
            "spot".into(),
            common::read_obj(&common::asset("keenan-crane/spot/spot_quadrangulated.obj")),
        ),
        (
            "blub".into(),
            common::read_obj(&common::asset("keenan-crane/blub/blub_quadrangulated.obj")),
        ),
        (model_name("bumpy-torus", 1_000), bumpy_torus(1_000)),
        (model_name("bumpy-torus", 10_000), bumpy_torus(10_000)),
        (model_name("bumpy-torus", 100_000), bumpy_torus(100_000)),
    ]
}

fn views(geometry: &Geometry) -> Vec<View> {
    let base = View::fit(&geometry.bounds(), 512, 512);
    (0..8)
        .map(|k| base.with_yaw_pitch_roll(f64::from(k) * 45.0 + 10.0, 20.0, 0.0))
        .collect()
}

fn per_frame(c: &mut Criterion) {
    for (name, mesh) in scenes() {
        let geometry = Geometry::new(&mesh).unwrap();
        let views = views(&geometry);
        let mut group = c.benchmark_group(format!("frame/{name}"));
        for kind in SorterKind::ALL {
            if kind == SorterKind::Newell && geometry.pieces().len() > 30_000 {
                continue; // per-frame pair cascade: minutes per sample at this size
            }
            let mut sorter = kind.build(&geometry);
            let mut list = DrawList::new();
            let mut k = 0;
            group.bench_function(BenchmarkId::from_parameter(kind.name()), |b| {
                b.iter(|| {
                    k = (k + 1) % views.len();
                    sorter.sort(&views[k], &mut list);
                    black_box(list.len())
                })
            });
        }
        group.finish();
    }
}

fn bsp_build(c: &mut Criterion) {
    let mut group = c.benchmark_group("build");
    for (name, mesh) in scenes().into_iter().take(3) {
        let geometry = Geometry::new(&mesh).unwrap();
        group.bench_function(BenchmarkId::new("bsp", &name), |b| {
            b.iter(|| black_box(SorterKind::Bsp.build(&geometry).stats().polygons))
        });
    }
    group.finish();
}

criterion_group!(benches, per_frame, bsp_build);
criterion_main!(benches);
