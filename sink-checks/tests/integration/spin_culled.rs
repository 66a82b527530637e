//! The spinning page of a picture bake (back faces culled by the browser) in headless
//! Chromium, paused at random times and a millisecond either side of every breakpoint, compared with
//! raster-sink's truth at the same angle. The full spot's page must show no wrong pixel,
//! through Chromium's software compositor and through GPU compositing (SwiftShader). Spot's
//! control mesh, with large faces, is held to the bar of the other Chromium page tests
//! through the software compositor (at most 0.2 % wrong unambiguous pixels; every frame's
//! count is printed): single pixels one ID step off just outside an anti-aliased join
//! (docs/CHROMIUM.md).

use raster_sink::{PixelError, pixel_error, truth};
use sprite_compose::aspect_bake::{Axis, Bake, PictureOptions, Spin, bake_picture, drawn_lists};
use sprite_compose::face_sort::{Geometry, View};
use vector_sink::{SpinOptions, write_canvas_spin_html, write_culled_spin_html};

use test_support::consumers::Compositor;

use crate::browser::{chromium, print_wrong_pixels, screenshot_with};
use crate::support;
use crate::writers::{SIZE, ids_of_rgba};

const PERIOD_S: f64 = 8.0;

/// A page writer of a picture bake: the culled CSS page or the canvas player.
type Writer = fn(&Bake, &[Vec<u32>], &Spin, &Geometry, &SpinOptions) -> String;

/// Shows the page at `random` times and either side of every breakpoint through each of
/// `compositors`; `exact`: every frame must show no wrong pixel, else at most 0.2 %.
fn check(
    name: &str,
    g: &Geometry,
    view: View,
    random: usize,
    compositors: &[Compositor],
    exact: bool,
) {
    check_page(
        write_culled_spin_html,
        name,
        g,
        view,
        random,
        compositors,
        exact,
    );
}

/// [`check`] of the page `write` makes.
fn check_page(
    write: Writer,
    name: &str,
    g: &Geometry,
    view: View,
    random: usize,
    compositors: &[Compositor],
    exact: bool,
) {
    let size = view.width();
    let Some(browser) = chromium() else {
        return;
    };
    let axis = Axis::Yaw {
        pitch: 20.0,
        roll: 0.0,
    };
    let spin = Spin::new(view, axis).expect("a named axis");
    let (baked, _) = bake_picture(g, &spin, &PictureOptions::DEFAULT).expect("a bake");
    let lists = drawn_lists(&baked, &spin).expect("a culling view");
    // Seconds into the turn: random ones, and 1 ms either side of each breakpoint.
    let mut rng = test_support::Rng::new(0x5EED);
    let mut times: Vec<f64> = (0..random).map(|_| PERIOD_S * rng.unit()).collect();
    for b in baked.breakpoints() {
        let t = (b.degrees - baked.domain().lo).rem_euclid(360.0) / 360.0 * PERIOD_S;
        times.extend([t - 1e-3, t + 1e-3]);
    }
    for t in times {
        let t = t.rem_euclid(PERIOD_S);
        let page = write(
            &baked,
            &lists,
            &spin,
            g,
            &SpinOptions::DEFAULT
                .with_period(PERIOD_S)
                .with_ids(true)
                .with_paused_at(Some(t)),
        );
        let degrees = baked.domain().lo + 360.0 * t / PERIOD_S;
        let t_img = truth(&spin.view_at(degrees), g);
        for &compositor in compositors {
            let show = || {
                let rgba = screenshot_with(
                    browser,
                    &page,
                    &format!("spin-culled-{name}-{t}"),
                    size,
                    compositor,
                );
                let e = pixel_error(&ids_of_rgba(size, size, &rgba), &t_img);
                (rgba, e)
            };
            let fails = |e: &PixelError| e.error > 2e-3 || (exact && e.wrong > 0);
            let (mut rgba, mut e) = show();
            if fails(&e) {
                // Shown again: a second screenshot of the same page that differs from the
                // first is Chromium's flake (docs/CHROMIUM.md), and the second is judged; an
                // identical one stands.
                let (again, e_again) = show();
                if again != rgba {
                    println!(
                        "notice: {name} at {t:.4} s through {compositor:?}: {} wrong, then {} in a second screenshot of the same page, which is judged",
                        e.wrong, e_again.wrong
                    );
                    (rgba, e) = (again, e_again);
                }
            }
            let shot = ids_of_rgba(size, size, &rgba);
            print_wrong_pixels(&shot, &t_img, &rgba);
            println!(
                "culled spin {name} at {t:.4} s = {degrees:.3}° ({} cells, page {} B), {compositor:?}: {}/{}",
                baked.cells().len(),
                page.len(),
                e.wrong,
                e.pixels
            );
            assert!(
                e.pixels > 1000,
                "{name} at {degrees}°: too few pixels to judge"
            );
            assert!(e.error <= 2e-3, "{name} at {degrees}°: {e:?}");
            if exact {
                assert_eq!(e.wrong, 0, "{name} at {degrees}° through {compositor:?}");
            }
        }
    }
}

/// The spinning pages `write` makes of spot's control mesh (fan triangles of non-planar
/// quads) and the book (planar quads, doubled covers), orthographic and perspective, through
/// the software compositor; `exact` as in [`check_page`].
fn small_models(write: Writer, prefix: &str, exact: bool) {
    for (name, path) in [
        ("spot", "keenan-crane/spot/spot_control_mesh.obj"),
        ("book", "combobulate-samples/book.obj"),
    ] {
        let mesh = support::load_obj(path);
        let g = Geometry::with_exact_corners(&mesh).expect("a model");
        let base = View::fit(&g.bounds(), SIZE, SIZE);
        let software = [Compositor::Software];
        let persp = base.with_perspective(f64::from(SIZE));
        check_page(
            write,
            &format!("{prefix}{name}-ortho"),
            &g,
            base,
            2,
            &software,
            exact,
        );
        check_page(
            write,
            &format!("{prefix}{name}-persp"),
            &g,
            persp,
            2,
            &software,
            exact,
        );
    }
}

#[test]
fn culled_spinning_pages_in_chromium_are_exact() {
    small_models(write_culled_spin_html, "", false);
}

/// The full spot (5,856 pieces, a 1.3 MB page) at 512 × 512, orthographic and perspective:
/// 22 frames, each through both compositors, none of which may show a wrong pixel.
/// Before the screenshots waited for every compositor stage, a frame now and then missed a
/// whole element (background where a piece is: 49 and 100 wrong pixels in two runs). Before
/// border triangles chose their shape, the software compositor showed one stray pixel beyond
/// a nearly edge-on triangle (docs/CHROMIUM.md).
#[test]
#[ignore = "the full spot page: three minutes in release; run with --release --ignored"]
fn the_full_spot_culled_page_in_chromium() {
    let mesh = support::load_obj("keenan-crane/spot/spot_quadrangulated.obj");
    let g = Geometry::with_exact_corners(&mesh).expect("a model");
    let base = View::fit(&g.bounds(), 512, 512);
    let both = [Compositor::Software, Compositor::SwiftShader];
    check("spot-full-ortho", &g, base, 3, &both, true);
    check(
        "spot-full-persp",
        &g,
        base.with_perspective(1024.0),
        3,
        &both,
        true,
    );
}

/// The canvas player of the same bakes, at random times and a millisecond either side of
/// every breakpoint: exact (no wrong unambiguous pixel; the CSS page is held to 0.2 % on
/// these models). In ID mode the player fills pixel centres itself, without the canvas's
/// anti-aliasing.
#[test]
fn canvas_spinning_pages_in_chromium_are_exact() {
    small_models(write_canvas_spin_html, "canvas-", true);
}

/// The full spot's canvas page (the page the CSS one is in
/// [`the_full_spot_culled_page_in_chromium`]) at 512 × 512, orthographic and perspective:
/// 3 random times and a millisecond either side of each breakpoint, through both compositors, no
/// wrong pixel.
#[test]
fn the_full_spot_canvas_page_in_chromium() {
    let mesh = support::load_obj("keenan-crane/spot/spot_quadrangulated.obj");
    let g = Geometry::with_exact_corners(&mesh).expect("a model");
    let base = View::fit(&g.bounds(), 512, 512);
    let both = [Compositor::Software, Compositor::SwiftShader];
    let write: Writer = write_canvas_spin_html;
    check_page(write, "canvas-spot-full-ortho", &g, base, 3, &both, true);
    check_page(
        write,
        "canvas-spot-full-persp",
        &g,
        base.with_perspective(1024.0),
        3,
        &both,
        true,
    );
}
