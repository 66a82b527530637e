//! BSP subtree culling by bounding sphere: zoomed in, the BSP draws fewer items, every item
//! it leaves out lies outside the image, and the order stays exact.

use crate::common;
use face_sort::glam::DVec2;
use face_sort::{Bsp, DrawItem, DrawList, FaceSorter, Geometry, ProjectionScratch, View, oracle};

#[test]
fn subtrees_outside_the_image_are_skipped() {
    let geometry = Geometry::new(&common::load_model(
        "keenan-crane/spot/spot_quadrangulated.obj",
    ))
    .unwrap();
    let fit = View::fit(&geometry.bounds(), 256, 256);
    let mut bsp = Bsp::new(&geometry);
    let mut list = DrawList::new();
    let mut scratch = ProjectionScratch::default();
    let mut points: Vec<DVec2> = Vec::new();
    for (k, view) in [
        fit.with_yaw_pitch_roll(30.0, 20.0, 0.0)
            .with_scale(fit.scale() * 4.0),
        fit.with_yaw_pitch_roll(200.0, -10.0, 0.0)
            .with_scale(fit.scale() * 3.0)
            .with_perspective(300.0),
        // The eye close to the model and inside it (the stress suite's views): spheres off
        // the axis of view and near the eye project far larger than their radius.
        fit.with_yaw_pitch_roll(90.0, 0.0, 0.0)
            .with_perspective(0.3 * fit.diagonal() * fit.scale()),
        fit.with_yaw_pitch_roll(35.0, 20.0, 0.0)
            .with_perspective(0.1 * fit.diagonal() * fit.scale())
            .with_cull(face_sort::CullMode::None),
        fit.with_yaw_pitch_roll(30.0, 20.0, 0.0), // whole model in view: nothing skipped
    ]
    .into_iter()
    .enumerate()
    {
        // Every drawn item, without culling by subtree.
        bsp.sort_culled(&view.cull_test(), &mut list);
        let all: Vec<DrawItem> = list.items().to_vec();
        let outside = |list: &DrawList,
                       item: DrawItem,
                       scratch: &mut ProjectionScratch,
                       points: &mut Vec<DVec2>| {
            view.project_polygon(list.corners(item), points, scratch);
            let (w, h) = (f64::from(view.width()), f64::from(view.height()));
            points.is_empty()
                || points.iter().all(|p| p.x < 0.0)
                || points.iter().all(|p| p.y < 0.0)
                || points.iter().all(|p| p.x > w)
                || points.iter().all(|p| p.y > h)
        };
        let off_image = all
            .iter()
            .filter(|&&i| outside(&list, i, &mut scratch, &mut points))
            .count();
        bsp.sort(&view, &mut list);
        assert_eq!(oracle::count_violations(&view, &list), 0, "view {k}");
        let kept: std::collections::HashSet<u32> = list.items().iter().map(|i| i.polygon).collect();
        // The order of the kept items is the full order's.
        let full_order: Vec<DrawItem> = all
            .iter()
            .copied()
            .filter(|i| kept.contains(&i.polygon))
            .collect();
        assert_eq!(list.items(), &full_order[..], "view {k}");
        // Only items off the image were skipped.
        let mut check = DrawList::new();
        bsp.sort_culled(&view.cull_test(), &mut check);
        for item in all.iter().filter(|i| !kept.contains(&i.polygon)) {
            assert!(
                outside(&check, *item, &mut scratch, &mut points),
                "view {k}: {item:?} skipped but on the image"
            );
        }
        let skipped = all.len() - kept.len();
        println!(
            "view {k}: {} items, {skipped} skipped ({off_image} off the image)",
            all.len()
        );
        if k < 2 {
            assert!(
                skipped * 4 > off_image,
                "view {k}: {skipped} of {off_image}"
            );
        } else if k == 4 {
            assert_eq!(skipped, 0);
        }
    }
}
