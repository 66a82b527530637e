//! The page that turns with the pointer (a `Presorted`'s certified orders, looked up by a few
//! lines of script), in headless Chromium at random views and a millionth of a radian either
//! side of region edges, compared with raster-sink's truth at the same view. The bar is that
//! of the other Chromium page tests (at most 0.2 % wrong unambiguous pixels); every frame's
//! count is printed.

use raster_sink::{pixel_error, truth};
use sprite_compose::face_sort::glam::DVec3;
use sprite_compose::face_sort::{CertifiedOrdersError, Geometry, Presorted, View};
use vector_sink::{TurnPage, TurnPageOptions, write_canvas_turn_html, write_turn_html};

use crate::browser::{chromium, print_wrong_pixels, screenshot_at};
use crate::support;
use crate::writers::{SIZE, ids_of_rgba};

/// Yaw and pitch (degrees) whose direction toward the viewer, `Rᵀ·ẑ` for
/// `R = Ry(yaw)·Rx(pitch)`, is the unit vector `u = (−sin yaw, sin pitch·cos yaw,
/// cos pitch·cos yaw)`.
fn yaw_pitch_of(u: DVec3) -> (f64, f64) {
    let u = u.normalize();
    (
        (-u.x).clamp(-1.0, 1.0).asin().to_degrees(),
        u.y.atan2(u.z).to_degrees(),
    )
}

/// A turning page's writer: the CSS page or the canvas player.
type Writer =
    fn(&Presorted, &Geometry, &View, &TurnPageOptions) -> Result<TurnPage, CertifiedOrdersError>;

fn check(name: &str, g: &Geometry, base: View, random: usize) {
    check_page(write_turn_html, name, g, base, random, false);
}

/// [`check`] of the page `write` makes; `exact`: no frame may show a wrong pixel.
fn check_page(write: Writer, name: &str, g: &Geometry, base: View, random: usize, exact: bool) {
    let Some(browser) = chromium() else {
        return;
    };
    let sorter = Presorted::new(g);
    let eye = match base.projection() {
        sprite_compose::face_sort::Projection::Orthographic => None,
        sprite_compose::face_sort::Projection::Perspective { distance } => {
            Some(distance / base.scale())
        }
    };
    let certified = sorter.certified_orders(eye).expect("certified orders");
    let mut rng = test_support::Rng::new(0x7u64 << 40 | random as u64);
    let mut views: Vec<(f64, f64)> = (0..random)
        .map(|_| (360.0 * rng.unit() - 180.0, 180.0 * rng.unit() - 90.0))
        .collect();
    // Either side of the edge between a region and the next: the edge's middle, nudged by a
    // millionth of a radian along the edge's normal.
    for k in 0..2 {
        let r = &certified.regions[(k * 7 + 3) % certified.regions.len()];
        let [a, b, _] = r.corners;
        let middle = (a + b).normalize();
        let n = r.edge_normals[0].normalize();
        views.push(yaw_pitch_of(middle + n * 1e-6));
        views.push(yaw_pitch_of(middle - n * 1e-6));
    }
    for (k, &(yaw, pitch)) in views.iter().enumerate() {
        let page = write(
            &sorter,
            g,
            &base,
            &TurnPageOptions::DEFAULT
                .with_ids(true)
                // Through every earlier view: switching must leave nothing of their orders.
                .with_start_path(&views[..=k]),
        )
        .expect("a page");
        let rgba = screenshot_at(browser, &page.html, &format!("turn-{name}"), base.width());
        let shot = ids_of_rgba(base.width(), base.height(), &rgba);
        let t = truth(&base.with_yaw_pitch_roll(yaw, pitch, 0.0), g);
        let e = pixel_error(&shot, &t);
        print_wrong_pixels(&shot, &t, &rgba);
        println!(
            "turn page {name} at yaw {yaw:.6}° pitch {pitch:.6}° ({} regions, {} orders, {} cycles, {} elements, {} B): {}/{}",
            page.regions,
            page.orders,
            page.cycles,
            page.elements,
            page.html.len(),
            e.wrong,
            e.pixels
        );
        assert!(
            e.pixels > 1000,
            "{name} at {yaw}°, {pitch}°: too few pixels to judge"
        );
        assert!(e.error <= 2e-3, "{name} at {yaw}°, {pitch}°: {e:?}");
        if exact {
            assert_eq!(e.wrong, 0, "{name} at {yaw}°, {pitch}°");
        }
    }
}

#[test]
fn turning_pages_in_chromium_are_exact() {
    // The book: one order for every view. spot's control mesh: cycles ordered by the viewer's
    // side of their planes. Fandisk in perspective.
    let load =
        |path: &str| Geometry::with_exact_corners(&support::load_obj(path)).expect("a model");
    let book = load("combobulate-samples/book.obj");
    check(
        "book-ortho",
        &book,
        View::fit(&book.bounds(), SIZE, SIZE),
        3,
    );
    let spot = load("keenan-crane/spot/spot_control_mesh.obj");
    check(
        "spot-control-ortho",
        &spot,
        View::fit(&spot.bounds(), SIZE, SIZE),
        4,
    );
    let fandisk = load("fandisk-quads/fandisk_quads.converted.obj");
    let base = View::fit(&fandisk.bounds(), SIZE, SIZE).with_perspective(2.0 * f64::from(SIZE));
    check("fandisk-persp", &fandisk, base, 4);
    // suzanne: cycles whose planes are decided region by region.
    let suzanne = load("suzanne/suzanne.obj");
    let base = View::fit(&suzanne.bounds(), SIZE, SIZE).with_perspective(2.0 * f64::from(SIZE));
    check("suzanne-persp", &suzanne, base, 3);
}

/// The full spot (6,134 elements) at 512 × 512, orthographic and perspective.
#[test]
#[ignore = "the full spot: a minute in release; run with --release --ignored"]
fn the_full_spot_turning_page_in_chromium() {
    let spot = Geometry::with_exact_corners(&support::load_obj(
        "keenan-crane/spot/spot_quadrangulated.obj",
    ))
    .expect("a model");
    let base = View::fit(&spot.bounds(), 512, 512);
    check("spot-full-ortho", &spot, base, 4);
    check("spot-full-persp", &spot, base.with_perspective(1024.0), 4);
}

/// The canvas player of the same certificates (one `<canvas>`; the script projects, looks up
/// the region and each cycle's key, culls and fills; ID mode fills pixel centres itself):
/// exact at random views and either side of region edges, orthographic and perspective,
/// the full spot included.
#[test]
fn canvas_turning_pages_in_chromium_are_exact() {
    let load =
        |path: &str| Geometry::with_exact_corners(&support::load_obj(path)).expect("a model");
    let write: Writer = write_canvas_turn_html;
    let spot = load("keenan-crane/spot/spot_control_mesh.obj");
    let base = View::fit(&spot.bounds(), SIZE, SIZE);
    check_page(write, "canvas-spot-control-ortho", &spot, base, 4, true);
    let suzanne = load("suzanne/suzanne.obj");
    let base = View::fit(&suzanne.bounds(), SIZE, SIZE).with_perspective(2.0 * f64::from(SIZE));
    check_page(write, "canvas-suzanne-persp", &suzanne, base, 3, true);
    let full = load("keenan-crane/spot/spot_quadrangulated.obj");
    let base = View::fit(&full.bounds(), 512, 512);
    check_page(write, "canvas-spot-full-ortho", &full, base, 4, true);
    check_page(
        write,
        "canvas-spot-full-persp",
        &full,
        base.with_perspective(1024.0),
        4,
        true,
    );
}
