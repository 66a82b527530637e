//! Materials are never dropped silently: an OBJ with uvs and no MTL reports its unmapped
//! faces, and given a texture it is embedded, unchanged, in the SVG, the PDF and the HTML.

use sprite_compose::face_sort::{Geometry, PolygonMesh, View};
use sprite_compose::{FacePaint, MaterialOptions, MaterialWarning, Materials};
use vector_sink::Export;

/// Spot's textured control mesh (180 quads with uvs); the test drops its `mtllib` and
/// `usemtl` lines.
const MODEL: &str = "keenan-crane/spot/spot_control_mesh_texture.obj";
const TEXTURE: &str = "keenan-crane/spot/spot_texture.png";

/// The model as an OBJ without an MTL: its text less the material lines.
fn without_mtl() -> sprite_compose::obj_quads::Mesh {
    let text = std::fs::read_to_string(test_support::model_path(MODEL)).expect("the model");
    let text: String = (text.lines())
        .filter(|l| !l.starts_with("mtllib") && !l.starts_with("usemtl"))
        .map(|l| format!("{l}\n"))
        .collect();
    let (mesh, _) =
        sprite_compose::obj_quads::load_obj_str(&text, &Default::default()).expect("the OBJ loads");
    mesh
}

#[test]
fn an_obj_without_mtl_reports_its_uvs_and_takes_a_given_texture_into_every_file() {
    let mesh = without_mtl();
    let geometry = Geometry::new(&PolygonMesh::new(mesh.positions(), mesh.faces()).unwrap())
        .expect("geometry");
    let faces = mesh.face_count();

    // No texture given: the faces keep the palette, and the resolution says why.
    let plain = Materials::of(&mesh, &geometry).expect("materials");
    assert!(plain.images().is_empty());
    assert!(
        matches!(
            plain.warnings(),
            [MaterialWarning::UvsWithoutTexture { faces: f, first: 0 }] if *f == faces
        ),
        "{:?}",
        plain.warnings()
    );

    // The texture given: every face maps it, nothing is reported.
    let texture = test_support::model_path(TEXTURE);
    let options = MaterialOptions::DEFAULT.with_texture(&texture);
    let materials =
        Materials::resolve(&mesh, geometry.bounds().centre(), &options).expect("materials");
    assert!(
        materials.warnings().is_empty(),
        "{:?}",
        materials.warnings()
    );
    // The texture itself, and any image of the tiles that faces with uvs past [0, 1] span.
    let png = std::fs::read(&texture).expect("the texture");
    let originals = (materials.images().iter())
        .filter(|image| image.original().is_some_and(|(bytes, _)| bytes == &png[..]))
        .count();
    assert_eq!(originals, 1, "the texture, unchanged, is one of the images");
    let textured = (0..faces as u32)
        .filter(|&f| matches!(materials.face(f), FacePaint::Texture { .. }))
        .count();
    assert_eq!(textured, faces);

    // Each file embeds each image once: the SVG and the HTML as data URIs (the texture as
    // the PNG's own bytes), the PDF as image objects.
    let view = View::fit(&geometry.bounds(), 256, 256).with_yaw_pitch_roll(145.0, -25.0, 0.0);
    let export = Export::new(&geometry, view).with_materials(&materials);
    let (svg, html, pdf) = (export.svg(), export.html(), export.pdf());
    let texture_uri = (materials.images().iter())
        .find(|image| image.original().is_some())
        .map(|image| vector_sink::image_data_uri(image))
        .expect("the texture's image");
    assert_eq!(
        svg.matches(&texture_uri).count(),
        1,
        "the SVG holds the texture once"
    );
    assert_eq!(
        html.matches(&texture_uri).count(),
        1,
        "the HTML holds it once"
    );
    for image in materials.images() {
        let uri = vector_sink::image_data_uri(image);
        assert!(svg.matches(&uri).count() <= 1 && html.matches(&uri).count() <= 1);
    }
    assert!(
        svg.contains("<use xlink:href=\"#t"),
        "textured cells use the images"
    );
    assert!(
        html.contains("<i class=\"t"),
        "textured elements use the images"
    );
    let pdf_text = String::from_utf8_lossy(&pdf);
    let images = pdf_text.matches("/Subtype /Image").count();
    assert!(images > 0, "the PDF draws the texture as image tiles");
    // The same file without the texture holds none.
    let flat = Export::new(&geometry, view).with_materials(&plain).pdf();
    assert_eq!(
        String::from_utf8_lossy(&flat)
            .matches("/Subtype /Image")
            .count(),
        0
    );
}
