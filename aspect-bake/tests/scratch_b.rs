use aspect_bake::face_sort::glam::DVec3;
use aspect_bake::face_sort::{DrawList, Geometry, PolygonMesh, View, oracle};
use aspect_bake::*;
#[test]
fn scratch() {
    let p = vec![
        DVec3::new(-1.25, 1.625, -2.875),
        DVec3::new(0.5, 0.5, -3.25),
        DVec3::new(-1.875, 3.4999999999999996, 2.75),
        DVec3::new(0.375, -3.0, 1.875),
        DVec3::new(-4.0, -3.0, 1.875),
    ];
    let idx = [1u32, 0, 3, 1, 3, 0, 0, 2, 2, 4, 2, 1, 0, 4, 3, 4];
    let off = [0usize, 4, 9, 12, 16];
    let faces: Vec<Vec<u32>> = (0..4).map(|f| idx[off[f]..off[f + 1]].to_vec()).collect();
    let g = Geometry::new(&PolygonMesh::new(p, faces).unwrap()).unwrap();
    for i in 0..g.pieces().len() {
        println!("piece {i}: {:?}", g.pieces().corners(i));
    }
    let view = View::fit(&g.bounds(), 21, 21).with_perspective(27.5830078125);
    let spin = Spin::new(
        view,
        Axis::Yaw {
            pitch: 43.59375,
            roll: 65.390625,
        },
    )
    .unwrap();
    let (b, stats) = bake_picture(&g, &spin, &PictureOptions::DEFAULT).unwrap();
    println!(
        "cells {:?}",
        b.cells()
            .iter()
            .map(|c| (c.range.lo, c.range.hi, c.order.clone()))
            .collect::<Vec<_>>()
    );
    println!("stats {stats:?}");
    for i in 0..b.polygons().len() {
        println!("baked piece {i}: {:?}", b.polygons().corners(i));
    }
    let mut list = DrawList::new();
    for deg in [0.000001, 0.001, 1.0, 10.0, 90.0, 180.0, 359.0] {
        let v = spin.view_at(deg);
        cell_list(&b, 0, &mut list);
        println!("{deg}: {:?}", oracle::find_violations(&v, &list, 5));
    }
}
