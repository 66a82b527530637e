//! Scenes of instances: 100 instances of suzanne (50,000 faces in all; one in four
//! interlocks with its neighbour), per frame, static and with 5 instances moving every
//! frame, against flattening the scene into one mesh: one BSP over it (static), Newell on it
//! (no tree to rebuild when things move), the centroid sort as the yardstick, and the
//! flattened BSP's rebuild that motion would force (timed once, printed).
//!
//! `cargo bench -p face-sort --bench scene -- --warm-up-time 0.5 --measurement-time 2 --sample-size 10`

use std::hint::black_box;
use std::time::Instant;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use face_sort::glam::DVec3;
use face_sort::{Bsp, Centroid, DrawList, FaceSorter, Geometry, Newell, SceneSorter, View};

#[path = "../tests/common/mod.rs"]
mod common;

fn scene(c: &mut Criterion) {
    // test-support's "suzanne-scene": 100 suzannes 5 units apart.
    let meshes = vec![common::load_model("suzanne/suzanne.obj")];
    let instances = face_sort::generate::scattered_instances(1, 100, 5, 5.0);
    let build = Instant::now();
    let mut scene = SceneSorter::new(meshes, instances.clone()).expect("scene");
    let scene_build = build.elapsed();
    // Room for the moving instances.
    let b = scene.bounds();
    scene.set_bounds(face_sort::Bounds {
        min: b.min - DVec3::splat(2.0),
        max: b.max + DVec3::splat(2.0),
    });
    let flat = Geometry::new_in_frame(&scene.flattened(), scene.bounds()).expect("flattened");
    let build = Instant::now();
    let mut flat_bsp = Bsp::new(&flat);
    let flat_build = build.elapsed();
    println!(
        "scene build (one BSP per mesh): {:.1} ms; flattened BSP build ({} pieces): {:.1} ms: what each frame with motion would pay on the flattened path",
        scene_build.as_secs_f64() * 1e3,
        flat.pieces().len(),
        flat_build.as_secs_f64() * 1e3
    );
    let base = View::fit(&scene.bounds(), 512, 512);
    let ld = base.diagonal() * base.scale();
    let views: Vec<View> = (0..4)
        .map(|k| {
            base.with_yaw_pitch_roll(f64::from(k) * 90.0 + 20.0, 35.0, 0.0)
                .with_perspective(1.5 * ld)
        })
        .collect();
    let mut list = DrawList::new();
    // Settle the clusters (their BSPs are built after a few unchanged frames).
    for _ in 0..10 {
        scene.sort(&views[0], &mut list);
    }
    println!("clusters in view 0: {:?}", scene.stats());
    let mut k = 0;
    let mut group = c.benchmark_group("scene/suzanne-100");
    group.bench_function(BenchmarkId::new("static", "scene"), |bench| {
        bench.iter(|| {
            k = (k + 1) % views.len();
            scene.sort(&views[k], &mut list);
            black_box(list.len())
        })
    });
    let mut flat_sorters: Vec<(&str, Box<dyn FaceSorter>)> = vec![
        ("flattened-bsp", Box::new(Bsp::new(&flat))),
        ("flattened-newell", Box::new(Newell::new(&flat))),
        ("flattened-centroid", Box::new(Centroid::new(&flat))),
    ];
    for (name, sorter) in &mut flat_sorters {
        group.bench_function(BenchmarkId::new("static", name), |bench| {
            bench.iter(|| {
                k = (k + 1) % views.len();
                sorter.sort(&views[k], &mut list);
                black_box(list.len())
            })
        });
    }
    // Five instances move every frame.
    let mut frame = 0u32;
    let mut move_five = |scene: &mut SceneSorter| {
        frame += 1;
        for i in (0..100).step_by(20) {
            let mut t = instances[i].transform;
            let a = f64::from(frame) * 0.1;
            t.translation += DVec3::new(a.cos(), 0.0, a.sin());
            scene.set_transform(i, t).expect("transform");
        }
    };
    group.bench_function(BenchmarkId::new("moving", "scene"), |bench| {
        bench.iter(|| {
            move_five(&mut scene);
            scene.sort(&views[0], &mut list);
            black_box(list.len())
        })
    });
    // The flattened path with motion and no tree: rebuild the mesh and its pieces, Newell.
    group.bench_function(BenchmarkId::new("moving", "flattened-newell"), |bench| {
        bench.iter(|| {
            move_five(&mut scene);
            let geometry =
                Geometry::new_in_frame(&scene.flattened(), scene.bounds()).expect("flattened");
            Newell::new(&geometry).sort(&views[0], &mut list);
            black_box(list.len())
        })
    });
    group.finish();
    black_box(&mut flat_bsp);
}

criterion_group!(benches, scene);
criterion_main!(benches);
