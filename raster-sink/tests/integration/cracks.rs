//! The ID fill leaves no cracks and no double cover where fragments meet.

use face_sort::sorter_api::DrawListWriter;
use raster_sink::face_sort::glam::{DVec2, DVec3};
use raster_sink::face_sort::{DrawList, Geometry, Plane, View, split_polygon};
use raster_sink::{for_each_span, render_ids};

use crate::common::{Rng, quads_mesh, square};

#[test]
fn square_cut_by_random_lines_is_covered_exactly_once() {
    for seed in 0..8 {
        let mut rng = Rng::new(seed + 100);
        let sq = square(DVec2::ZERO, 1.0, 0.0);
        let geometry = Geometry::new(&quads_mesh(&[sq])).expect("square");
        let view = View::fit(&geometry.bounds(), 97, 83).with_yaw_pitch_roll(
            rng.range(-40.0, 40.0),
            rng.range(-40.0, 40.0),
            7.0,
        );
        let view = if seed % 2 == 1 {
            view.with_perspective(150.0)
        } else {
            view
        };
        // Cut the square by 12 random planes perpendicular to it.
        let mut fragments: Vec<Vec<DVec3>> = vec![geometry.pieces().corners(0).to_vec()];
        for _ in 0..12 {
            let through = DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), 0.0);
            let angle = rng.range(0.0, std::f64::consts::TAU);
            let plane =
                Plane::try_from_point_normal(through, DVec3::new(angle.cos(), angle.sin(), 0.0))
                    .expect("plane");
            let mut next = Vec::new();
            for f in &fragments {
                let (mut front, mut back) = (Vec::new(), Vec::new());
                split_polygon(f, &plane, 0.0, &mut front, &mut back);
                next.extend([front, back].into_iter().filter(|p| p.len() >= 3));
            }
            fragments = next;
        }
        assert!(fragments.len() > 12);
        let mut list = DrawList::new();
        list.begin(geometry.pieces());
        let plane = *geometry.pieces().plane(0);
        for f in &fragments {
            let p = list.add_frame_polygon(f, 0, plane);
            list.push(p, 0);
        }
        // Coverage count per pixel, fragments vs the whole square.
        let (w, h) = (view.width(), view.height());
        let mut count = vec![0u32; (w * h) as usize];
        let mut whole = vec![false; (w * h) as usize];
        let mut pts = Vec::new();
        let mut scratch = Default::default();
        for item in list.items() {
            view.project_polygon(list.corners(*item), &mut pts, &mut scratch);
            for_each_span(&pts, w, h, |y, a, b| {
                for x in a..b {
                    count[(y * w + x) as usize] += 1;
                }
            });
        }
        view.project_polygon(&sq, &mut pts, &mut scratch);
        for_each_span(&pts, w, h, |y, a, b| {
            for x in a..b {
                whole[(y * w + x) as usize] = true;
            }
        });
        let covered = whole.iter().filter(|&&b| b).count();
        assert!(covered > 1000, "seed {seed}: {covered}");
        for k in 0..count.len() {
            assert_eq!(count[k], u32::from(whole[k]), "seed {seed}, pixel {k}");
        }
        let ids = render_ids(&view, &list);
        assert_eq!(ids.ids.iter().filter(|&&id| id == 1).count(), covered);
    }
}
