//! ID render, colour render and truth of spot (2,928 quads) at 512² and 2048², beside a
//! plain tiny-skia fill of the same polygons (no projection, no seams, no brushes).
//!
//! `cargo bench -p raster-sink --bench raster -- --warm-up-time 0.5 --measurement-time 1 --sample-size 10`

#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use raster_sink::face_sort::glam::DVec2;
use raster_sink::face_sort::{
    Centroid, DrawList, FaceSorter, Geometry, PolygonMesh, ProjectionScratch, View,
};
use raster_sink::tiny_skia::{FillRule, Paint, Pixmap, Transform};
use raster_sink::{RasterOptions, Style, render_colour, render_ids, truth};

fn spot() -> PolygonMesh {
    test_support::load_polygon_mesh("keenan-crane/spot/spot_quadrangulated.obj")
}

fn bench(c: &mut Criterion) {
    let geometry = Geometry::new(&spot()).expect("geometry");
    for size in [512u32, 2048] {
        let view = View::fit(&geometry.bounds(), size, size).with_yaw_pitch_roll(35.0, 15.0, 0.0);
        let mut list = DrawList::new();
        Centroid::new(&geometry).sort(&view, &mut list);
        // Pre-projected paths for the plain tiny-skia baseline.
        let mut scratch = ProjectionScratch::default();
        let mut points: Vec<DVec2> = Vec::new();
        let paths: Vec<_> = list
            .items()
            .iter()
            .filter_map(|&item| {
                view.project_polygon(list.corners(item), &mut points, &mut scratch);
                raster_sink::polygon_path(&points)
            })
            .collect();
        let style = Style::solid([230, 120, 40, 255]);
        let mut group = c.benchmark_group(format!("spot_{size}"));
        group.bench_function("tiny_skia_fill_only", |b| {
            let mut pixmap = Pixmap::new(size, size).expect("pixmap");
            let mut paint = Paint::default();
            paint.set_color_rgba8(230, 120, 40, 255);
            b.iter(|| {
                pixmap.fill(raster_sink::tiny_skia::Color::WHITE);
                for path in &paths {
                    pixmap.fill_path(path, &paint, FillRule::Winding, Transform::identity(), None);
                }
                black_box(&pixmap);
            });
        });
        group.bench_function("colour", |b| {
            b.iter(|| black_box(render_colour(&view, &list, &style, &RasterOptions::DEFAULT)))
        });
        group.bench_function("colour_no_seams", |b| {
            let options = RasterOptions::DEFAULT.with_seam_outset(0.0);
            b.iter(|| black_box(render_colour(&view, &list, &style, &options)))
        });
        group.bench_function("ids", |b| b.iter(|| black_box(render_ids(&view, &list))));
        group.bench_function("truth", |b| b.iter(|| black_box(truth(&view, &geometry))));
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
