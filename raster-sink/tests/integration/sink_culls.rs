//! A draw list whose sink culls ([`DrawList::set_sink_culls`]) holds every piece; raster-sink
//! skips those the view does not draw while painting, so the picture equals that of the list
//! culled beforehand, and the oracle judges only what is painted.

use face_sort::sorter_api::DrawListWriter;
use face_sort::{Bsp, DrawList, FaceSorter, Geometry, View, oracle};
use raster_sink::render_ids;

#[test]
fn a_list_whose_sink_culls_paints_like_the_culled_list() {
    let mesh = test_support::load_polygon_mesh("keenan-crane/spot/spot_control_mesh.obj");
    let g = Geometry::new(&mesh).unwrap();
    let view = View::fit(&g.bounds(), 128, 128).with_yaw_pitch_roll(40.0, 20.0, 0.0);
    // An exact order of the drawn pieces, and the same order with every culled piece put
    // back in front of it, at the end of the list (where a culling sink must skip them).
    let mut culled = DrawList::new();
    Bsp::new(&g).sort(&view, &mut culled);
    let test = view.cull_test();
    // The BSP's fragments: every polygon of its list comes from this shared set.
    let pieces = std::sync::Arc::clone(culled.shared().expect("a shared set"));
    let mut full = DrawList::new();
    full.begin(&pieces);
    full.set_sink_culls(true);
    let drawn: Vec<u32> = culled.items().iter().map(|i| i.polygon).collect();
    for &p in &drawn {
        full.push(p, pieces.face(p as usize));
    }
    let mut hidden = 0;
    for p in 0..pieces.len() {
        if !test.is_drawn(pieces.plane(p), pieces.corners(p)[0]) {
            full.push(p as u32, pieces.face(p));
            hidden += 1;
        }
    }
    assert!(hidden > 10, "the view culls some pieces");
    assert_eq!(render_ids(&view, &full).ids, render_ids(&view, &culled).ids);
    assert_eq!(oracle::count_violations(&view, &full), 0);
    // Without the declaration the back faces are painted on top, and judged.
    full.set_sink_culls(false);
    assert_ne!(render_ids(&view, &full).ids, render_ids(&view, &culled).ids);
    assert!(oracle::count_violations(&view, &full) > 0);
}
