//! PDF through a real consumer: poppler's `pdftoppm`, anti-aliasing off, in ID mode against
//! raster-sink's truth.
//!
//! Poppler's non-anti-aliased fill paints every pixel a shape touches within its scanline, not
//! the pixels whose centres it covers. Where the visible face changes along an edge of a drawn
//! piece that makes no difference (unambiguous pixels are 0.75 px from those edges, more than a
//! pixel's half-diagonal), but where it changes along an interpenetration curve (spot's
//! control mesh has some between neighbouring fan triangles) or a BSP cut, a pixel whose centre
//! is clear of the curve can still be touched. So each page is also rasterised at 5× (pdftoppm
//! `-r 360`) and sampled at the centre of each 5 × 5 block, the hi-res pixel whose centre is the
//! pixel centre: there touching reaches 0.3 px, and the PDF must be exact. The 1× counts are
//! printed beside it.
//!
//! Needs `pdftoppm` (Debian package `poppler-utils`). Without it the tests print a notice and
//! pass, unless the environment variable `CI` is set: then they fail (`.ci/run` installs it).

use raster_sink::{pixel_error, truth};
use sprite_compose::face_sort::{CullMode, Geometry, SorterKind, View};
use sprite_compose::{RecordingCompositor, SpritePainter};
use vector_sink::{HiddenParts, PdfOptions, write_pdf};

use crate::support;
use crate::writers::ids_of_rgba;

const SIZE: u32 = 200;
/// Odd, so that one hi-res pixel is centred on each pixel centre.
pub const ZOOM: u32 = 5;

pub use test_support::consumers::pdftoppm_available;

/// Rasterises a one-page PDF at `72 · zoom` dpi (one point to `zoom` pixels), anti-aliasing off.
pub fn rasterise(pdf: &[u8], name: &str, zoom: u32) -> resvg::tiny_skia::Pixmap {
    let dir =
        std::env::temp_dir().join(format!("sprite-compose-pdf-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let input = dir.join("page.pdf");
    std::fs::write(&input, pdf).expect("write pdf");
    let png = test_support::consumers::pdftoppm(&input, &dir.join("page"), zoom, false);
    resvg::tiny_skia::Pixmap::load_png(png).expect("pdftoppm's PNG")
}

/// Every model of the repository (assets/models/SOURCES.md).
pub const MODELS: [&str; 27] = [
    "keenan-crane/spot/spot_control_mesh.obj",
    "keenan-crane/spot/spot_control_mesh_texture.obj",
    "keenan-crane/spot/spot_quadrangulated.obj",
    "keenan-crane/spot/spot_triangulated.obj",
    "keenan-crane/blub/blub_control_mesh.obj",
    "keenan-crane/blub/blub_quadrangulated.obj",
    "suzanne/suzanne.obj",
    "cornell-box/cornell_box.obj",
    "fandisk-quads/fandisk_quads.converted.obj",
    "opensubdiv-torus/catmark_torus_creases0.obj",
    "compas/boxes.obj",
    "compas/faces.obj",
    "compas/hypar.obj",
    "compas/quadmesh.obj",
    "compas/tubemesh.obj",
    "combobulate-samples/book.obj",
    "combobulate-samples/octahedron.obj",
    "combobulate-samples/tetrahedron.obj",
    "assimp-obj/box.obj",
    "assimp-obj/concave_polygon.obj",
    "gltf/AnimatedMorphCube/AnimatedMorphCube.gltf",
    "gltf/Box/Box.gltf",
    "gltf/BoxTextured/BoxTextured.gltf",
    "gltf/BoxVertexColors/BoxVertexColors.gltf",
    "gltf/Cube/Cube.gltf",
    "gltf/MultipleScenes/MultipleScenes.gltf",
    "gltf/SimpleMeshes/SimpleMeshes.gltf",
];

/// The page side for a model: models of many small faces need a larger page for pixels
/// away from every edge.
pub fn page_size(geometry: &Geometry) -> u32 {
    if geometry.face_count() > 5_000 {
        3 * SIZE
    } else {
        SIZE
    }
}

/// Open models (a room, sheets, single polygons) are seen from both sides.
pub fn cull_for(model: &str) -> CullMode {
    let open = [
        "cornell",
        "compas/",
        "combobulate-samples/book",
        "assimp-obj/concave",
    ];
    if open.iter().any(|m| model.starts_with(m)) {
        CullMode::None
    } else {
        CullMode::Back
    }
}

/// ID-mode PDFs of a model (hidden parts kept and removed) rasterised by poppler: every
/// unambiguous pixel must carry the truth's face.
fn check_model(name: &str, geometry: &Geometry, views: &[View]) {
    let mut judged = 0;
    for (k, view) in views.iter().enumerate() {
        let size = view.width();
        for kind in [SorterKind::Bsp, SorterKind::Newell] {
            let mut painter = SpritePainter::new(
                geometry,
                kind.build(geometry),
                *view,
                RecordingCompositor::new(),
            );
            painter.frame();
            let t = truth(view, geometry);
            for hidden in [HiddenParts::Keep, HiddenParts::Remove] {
                let pdf = write_pdf(
                    painter.compositor().scene(),
                    &PdfOptions::DEFAULT
                        .with_size(size, size)
                        .with_ids(true)
                        .with_background(Some([0, 0, 0, 255]))
                        .with_hidden(hidden),
                );
                let at_size = rasterise(&pdf, &format!("{name}-{k}"), 1);
                assert_eq!(
                    (at_size.width(), at_size.height()),
                    (size, size),
                    "page size"
                );
                // Pixmap data is premultiplied; the page is opaque, so it is the colour.
                let e1 = pixel_error(&ids_of_rgba(size, size, at_size.data()), &t);
                let fine = rasterise(&pdf, &format!("{name}-{k}-x{ZOOM}"), ZOOM);
                assert_eq!(fine.width(), size * ZOOM, "page size at {ZOOM}x");
                let centres: Vec<u8> = (0..size * size)
                    .flat_map(|i| {
                        let (x, y) = (i % size, i / size);
                        let at =
                            ((y * ZOOM + ZOOM / 2) * size * ZOOM + x * ZOOM + ZOOM / 2) as usize;
                        fine.data()[4 * at..4 * at + 4].to_vec()
                    })
                    .collect();
                let e = pixel_error(&ids_of_rgba(size, size, &centres), &t);
                println!(
                    "pdf {name} view {k} {} {hidden:?}: {} bytes; wrong at 1x {}/{}, at pixel centres ({ZOOM}x) {}/{}",
                    kind.name(),
                    pdf.len(),
                    e1.wrong,
                    e1.pixels,
                    e.wrong,
                    e.pixels
                );
                judged += e.pixels;
                assert_eq!(
                    e.wrong,
                    0,
                    "{name} view {k} {} {hidden:?}: {e:?}",
                    kind.name()
                );
            }
        }
    }
    assert!(judged > 0, "{name}: nothing judged");
}

#[test]
fn pdf_ids_through_poppler_are_exact_on_the_models() {
    if !pdftoppm_available() {
        return;
    }
    for model in MODELS {
        let geometry = support::geometry(&support::load_obj(model));
        // Models of many small faces need a larger page for pixels away from every edge.
        let size = if geometry.face_count() > 5_000 {
            3 * SIZE
        } else {
            SIZE
        };
        let base = View::fit(&geometry.bounds(), size, size);
        // Open models (a room, sheets, single polygons) are seen from both sides.
        let open = [
            "cornell",
            "compas/",
            "combobulate-samples/book",
            "assimp-obj/concave",
        ];
        let cull = if open.iter().any(|m| model.starts_with(m)) {
            CullMode::None
        } else {
            CullMode::Back
        };
        let views = [
            base.with_yaw_pitch_roll(35.0, 20.0, 0.0).with_cull(cull),
            base.with_yaw_pitch_roll(200.0, -30.0, 10.0)
                .with_perspective(f64::from(size))
                .with_cull(cull),
        ];
        let name = model.rsplit('/').next().unwrap_or(model);
        check_model(name, &geometry, &views);
    }
}
