//! The writer target: a small model with arbitrary material names, texture names and
//! paths, colours (NaN included), texture coordinates, embedded images and writer options
//! gives SVG, HTML and PDF files that real parsers accept:
//!
//! - SVG: [`roxmltree`] (XML 1.0 well-formedness), with every linked texture's `href`
//!   reading back as the name given;
//! - HTML: html5ever, the WHATWG parsing algorithm, with no parse error and one style sheet;
//! - PDF: [`lopdf`], every page's content stream decoded into operators.

use std::sync::Arc;

use arbitrary::{Result, Unstructured};
use face_sort::{Geometry, PolygonMesh, SorterKind, View};
use glam::Vec2;
use obj_quads::{AlphaMode, EmbeddedTexture, Material, Mesh, WrapMode};
use sprite_compose::{Image, Materials};
use vector_sink::{
    Export, HiddenParts, HtmlOptions, PdfOptions, SvgOptions, write_html, write_pdf, write_svg,
};

use crate::input::{number, soup, tame};

/// A colour channel: any f32 sometimes, else in `[0, 1]`.
fn channel(u: &mut Unstructured) -> Result<f32> {
    Ok(if u.ratio(1u8, 8)? {
        f32::from_bits(u.arbitrary()?)
    } else {
        tame(u, 0.0, 1.0)? as f32
    })
}

/// A small PNG (1 to 4 pixels a side), or arbitrary bytes.
fn embedded(u: &mut Unstructured) -> Result<EmbeddedTexture> {
    let name: String = u.arbitrary()?;
    if u.ratio(1u8, 4)? {
        let bytes: Vec<u8> = u.arbitrary()?;
        return Ok(EmbeddedTexture::new(name, bytes));
    }
    let (w, h) = (u.int_in_range(1u32..=4)?, u.int_in_range(1u32..=4)?);
    let rgba = (0..w * h * 4)
        .map(|_| u.arbitrary())
        .collect::<Result<Vec<u8>>>()?;
    let image = Image::from_rgba(w, h, rgba, name.clone()).expect("the length matches");
    Ok(EmbeddedTexture::new(
        name,
        vector_sink::encoded_image(&image).0.into_owned(),
    ))
}

fn material(u: &mut Unstructured) -> Result<Material> {
    let mut material = Material::new(
        u.arbitrary::<String>()?,
        [channel(u)?, channel(u)?, channel(u)?, channel(u)?],
    );
    match u.int_in_range(0u8..=2)? {
        0 => {}
        1 => material = material.with_texture(u.arbitrary::<String>()?),
        _ => material.embedded_texture = Some(embedded(u)?),
    }
    material.texture_times_diffuse = u.arbitrary()?;
    material.alpha_mode = match u.int_in_range(0u8..=2)? {
        0 => AlphaMode::Opaque,
        1 => AlphaMode::Blend,
        _ => AlphaMode::Mask {
            cutoff: channel(u)?,
        },
    };
    let wrap = [
        WrapMode::Repeat,
        WrapMode::MirroredRepeat,
        WrapMode::ClampToEdge,
    ];
    material.wrap = [*u.choose(&wrap)?, *u.choose(&wrap)?];
    Ok(material)
}

/// The model: a mesh with materials and perhaps uvs, its geometry and a view.
fn model(u: &mut Unstructured) -> Result<Option<(Mesh, Geometry, View)>> {
    let (positions, faces) = soup(u, number, 8, 4)?;
    let Ok(mesh) = Mesh::from_faces(positions, faces) else {
        return Ok(None);
    };
    let materials = (0..u.int_in_range(0..=3)?)
        .map(|_| material(u))
        .collect::<Result<Vec<_>>>()?;
    let face_materials = (0..mesh.face_count())
        .map(|_| {
            Ok(if materials.is_empty() || u.ratio(1u8, 5)? {
                None
            } else {
                Some(u.int_in_range(0..=materials.len() as u32 - 1)?)
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let Ok(mut mesh) = mesh.with_materials(materials, face_materials) else {
        return Ok(None);
    };
    if u.arbitrary()? {
        let uvs = (0..mesh.corner_count())
            .map(|_| Ok(Vec2::new(number(u)? as f32, number(u)? as f32)))
            .collect::<Result<Vec<_>>>()?;
        let Ok(with_uvs) = mesh.clone().with_uvs(uvs) else {
            return Ok(None);
        };
        mesh = with_uvs;
    }
    let Ok(polygons) = PolygonMesh::new(mesh.positions().iter().copied(), mesh.faces()) else {
        return Ok(None);
    };
    let Ok(geometry) = Geometry::new(&polygons) else {
        return Ok(None);
    };
    let (width, height) = (u.int_in_range(1u32..=64)?, u.int_in_range(1u32..=64)?);
    let mut view = View::fit(&geometry.bounds(), width, height).with_yaw_pitch_roll(
        tame(u, -180.0, 180.0)?,
        tame(u, -90.0, 90.0)?,
        tame(u, -180.0, 180.0)?,
    );
    if u.arbitrary()? {
        view = view.with_perspective(f64::from(width) * tame(u, 1.0, 4.0)?);
    }
    Ok(Some((mesh, geometry, view)))
}

/// The check. Panics when a file does not parse.
pub fn writers(data: &[u8]) {
    let mut u = Unstructured::new(data);
    let Ok(Some((mesh, geometry, view))) = model(&mut u) else {
        return;
    };
    let Ok(materials) = Materials::of(&mesh, &geometry) else {
        return;
    };
    let hidden = if u.arbitrary().unwrap_or(false) {
        HiddenParts::Remove
    } else {
        HiddenParts::Keep
    };
    let export = Export::with_sorter(&geometry, view, SorterKind::Bsp)
        .with_materials(&materials)
        .with_hidden(hidden);
    check_svg(&export.svg(), &[]);
    check_html(&export.html());
    check_pdf(&export.pdf());

    // Textures linked by names from the caller (the CLI's --link-textures), with the
    // options `Export` leaves at their defaults.
    let names: Vec<String> = (0..materials.images().len())
        .map(|_| u.arbitrary())
        .collect::<Result<_>>()
        .unwrap_or_default();
    let ids = u.arbitrary().unwrap_or(false);
    let background: [u8; 4] = u.arbitrary().unwrap_or_default();
    let (width, height) = (view.width(), view.height());
    let scene = export.scene();
    let svg = write_svg(
        scene,
        &SvgOptions::DEFAULT
            .with_size(width, height)
            .with_textures(names.clone())
            .with_ids(ids)
            .with_background(Some(background))
            .with_hidden(hidden),
    );
    check_svg(&svg, if ids { &[] } else { &names });
    check_html(&write_html(
        scene,
        &HtmlOptions::DEFAULT
            .with_size(width, height)
            .with_textures(names)
            .with_ids(ids)
            .with_background(Some(background)),
    ));
    check_pdf(&write_pdf(
        scene,
        &PdfOptions::DEFAULT
            .with_size(width, height)
            .with_ids(ids)
            .with_background(Some(background))
            .with_images(materials.images().iter().map(Arc::clone).collect()),
    ));
}

/// The SVG parses as XML with an `svg` root, and every image's `href` reads back as one of
/// `names` (as XML can carry it) when names are given.
fn check_svg(svg: &str, names: &[String]) {
    let document = roxmltree::Document::parse(svg)
        .unwrap_or_else(|e| panic!("the SVG does not parse: {e}\n{svg}"));
    assert_eq!(document.root_element().tag_name().name(), "svg");
    if names.is_empty() {
        return;
    }
    for image in document
        .descendants()
        .filter(|n| n.has_tag_name(("http://www.w3.org/2000/svg", "image")))
    {
        let href = image
            .attributes()
            .find(|a| a.name() == "href")
            .map(|a| a.value())
            .unwrap_or_else(|| panic!("an image without href\n{svg}"));
        assert!(
            names.iter().any(|n| xml_carries(n) == href),
            "href {href:?} is none of the names {names:?}\n{svg}"
        );
    }
}

/// `name` as XML 1.0 can carry it: characters it does not allow at all become U+FFFD.
fn xml_carries(name: &str) -> String {
    name.chars()
        .map(|c| match c {
            '\t' | '\n' | '\r' => c,
            '\u{0}'..='\u{1f}' | '\u{fffe}' | '\u{ffff}' => '\u{fffd}',
            _ => c,
        })
        .collect()
}

/// The page parses by the HTML algorithm without a parse error, with one style sheet.
pub(crate) fn check_html(html: &str) {
    use html5ever::tendril::TendrilSink;
    let dom = html5ever::parse_document(markup5ever_rcdom::RcDom::default(), Default::default())
        .one(html);
    let errors = dom.errors.borrow();
    assert!(
        errors.is_empty(),
        "the HTML has parse errors: {errors:?}\n{html}"
    );
    let mut styles = 0;
    let mut stack = vec![dom.document.clone()];
    while let Some(node) = stack.pop() {
        if let markup5ever_rcdom::NodeData::Element { name, .. } = &node.data
            && &*name.local == "style"
        {
            styles += 1;
        }
        stack.extend(node.children.borrow().iter().cloned());
    }
    assert_eq!(styles, 1, "style sheets in the page\n{html}");
}

/// The PDF loads, has one page, and every page's content decodes into operators.
fn check_pdf(pdf: &[u8]) {
    let document =
        lopdf::Document::load_mem(pdf).unwrap_or_else(|e| panic!("the PDF does not load: {e}"));
    let pages = document.get_pages();
    assert_eq!(pages.len(), 1, "pages");
    for (_, id) in pages {
        let content = document
            .get_and_decode_page_content(id)
            .unwrap_or_else(|e| panic!("the content stream does not decode: {e}"));
        assert!(!content.operations.is_empty(), "an empty page");
    }
}
