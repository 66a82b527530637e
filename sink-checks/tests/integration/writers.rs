//! SVG through resvg and picking, compared with raster-sink at the same view.

use raster_sink::{IdImage, Truth, pixel_error, render_ids, truth};
use sprite_compose::face_sort::colours::{golden_angle_colour, id_colour};
use sprite_compose::face_sort::{Geometry, SorterKind, View};
use sprite_compose::glam::DVec2;
use sprite_compose::{Brush, RecordingCompositor, SpritePainter};
use vector_sink::{SvgOptions, outline_svg_path, write_svg};

use crate::support::{self, Rng};

pub const SIZE: u32 = 256;

/// A painter on spot's control mesh (non-planar quads: fan triangles with clips) at a view.
pub fn spot_painter(
    kind: SorterKind,
    yaw: f64,
    perspective: bool,
) -> (Geometry, SpritePainter<RecordingCompositor>) {
    let g = support::geometry(&support::load_obj(
        "keenan-crane/spot/spot_control_mesh.obj",
    ));
    let mut view = View::fit(&g.bounds(), SIZE, SIZE).with_yaw_pitch_roll(yaw, 20.0, 0.0);
    if perspective {
        view = view.with_perspective(f64::from(SIZE));
    }
    let mut p = SpritePainter::new(&g, kind.build(&g), view, RecordingCompositor::new());
    p.frame();
    (g, p)
}

/// Decodes an RGBA image (opaque) into face IDs (CONVENTIONS.md colours).
pub fn ids_of_rgba(width: u32, height: u32, rgba: &[u8]) -> IdImage {
    let ids = rgba
        .chunks_exact(4)
        .map(|p| (u32::from(p[0]) << 16) | (u32::from(p[1]) << 8) | u32::from(p[2]))
        .collect();
    IdImage { width, height, ids }
}

fn rasterise_svg(svg: &str) -> resvg::tiny_skia::Pixmap {
    let tree =
        resvg::usvg::Tree::from_str(svg, &resvg::usvg::Options::default()).expect("valid SVG");
    let size = tree.size();
    let mut pixmap =
        resvg::tiny_skia::Pixmap::new(size.width() as u32, size.height() as u32).expect("pixmap");
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    pixmap
}

/// Pixels whose ID differs, over all pixels at least 0.75 px from every edge
/// (the truth's unambiguous pixels, plus uncovered ones deep in the background).
pub fn differing(a: &IdImage, b: &IdImage, t: &Truth) -> (usize, usize) {
    let (mut n, mut wrong) = (0, 0);
    for k in 0..t.ids.len() {
        if t.unambiguous[k] {
            n += 1;
            wrong += usize::from(a.ids[k] != b.ids[k]);
        }
    }
    (wrong, n)
}

#[test]
fn svg_ids_through_resvg_match_raster_sink() {
    for (kind, perspective) in [
        (SorterKind::Newell, false),
        (SorterKind::Newell, true),
        (SorterKind::Centroid, true),
    ] {
        let (g, p) = spot_painter(kind, 35.0, perspective);
        let svg = write_svg(
            p.compositor().scene(),
            &SvgOptions::DEFAULT
                .with_ids(true)
                .with_background(Some([0, 0, 0, 255])),
        );
        let pixmap = rasterise_svg(&svg);
        let svg_ids = ids_of_rgba(SIZE, SIZE, pixmap.data());
        let ours = render_ids(p.view(), p.draw_list());
        let t = truth(p.view(), &g);
        let (wrong, n) = differing(&svg_ids, &ours, &t);
        // resvg's crispEdges fill samples pixel centres like raster-sink's ID fill: on the
        // unambiguous pixels (0.75 px from every edge) the two images agree exactly.
        assert!(n > 5_000, "the comparison covers pixels: {n}");
        assert_eq!(
            wrong,
            0,
            "{} persp={perspective}: {wrong} of {n} unambiguous pixels differ from raster-sink's ID image",
            kind.name()
        );
        let e = pixel_error(&svg_ids, &t);
        println!(
            "svg ids {} persp={perspective}: vs render_ids {wrong}/{n}; vs truth {}/{} = {:.4} %",
            kind.name(),
            e.wrong,
            e.pixels,
            e.error * 100.0
        );
        if kind == SorterKind::Newell {
            assert_eq!(e.wrong, 0, "exact sorter through SVG: {e:?}");
        }
    }
}

#[test]
fn svg_colours_through_resvg_match_the_palette_image() {
    // Anti-aliased colour: compare with raster-sink's ID image coloured by the same palette.
    // Rule: at most 1 % of the pixels at least 0.75 px from every edge may differ by more than
    // 8 (of 255) in any channel.
    let (g, mut p) = spot_painter(SorterKind::Newell, -50.0, true);
    p.set_brushes(|f| {
        if f % 7 == 0 {
            Brush::Solid([250, 40, 30, 255])
        } else {
            Brush::Palette
        }
    });
    p.frame();
    // A measurement of where colours lie: without the seam stroke, which moves every
    // boundary outward by half a pixel.
    let svg = write_svg(
        p.compositor().scene(),
        &SvgOptions::DEFAULT
            .with_background(Some([255, 255, 255, 255]))
            .with_seam_stroke(0.0),
    );
    let pixmap = rasterise_svg(&svg);
    let ids = render_ids(p.view(), p.draw_list());
    let t = truth(p.view(), &g);
    let (mut n, mut bad) = (0, 0);
    for k in 0..ids.ids.len() {
        if !t.unambiguous[k] {
            continue;
        }
        n += 1;
        let want = match ids.ids[k] {
            0 => [255, 255, 255, 255],
            id if (id - 1) % 7 == 0 => [250, 40, 30, 255],
            id => golden_angle_colour(id - 1),
        };
        let got = &pixmap.data()[4 * k..4 * k + 4];
        if (0..3).any(|c| got[c].abs_diff(want[c]) > 8) {
            bad += 1;
        }
    }
    println!("svg colour: {bad} of {n} pixels differ by more than 8");
    assert!(bad * 100 <= n, "{bad} of {n}");
}

#[test]
fn picking_agrees_with_the_id_image() {
    let mut rng = Rng::new(2024);
    for (kind, yaw, perspective) in [
        (SorterKind::Newell, 10.0, false),
        (SorterKind::Centroid, 130.0, true),
        (SorterKind::Bsp, 250.0, true),
    ] {
        let (g, p) = spot_painter(kind, yaw, perspective);
        let ids = render_ids(p.view(), p.draw_list());
        let t = truth(p.view(), &g);
        let frame = p.projected_frame();
        let mut checked = 0;
        while checked < 500 {
            let x = (rng.next_u64() % u64::from(SIZE)) as u32;
            let y = (rng.next_u64() % u64::from(SIZE)) as u32;
            let k = (y * SIZE + x) as usize;
            if !t.unambiguous[k] && t.ids[k] != 0 {
                continue; // near an edge
            }
            checked += 1;
            let picked = frame
                .pick(DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5))
                .map_or(0, |item| item.face + 1);
            assert_eq!(picked, ids.ids[k], "{} at ({x}, {y})", kind.name());
            assert_eq!(
                p.pick(f64::from(x) + 0.5, f64::from(y) + 0.5)
                    .map_or(0, |i| i.face + 1),
                picked
            );
        }
    }
}

#[test]
fn selection_outline_surrounds_the_visible_part() {
    let (_, p) = spot_painter(SorterKind::Newell, 35.0, false);
    let frame = p.projected_frame();
    let centre = DVec2::splat(f64::from(SIZE) * 0.5);
    let face = frame.pick(centre).expect("spot covers the centre").face;
    let outline = frame.selection_outline(|f| f == face);
    assert!(outline.len() >= 3, "{outline:?}");
    // Every outline segment separates the selected face from something else.
    for [a, b] in &outline {
        let m = (*a + *b) * 0.5;
        let n = (*b - *a).perp().normalize() * 0.01;
        let sides =
            [frame.pick(m + n), frame.pick(m - n)].map(|i| i.is_some_and(|i| i.face == face));
        assert_ne!(sides[0], sides[1]);
    }
    let overlay = outline_svg_path(&outline, [255, 255, 0, 255], 2.0);
    let svg = write_svg(
        p.compositor().scene(),
        &SvgOptions::DEFAULT.with_overlay(overlay),
    );
    let _ = rasterise_svg(&svg);
    let _ = id_colour(face);
}

/// Spot's painter (Centroid order) with every sprite under texture 0 by the identity map.
fn textured_spot_painter() -> SpritePainter<RecordingCompositor> {
    let (_, mut p) = spot_painter(SorterKind::Centroid, 0.0, false);
    let texture = Brush::Texture {
        texture: sprite_compose::TextureId(0),
        uv: sprite_compose::glam::DAffine2::IDENTITY,
        fallback: [10, 20, 30, 255],
    };
    p.set_brushes(|_| texture);
    p.frame();
    p
}

#[test]
fn textured_sprites_become_clipped_images() {
    let p = textured_spot_painter();
    let png = "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg==";
    let svg = write_svg(
        p.compositor().scene(),
        &SvgOptions::DEFAULT.with_textures(vec![png.to_owned()]),
    );
    // The image once, in <defs>; one <use> of it per sprite.
    assert_eq!(svg.matches("<image").count(), 1);
    assert_eq!(svg.matches("data:image/png").count(), 1);
    assert_eq!(svg.matches("<use").count(), p.draw_list().len());
    assert_eq!(svg.matches("<clipPath").count(), p.draw_list().len());
    let _ = rasterise_svg(&svg);
}

/// Pixels deep inside the silhouette (5×5 neighbourhood covered in the truth) whose colour
/// shows background tint: any channel more than 10 above the mesh colour's (8-bit
/// premultiplied blending of a colour over itself drifts by a few units; a hairline of white
/// background shows as 40 and more).
fn tinted_inside(svg: &str, t: &Truth, colour: [u8; 4]) -> usize {
    let pixmap = rasterise_svg(svg);
    let (w, h) = (t.width as usize, t.height as usize);
    let mut tinted = 0;
    for y in 2..h - 2 {
        for x in 2..w - 2 {
            let inside =
                (0..5).all(|dy| (0..5).all(|dx| t.ids[(y + dy - 2) * w + x + dx - 2] != 0));
            if !inside {
                continue;
            }
            let px = &pixmap.data()[4 * (y * w + x)..4 * (y * w + x) + 4];
            if (0..3).any(|c| px[c] > colour[c].saturating_add(10)) {
                tinted += 1;
            }
        }
    }
    tinted
}

#[test]
fn svg_seam_stroke_hides_conflation_hairlines() {
    // A closed mesh in one dark colour on white: anti-aliased neighbours let the background
    // through along shared edges unless each polygon is stroked in its own colour.
    let g = support::geometry(&test_support::models::uv_sphere(24, 12));
    let view = View::fit(&g.bounds(), SIZE, SIZE).with_yaw_pitch_roll(30.0, 20.0, 0.0);
    let mut p = SpritePainter::new(
        &g,
        SorterKind::Bsp.build(&g),
        view,
        RecordingCompositor::new(),
    );
    let colour = [40, 60, 90, 255];
    p.set_brushes(|_| Brush::Solid(colour));
    p.frame();
    let t = truth(p.view(), &g);
    // The default strokes; without it, seams show.
    let stroked = SvgOptions::DEFAULT.with_background(Some([255, 255, 255, 255]));
    let options = stroked.clone().with_seam_stroke(0.0);
    let with = tinted_inside(&write_svg(p.compositor().scene(), &stroked), &t, colour);
    let without = tinted_inside(&write_svg(p.compositor().scene(), &options), &t, colour);
    println!("svg seams: {with} tinted pixels with the stroke, {without} without");
    assert_eq!(with, 0);
    assert!(without > 0, "the test must be able to see seams");
}

/// Hostile texture names reach SVG and HTML escaped: the SVG still parses as XML (usvg), and
/// the HTML's one CSS rule keeps the name inside its string.
#[test]
fn hostile_texture_names_are_escaped() {
    let p = textured_spot_painter();
    let hostile = "a&b\"c<d>'e\\f\n</style><script>x</script>.png".to_owned();
    let svg = write_svg(
        p.compositor().scene(),
        &SvgOptions::DEFAULT.with_textures(vec![hostile.clone()]),
    );
    assert!(!svg.contains(&hostile));
    assert!(svg.contains("a&amp;b&quot;c&lt;d&gt;&apos;e"));
    resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default())
        .expect("the SVG parses with a hostile texture name");
    let html = vector_sink::write_html(
        p.compositor().scene(),
        &vector_sink::HtmlOptions::DEFAULT.with_textures(vec![hostile.clone()]),
    );
    assert!(!html.contains(&hostile));
    assert!(
        !html.contains("</style><script>"),
        "the name cannot end the style sheet"
    );
    assert_eq!(html.matches("</style>").count(), 1);
    let rule = html
        .lines()
        .find(|l| l.starts_with(".t0{"))
        .expect("the texture's rule");
    assert!(rule.ends_with("\")}"), "{rule}");
}
