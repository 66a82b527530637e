//! Material → brush resolution and the sprite brushes derived from it.

use std::path::{Path, PathBuf};

use raster_sink::face_sort::View;
use raster_sink::face_sort::glam::{DVec3, Vec2};
use raster_sink::sprite_compose;
use raster_sink::{Brush, FaceMaterials, Light, MaterialOptions, Style};

/// Three unit squares side by side: a textured one, a solid one, one without material.
struct Squares {
    positions: Vec<DVec3>,
    faces: Vec<[u32; 4]>,
    uvs: [Vec2; 4],
    texture: PathBuf,
}

impl Squares {
    fn new(texture: PathBuf) -> Self {
        let mut positions = Vec::new();
        let mut faces = Vec::new();
        for i in 0..3u32 {
            let x = f64::from(i) * 2.0;
            positions.extend([
                DVec3::new(x, 0.0, 0.0),
                DVec3::new(x + 1.0, 0.0, 0.0),
                DVec3::new(x + 1.0, 1.0, 0.0),
                DVec3::new(x, 1.0, 0.0),
            ]);
            faces.push([4 * i, 4 * i + 1, 4 * i + 2, 4 * i + 3]);
        }
        let uvs = [
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
        ];
        Squares {
            positions,
            faces,
            uvs,
            texture,
        }
    }
}

impl FaceMaterials for Squares {
    fn face_count(&self) -> usize {
        self.faces.len()
    }
    fn positions(&self) -> &[DVec3] {
        &self.positions
    }
    fn face_corners(&self, face: usize) -> Option<&[u32]> {
        self.faces.get(face).map(|f| &f[..])
    }
    fn face_uvs(&self, face: usize) -> Option<&[Vec2]> {
        (face == 0).then_some(&self.uvs[..])
    }
    fn face_diffuse(&self, face: usize) -> Option<[f32; 4]> {
        (face < 2).then_some([1.0, 0.5, 0.0, 1.0])
    }
    fn face_texture(&self, face: usize) -> Option<&Path> {
        (face == 0).then_some(self.texture.as_path())
    }
}

fn spot_texture() -> PathBuf {
    test_support::model_path("keenan-crane/spot/spot_texture.png")
}

#[test]
fn textures_diffuse_colours_and_the_palette() {
    let squares = Squares::new(spot_texture());
    let resolved = Style::from_materials(&squares, DVec3::ZERO, &MaterialOptions::DEFAULT).unwrap();
    assert!(resolved.warnings.is_empty(), "{:?}", resolved.warnings);
    let style = resolved.style;
    let Some(Brush::Texture(texture)) = style.brush(0) else {
        panic!("face 0 is textured: {:?}", style.brush(0));
    };
    // uv (0, 0) (OBJ: bottom left) is the texture's top-left in raster terms at v = 1 − 0.
    let uv = texture.map.uv(DVec3::new(0.0, 0.0, 0.0));
    assert!(
        (uv - raster_sink::face_sort::glam::DVec2::new(0.0, 1.0)).length() < 1e-9,
        "{uv}"
    );
    assert!(matches!(
        style.brush(1),
        Some(Brush::Solid([255, 128, 0, 255]))
    ));
    assert!(style.brush(2).is_none(), "no material: the palette");
}

#[test]
fn a_missing_material_texture_warns_and_falls_back_to_the_diffuse_colour() {
    let squares = Squares::new(PathBuf::from("/nonexistent/texture.png"));
    let resolved = Style::from_materials(&squares, DVec3::ZERO, &MaterialOptions::DEFAULT).unwrap();
    assert_eq!(resolved.warnings.len(), 1);
    assert!(
        resolved.warnings[0]
            .to_string()
            .contains("nonexistent/texture.png"),
        "{}",
        resolved.warnings[0]
    );
    assert!(matches!(resolved.style.brush(0), Some(Brush::Solid(_))));
    // An explicitly requested texture that does not load is an error, naming the file.
    struct NoTexture(Squares);
    impl FaceMaterials for NoTexture {
        fn face_count(&self) -> usize {
            self.0.face_count()
        }
        fn positions(&self) -> &[DVec3] {
            self.0.positions()
        }
        fn face_corners(&self, face: usize) -> Option<&[u32]> {
            self.0.face_corners(face)
        }
        fn face_uvs(&self, face: usize) -> Option<&[Vec2]> {
            self.0.face_uvs(face)
        }
        fn face_diffuse(&self, face: usize) -> Option<[f32; 4]> {
            self.0.face_diffuse(face)
        }
        fn face_texture(&self, _face: usize) -> Option<&Path> {
            None
        }
    }
    let options = MaterialOptions::DEFAULT.with_texture("/nonexistent/asked.png");
    let err = Style::from_materials(
        &NoTexture(Squares::new(PathBuf::new())),
        DVec3::ZERO,
        &options,
    )
    .unwrap_err();
    assert!(err.to_string().contains("asked.png"), "{err}");
}

#[test]
fn sprite_brushes_follow_the_style() {
    let squares = Squares::new(spot_texture());
    let mut style = Style::from_materials(&squares, DVec3::ZERO, &MaterialOptions::DEFAULT)
        .unwrap()
        .style;
    let bounds =
        raster_sink::face_sort::Bounds::from_points(squares.positions.iter().copied()).unwrap();
    let grid = raster_sink::GroundGrid::new(&bounds, 10.0);
    style.set_face(3, Brush::Grid(std::sync::Arc::new(grid)));

    let flat = style.sprite_brushes(&squares, None);
    assert_eq!(flat.len(), 4, "faces of the mesh and the grid's face");
    let sprite_compose::Brush::Solid(mean) = flat[0] else {
        panic!("a texture becomes its mean colour: {:?}", flat[0]);
    };
    assert_eq!(mean[3], 255);
    assert_eq!(flat[1], sprite_compose::Brush::Solid([255, 128, 0, 255]));
    assert_eq!(flat[2], sprite_compose::Brush::Palette);
    assert_eq!(flat[3], sprite_compose::Brush::Solid([0, 0, 0, 0]));

    // Shaded: the squares face +Z; seen head-on the factor is the light's for normal +Z.
    let view = View::fit(&bounds, 64, 64);
    let light = Light::DEFAULT;
    let shaded = style.sprite_brushes(&squares, Some((&view, &light)));
    let k = light.factor(DVec3::Z);
    assert!(k < 1.0);
    assert_eq!(
        shaded[1],
        sprite_compose::Brush::Solid(raster_sink::shade_colour([255, 128, 0, 255], k))
    );
    assert_eq!(shaded[2], sprite_compose::Brush::Palette);
}

/// sRGB byte → linear, and back (the glTF colour spaces), written here independently of the
/// library's.
fn srgb_to_linear(c: u8) -> f64 {
    let c = f64::from(c) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn linear_to_srgb(l: f64) -> f64 {
    let l = l.clamp(0.0, 1.0);
    255.0
        * if l <= 0.0031308 {
            l * 12.92
        } else {
            1.055 * l.powf(1.0 / 2.4) - 0.055
        }
}

/// The box's texture held in the file (data URI, GLB) draws exactly as the file beside it,
/// and `baseColorFactor` multiplies it (in linear light, as glTF says).
#[test]
fn embedded_gltf_textures_draw_and_the_factor_multiplies_them() {
    use raster_sink::face_sort::{Centroid, DrawList, FaceSorter, Geometry};
    use test_support::textured_box::{ImageSource, textured_box};

    let factor = [0.5f32, 1.0, 0.25, 1.0];
    // The file variant with the factor: the JSON written beside copies of its files.
    let dir = std::env::temp_dir().join(format!("raster-sink-box-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for file in ["BoxTextured0.bin", "CesiumLogoFlat.png"] {
        std::fs::copy(
            test_support::model_path(&format!("gltf/BoxTextured/{file}")),
            dir.join(file),
        )
        .unwrap();
    }
    let mut pictures = Vec::new();
    for source in [ImageSource::File, ImageSource::DataUri, ImageSource::Glb] {
        for factor in [None, Some(factor)] {
            let bytes = textured_box(source, factor);
            let mesh = match source {
                ImageSource::File => {
                    let path = dir.join("box.gltf");
                    std::fs::write(&path, &bytes).unwrap();
                    test_support::load_model_at(&path)
                }
                _ => {
                    obj_quads::load_gltf_slice(&bytes, &obj_quads::LoadOptions::DEFAULT)
                        .unwrap()
                        .0
                }
            };
            let polygons = test_support::polygon_mesh(&mesh);
            let geometry = Geometry::new(&polygons).unwrap();
            let resolved =
                Style::from_materials(&mesh, geometry.bounds().centre(), &MaterialOptions::DEFAULT)
                    .unwrap();
            assert!(resolved.warnings.is_empty(), "{:?}", resolved.warnings);
            let Some(Brush::Texture(texture)) = resolved.style.brush(0) else {
                panic!("{source:?}: face 0 is not textured");
            };
            // Texels: the PNG's, times the factor in linear light.
            let png = raster_sink::load_texture(&dir.join("CesiumLogoFlat.png")).unwrap();
            for (k, (got, raw)) in texture
                .image
                .pixels()
                .iter()
                .zip(png.pixels())
                .enumerate()
                .step_by(97)
            {
                let (got, raw) = (got.demultiply(), raw.demultiply());
                let f = factor.unwrap_or([1.0; 4]);
                for (channel, (g, r)) in [
                    (got.red(), raw.red()),
                    (got.green(), raw.green()),
                    (got.blue(), raw.blue()),
                ]
                .into_iter()
                .enumerate()
                {
                    let want = linear_to_srgb(srgb_to_linear(r) * f64::from(f[channel]));
                    assert!(
                        (f64::from(g) - want).abs() <= 1.0,
                        "{source:?} texel {k} channel {channel}: {g} vs {want:.1}"
                    );
                }
            }
            let view = View::fit(&geometry.bounds(), 96, 96).with_yaw_pitch_roll(30.0, 25.0, 0.0);
            let mut list = DrawList::new();
            Centroid::new(&geometry).sort(&view, &mut list);
            let image = raster_sink::render_colour(
                &view,
                &list,
                &resolved.style,
                &raster_sink::RasterOptions::DEFAULT,
            )
            .unwrap();
            pictures.push((source, factor.is_some(), image));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    // Every source draws the same picture, with and without the factor; the factor changes it.
    for (source, tinted, image) in &pictures[2..] {
        let same_as = &pictures[usize::from(*tinted)].2;
        assert!(
            image.data() == same_as.data(),
            "{source:?} (tinted: {tinted}) differs from the file's"
        );
    }
    assert!(pictures[0].2.data() != pictures[1].2.data());
}

/// glTF `alphaMode`: OPAQUE ignores alpha, BLEND keeps it, MASK cuts at `alphaCutoff`, for
/// textures (a 2 × 1 texture with alpha 64 and 200) and plain base colours (alpha 0.3).
#[test]
fn gltf_alpha_modes_shape_the_brushes() {
    use raster_sink::face_sort::Geometry;
    use test_support::gltf_scene::data_uri;
    let mut texture = raster_sink::tiny_skia::Pixmap::new(2, 1).unwrap();
    texture.pixels_mut()[0] =
        raster_sink::tiny_skia::ColorU8::from_rgba(200, 40, 40, 64).premultiply();
    texture.pixels_mut()[1] =
        raster_sink::tiny_skia::ColorU8::from_rgba(40, 200, 40, 200).premultiply();
    let png = data_uri("image/png", &texture.encode_png().unwrap());
    // Two quads side by side: the first textured, the second with a base colour only.
    let mut bin: Vec<u8> = Vec::new();
    let positions: [[f32; 3]; 8] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [2.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
        [3.0, 1.0, 0.0],
        [2.0, 1.0, 0.0],
    ];
    let uvs: [[f32; 2]; 8] = [
        [0.0, 1.0],
        [1.0, 1.0],
        [1.0, 0.0],
        [0.0, 0.0],
        [0.0, 1.0],
        [1.0, 1.0],
        [1.0, 0.0],
        [0.0, 0.0],
    ];
    for p in positions {
        for v in p {
            bin.extend(v.to_le_bytes());
        }
    }
    for t in uvs {
        for v in t {
            bin.extend(v.to_le_bytes());
        }
    }
    for i in [0u16, 1, 2, 0, 2, 3, 0, 1, 2, 0, 2, 3] {
        bin.extend(i.to_le_bytes());
    }
    let buffer = data_uri("application/octet-stream", &bin);
    let gltf = |mode: &str| {
        format!(
            r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"mesh": 0}}],
  "meshes": [{{"primitives": [
    {{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1}}, "indices": 2, "material": 0}},
    {{"attributes": {{"POSITION": 3, "TEXCOORD_0": 4}}, "indices": 5, "material": 1}}]}}],
  "materials": [
    {{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0}}}}, {mode}}},
    {{"pbrMetallicRoughness": {{"baseColorFactor": [0.2, 0.4, 0.8, 0.3]}}, {mode}}}],
  "textures": [{{"source": 0}}],
  "images": [{{"uri": "{png}"}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"}},
    {{"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}},
    {{"bufferView": 0, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3", "min": [2,0,0], "max": [3,1,0]}},
    {{"bufferView": 1, "byteOffset": 32, "componentType": 5126, "count": 4, "type": "VEC2"}},
    {{"bufferView": 2, "byteOffset": 12, "componentType": 5123, "count": 6, "type": "SCALAR"}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 96}},
    {{"buffer": 0, "byteOffset": 96, "byteLength": 64}},
    {{"buffer": 0, "byteOffset": 160, "byteLength": 24}}],
  "buffers": [{{"byteLength": {len}, "uri": "{buffer}"}}]}}"#,
            len = bin.len()
        )
    };
    // (mode, texel alphas, base colour alpha)
    for (mode, texels, base) in [
        (r#""alphaMode": "OPAQUE""#, [255, 255], 255),
        (r#""alphaMode": "BLEND""#, [64, 200], 77),
        (r#""alphaMode": "MASK", "alphaCutoff": 0.5"#, [0, 255], 0),
        (
            r#""alphaMode": "MASK", "alphaCutoff": 0.2"#,
            [255, 255],
            255,
        ),
    ] {
        let options =
            obj_quads::LoadOptions::DEFAULT.with_face_policy(obj_quads::FacePolicy::MergeTriangles);
        let (mesh, _) = obj_quads::load_gltf_slice(gltf(mode).as_bytes(), &options).unwrap();
        let geometry = Geometry::new(&test_support::polygon_mesh(&mesh)).unwrap();
        let style =
            Style::from_materials(&mesh, geometry.bounds().centre(), &MaterialOptions::DEFAULT)
                .unwrap()
                .style;
        let textured = (0..mesh.face_count() as u32)
            .find_map(|f| match style.brush(f) {
                Some(Brush::Texture(t)) => Some(t.image.clone()),
                _ => None,
            })
            .expect("a textured face");
        let alphas: Vec<u8> = textured.pixels().iter().map(|p| p.alpha()).collect();
        assert_eq!(alphas, texels, "{mode}");
        let solid = (0..mesh.face_count() as u32)
            .find_map(|f| match style.brush(f) {
                Some(Brush::Solid(c)) => Some(c[3]),
                _ => None,
            })
            .expect("a plain face");
        assert_eq!(solid, base, "{mode}");
    }
}
