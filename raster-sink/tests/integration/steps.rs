//! Render steps, overrides, supersampling and size limits.

use raster_sink::face_sort::{DrawItem, Geometry, View};
use raster_sink::{
    Override, RasterError, RasterOptions, Step, Style, new_pixmap, render_colour, render_ids,
    run_steps,
};

use crate::common::subdivided_cube;
use crate::scenes::centroid_list;

#[test]
fn id_colour_override_matches_id_image_away_from_edges() {
    let cube = Geometry::new(&subdivided_cube(2)).expect("cube");
    let view = View::fit(&cube.bounds(), 64, 64).with_yaw_pitch_roll(30.0, 20.0, 0.0);
    let list = centroid_list(&view, &cube);
    let options = RasterOptions::DEFAULT
        .with_anti_alias(false)
        .with_brush_override(Override::IdColours)
        .with_background([0, 0, 0, 255]);
    let image = render_colour(&view, &list, &Style::palette(), &options).expect("render");
    let ids = render_ids(&view, &list);
    let t = raster_sink::truth(&view, &cube);
    let mut checked = 0;
    for (k, px) in image.pixels().iter().enumerate() {
        if t.unambiguous[k] {
            let id =
                (u32::from(px.red()) << 16) | (u32::from(px.green()) << 8) | u32::from(px.blue());
            assert_eq!(id, ids.ids[k]);
            checked += 1;
        }
    }
    assert!(checked > 500);
}

#[test]
fn steps_filter_and_override_and_supersample() {
    let cube = Geometry::new(&subdivided_cube(2)).expect("cube");
    let view = View::fit(&cube.bounds(), 48, 48).with_yaw_pitch_roll(30.0, 20.0, 0.0);
    let list = centroid_list(&view, &cube);
    let only_face_0 = |item: DrawItem| item.face == 0;
    let steps = [
        Step::Clear([0, 0, 0, 255]),
        Step::Draw {
            filter: Some(&only_face_0),
            brush: Override::Solid([255, 0, 0, 255]),
        },
        Step::Resolve,
    ];
    let options = RasterOptions::DEFAULT.with_supersample(3);
    let image = run_steps(&view, &list, &Style::palette(), &options, &steps).expect("render");
    assert_eq!((image.width(), image.height()), (48, 48));
    let red = image
        .pixels()
        .iter()
        .filter(|p| p.red() > 250 && p.green() == 0)
        .count();
    let ids = render_ids(&view, &list);
    let face0 = ids.ids.iter().filter(|&&id| id == 1).count();
    assert!(red > 0 && red <= face0, "red {red} face 0 {face0}");
    assert!(
        image
            .pixels()
            .iter()
            .all(|p| p.green() == 0 && p.blue() == 0)
    );
    // Without Resolve the canvas stays supersampled.
    let raw = run_steps(&view, &list, &Style::palette(), &options, &steps[..2]).expect("render");
    assert_eq!(raw.width(), 144);
}

#[test]
fn huge_sizes_and_bad_options_are_errors_not_aborts() {
    assert!(matches!(
        new_pixmap(100_000, 100_000),
        Err(RasterError::ImageSize { .. })
    ));
    assert!(matches!(
        new_pixmap(0, 10),
        Err(RasterError::ImageSize { .. })
    ));
    let cube = Geometry::new(&subdivided_cube(1)).expect("cube");
    let view = View::fit(&cube.bounds(), 10_000, 10_000);
    let list = centroid_list(&view, &cube);
    let options = RasterOptions::DEFAULT.with_supersample(4);
    let error = render_colour(&view, &list, &Style::palette(), &options).expect_err("too big");
    assert!(error.to_string().contains("40000"), "{error}");
    let options = RasterOptions::DEFAULT.with_supersample(0);
    assert!(matches!(
        render_colour(&view, &list, &Style::palette(), &options),
        Err(RasterError::InvalidOption {
            option: "supersample",
            ..
        })
    ));
}
