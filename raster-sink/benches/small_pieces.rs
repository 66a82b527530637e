//! The small-piece threshold as a time-against-error curve: blub (7,104 quads) at 1024²,
//! BSP order, items under 0 / 0.5 / 2 / 8 / 32 px² dropped (`face_sort::SmallPieceFilter`),
//! then the colour raster; printed beside it per threshold: items kept and the pixel error
//! of the same list against the truth.
//!
//! `cargo bench -p raster-sink --bench small_pieces -- --warm-up-time 0.5 --measurement-time 2 --sample-size 10`

#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use raster_sink::face_sort::{Bsp, DrawList, FaceSorter, Geometry, SmallPieceFilter, View};
use raster_sink::{RasterOptions, Style, pixel_error, render_colour, render_ids, truth};

fn bench(c: &mut Criterion) {
    let geometry = Geometry::new(&test_support::load_polygon_mesh(
        "keenan-crane/blub/blub_quadrangulated.obj",
    ))
    .expect("geometry");
    let view = View::fit(&geometry.bounds(), 1024, 1024).with_yaw_pitch_roll(30.0, 20.0, 0.0);
    let mut full = DrawList::new();
    Bsp::new(&geometry).sort(&view, &mut full);
    let reference = truth(&view, &geometry);
    let style = Style::palette();
    let options = RasterOptions::DEFAULT;
    let mut group = c.benchmark_group("small-pieces/blub-1024");
    let mut filter = SmallPieceFilter::new();
    for threshold in [0.0, 0.5, 2.0, 8.0, 32.0] {
        let mut list = full.clone();
        let dropped = filter.apply(&view, &mut list, threshold);
        let error = pixel_error(&render_ids(&view, &list), &reference);
        println!(
            "threshold {threshold} px²: {} of {} items kept ({dropped} dropped), pixel error {:.4} % ({} of {})",
            list.len(),
            full.len(),
            100.0 * error.error,
            error.wrong,
            error.pixels
        );
        group.bench_function(BenchmarkId::from_parameter(threshold), |b| {
            b.iter(|| {
                let mut list = full.clone();
                filter.apply(&view, &mut list, threshold);
                black_box(render_colour(&view, &list, &style, &options).expect("raster"))
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
