//! Lines and points among faces, in PNG (raster-sink), SVG (resvg) and PDF (poppler),
//! against an independent expectation: the faces from raster-sink's z-buffer truth, each
//! line and point seen or hidden by casting a ray from the viewer (the plot tests' brute
//! force). Faces in ID colours, lines red, points blue, no anti-aliasing.

use raster_sink::{
    OverlayTruth, RasterOptions, Seen, Style, Truth, draw_overlay, render_colour, truth,
};
use sprite_compose::face_sort::colours::id_colour;
use sprite_compose::face_sort::glam::{DVec2, DVec3};
use sprite_compose::face_sort::{CullMode, DrawList, Geometry, PolygonMesh, SorterKind, View};
use sprite_compose::{
    DrawnOverlay, Line, Overlay, RecordingCompositor, SpritePainter, visible_overlay,
};
use vector_sink::{HtmlOptions, PdfOptions, SvgOptions, write_html, write_pdf, write_svg};

const SIZE: u32 = 200;
const RED: [u8; 4] = [255, 0, 0, 255];
const BLUE: [u8; 4] = [0, 0, 255, 255];
const BACKGROUND: [u8; 4] = [0, 0, 0, 255];
const LINE_PX: f64 = 3.0;
const DOT_PX: f64 = 3.0;
/// Pixels whose centre is within this of a stroke's or disc's outline are not judged.
const MARGIN_PX: f64 = 0.75;

/// Boxes passing through each other on a ground plate, their wireframe and vertices, grid
/// lines on the plate, and three long lines through the whole scene (the axes), some parts
/// behind faces, some in front. The plate is twisted by 1e-7 of its size (planar within
/// CONVENTIONS.md's tolerance, so the geometry snaps it onto its plane): its grid lines,
/// interpolated between the file's corners, lie up to that far off the plane the pieces use,
/// and only naming the plate in `Line::faces` keeps them from a z-fight with it.
fn scene() -> (PolygonMesh, Overlay) {
    let v = DVec3::new;
    let boxes = test_support::models::boxes(&[
        (v(-1.0, -1.0, -1.0), v(1.0, 1.0, 1.0)),
        (v(0.2, -0.4, -0.4), v(1.6, 0.3, 0.5)),
        (v(-0.8, 1.0, -0.6), v(-0.1, 1.5, 0.2)),
    ]);
    let twist = 4.0 * 1e-7;
    let plate = [
        v(-2.0, -1.2, 2.0),
        v(2.0, -1.2, 2.0),
        v(2.0, -1.2 + twist, -2.0),
        v(-2.0, -1.2, -2.0),
    ];
    let mut positions = boxes.positions().to_vec();
    let mut faces: Vec<Vec<u32>> = boxes.faces().map(<[u32]>::to_vec).collect();
    let first = positions.len() as u32;
    positions.extend(plate);
    faces.push((first..first + 4).collect());
    let plate_face = (faces.len() - 1) as u32;
    let mesh = PolygonMesh::new(positions, faces).expect("scene");
    let bilinear = |u: f64, w: f64| {
        let near = plate[0].lerp(plate[1], u);
        let far = plate[3].lerp(plate[2], u);
        near.lerp(far, w)
    };
    let mut grid: Vec<Line> = (1..8)
        .flat_map(|k| {
            let f = f64::from(k) / 8.0;
            [
                [bilinear(0.0, f), bilinear(1.0, f)],
                [bilinear(f, 0.0), bilinear(f, 1.0)],
            ]
        })
        .map(|ends| Line {
            ends,
            colour: RED,
            width_px: LINE_PX,
            faces: vec![plate_face],
        })
        .collect();
    let axes = [
        [v(-2.0, 0.1, 0.2), v(2.2, 0.1, 0.2)],
        [v(0.3, -2.0, -0.1), v(0.3, 2.0, -0.1)],
        [v(-0.6, 0.5, -2.0), v(-0.6, 0.5, 2.0)],
    ];
    grid.extend(axes.into_iter().map(|ends| Line {
        ends,
        colour: RED,
        width_px: LINE_PX,
        faces: Vec::new(),
    }));
    let overlay = Overlay::wireframe(&mesh, RED, LINE_PX)
        .with(Overlay::vertices(&mesh, BLUE, DOT_PX))
        .with(Overlay {
            lines: grid,
            points: Vec::new(),
        });
    (mesh, overlay)
}

fn views(geometry: &Geometry) -> Vec<View> {
    let base = View::fit(&geometry.bounds(), SIZE, SIZE);
    let ld = base.diagonal() * base.scale();
    vec![
        base.with_yaw_pitch_roll(30.0, 20.0, 0.0),
        base.with_yaw_pitch_roll(200.0, -35.0, 10.0)
            .with_cull(CullMode::None),
        base.with_yaw_pitch_roll(120.0, 25.0, 0.0)
            .with_perspective(1.6 * ld),
    ]
}

/// One view's references: what a viewer sees of lines and points (raster-sink's
/// `OverlayTruth`), the faces' truth, and the writer's picture without the overlay.
struct Judge<'a> {
    view: &'a View,
    geometry: &'a Geometry,
    seen: &'a OverlayTruth,
    overlay: &'a Overlay,
    truth: &'a Truth,
    faces: &'a [u8],
}

/// What a pixel centre must show, or `None` where it cannot be judged.
fn expected(judge: &Judge<'_>, c: DVec2, index: usize) -> Option<[u8; 4]> {
    let Judge {
        view,
        geometry,
        seen: sight,
        overlay,
        truth,
        faces,
    } = *judge;
    let centre = geometry.bounds().centre();
    let project = |p: DVec3| view.project_view_point(view.to_view(p - centre));
    // Points, drawn last.
    for point in &overlay.points {
        let p = project(point.at)?;
        let d = p.distance(c);
        if d >= point.radius_px + MARGIN_PX {
            continue;
        }
        match sight.seen(point.at) {
            Seen::Hidden => {}
            Seen::Visible if d <= point.radius_px - MARGIN_PX => return Some(point.colour),
            _ => return None,
        }
    }
    // Lines: the point of the line nearest the pixel centre on screen.
    let mut line_colour = None;
    for line in &overlay.lines {
        let (a, b) = (project(line.ends[0])?, project(line.ends[1])?);
        let ab = b - a;
        let s = ((c - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
        let d = (a + ab * s).distance(c);
        if d >= line.width_px / 2.0 + MARGIN_PX {
            continue;
        }
        // Near an end (butt caps), or on screen so close to one that the perspective map
        // of `s` matters: not judged.
        if (s * ab.length()).min((1.0 - s) * ab.length()) < MARGIN_PX {
            return None;
        }
        // The 3D point that projects to screen parameter `s` (perspective: solve in
        // homogeneous coordinates along the line), seen or hidden. Judged at 1 px: the
        // verdict must be the same 1 px before and after along the line (a line passing
        // through a face changes from seen to hidden where it crosses the plane, with no
        // outline nearby).
        let (pa, pb) = (line.ends[0] - centre, line.ends[1] - centre);
        let (wa, wb) = (
            view.w_of_view_point(view.to_view(pa)),
            view.w_of_view_point(view.to_view(pb)),
        );
        let seen = |s: f64| {
            let t = s * wa / (s * wa + (1.0 - s) * wb);
            sight.seen(pa.lerp(pb, t) + centre)
        };
        let step = 1.0 / ab.length();
        let verdict = seen(s);
        if seen(s - step) != verdict || seen(s + step) != verdict {
            return None;
        }
        match verdict {
            Seen::Hidden => {}
            Seen::Visible if d <= line.width_px / 2.0 - MARGIN_PX => {
                line_colour = Some(line.colour);
            }
            _ => return None,
        }
    }
    if line_colour.is_some() {
        return line_colour;
    }
    // No line or point here: the faces as the writer paints them without the overlay (their
    // exactness against the truth is the other tests' subject), where the truth is clear.
    truth.unambiguous[index].then(|| {
        let f = &faces[index * 4..index * 4 + 4];
        [f[0], f[1], f[2], f[3]]
    })
}

/// Compares an RGBA picture with the expectation: (judged, of which line or point, wrong).
/// `faces` is the same writer's picture without the overlay.
fn compare(
    rgba: &[u8],
    faces: &[u8],
    view: &View,
    geometry: &Geometry,
    overlay: &Overlay,
    truth: &Truth,
) -> (usize, usize, usize, Vec<String>) {
    let sight = OverlayTruth::new(view, geometry);
    let judge = Judge {
        view,
        geometry,
        seen: &sight,
        overlay,
        truth,
        faces,
    };
    let (mut judged, mut marks, mut wrong) = (0, 0, 0);
    let mut examples = Vec::new();
    for y in 0..SIZE {
        for x in 0..SIZE {
            let index = (y * SIZE + x) as usize;
            let c = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
            let Some(want) = expected(&judge, c, index) else {
                continue;
            };
            judged += 1;
            marks += usize::from(want == RED || want == BLUE);
            let got = &rgba[index * 4..index * 4 + 4];
            if got != want {
                wrong += 1;
                if examples.len() < 8 {
                    examples.push(format!("({x}, {y}): want {want:?}, got {got:?}"));
                }
            }
        }
    }
    (judged, marks, wrong, examples)
}

/// The BSP's draw list and sprite scene of a view, faces in ID colours.
fn painted(geometry: &Geometry, view: View) -> (DrawList, sprite_compose::Scene) {
    let mut painter = SpritePainter::new(
        geometry,
        SorterKind::Bsp.build(geometry),
        view,
        RecordingCompositor::new(),
    );
    painter.frame();
    (
        painter.draw_list().clone(),
        painter.compositor().scene().clone(),
    )
}

/// `rgba_of(geometry, view, overlay)`: the writer's picture, with the overlay or without.
fn check_all(name: &str, rgba_of: impl Fn(&Geometry, View, Option<&DrawnOverlay>) -> Vec<u8>) {
    let (mesh, overlay) = scene();
    let geometry = Geometry::new(&mesh).unwrap();
    let (mut judged, mut marks, mut wrong) = (0, 0, 0);
    let mut examples = Vec::new();
    for (k, view) in views(&geometry).into_iter().enumerate() {
        let drawn = visible_overlay(&geometry, &view, &overlay);
        let rgba = rgba_of(&geometry, view, Some(&drawn));
        let faces = rgba_of(&geometry, view, None);
        let t = truth(&view, &geometry);
        let (j, m, w, e) = compare(&rgba, &faces, &view, &geometry, &overlay, &t);
        judged += j;
        marks += m;
        wrong += w;
        examples.extend(e.into_iter().map(|e| format!("view {k}: {e}")));
    }
    println!("{name}: {judged} pixels judged, {marks} of them on a line or point, {wrong} wrong");
    assert_eq!(wrong, 0, "{name}: {examples:#?}");
    assert!(judged > 10_000 && marks > 2_000, "{judged} {marks}");
}

fn id_style(geometry: &Geometry) -> Style {
    let mut style = Style::solid([0, 0, 0, 0]);
    for face in 0..geometry.face_count() as u32 {
        style.set_face(face, raster_sink::Brush::Solid(id_colour(face)));
    }
    style
}

#[test]
fn lines_and_points_are_exact_in_png() {
    check_all("png", |geometry, view, drawn| {
        let (list, _) = painted(geometry, view);
        let mut pixmap = render_colour(
            &view,
            &list,
            &id_style(geometry),
            &RasterOptions::DEFAULT
                .with_anti_alias(false)
                .with_background(BACKGROUND),
        )
        .unwrap();
        if let Some(drawn) = drawn {
            draw_overlay(&mut pixmap, drawn, false);
        }
        pixmap.data().to_vec()
    });
}

#[test]
fn lines_and_points_are_exact_in_svg() {
    check_all("svg", |geometry, view, drawn| {
        let (_, scene) = painted(geometry, view);
        let overlay = drawn.map_or_else(String::new, |d| {
            vector_sink::overlay_svg(d).replacen("<g ", "<g shape-rendering=\"crispEdges\" ", 1)
        });
        let svg = write_svg(
            &scene,
            &SvgOptions::DEFAULT
                .with_size(SIZE, SIZE)
                .with_ids(true)
                .with_background(Some(BACKGROUND))
                .with_overlay(overlay),
        );
        let tree = resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).unwrap();
        let mut pixmap = resvg::tiny_skia::Pixmap::new(SIZE, SIZE).unwrap();
        resvg::render(
            &tree,
            resvg::tiny_skia::Transform::default(),
            &mut pixmap.as_mut(),
        );
        pixmap.data().to_vec()
    });
}

#[test]
fn lines_and_points_are_exact_in_html() {
    let Some(browser) = crate::browser::chromium() else {
        return;
    };
    check_all("html", |geometry, view, drawn| {
        let (_, scene) = painted(geometry, view);
        // The SVG writer's overlay markup, with the same crisp edges as its test.
        let overlay = drawn.map_or_else(String::new, |d| {
            vector_sink::overlay_svg(d).replacen("<g ", "<g shape-rendering=\"crispEdges\" ", 1)
        });
        let html = write_html(
            &scene,
            &HtmlOptions::DEFAULT
                .with_size(SIZE, SIZE)
                .with_ids(true)
                .with_background(Some(BACKGROUND))
                .with_overlay(overlay),
        );
        crate::browser::screenshot_at(browser, &html, "overlay", SIZE)
    });
}

#[test]
fn lines_and_points_are_exact_in_pdf() {
    if !crate::pdf::pdftoppm_available() {
        return;
    }
    check_all("pdf", |geometry, view, drawn| {
        let (_, scene) = painted(geometry, view);
        let mut options = PdfOptions::DEFAULT
            .with_size(SIZE, SIZE)
            .with_ids(true)
            .with_background(Some(BACKGROUND));
        if let Some(drawn) = drawn {
            options = options.with_overlay(drawn.clone());
        }
        let pdf = write_pdf(&scene, &options);
        // 5× and the centre of each 5 × 5 block (see the PDF tests: poppler without
        // anti-aliasing paints every pixel a shape touches).
        let zoom = crate::pdf::ZOOM;
        let big = crate::pdf::rasterise(&pdf, "overlay", zoom);
        let mut rgba = Vec::with_capacity((SIZE * SIZE * 4) as usize);
        for y in 0..SIZE {
            for x in 0..SIZE {
                let (bx, by) = (x * zoom + zoom / 2, y * zoom + zoom / 2);
                let i = ((by * big.width() + bx) * 4) as usize;
                rgba.extend_from_slice(&big.data()[i..i + 4]);
            }
        }
        rgba
    });
}

/// Cases per property: 24, or `PROPTEST_CASES`.
fn proptest_config() -> proptest::test_runner::Config {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(24);
    proptest::test_runner::Config::with_cases(cases)
}

proptest::proptest! {
    #![proptest_config(proptest_config())]

    /// Random scenes (non-intersecting, interpenetrating, cyclic; tiny and huge scales) and
    /// views, and random lines through their bounds: every point of a line that the truth
    /// for lines (raster-sink's ray-cast `OverlayTruth`, judged at 1 px) sees is drawn, and
    /// none it finds hidden.
    #[test]
    fn a_lines_visible_parts_are_what_the_rays_see(
        scene in sprite_compose::face_sort::strategies::any_scene(),
        spec in sprite_compose::face_sort::strategies::view_spec(),
        fractions in proptest::collection::vec(proptest::array::uniform6(0.0..1.0f64), 1..4),
    ) {
        let Ok(geometry) = Geometry::new(&scene) else { return Ok(()); };
        let view = spec.view(&geometry);
        let bounds = geometry.bounds();
        let at = |f: &[f64]| bounds.min + (bounds.max - bounds.min) * DVec3::new(f[0], f[1], f[2]);
        let overlay = Overlay {
            lines: fractions
                .iter()
                .map(|f| Line { ends: [at(&f[..3]), at(&f[3..])], colour: RED, width_px: 1.0, faces: Vec::new() })
                .collect(),
            points: Vec::new(),
        };
        let drawn = visible_overlay(&geometry, &view, &overlay);
        let error = OverlayTruth::new(&view, &geometry).compare(&overlay, &drawn);
        proptest::prop_assert_eq!(error.wrong, 0, "{:?}", error.examples);
    }
}
