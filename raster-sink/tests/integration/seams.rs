//! A closed one-colour mesh on a contrasting background shows no background tint inside
//! its silhouette.

use face_sort::sorter_api::DrawListWriter;
use raster_sink::face_sort::glam::DVec3;
use raster_sink::face_sort::{
    Centroid, DrawList, FaceSorter, Geometry, Plane, PolygonMesh, View, split_polygon,
};
use raster_sink::tiny_skia::Pixmap;
use raster_sink::{RasterOptions, Style, Truth, render_colour, truth};

use crate::common::{Rng, spot, subdivided_cube};

const MESH: [u8; 4] = [200, 30, 30, 255];
const BACKGROUND: [u8; 4] = [20, 60, 230, 255];

/// Largest channel difference from the mesh colour over pixels whose 3×3 neighbourhood is
/// fully covered in the truth, and how many such pixels there are.
fn worst_inside_tint(image: &Pixmap, t: &Truth) -> (u8, usize) {
    let (w, h) = (t.width as i64, t.height as i64);
    let (mut worst, mut count) = (0u8, 0usize);
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let inside =
                (-1..=1).all(|dy| (-1..=1).all(|dx| t.ids[((y + dy) * w + x + dx) as usize] != 0));
            if !inside {
                continue;
            }
            count += 1;
            let px = image
                .pixel(x as u32, y as u32)
                .expect("in image")
                .demultiply();
            let got = [px.red(), px.green(), px.blue()];
            for c in 0..3 {
                worst = worst.max(got[c].abs_diff(MESH[c]));
            }
        }
    }
    (worst, count)
}

fn check(view: &View, geometry: &Geometry, list: &DrawList, name: &str) {
    let t = truth(view, geometry);
    let options = RasterOptions::DEFAULT.with_background(BACKGROUND);
    let image = render_colour(view, list, &Style::solid(MESH), &options).expect("render");
    let (worst, count) = worst_inside_tint(&image, &t);
    assert!(count > 500, "{name}: {count}");
    assert!(
        worst <= 2,
        "{name}: background tint of {worst} inside the silhouette"
    );
    // Without the outset the same test sees the hairlines: the test is sensitive.
    let plain = render_colour(
        view,
        list,
        &Style::solid(MESH),
        &options.with_seam_outset(0.0),
    )
    .expect("render");
    let (worst_plain, _) = worst_inside_tint(&plain, &t);
    assert!(
        worst_plain > 10,
        "{name}: expected seams without outset, got {worst_plain}"
    );
}

fn sorted(view: &View, geometry: &Geometry) -> DrawList {
    let mut list = DrawList::new();
    Centroid::new(geometry).sort(view, &mut list);
    list
}

#[test]
fn subdivided_cube_has_no_seams() {
    let cube = Geometry::new(&subdivided_cube(5)).expect("cube");
    for view in [
        View::fit(&cube.bounds(), 128, 128).with_yaw_pitch_roll(33.0, 21.0, 7.0),
        View::fit(&cube.bounds(), 128, 128)
            .with_yaw_pitch_roll(-50.0, -35.0, 0.0)
            .with_perspective(160.0),
    ] {
        check(&view, &cube, &sorted(&view, &cube), "cube");
    }
}

#[test]
fn spot_has_no_seams() {
    let mesh: PolygonMesh = test_support::polygon_mesh(&spot());
    let geometry = Geometry::new(&mesh).expect("spot");
    for view in [
        View::fit(&geometry.bounds(), 200, 200).with_yaw_pitch_roll(30.0, 15.0, 0.0),
        View::fit(&geometry.bounds(), 200, 200)
            .with_yaw_pitch_roll(150.0, -20.0, 0.0)
            .with_perspective(260.0),
    ] {
        check(&view, &geometry, &sorted(&view, &geometry), "spot");
    }
}

#[test]
fn split_fragments_with_t_junctions_have_no_seams() {
    // Every other piece of the cube cut in two by a random plane: its unsplit neighbours
    // meet the fragments at T-junctions.
    let cube = Geometry::new(&subdivided_cube(4)).expect("cube");
    let view = View::fit(&cube.bounds(), 128, 128).with_yaw_pitch_roll(25.0, 30.0, 0.0);
    let base = sorted(&view, &cube);
    let mut rng = Rng::new(7);
    let mut list = DrawList::new();
    list.begin(cube.pieces());
    for (n, item) in base.items().iter().enumerate() {
        let corners = base.corners(*item);
        if n % 2 == 1 {
            list.push(item.polygon, item.face);
            continue;
        }
        let centre = corners.iter().copied().sum::<DVec3>() / corners.len() as f64;
        let dir = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let plane = Plane::try_from_point_normal(centre, dir).expect("plane");
        let (mut front, mut back) = (Vec::new(), Vec::new());
        split_polygon(corners, &plane, 0.0, &mut front, &mut back);
        for part in [front, back] {
            if part.len() >= 3 {
                let p = list.add_frame_polygon(&part, item.face, *base.plane(*item));
                list.push(p, item.face);
            }
        }
    }
    assert!(list.frame_fragments() > 20);
    check(&view, &cube, &list, "split cube");
}
