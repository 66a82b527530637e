//! 400 frames of one sorter on spot (a 0.9° yaw spin), for instruction-count profiles:
//!
//! ```sh
//! cargo build --release -p face-sort --example profile_frame
//! valgrind --tool=callgrind target/release/examples/profile_frame bsp
//! valgrind --tool=callgrind target/release/examples/profile_frame centroid
//! ```

#[path = "../tests/common/mod.rs"]
mod common;

use face_sort::{DrawList, Geometry, SorterKind, View};

fn main() {
    let name = std::env::args().nth(1).unwrap_or_else(|| "bsp".into());
    let Some(kind) = SorterKind::from_name(&name) else {
        eprintln!("unknown sorter {name}: centroid, topological, newell or bsp");
        std::process::exit(2);
    };
    let mesh = common::read_obj(&common::asset("keenan-crane/spot/spot_quadrangulated.obj"));
    let geometry = Geometry::new(&mesh).expect("valid model");
    let mut sorter = kind.build(&geometry);
    let base = View::fit(&geometry.bounds(), 512, 512);
    let mut list = DrawList::new();
    let mut drawn = 0;
    for k in 0..400 {
        sorter.sort(
            &base.with_yaw_pitch_roll(f64::from(k) * 0.9, 20.0, 0.0),
            &mut list,
        );
        drawn += list.len();
    }
    println!("{name}: {drawn} items over 400 frames");
}
