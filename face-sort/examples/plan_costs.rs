//! Measures the planner's cost model (`face_sort::CostModel`): BSP build per piece and level,
//! BSP and Newell per-frame cost per piece, on spot, blub and generated tori, orthographic.
//! Prints each model's figures and the medians the planner's constants come from.
//!
//! `cargo run --release -p face-sort --example plan_costs`

#[path = "../tests/common/mod.rs"]
mod common;

use std::time::Instant;

use face_sort::{Bsp, DrawList, FaceSorter, Geometry, Newell, PolygonMesh, View, generate};

const YAWS: [f64; 8] = [0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0];

/// Median nanoseconds per frame over the yaw ring (three passes).
fn frame_ns(sorter: &mut dyn FaceSorter, geometry: &Geometry) -> f64 {
    let mut list = DrawList::new();
    let mut times = Vec::new();
    for _ in 0..3 {
        for yaw in YAWS {
            let view = View::fit(&geometry.bounds(), 512, 512).with_yaw_pitch_roll(yaw, 20.0, 0.0);
            let start = Instant::now();
            sorter.sort(&view, &mut list);
            times.push(start.elapsed().as_secs_f64() * 1e9);
        }
    }
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let models: Vec<(String, PolygonMesh)> = vec![
        (
            "spot".to_owned(),
            common::read_obj(&common::asset("keenan-crane/spot/spot_quadrangulated.obj")),
        ),
        (
            "blub".to_owned(),
            common::read_obj(&common::asset("keenan-crane/blub/blub_quadrangulated.obj")),
        ),
        ("bumpy torus 4k".to_owned(), generate::torus(4_000)),
        ("bumpy torus 20k".to_owned(), generate::torus(20_000)),
    ];
    let (mut build, mut bsp_frame, mut newell_frame) = (Vec::new(), Vec::new(), Vec::new());
    println!(
        "| model | pieces | BSP build ns/(n·log2 n) | BSP frame ns/piece | Newell frame ns/piece |"
    );
    println!("| --- | ---: | ---: | ---: | ---: |");
    for (name, mesh) in &models {
        let geometry = Geometry::new(mesh).expect("valid model");
        let n = geometry.pieces().len() as f64;
        let start = Instant::now();
        let mut bsp = Bsp::new(&geometry);
        let b = start.elapsed().as_secs_f64() * 1e9 / (n * n.log2());
        let f = frame_ns(&mut bsp, &geometry) / n;
        let mut newell = Newell::new(&geometry);
        let w = frame_ns(&mut newell, &geometry) / n;
        println!("| {name} | {n} | {b:.0} | {f:.1} | {w:.0} |");
        build.push(b);
        bsp_frame.push(f);
        newell_frame.push(w);
    }
    println!(
        "\nmedians: bsp_build_per_piece_level {:.0}, bsp_frame_per_piece {:.1}, newell_frame_per_piece {:.0}",
        median(build),
        median(bsp_frame),
        median(newell_frame)
    );
}
