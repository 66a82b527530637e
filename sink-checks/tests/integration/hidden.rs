//! Hidden-part removal in SVG: fewer shapes, and the file rasterised independently (resvg) is
//! as exact as the painter's SVG at its own size and at 2× zoom.

use raster_sink::{pixel_error, truth};
use sprite_compose::face_sort::{CullMode, Geometry, SorterKind, View};
use sprite_compose::glam::DVec3;
use sprite_compose::{RecordingCompositor, SpritePainter};
use vector_sink::{HiddenParts, SvgOptions, write_svg};

use crate::support;
use crate::writers::{SIZE, ids_of_rgba};

/// Rasterises an SVG written at `SIZE` at `zoom` times its size (viewBox unchanged).
fn rasterise(svg: &str, zoom: u32) -> resvg::tiny_skia::Pixmap {
    let zoomed = svg.replacen(
        &format!("width=\"{SIZE}\" height=\"{SIZE}\""),
        &format!("width=\"{}\" height=\"{}\"", SIZE * zoom, SIZE * zoom),
        1,
    );
    let tree =
        resvg::usvg::Tree::from_str(&zoomed, &resvg::usvg::Options::default()).expect("valid SVG");
    let mut pixmap = resvg::tiny_skia::Pixmap::new(SIZE * zoom, SIZE * zoom).expect("pixmap");
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    pixmap
}

/// The same picture `zoom` times larger.
fn zoomed(view: &View, zoom: u32, perspective: Option<f64>) -> View {
    let z = f64::from(zoom);
    let mut v = view
        .with_size(view.width() * zoom, view.height() * zoom)
        .with_scale(view.scale() * z);
    if let Some(d) = perspective {
        v = v.with_perspective(d * z);
    }
    v
}

fn shapes(svg: &str) -> usize {
    svg.matches("<polygon").count() + svg.matches("<path").count()
}

/// Writes keep and remove SVGs (ID mode) of a scene and checks both against the truth at 1×
/// and 2×. Returns (shapes kept, shapes removed-version).
fn check(name: &str, geometry: &Geometry, view: View, perspective: Option<f64>) -> (usize, usize) {
    let mut painter = SpritePainter::new(
        geometry,
        SorterKind::Bsp.build(geometry),
        view,
        RecordingCompositor::new(),
    );
    painter.frame();
    let scene = painter.compositor().scene();
    let options = SvgOptions::DEFAULT
        .with_ids(true)
        .with_background(Some([0, 0, 0, 255]));
    let keep = write_svg(scene, &options);
    let remove = write_svg(scene, &options.clone().with_hidden(HiddenParts::Remove));
    for zoom in [1, 2] {
        let zview = zoomed(&view, zoom, perspective);
        let t = truth(&zview, geometry);
        for (mode, svg) in [("keep", &keep), ("remove", &remove)] {
            let pixmap = rasterise(svg, zoom);
            let ids = ids_of_rgba(SIZE * zoom, SIZE * zoom, pixmap.data());
            let e = pixel_error(&ids, &t);
            println!(
                "{name} {mode} {zoom}x: {} shapes, {} bytes, {}/{} wrong",
                shapes(svg),
                svg.len(),
                e.wrong,
                e.pixels
            );
            assert_eq!(e.wrong, 0, "{name} {mode} at {zoom}x: {e:?}");
        }
    }
    (shapes(&keep), shapes(&remove))
}

#[test]
fn removing_hidden_parts_keeps_the_picture_exact_at_any_zoom() {
    // Spot with no culling: the back of the cow is drawn first and then covered.
    let spot = support::geometry(&support::load_obj(
        "keenan-crane/spot/spot_control_mesh.obj",
    ));
    let view = View::fit(&spot.bounds(), SIZE, SIZE)
        .with_yaw_pitch_roll(35.0, 20.0, 0.0)
        .with_cull(CullMode::None);
    let (keep, remove) = check("spot, no culling", &spot, view, None);
    assert!(
        remove * 10 <= keep * 6,
        "heavy occlusion: {remove} shapes of {keep}"
    );

    // A row of boxes seen along the row, in perspective: the first hides the rest.
    let row: Vec<(DVec3, DVec3)> = (0..6)
        .map(|k| {
            let z = -2.0 * f64::from(k);
            (DVec3::new(-0.5, -0.5, z - 1.0), DVec3::new(0.5, 0.5, z))
        })
        .collect();
    let boxes = support::geometry(&support::boxes(&row));
    let d = f64::from(SIZE) * 1.5;
    let view = View::fit(&boxes.bounds(), SIZE, SIZE).with_perspective(d);
    let (keep, remove) = check("row of boxes", &boxes, view, Some(d));
    assert_eq!(
        (keep, remove),
        (6, 1),
        "front faces of six boxes, of which one is seen"
    );
}
