//! The oracle on a piece seen almost edge-on: its depth along a ray is known only to the
//! rounding of where the overlap's points lie, so a sliver behind a face does not count as in
//! front of it, while a real misorder of the same pair still does.

use face_sort::sorter_api::DrawListWriter;
use face_sort::{DrawList, Geometry, View, oracle};

mod common;

use common::{asset, read_obj};

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
    let mut list = DrawList::new();
    let mut judge = |order: [u32; 2]| {
        list.begin(g.pieces());
        for i in order {
            list.push(i, g.pieces().face(i as usize));
        }
        oracle::find_violations(&view, &list, 1)
    };
    // The floor first, then the face: right.
    let right = judge([floor, face]);
    assert!(right.is_empty(), "{right:?}");
    // The face first: the floor's sliver paints over it, deep behind it.
    let wrong = judge([face, floor]);
    assert_eq!(wrong.len(), 1);
    assert!(wrong[0].depth_gap > 1.0, "{wrong:?}");
}
