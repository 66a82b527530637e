//! What `Presorted` makes of every OBJ model of the repository: pieces, cuts, pairs the build
//! looked at, whether one
//! order serves every view, certified orders, small cycles, uncertified regions, cached bytes
//! and build time on every core; the certified orders a page turned by the pointer would carry
//! (`Presorted::certified_orders`, orthographic and an eye at 2 bounding radii: regions,
//! orders, cycles and the most planes of a cycle's tree, or why there are none); then, for spot, blub and the scan-like blob, the planner's `CostModel` figures
//! (build per piece and level on one thread, frame per piece, orthographic).
//!
//! `cargo run --release -p face-sort --example presort_models`

#[path = "../tests/common/mod.rs"]
mod common;

use std::time::Instant;

use face_sort::{DrawList, FaceSorter, Geometry, PresortOptions, Presorted, SorterKind, View};

const MODELS: [&str; 20] = [
    "assimp-obj/box.obj",
    "assimp-obj/concave_polygon.obj",
    "combobulate-samples/book.obj",
    "combobulate-samples/octahedron.obj",
    "combobulate-samples/tetrahedron.obj",
    "compas/boxes.obj",
    "compas/faces.obj",
    "compas/hypar.obj",
    "compas/quadmesh.obj",
    "compas/tubemesh.obj",
    "cornell-box/cornell_box.obj",
    "fandisk-quads/fandisk_quads.converted.obj",
    "keenan-crane/blub/blub_control_mesh.obj",
    "keenan-crane/blub/blub_quadrangulated.obj",
    "keenan-crane/spot/spot_control_mesh.obj",
    "keenan-crane/spot/spot_control_mesh_texture.obj",
    "keenan-crane/spot/spot_quadrangulated.obj",
    "keenan-crane/spot/spot_triangulated.obj",
    "opensubdiv-torus/catmark_torus_creases0.obj",
    "suzanne/suzanne.obj",
];

fn geometry(model: &str) -> Geometry {
    let mesh = common::read_obj(&common::asset(model));
    SorterKind::Presorted.geometry_for(&mesh).unwrap()
}

/// Regions, orders, cycles and the most planes of a cycle's tree of the certified orders.
fn page(sorter: &Presorted, eye_distance: Option<f64>) -> String {
    match sorter.certified_orders(eye_distance) {
        Ok(c) => format!(
            "{} regions, {} orders, {} cycles, {} planes at most",
            c.regions.len(),
            c.orders.len(),
            c.cores.len(),
            c.cores.iter().map(|k| k.planes.len()).max().unwrap_or(0)
        ),
        Err(e) => e.to_string(),
    }
}

fn main() {
    println!(
        "model | pieces | cuts | pairs looked at | one order | orders | small cycles | uncertified | cached MB | build ms | page ortho | page eye at 2 radii"
    );
    for model in MODELS {
        let geometry = geometry(model);
        let start = Instant::now();
        let sorter = Presorted::new(&geometry);
        let build = start.elapsed().as_secs_f64() * 1e3;
        println!(
            "{model} | {} | {} | {} | {} | {} | {} | {} | {:.1} | {build:.0} | {} | {}",
            geometry.pieces().len(),
            sorter.cuts(),
            sorter.pairs().0,
            sorter.one_order_for_every_view(),
            sorter.orders(),
            sorter.cores().0,
            sorter.uncertified_regions(),
            sorter.stats().cached_bytes as f64 / 1e6,
            page(&sorter, None),
            page(&sorter, Some(geometry.bounds().diagonal())),
        );
    }
    println!(
        "\nCostModel: build ns per piece and level (n log2 n) on one thread, frame ns per piece"
    );
    let scan = SorterKind::Presorted
        .geometry_for(&face_sort::generate::scan_blob(264, 132))
        .unwrap();
    for (model, geometry) in [
        "keenan-crane/spot/spot_quadrangulated.obj",
        "keenan-crane/blub/blub_quadrangulated.obj",
    ]
    .map(|model| (model, geometry(model)))
    .into_iter()
    .chain([("scan_blob(264, 132)", scan)])
    {
        let n = geometry.pieces().len() as f64;
        let start = Instant::now();
        let one_thread = PresortOptions {
            threads: 1,
            ..PresortOptions::default()
        };
        let mut sorter = Presorted::try_new(&geometry, &one_thread).unwrap();
        let build = start.elapsed().as_secs_f64() * 1e9;
        let mut list = DrawList::new();
        let mut times = Vec::new();
        for k in 0..2000 {
            let view = View::fit(&geometry.bounds(), 512, 512).with_yaw_pitch_roll(
                15.0 + 0.02 * f64::from(k),
                25.0,
                0.0,
            );
            let start = Instant::now();
            sorter.sort(&view, &mut list);
            times.push(start.elapsed().as_secs_f64() * 1e9);
        }
        times.sort_by(f64::total_cmp);
        println!(
            "{model}: build {:.0} ns per piece and level, frame {:.2} ns per piece",
            build / (n * n.log2()),
            times[times.len() / 2] / n
        );
    }
}
