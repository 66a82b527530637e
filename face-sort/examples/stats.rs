//! Build time, fragments, tree depth and cached bytes per face of every sorter on spot and blub.
//!
//! `cargo run --release -p face-sort --example stats`
//!
//! With arguments `WEIGHT,CANDIDATES,SAMPLE …` it instead builds the BSP of each real model of
//! the bench (spot, blub, suzanne, fandisk) with those splitter options and prints fragments,
//! depth and build time for each (the tuning behind the README):
//! `cargo run --release -p face-sort --example stats -- 8,12,1024 8,48,8000 32,12,1024`

#[path = "../tests/common/mod.rs"]
mod common;

use face_sort::{DrawList, Geometry, SorterKind, View};

/// The bench's real models (name, path under `assets/models`); the full table covers the
/// first two.
const MODELS: [(&str, &str); 4] = [
    ("spot", "keenan-crane/spot/spot_quadrangulated.obj"),
    ("blub", "keenan-crane/blub/blub_quadrangulated.obj"),
    ("suzanne", "suzanne/suzanne.obj"),
    ("fandisk", "fandisk-quads/fandisk_quads.converted.obj"),
];

fn main() {
    let tunings: Vec<Vec<f64>> = std::env::args()
        .skip(1)
        .map(|a| {
            a.split(',')
                .map(|v| v.parse().expect("WEIGHT,CANDIDATES,SAMPLE"))
                .collect()
        })
        .collect();
    if !tunings.is_empty() {
        tune_bsp(&tunings);
        return;
    }
    for (_, model) in &MODELS[..2] {
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

fn tune_bsp(tunings: &[Vec<f64>]) {
    for (name, model) in MODELS {
        let mesh = common::read_obj(&common::asset(model));
        let geometry = Geometry::new(&mesh).expect("valid model");
        let pieces = geometry.pieces().len() as f64;
        for t in tunings {
            let [weight, candidates, sample] = t[..] else {
                panic!("expected WEIGHT,CANDIDATES,SAMPLE, got {t:?}");
            };
            let mut options = face_sort::BspOptions::DEFAULT;
            options.split_weight = weight;
            options.candidates = candidates as usize;
            options.score_sample = sample as usize;
            let tree = face_sort::BspTree::build(&geometry, &options);
            println!(
                "{name} bsp weight {weight} candidates {candidates} sample {sample}: {:.3}x pieces, depth {}, {} nodes, build {:.1} ms ({:.2} µs per piece)",
                tree.fragment_count() as f64 / pieces,
                tree.depth(),
                tree.node_count(),
                tree.build_ms(),
                tree.build_ms() * 1e3 / pieces
            );
        }
    }
}
