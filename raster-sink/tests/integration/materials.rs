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
