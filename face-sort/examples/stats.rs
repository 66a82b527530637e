//! Build time, fragments, tree depth and cached bytes per face of every sorter on spot and blub.
//!
//! `cargo run --release -p face-sort --example stats`

#[path = "../tests/common/mod.rs"]
mod common;

use face_sort::{DrawList, Geometry, SorterKind, View};

fn main() {
    for model in [
        "keenan-crane/spot/spot_quadrangulated.obj",
        "keenan-crane/blub/blub_quadrangulated.obj",
    ] {
        let mesh = common::read_obj(&common::asset(model));
        let geometry = Geometry::new(&mesh).expect("valid model");
        let faces = geometry.face_count();
        let pieces = geometry.pieces().len();
        println!("{model}: {faces} faces, {pieces} pieces");
        for kind in SorterKind::ALL {
            let start = std::time::Instant::now();
            let mut sorter = kind.build(&geometry);
            let build_ms = start.elapsed().as_secs_f64() * 1e3;
            let mut list = DrawList::new();
            sorter.sort(&View::fit(&geometry.bounds(), 512, 512), &mut list);
            let stats = sorter.stats();
            println!(
                "  {:<12} build {:>8.1} ms  polygons {:>6} ({:.2}x pieces)  depth {:>4}  cached {:>6.0} B/face  fallbacks {}",
                kind.name(),
                build_ms,
                stats.polygons,
                stats.polygons as f64 / pieces as f64,
                stats.depth,
                stats.cached_bytes as f64 / faces as f64,
                stats.fallbacks
            );
        }
    }
}
