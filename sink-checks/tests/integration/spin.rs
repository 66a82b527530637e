//! The spinning page of a bake in headless Chromium, paused at chosen times (a negative
//! `animation-delay`), compared with raster-sink's truth at the same angle: the bar of the
//! static flat pages (at most 0.2 % wrong unambiguous pixels).

use raster_sink::{pixel_error, truth};
use sprite_compose::aspect_bake::{Axis, BakeOptions, BspSource, Spin, bake};
use sprite_compose::face_sort::{Geometry, View};
use vector_sink::{SpinOptions, write_spin_html};

use crate::browser::{chromium, screenshot};
use crate::support;
use crate::writers::{SIZE, ids_of_rgba};

const PERIOD_S: f64 = 8.0;

fn check(name: &str, g: &Geometry, view: View, angles: &[f64]) {
    let Some(browser) = chromium() else {
        return;
    };
    let spin = Spin::new(
        view,
        Axis::Yaw {
            pitch: 20.0,
            roll: 0.0,
        },
    )
    .expect("a named axis");
    let baked = bake(&BspSource::of(g), &spin, &BakeOptions::DEFAULT).expect("a bake");
    // A chosen angle and the middle of the first cell (a screenshot of these ~16 MB pages
    // takes about 13 s on the 2-core machine).
    let mut degrees = angles.to_vec();
    degrees.extend(baked.cells().first().map(|c| c.range.lerp(0.5) % 360.0));
    for d in degrees {
        let t = d / 360.0 * PERIOD_S;
        let page = write_spin_html(
            &baked,
            &spin,
            g,
            &SpinOptions::DEFAULT
                .with_period(PERIOD_S)
                .with_ids(true)
                .with_paused_at(Some(t)),
        );
        let rgba = screenshot(browser, &page, &format!("spin-{name}-{d}"));
        let shot = ids_of_rgba(SIZE, SIZE, &rgba);
        let e = pixel_error(&shot, &truth(&spin.view_at(d), g));
        println!(
            "spin {name} at {d:.3}° ({} cells, page {} B): {}/{} = {:.4} %",
            baked.cells().len(),
            page.len(),
            e.wrong,
            e.pixels,
            e.error * 100.0
        );
        assert!(e.pixels > 1000, "{name} at {d}°: too few pixels to judge");
        assert!(e.error <= 2e-3, "{name} at {d}°: {e:?}");
    }
}

#[test]
fn spinning_pages_in_chromium_match_raster_sink() {
    // spot's control mesh (180 faces, non-planar quads: fan triangles), as in the static
    // page test: orthographic and perspective.
    let spot = support::geometry(&support::load_obj(
        "keenan-crane/spot/spot_control_mesh.obj",
    ));
    let base = View::fit(&spot.bounds(), SIZE, SIZE);
    check("spot-ortho", &spot, base, &[200.0]);
    check(
        "spot-persp",
        &spot,
        base.with_perspective(f64::from(SIZE)),
        &[300.0],
    );
}
