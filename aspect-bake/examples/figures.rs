//! The README's table: spot, blub and the book under a yaw spin (pitch 20°), orthographic
//! and perspective; the exact BSP bake (time, breakpoints, cells, bytes of both encodings,
//! verification) beside the seed's 720-sample baseline (time, exact breakpoints missed).
//!
//! `cargo run --release -p aspect-bake --example figures`

use std::time::Instant;

use aspect_bake::{Axis, BakeOptions, BspSource, Spin, bake, bake_sampled, verify};
use face_sort::{Geometry, View};

fn main() {
    let models = [
        ("spot", "keenan-crane/spot/spot_quadrangulated.obj"),
        ("blub", "keenan-crane/blub/blub_quadrangulated.obj"),
        ("book", "combobulate-samples/book.obj"),
    ];
    println!(
        "| model | pieces | view | exact bake | breakpoints | cells | full lists | delta timeline | verified | 720 samples | missed |"
    );
    println!("|---|---:|---|---:|---:|---:|---:|---:|---|---:|---:|");
    for (name, path) in models {
        let mesh = test_support::load_polygon_mesh(path);
        let geometry = Geometry::new(&mesh).expect("a mesh with faces");
        let started = Instant::now();
        let source = BspSource::of(&geometry);
        let tree_ms = started.elapsed().as_secs_f64() * 1e3;
        let base = View::fit(&geometry.bounds(), 512, 512);
        let views = [
            ("ortho", base),
            // The eye two diagonals from the centre.
            (
                "persp",
                base.with_perspective(2.0 * base.diagonal() * base.scale()),
            ),
        ];
        for (kind, view) in views {
            let spin = Spin::new(
                view,
                Axis::Yaw {
                    pitch: 20.0,
                    roll: 0.0,
                },
            )
            .expect("a named axis");
            // Blub's full lists pass 1 GiB (the default budget).
            let options = BakeOptions {
                budget_bytes: 3 << 30,
                ..BakeOptions::DEFAULT
            };
            let exact = match bake(&source, &spin, &options) {
                Ok(exact) => exact,
                Err(e) => {
                    println!("| {name} | | {kind} | stopped: {e} | | | | | | | |");
                    continue;
                }
            };
            let sizes = exact.sizes();
            let checked = match verify(&exact, &source, &spin, 1, 7) {
                Ok(r) => format!(
                    "yes ({} angles, {} breakpoints)",
                    r.interior_checks, r.breakpoint_checks
                ),
                Err(e) => format!("NO: {e}"),
            };
            let sampled = bake_sampled(&source, &spin, 720, 1e-3, &options).expect("sampled");
            let missed = sampled.missed(&exact, 2e-3).len();
            println!(
                "| {name} | {} | {kind} | {:.0} ms (+ tree {tree_ms:.0} ms) | {} | {} | {:.1} MB | {:.2} MB | {checked} | {:.0} ms | {missed} of {} |",
                geometry.pieces().len(),
                exact.bake_ms(),
                exact.breakpoints().len(),
                exact.cells().len(),
                sizes.full_bytes as f64 / 1e6,
                sizes.delta_bytes as f64 / 1e6,
                sampled.bake_ms(),
                exact.breakpoints().len(),
            );
        }
    }
}
