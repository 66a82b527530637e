//! The small-piece filter: drops exactly the items below the area, keeps the others' order.

use crate::common;
use face_sort::{
    Bsp, DrawList, FaceSorter, Geometry, ProjectionScratch, SmallPieceFilter, View, signed_area_2d,
};

#[test]
fn small_pieces_go_and_the_rest_keep_their_order() {
    let geometry = Geometry::new(&common::load_model(
        "keenan-crane/spot/spot_quadrangulated.obj",
    ))
    .unwrap();
    let view = View::fit(&geometry.bounds(), 256, 256).with_yaw_pitch_roll(35.0, 15.0, 0.0);
    let mut list = DrawList::new();
    Bsp::new(&geometry).sort(&view, &mut list);
    let all: Vec<_> = list.items().to_vec();
    let area = |item| {
        let mut points = Vec::new();
        view.project_polygon(
            list.corners(item),
            &mut points,
            &mut ProjectionScratch::default(),
        );
        signed_area_2d(&points).abs()
    };
    let areas: Vec<f64> = all.iter().map(|&i| area(i)).collect();
    let mut filter = SmallPieceFilter::new();
    assert_eq!(filter.apply(&view, &mut list, 0.0), 0);
    let threshold = 4.0;
    let expected: Vec<_> = all
        .iter()
        .zip(&areas)
        .filter(|(_, a)| **a >= threshold)
        .map(|(i, _)| *i)
        .collect();
    let removed = filter.apply(&view, &mut list, threshold);
    assert_eq!(removed, all.len() - expected.len());
    assert!(
        removed > 100 && !expected.is_empty(),
        "{removed} of {}",
        all.len()
    );
    assert_eq!(list.items(), &expected[..]);
    assert_eq!(
        filter.apply(&view, &mut list, f64::INFINITY),
        expected.len()
    );
    assert!(list.is_empty());
}
