//! From a loaded model's materials to raster brushes.
//!
//! sprite-compose resolves materials ([`sprite_compose::Materials`]: textures decoded and
//! tinted once, uv maps fitted per face); [`Style::from_materials`] turns that resolution
//! into raster brushes, and [`Style::sprite_brushes`] projects a raster style (with its
//! ground grid and flat shading by the same [`Light`]) back onto sprite brushes.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use face_sort::View;
use face_sort::glam::DVec3;
use tiny_skia::Pixmap;

use sprite_compose::{
    FaceMaterials, FacePaint, Image, MaterialOptions, MaterialWarning, Materials,
};

use crate::{Brush, Light, RasterError, Style, TextureBrush, shade_colour};

/// A style resolved from materials, and the material textures that could not be loaded
/// (their faces fall back to the diffuse colour).
#[derive(Debug)]
pub struct MaterialStyle {
    /// One brush per face that has a material or a texture.
    pub style: Style,
    /// What the materials could not show ([`Materials::warnings`]).
    pub warnings: Vec<MaterialWarning>,
}

/// Loads a PNG or JPEG texture within the default texture limits of
/// `obj_quads::LoadOptions::DEFAULT` (see [`load_texture_with`]).
pub fn load_texture(path: &Path) -> Result<Pixmap, RasterError> {
    load_texture_with(path, &obj_quads::LoadOptions::DEFAULT)
}

/// Loads a PNG or JPEG texture within the texture limits of `limits`: file size before
/// reading, width, height and pixel count from the image header before decoding
/// ([`sprite_compose::load_image`]), so a small file declaring a huge image fails fast with
/// [`RasterError::Texture`] instead of allocating it.
pub fn load_texture_with(
    path: &Path,
    limits: &obj_quads::LoadOptions,
) -> Result<Pixmap, RasterError> {
    let image = sprite_compose::load_image(path, limits)?;
    pixmap_of(&image)
}

/// A decoded image (straight RGBA) as a premultiplied pixmap.
pub(crate) fn pixmap_of(image: &Image) -> Result<Pixmap, RasterError> {
    let size = tiny_skia::IntSize::from_wh(image.width(), image.height());
    let mut data = image.rgba().to_vec();
    for pixel in data.chunks_exact_mut(4) {
        let c = tiny_skia::ColorU8::from_rgba(pixel[0], pixel[1], pixel[2], pixel[3]).premultiply();
        pixel.copy_from_slice(&[c.red(), c.green(), c.blue(), c.alpha()]);
    }
    size.and_then(|size| Pixmap::from_vec(data, size))
        .ok_or_else(|| RasterError::Png {
            path: PathBuf::from(image.name()),
            message: "decoded texture does not fit a pixmap".into(),
        })
}

impl Style {
    /// Per-face brushes of a loaded model ([`Materials::resolve`]): the material's texture
    /// (or `options.texture`) where the face has uvs, fitted per face; else the material's
    /// diffuse colour; faces without a material keep the palette. `centre` is the draw
    /// lists' centre, `geometry.bounds().centre()`.
    ///
    /// A material texture that does not load becomes a warning and its faces use the
    /// diffuse colour; `options.texture` failing to load is an error.
    pub fn from_materials(
        faces: &impl FaceMaterials,
        centre: DVec3,
        options: &MaterialOptions,
    ) -> Result<MaterialStyle, RasterError> {
        let materials = Materials::resolve(faces, centre, options)?;
        Ok(MaterialStyle {
            style: Style::from_resolved(&materials)?,
            warnings: materials.warnings().to_vec(),
        })
    }

    /// The raster brushes of resolved materials: each image becomes one pixmap, shared by
    /// the faces that use it.
    pub fn from_resolved(materials: &Materials) -> Result<Style, RasterError> {
        let pixmaps: Vec<Arc<Pixmap>> = materials
            .images()
            .iter()
            .map(|image| pixmap_of(image).map(Arc::new))
            .collect::<Result<_, _>>()?;
        let mut style = Style::palette();
        for face in 0..materials.face_count() as u32 {
            match materials.face(face) {
                FacePaint::Palette => {}
                FacePaint::Solid(colour) => style.set_face(face, Brush::Solid(*colour)),
                FacePaint::Texture { image, map } => style.set_face(
                    face,
                    Brush::Texture(TextureBrush {
                        image: Arc::clone(&pixmaps[*image]),
                        map: *map,
                    }),
                ),
            }
        }
        Ok(style)
    }

    /// The sprite brushes closest to this style, one per face (`0..` the larger of
    /// `faces.face_count()` and the faces this style names), for sprite-compose's painter
    /// and its SVG and HTML writers: solid colours as they are, a texture as its mean
    /// colour, the ground grid transparent, the palette as the palette. With `shading`,
    /// solid colours are flat-shaded with the light for the view, each face by its normal
    /// ([`FaceMaterials::face_normal`]) turned toward the viewer.
    #[must_use]
    pub fn sprite_brushes(
        &self,
        faces: &impl FaceMaterials,
        shading: Option<(&View, &Light)>,
    ) -> Vec<sprite_compose::Brush> {
        let mut means: HashMap<*const Pixmap, [u8; 4]> = HashMap::new();
        let count = faces.face_count().max(self.face_slots());
        (0..count)
            .map(|face| {
                let shaded = |colour: [u8; 4]| match (shading, faces.face_normal(face)) {
                    (Some((view, light)), Some(normal)) => {
                        shade_colour(colour, light.facing_factor(view, normal))
                    }
                    _ => colour,
                };
                match self.brush(face as u32) {
                    Some(Brush::Solid(colour)) => sprite_compose::Brush::Solid(shaded(*colour)),
                    Some(Brush::Texture(texture)) => {
                        let mean = *means
                            .entry(Arc::as_ptr(&texture.image))
                            .or_insert_with(|| mean_colour(&texture.image));
                        sprite_compose::Brush::Solid(shaded(mean))
                    }
                    Some(Brush::Grid(_)) => sprite_compose::Brush::Solid([0, 0, 0, 0]),
                    None => sprite_compose::Brush::Palette,
                }
            })
            .collect()
    }
}

/// The mean straight-alpha colour of an image, opaque.
fn mean_colour(image: &Pixmap) -> [u8; 4] {
    let mut sum = [0u64; 3];
    let pixels = image.pixels();
    for p in pixels {
        let c = p.demultiply();
        sum[0] += u64::from(c.red());
        sum[1] += u64::from(c.green());
        sum[2] += u64::from(c.blue());
    }
    let n = pixels.len().max(1) as u64;
    [
        (sum[0] / n) as u8,
        (sum[1] / n) as u8,
        (sum[2] / n) as u8,
        255,
    ]
}

#[cfg(test)]
mod texture_tests {
    use super::*;

    const SPOT: &str = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/models/keenan-crane/spot/spot_texture.png"
    );

    #[test]
    fn bounded_texture_loading_matches_tiny_skia_decoding() {
        let bytes = std::fs::read(SPOT).unwrap();
        let reference = Pixmap::decode_png(&bytes).unwrap();
        let loaded = load_texture(Path::new(SPOT)).unwrap();
        assert_eq!(
            (loaded.width(), loaded.height()),
            (reference.width(), reference.height())
        );
        assert!(loaded.data() == reference.data());
    }

    #[test]
    fn texture_limits_apply() {
        let small = obj_quads::LoadOptions::DEFAULT.with_max_texture_side(512);
        match load_texture_with(Path::new(SPOT), &small) {
            Err(RasterError::Texture { source, .. }) => match *source {
                obj_quads::LoadError::TooLarge { actual, limit, .. } => {
                    assert_eq!((actual, limit), (1024, 512))
                }
                other => panic!("{other:?}"),
            },
            other => panic!("{other:?}"),
        }
    }
}
