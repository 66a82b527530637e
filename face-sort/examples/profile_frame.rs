//! 400 frames of one sorter on one model (default spot), turning the yaw by `STEP` degrees per
//! frame (default 0.9; `STEP=0` repeats one view), for instruction-count profiles and for
//! per-frame wall time:
//!
//! ```sh
//! cargo build --release -p face-sort --example profile_frame
//! valgrind --tool=callgrind target/release/examples/profile_frame bsp
//! valgrind --tool=callgrind target/release/examples/profile_frame centroid
//! STEP=0.02 MODEL=suzanne/suzanne.obj target/release/examples/profile_frame centroid
//! ```
//!
//! `MODEL` is a path under `assets/models`; `PERSP=1` views in perspective (eye 512 px away,
//! as the bench's); `CULL=none` draws back faces too (default: back faces culled);
//! `COVERAGE=none` makes Newell's sorter without its coverage test (`Newell::without_coverage`,
//! what the planner makes for a few frames). `MODEL` may also be an absolute path (a generated
//! model: `cargo run --release -p face-sort --example torus_obj -- 1000 /tmp/torus1k.obj`).

#[path = "../tests/common/mod.rs"]
mod common;

use std::time::Instant;

use face_sort::{CullMode, DrawList, Geometry, Newell, SorterKind, View};

fn main() {
    let name = std::env::args().nth(1).unwrap_or_else(|| "bsp".into());
    let Some(kind) = SorterKind::from_name(&name) else {
        eprintln!("unknown sorter {name}: centroid, topological, newell, bsp or bsp-merged");
        std::process::exit(2);
    };
    let model = std::env::var("MODEL")
        .unwrap_or_else(|_| "keenan-crane/spot/spot_quadrangulated.obj".into());
    let step: f64 = match std::env::var("STEP") {
        Ok(step) => step.parse().unwrap_or_else(|_| {
            eprintln!("STEP must be a number of degrees, not {step:?}");
            std::process::exit(2);
        }),
        Err(_) => 0.9,
    };
    let mesh = common::read_obj(&common::asset(&model));
    let geometry = Geometry::new(&mesh).expect("valid model");
    let mut sorter = match std::env::var("COVERAGE").as_deref() {
        Ok("none") if kind == SorterKind::Newell => Box::new(Newell::without_coverage(&geometry)),
        Ok("none") | Ok("on") | Err(_) => kind.build(&geometry),
        Ok(other) => {
            eprintln!("COVERAGE must be none or on, not {other:?}");
            std::process::exit(2);
        }
    };
    let mut base = View::fit(&geometry.bounds(), 512, 512);
    if std::env::var_os("PERSP").is_some() {
        base = base.with_perspective(512.0);
    }
    match std::env::var("CULL").as_deref() {
        Ok("none") => base = base.with_cull(CullMode::None),
        Ok("back") | Err(_) => {}
        Ok(other) => {
            eprintln!("CULL must be none or back, not {other:?}");
            std::process::exit(2);
        }
    }
    let views: Vec<View> = (0..400)
        .map(|k| base.with_yaw_pitch_roll(f64::from(k) * step, 20.0, 0.0))
        .collect();
    let mut list = DrawList::new();
    let mut drawn = 0;
    let start = Instant::now();
    for view in &views {
        sorter.sort(view, &mut list);
        drawn += list.len();
    }
    let per_frame = start.elapsed().as_secs_f64() * 1e6 / views.len() as f64;
    println!("{name}: {drawn} items over 400 frames, {per_frame:.2} µs per frame");
}
