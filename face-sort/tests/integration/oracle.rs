//! The oracle on a piece seen almost edge-on: its depth along a ray is known only to the
//! rounding of where the overlap's points lie, so a sliver behind a face does not count as in
//! front of it, while a real misorder of the same pair still does.

use face_sort::sorter_api::DrawListWriter;
use face_sort::{DrawList, Geometry, View, oracle};

/// The oracle's first violation, if any, of two pieces of `g` drawn in `order`.
fn violations_in_order(g: &Geometry, view: &View, order: [u32; 2]) -> Vec<oracle::Violation> {
    let mut list = DrawList::new();
    list.begin(g.pieces());
    for i in order {
        list.push(i, g.pieces().face(i as usize));
    }
    oracle::find_violations(view, &list, 1)
}

use crate::common::{asset, read_obj};

#[test]
fn a_sliver_seen_edge_on_is_judged_within_the_rounding_of_its_position() {
    // compas' boxes at yaw 90.000001°, pitch 20°: piece 4 faces the viewer (x = 0, facing
    // −x), and piece 8, the floor of the box behind it (y = 0, x from 0 to 10, facing −y), is
    // seen 6e-9 from edge-on. The floor lies behind the face wherever they overlap.
    let g = Geometry::new(&read_obj(&asset("compas/boxes.obj"))).unwrap();
    let view = View::fit(&g.bounds(), 512, 512).with_yaw_pitch_roll(90.000001, 20.0, 0.0);
    let (face, floor) = (4u32, 8u32);
    let facing = |i: u32| view.viewer().facing(g.pieces().plane(i as usize));
    assert!(facing(face) > 0.99, "{}", facing(face));
    assert!(
        facing(floor) > 0.0 && facing(floor) < 1e-8,
        "{}",
        facing(floor)
    );
    let judge = |order: [u32; 2]| violations_in_order(&g, &view, order);
    // The floor first, then the face: right.
    let right = judge([floor, face]);
    assert!(right.is_empty(), "{right:?}");
    // The face first: the floor's sliver paints over it, deep behind it.
    let wrong = judge([face, floor]);
    assert_eq!(wrong.len(), 1);
    assert!(wrong[0].depth_gap > 1.0, "{wrong:?}");
}

/// Two squares next to the near plane (`w` 0.002 and 0.004), one behind the other: projecting
/// there rounds 500 times worse than far from the eye, and the oracle allows for it
/// (`View::rounding_gain`), yet the pair drawn front first is still a violation, by the full
/// unit between them.
#[test]
fn a_misorder_next_to_the_near_plane_still_counts() {
    let square = |z: f64| {
        [
            [-1.0, -1.0, z],
            [1.0, -1.0, z],
            [1.0, 1.0, z],
            [-1.0, 1.0, z],
        ]
    };
    let positions = square(0.5)
        .into_iter()
        .chain(square(-0.5))
        .map(glam::DVec3::from);
    let mesh = face_sort::PolygonMesh::new(positions, [[0u32, 1, 2, 3], [4, 5, 6, 7]]).unwrap();
    let g = Geometry::new(&mesh).unwrap();
    let fitted = View::fit(&g.bounds(), 64, 64);
    // The eye at `d/s` in view units; the front square's w = 0.002 and the back one's 0.004.
    let distance = fitted.scale() / 0.002;
    let eye = distance / fitted.scale();
    let view = fitted
        .with_perspective(distance)
        .with_view_offset(glam::DVec3::new(0.0, 0.0, 0.998 * eye - 0.5));
    g.check_view(&view).unwrap();
    let gain = |i: usize| view.rounding_gain(g.pieces().corners(i));
    assert!((gain(0) - 500.0).abs() < 1e-6, "{}", gain(0));
    assert!((gain(1) - 250.0).abs() < 1e-6, "{}", gain(1));
    let judge = |order: [u32; 2]| violations_in_order(&g, &view, order);
    let right = judge([1, 0]);
    assert!(right.is_empty(), "{right:?}");
    let wrong = judge([0, 1]);
    assert_eq!(wrong.len(), 1, "{wrong:?}");
    assert!(wrong[0].depth_gap > 0.99, "{wrong:?}");
}
