//! From a loaded model's materials to brushes: the one path from a mesh to pixels.
//!
//! raster-sink owns material → brush resolution and flat shading. A loader describes each
//! face through [`FaceMaterials`] (implemented for `obj_quads::Mesh` behind the `obj-quads`
//! feature); [`Style::from_materials`] turns that into raster brushes (textures fitted per
//! face, diffuse colours, else the palette) and [`Style::sprite_brushes`] projects the same
//! style onto sprite-compose's brushes for the SVG and HTML writers, flat-shaded with the
//! same [`Light`].

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use face_sort::View;
use face_sort::glam::{DVec2, DVec3, Vec2};
use tiny_skia::Pixmap;

use crate::{Brush, Light, RasterError, Style, TextureBrush, UvMap, shade_colour};

/// What raster-sink needs to know about a loaded model's faces to paint them: positions,
/// each face's corners, uvs, diffuse colour and texture file.
///
/// Face indices are those of the draw list (the file order of CONVENTIONS.md).
pub trait FaceMaterials {
    /// Number of faces.
    fn face_count(&self) -> usize;
    /// Vertex positions in model space.
    fn positions(&self) -> &[DVec3];
    /// A face's corners as indices into [`positions`](Self::positions); `None` when out of
    /// range.
    fn face_corners(&self, face: usize) -> Option<&[u32]>;
    /// A face's uvs, one per corner, `v = 0` at the texture's bottom (OBJ and glTF as
    /// loaded by obj-quads); `None` when the face has none.
    fn face_uvs(&self, face: usize) -> Option<&[Vec2]>;
    /// A face's diffuse colour, RGBA in 0..=1, mapped linearly to bytes; `None` when the
    /// face has no material (it is then painted in its palette colour).
    fn face_diffuse(&self, face: usize) -> Option<[f32; 4]>;
    /// A face's diffuse texture file (PNG or JPEG), if its material has one.
    fn face_texture(&self, face: usize) -> Option<&Path>;
    /// A face's diffuse texture held in the model file (encoded PNG or JPEG), with a name for
    /// messages, when it has no texture file. Default: none.
    fn face_embedded_texture(&self, face: usize) -> Option<(&str, &[u8])> {
        let _ = face;
        None
    }
    /// The factor a face's texture is multiplied by (linear RGBA, e.g. glTF's
    /// `baseColorFactor`); `None` leaves the texture as it is. Default: none.
    fn face_texture_factor(&self, face: usize) -> Option<[f32; 4]> {
        let _ = face;
        None
    }
    /// How a face's alpha is used (glTF `alphaMode`): opaque, blended, or masked at a
    /// cutoff. Default: blended.
    fn face_alpha_mode(&self, face: usize) -> obj_quads::AlphaMode {
        let _ = face;
        obj_quads::AlphaMode::Blend
    }
    /// A face's model-space normal (any length) for flat shading: by default Newell's
    /// normal of its corners.
    fn face_normal(&self, face: usize) -> Option<DVec3> {
        let positions = self.positions();
        let corners: Vec<DVec3> = self
            .face_corners(face)?
            .iter()
            .map(|&i| positions.get(i as usize).copied())
            .collect::<Option<_>>()?;
        Some(face_sort::newell_normal(&corners))
    }
}

/// Options of [`Style::from_materials`].
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct MaterialOptions {
    /// A texture for faces that have uvs but no texture of their own (e.g. a model whose
    /// OBJ has uvs and no MTL). Unlike a material's texture, failing to load it is an error.
    /// Default: none.
    pub texture: Option<PathBuf>,
}

impl MaterialOptions {
    /// The defaults.
    pub const DEFAULT: MaterialOptions = MaterialOptions { texture: None };

    /// The texture for faces with uvs and no texture of their own.
    #[must_use]
    pub fn with_texture(mut self, texture: impl Into<PathBuf>) -> Self {
        self.texture = Some(texture.into());
        self
    }
}

/// A style resolved from materials, and the material textures that could not be loaded
/// (their faces fall back to the diffuse colour).
#[derive(Debug)]
pub struct MaterialStyle {
    /// One brush per face that has a material or a texture.
    pub style: Style,
    /// One error per material texture that failed to load.
    pub warnings: Vec<RasterError>,
}

/// Loads a PNG or JPEG texture within the default texture limits of
/// `obj_quads::LoadOptions::DEFAULT` (see [`load_texture_with`]).
pub fn load_texture(path: &Path) -> Result<Pixmap, RasterError> {
    load_texture_with(path, &obj_quads::LoadOptions::DEFAULT)
}

/// Loads a PNG or JPEG texture within the texture limits of `limits`: file size before
/// reading, width, height and pixel count from the image header before decoding
/// (`obj_quads::load_texture`), so a small file declaring a huge image fails fast with
/// [`RasterError::Texture`] instead of allocating it.
pub fn load_texture_with(
    path: &Path,
    limits: &obj_quads::LoadOptions,
) -> Result<Pixmap, RasterError> {
    let texture = obj_quads::load_texture(path, limits).map_err(|source| RasterError::Texture {
        path: path.to_path_buf(),
        source: Box::new(source),
    })?;
    pixmap_of(texture, path)
}

/// Where a face's texture comes from.
#[derive(Clone, Copy)]
enum TextureSource<'a> {
    File(&'a Path),
    /// Name for messages, encoded bytes.
    Embedded(&'a str, &'a [u8]),
}

/// A decoded texture's cache key: its file, or its bytes' address and length.
#[derive(Clone, PartialEq, Eq, Hash)]
enum TextureKey {
    File(PathBuf),
    Embedded(usize, usize),
}

impl TextureSource<'_> {
    fn key(&self) -> TextureKey {
        match *self {
            TextureSource::File(path) => TextureKey::File(path.to_path_buf()),
            TextureSource::Embedded(_, bytes) => {
                TextureKey::Embedded(bytes.as_ptr() as usize, bytes.len())
            }
        }
    }
}

/// Decodes a texture held in a model file within the default texture limits.
fn decode_embedded(name: &str, bytes: &[u8]) -> Result<Pixmap, RasterError> {
    let path = PathBuf::from(name);
    let texture = obj_quads::decode_texture(bytes, name, &obj_quads::LoadOptions::DEFAULT)
        .map_err(|source| RasterError::Texture {
            path: path.clone(),
            source: Box::new(source),
        })?;
    pixmap_of(texture, &path)
}

/// A decoded texture (straight RGBA) as a premultiplied pixmap.
fn pixmap_of(texture: obj_quads::Texture, path: &Path) -> Result<Pixmap, RasterError> {
    let size = tiny_skia::IntSize::from_wh(texture.width, texture.height);
    let mut data = texture.rgba;
    for pixel in data.chunks_exact_mut(4) {
        let c = tiny_skia::ColorU8::from_rgba(pixel[0], pixel[1], pixel[2], pixel[3]).premultiply();
        pixel.copy_from_slice(&[c.red(), c.green(), c.blue(), c.alpha()]);
    }
    size.and_then(|size| Pixmap::from_vec(data, size))
        .ok_or_else(|| RasterError::Png {
            path: path.to_path_buf(),
            message: "decoded texture does not fit a pixmap".into(),
        })
}

/// An alpha mode as a hashable cache key.
type AlphaKey = (u8, u32);

fn alpha_key(mode: obj_quads::AlphaMode) -> AlphaKey {
    match mode {
        obj_quads::AlphaMode::Opaque => (0, 0),
        obj_quads::AlphaMode::Mask { cutoff } => (2, cutoff.to_bits()),
        _ => (1, 0),
    }
}

/// An alpha byte under an alpha mode: as is (blend), 255 (opaque), or 255 / 0 at the
/// cutoff (mask).
fn alpha_byte(alpha: u8, mode: obj_quads::AlphaMode) -> u8 {
    match mode {
        obj_quads::AlphaMode::Opaque => 255,
        obj_quads::AlphaMode::Mask { cutoff } => {
            if f32::from(alpha) / 255.0 >= cutoff {
                255
            } else {
                0
            }
        }
        _ => alpha,
    }
}

/// `image` with every texel multiplied by `factor` (linear RGBA, as glTF's
/// `baseColorFactor`: sRGB texels to linear, times the factor, back to sRGB) and its alpha
/// then taken as `alpha` says.
fn tint(image: &Pixmap, factor: [f32; 4], alpha: obj_quads::AlphaMode) -> Pixmap {
    let to_linear = |c: u8| {
        let c = f32::from(c) / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    let to_srgb = |l: f32| {
        let l = l.clamp(0.0, 1.0);
        let c = if l <= 0.003_130_8 {
            l * 12.92
        } else {
            1.055 * l.powf(1.0 / 2.4) - 0.055
        };
        (c * 255.0).round() as u8
    };
    let mut out = image.clone();
    for pixel in out.pixels_mut() {
        let c = pixel.demultiply();
        let a = alpha_byte(
            (f32::from(c.alpha()) * factor[3].clamp(0.0, 1.0)).round() as u8,
            alpha,
        );
        let scale = |v: u8, f: f32| {
            if f == 1.0 {
                v // no round trip through linear light
            } else {
                to_srgb(to_linear(v) * f)
            }
        };
        let tinted = tiny_skia::ColorU8::from_rgba(
            scale(c.red(), factor[0]),
            scale(c.green(), factor[1]),
            scale(c.blue(), factor[2]),
            a,
        );
        *pixel = tinted.premultiply();
    }
    out
}

/// A diffuse colour in 0..=1 as bytes.
fn diffuse_bytes(diffuse: [f32; 4]) -> [u8; 4] {
    diffuse.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
}

impl Style {
    /// Per-face brushes of a loaded model: the material's texture (or `options.texture`)
    /// where the face has uvs, fitted per face ([`UvMap::fit`]); else the material's diffuse
    /// colour; faces without a material keep the palette. `centre` is the draw lists'
    /// centre, `geometry.bounds().centre()`.
    ///
    /// A material texture that does not load becomes a warning and its faces use the
    /// diffuse colour; `options.texture` failing to load is an error.
    pub fn from_materials(
        faces: &impl FaceMaterials,
        centre: DVec3,
        options: &MaterialOptions,
    ) -> Result<MaterialStyle, RasterError> {
        let mut style = Style::palette();
        let mut warnings = Vec::new();
        // Decoded textures by source, and tinted copies by source and factor.
        let mut textures: HashMap<TextureKey, Option<Arc<Pixmap>>> = HashMap::new();
        let mut tinted: HashMap<(TextureKey, [u32; 4], AlphaKey), Arc<Pixmap>> = HashMap::new();
        let mut load = |source: TextureSource<'_>,
                        factor: Option<[f32; 4]>,
                        alpha: obj_quads::AlphaMode|
         -> Result<Option<Arc<Pixmap>>, RasterError> {
            let key = source.key();
            let image = match textures.get(&key) {
                Some(t) => t.clone(),
                None => {
                    let decoded = match source {
                        TextureSource::File(path) => load_texture(path),
                        TextureSource::Embedded(name, bytes) => decode_embedded(name, bytes),
                    };
                    let image = match decoded {
                        Ok(image) => Some(Arc::new(image)),
                        Err(e) if matches!(source, TextureSource::File(p) if options.texture.as_deref() == Some(p)) =>
                        {
                            return Err(e);
                        }
                        Err(e) => {
                            warnings.push(e);
                            None
                        }
                    };
                    textures.insert(key.clone(), image.clone());
                    image
                }
            };
            let f = factor.unwrap_or([1.0; 4]);
            Ok(match image {
                Some(image) if f != [1.0; 4] || alpha != obj_quads::AlphaMode::Blend => {
                    Some(Arc::clone(
                        tinted
                            .entry((key, f.map(f32::to_bits), alpha_key(alpha)))
                            .or_insert_with(|| Arc::new(tint(&image, f, alpha))),
                    ))
                }
                image => image,
            })
        };
        let positions = faces.positions();
        let mut corners = Vec::new();
        let mut uv_points = Vec::new();
        for face in 0..faces.face_count() {
            let source = faces
                .face_texture(face)
                .map(TextureSource::File)
                .or_else(|| {
                    faces
                        .face_embedded_texture(face)
                        .map(|(name, bytes)| TextureSource::Embedded(name, bytes))
                })
                .or(options.texture.as_deref().map(TextureSource::File));
            let mut brush = None;
            if let (Some(source), Some(uvs), Some(indices)) =
                (source, faces.face_uvs(face), faces.face_corners(face))
                && let Some(image) = load(
                    source,
                    faces.face_texture_factor(face),
                    faces.face_alpha_mode(face),
                )?
            {
                corners.clear();
                corners.extend(indices.iter().map(|&i| positions[i as usize] - centre));
                uv_points.clear();
                uv_points.extend(
                    uvs.iter()
                        .map(|uv| DVec2::new(f64::from(uv.x), 1.0 - f64::from(uv.y))),
                );
                brush = UvMap::fit(&corners, &uv_points)
                    .map(|map| Brush::Texture(TextureBrush { image, map }));
            }
            let brush = brush.or_else(|| {
                faces.face_diffuse(face).map(|d| {
                    let mut colour = diffuse_bytes(d);
                    colour[3] = alpha_byte(colour[3], faces.face_alpha_mode(face));
                    Brush::Solid(colour)
                })
            });
            if let Some(brush) = brush {
                style.set_face(face as u32, brush);
            }
        }
        Ok(MaterialStyle { style, warnings })
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

    /// Gives every visible sprite of `scene` whose face has a [`Brush::Texture`] here its
    /// exact texture brush (`sprite_compose::set_plane_textures` with this style's plane uv
    /// maps), for the SVG and HTML writers; the other sprites keep theirs (e.g. the mean
    /// colours of [`sprite_brushes`](Self::sprite_brushes)). `space` is the painter's
    /// `SpriteSpace::of_view(view)`.
    ///
    /// Returns the distinct images in `TextureId` order: the writers take one URI per id
    /// (`SvgOptions::with_textures`, `HtmlOptions::with_textures`), e.g. the texture files'
    /// paths.
    pub fn set_sprite_textures(
        &self,
        scene: &mut sprite_compose::Scene,
        space: &sprite_compose::SpriteSpace,
    ) -> Vec<Arc<Pixmap>> {
        let mut images: Vec<Arc<Pixmap>> = Vec::new();
        let mut ids: HashMap<*const Pixmap, u32> = HashMap::new();
        // `face_slots()` itself has no brush of its own: it stands for the default brush.
        for face in 0..=self.face_slots() {
            if let Some(Brush::Texture(t)) = self.brush(face as u32) {
                ids.entry(Arc::as_ptr(&t.image)).or_insert_with(|| {
                    images.push(Arc::clone(&t.image));
                    (images.len() - 1) as u32
                });
            }
        }
        sprite_compose::set_plane_textures(scene, space, |face, p| match self.brush(face) {
            Some(Brush::Texture(t)) => Some((
                sprite_compose::TextureId(*ids.get(&Arc::as_ptr(&t.image))?),
                t.map.uv(p),
            )),
            _ => None,
        });
        images
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

impl FaceMaterials for obj_quads::Mesh {
    fn face_count(&self) -> usize {
        obj_quads::Mesh::face_count(self)
    }
    fn positions(&self) -> &[DVec3] {
        obj_quads::Mesh::positions(self)
    }
    fn face_corners(&self, face: usize) -> Option<&[u32]> {
        self.face(face)
    }
    fn face_uvs(&self, face: usize) -> Option<&[Vec2]> {
        obj_quads::Mesh::face_uvs(self, face)
    }
    fn face_diffuse(&self, face: usize) -> Option<[f32; 4]> {
        self.face_material(face)
            .and_then(|m| self.materials().get(m as usize))
            .map(|m| m.diffuse)
    }
    fn face_texture(&self, face: usize) -> Option<&Path> {
        self.face_material(face)
            .and_then(|m| self.materials().get(m as usize))
            .and_then(|m| m.texture.as_deref())
    }
    fn face_embedded_texture(&self, face: usize) -> Option<(&str, &[u8])> {
        self.face_material(face)
            .and_then(|m| self.materials().get(m as usize))
            .and_then(|m| m.embedded_texture.as_ref())
            .map(|t| (t.name.as_str(), &t.bytes[..]))
    }
    fn face_texture_factor(&self, face: usize) -> Option<[f32; 4]> {
        self.face_material(face)
            .and_then(|m| self.materials().get(m as usize))
            .filter(|m| m.texture_times_diffuse)
            .map(|m| m.diffuse)
    }
    fn face_alpha_mode(&self, face: usize) -> obj_quads::AlphaMode {
        self.face_material(face)
            .and_then(|m| self.materials().get(m as usize))
            .map_or(obj_quads::AlphaMode::Blend, |m| m.alpha_mode)
    }
    fn face_normal(&self, face: usize) -> Option<DVec3> {
        obj_quads::Mesh::face_normal(self, face)
    }
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
