//! Materials from a loader (feature `obj-quads`): each face described through
//! [`FaceMaterials`], its texture decoded once within obj-quads' texture limits, tinted by
//! its factor, and fitted with its [`UvMap`].

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DVec2, DVec3, Vec2};

use super::decode::{self, TextureError, TextureSource, alpha_byte};
use super::image::Image;
use super::wrapping;
use super::{FacePaint, Materials, UvMap};

/// What sprite-compose needs to know about a loaded model's faces to paint them: positions,
/// each face's corners, uvs, diffuse colour and texture.
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
    /// How a face's texture is sampled outside `[0, 1]` along u and v (glTF's sampler
    /// wrap modes). Default: repeat.
    fn face_texture_wrap(&self, face: usize) -> [obj_quads::WrapMode; 2] {
        let _ = face;
        [obj_quads::WrapMode::Repeat; 2]
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

/// Options of [`Materials::resolve`].
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

/// A face whose texture coordinates span several tiles: the face, its plain map, its tiles.
type Spanning = (usize, UvMap, (DVec2, DVec2));

/// Something a model asked for that its materials do not show: reported, never dropped
/// silently.
#[derive(Clone, Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MaterialWarning {
    /// A material's texture that could not be loaded: its faces use the diffuse colour.
    #[error("texture {0}; its faces use the diffuse colour")]
    Texture(Arc<TextureError>),
    /// Faces with texture coordinates and no texture to map (e.g. an OBJ without an MTL):
    /// they keep their diffuse colour or the palette.
    #[error(
        "{faces} faces have texture coordinates but no texture (the first is face {first}); give one with MaterialOptions::with_texture (render --texture)"
    )]
    UvsWithoutTexture {
        /// How many faces.
        faces: usize,
        /// The first of them.
        first: usize,
    },
}

impl Materials {
    /// Resolves each face's material: its texture (or `options.texture`) where the face has
    /// uvs, fitted per face ([`UvMap::fit`]); else its diffuse colour; faces without a
    /// material keep the palette. `centre` is the draw lists' centre,
    /// `geometry.bounds().centre()`. Each texture is decoded once, within
    /// `obj_quads::LoadOptions::DEFAULT`'s texture limits, and tinted once per factor.
    ///
    /// A material texture that does not load becomes a warning and its faces use the
    /// diffuse colour; `options.texture` failing to load is an error.
    pub fn resolve(
        faces: &impl FaceMaterials,
        centre: DVec3,
        options: &MaterialOptions,
    ) -> Result<Materials, TextureError> {
        let mut out = Materials::default();
        let mut decoded: HashMap<decode::TextureKey, Option<Arc<Image>>> = HashMap::new();
        // Decoded and tinted images, each once; only those a face ends up using are kept.
        let mut sources: Vec<Arc<Image>> = Vec::new();
        let mut source_of: HashMap<(decode::TextureKey, [u32; 4], decode::AlphaKey), usize> =
            HashMap::new();
        // Faces whose coordinates span several tiles, by (source, wrap): one tiled image
        // each, over the union of their tiles.
        let mut spanning: HashMap<(usize, [obj_quads::WrapMode; 2]), Vec<Spanning>> =
            HashMap::new();
        let mut textured: Vec<(usize, usize, UvMap)> = Vec::new(); // (face, source, map)
        let positions = faces.positions();
        let (mut corners, mut uv_points) = (Vec::new(), Vec::new());
        // Faces with uvs and no texture to map (an OBJ without an MTL): reported once.
        let (mut unmapped, mut first_unmapped) = (0, None);
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
            let mut paint = None;
            if source.is_none() && faces.face_uvs(face).is_some() {
                unmapped += 1;
                first_unmapped.get_or_insert(face);
            }
            if let (Some(source), Some(uvs), Some(indices)) =
                (source, faces.face_uvs(face), faces.face_corners(face))
            {
                let key = source.key();
                let image = match decoded.get(&key) {
                    Some(image) => image.clone(),
                    None => {
                        let image = match source.decode() {
                            Ok(image) => Some(Arc::new(image)),
                            Err(e) if matches!(source, TextureSource::File(p) if options.texture.as_deref() == Some(p)) =>
                            {
                                return Err(e);
                            }
                            Err(e) => {
                                out.warnings.push(MaterialWarning::Texture(Arc::new(e)));
                                None
                            }
                        };
                        decoded.insert(key.clone(), image.clone());
                        image
                    }
                };
                corners.clear();
                corners.extend(
                    indices
                        .iter()
                        .filter_map(|&i| positions.get(i as usize))
                        .map(|&p| p - centre),
                );
                uv_points.clear();
                uv_points.extend(
                    uvs.iter()
                        .map(|uv| DVec2::new(f64::from(uv.x), 1.0 - f64::from(uv.y))),
                );
                if let (Some(image), Some(map)) = (image, UvMap::fit(&corners, &uv_points)) {
                    let factor = faces.face_texture_factor(face).unwrap_or([1.0; 4]);
                    let alpha = faces.face_alpha_mode(face);
                    let plain = factor == [1.0; 4] && alpha == obj_quads::AlphaMode::Blend;
                    let cache_key = (
                        key,
                        if plain {
                            [0; 4]
                        } else {
                            factor.map(f32::to_bits)
                        },
                        if plain {
                            (9, 0)
                        } else {
                            decode::alpha_key(alpha)
                        },
                    );
                    let slot = *source_of.entry(cache_key).or_insert_with(|| {
                        sources.push(if plain {
                            Arc::clone(&image)
                        } else {
                            Arc::new(image.tinted(factor, alpha))
                        });
                        sources.len() - 1
                    });
                    // Coordinates outside [0, 1]: an affine remap for one tile, else an
                    // image of the tiles (below), so that every sink samples inside [0, 1]
                    // and sees the wrap modes alike.
                    let wrap = faces.face_texture_wrap(face);
                    let tiles = wrapping::tiles_of(&uv_points);
                    match wrapping::single_tile(tiles, wrap) {
                        Some((scale, offset)) => {
                            textured.push((face, slot, map.remapped(scale, offset)));
                        }
                        None => spanning
                            .entry((slot, wrap))
                            .or_default()
                            .push((face, map, tiles)),
                    }
                    paint = Some(FacePaint::Palette); // set below
                }
            }
            let paint = paint.or_else(|| {
                faces.face_diffuse(face).map(|d| {
                    let mut colour = d.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
                    colour[3] = alpha_byte(colour[3], faces.face_alpha_mode(face));
                    FacePaint::Solid(colour)
                })
            });
            out.faces.push(paint.unwrap_or(FacePaint::Palette));
        }
        // Images in the order faces first use them.
        let mut kept: HashMap<usize, usize> = HashMap::new();
        let mut keep = |out: &mut Materials, slot: usize| {
            *kept.entry(slot).or_insert_with(|| {
                out.images.push(Arc::clone(&sources[slot]));
                out.images.len() - 1
            })
        };
        if let Some(first) = first_unmapped {
            out.warnings.push(MaterialWarning::UvsWithoutTexture {
                faces: unmapped,
                first,
            });
        }
        tile_spanning_faces(&mut out, &sources, spanning, &mut textured);
        textured.sort_by_key(|t| t.0);
        for (face, slot, map) in textured {
            let image = keep(&mut out, slot);
            out.faces[face] = FacePaint::Texture { image, map };
        }
        Ok(out)
    }

    /// [`resolve`](Self::resolve) with the default options for `geometry`'s draw lists.
    pub fn of(
        faces: &impl FaceMaterials,
        geometry: &face_sort::Geometry,
    ) -> Result<Materials, TextureError> {
        Self::resolve(faces, geometry.bounds().centre(), &MaterialOptions::DEFAULT)
    }

    /// What the resolution could not use: material textures that did not load, and faces
    /// with texture coordinates but no texture.
    #[must_use]
    pub fn warnings(&self) -> &[MaterialWarning] {
        &self.warnings
    }
}

/// Faces whose coordinates span several tiles, grouped by (source, wrap): each group gets one
/// image of the union of its tiles, its maps remapped into it; a group whose tiles would be
/// too large keeps the plain maps (the texture's own tile only), pushed to `textured`.
fn tile_spanning_faces(
    out: &mut Materials,
    sources: &[Arc<Image>],
    spanning: HashMap<(usize, [obj_quads::WrapMode; 2]), Vec<Spanning>>,
    textured: &mut Vec<(usize, usize, UvMap)>,
) {
    let mut groups: Vec<_> = spanning.into_iter().collect();
    groups.sort_by_key(|(_, members)| members[0].0);
    for ((slot, wrap), members) in groups {
        let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
        for (_, _, (first, n)) in &members {
            lo = lo.min(*first);
            hi = hi.max(*first + *n);
        }
        let union = (lo, hi - lo);
        if wrapping::tiles_fit(&sources[slot], union) {
            out.images
                .push(Arc::new(wrapping::tiled(&sources[slot], wrap, union)));
            let image = out.images.len() - 1;
            for (face, map, _) in members {
                let map = map.remapped(DVec2::ONE / union.1, -lo / union.1);
                out.faces[face] = FacePaint::Texture { image, map };
            }
        } else {
            // Too many tiles: the plain map (the texture's own tile only).
            for (face, map, _) in members {
                textured.push((face, slot, map));
            }
        }
    }
}
