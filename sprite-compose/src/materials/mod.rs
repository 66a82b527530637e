//! A model's materials resolved per face: what every sink paints each face with.
//!
//! sprite-compose owns brushes, so it owns materials too, as plain data: per face a
//! [`FacePaint`] (palette, colour, or a texture [`Image`] with its [`UvMap`]). The writers
//! take sprite [`Brush`]es from it ([`Materials::brush`], [`Materials::set_textures`]);
//! raster-sink turns the same resolution into its raster brushes.
//!
//! With the feature `obj-quads`, a loader describes each face through `FaceMaterials`
//! (implemented for `obj_quads::Mesh`), and `Materials::resolve` decodes its textures once
//! (within obj-quads' texture limits), tints them by their factor and fits each textured
//! face's [`UvMap`].

#[cfg(feature = "obj-quads")]
mod decode;
mod image;
#[cfg(feature = "obj-quads")]
mod obj_mesh;
#[cfg(feature = "obj-quads")]
mod resolve;
mod uv_map;
#[cfg(feature = "obj-quads")]
mod wrapping;

use std::sync::Arc;

#[cfg(feature = "obj-quads")]
pub use decode::{TextureError, decode_image, load_image};
pub use image::Image;
#[cfg(feature = "obj-quads")]
pub use resolve::{FaceMaterials, MaterialOptions, MaterialWarning};
pub use uv_map::UvMap;

use crate::{Brush, Scene, SpriteSpace, TextureId};

/// How one face is painted, resolved from its material.
#[derive(Clone, Debug, PartialEq)]
pub enum FacePaint {
    /// The golden-angle palette colour of the face (no material).
    Palette,
    /// One colour, sRGB with straight alpha.
    Solid([u8; 4]),
    /// A texture.
    Texture {
        /// Index into [`Materials::images`].
        image: usize,
        /// Where each point of the face (centred model space) lands in the texture.
        map: UvMap,
    },
}

/// A model's materials resolved per face (`Materials::resolve`, feature `obj-quads`):
/// decoded (and tinted) images, each face's paint, and the material textures that could
/// not be loaded (their faces fall back to the diffuse colour).
#[derive(Clone, Debug, Default)]
pub struct Materials {
    faces: Vec<FacePaint>,
    images: Vec<Arc<Image>>,
    #[cfg(feature = "obj-quads")]
    warnings: Vec<MaterialWarning>,
}

impl Materials {
    /// Every face in its palette colour.
    #[must_use]
    pub fn palette() -> Self {
        Materials::default()
    }

    /// One solid colour per face (sRGB, straight alpha), in face order: materials for a
    /// mesh without a loader's materials (faces past the list keep the palette).
    #[must_use]
    pub fn solid(colours: impl IntoIterator<Item = [u8; 4]>) -> Self {
        Materials {
            faces: colours.into_iter().map(FacePaint::Solid).collect(),
            ..Materials::default()
        }
    }

    /// A face's paint ([`FacePaint::Palette`] for faces past the resolved ones).
    #[must_use]
    pub fn face(&self, face: u32) -> &FacePaint {
        self.faces.get(face as usize).unwrap_or(&FacePaint::Palette)
    }

    /// The number of resolved faces.
    #[must_use]
    pub fn face_count(&self) -> usize {
        self.faces.len()
    }

    /// The distinct images, each once (a tinted texture is its own image), in the order
    /// [`FacePaint::Texture`] and [`TextureId`]s index them.
    #[must_use]
    pub fn images(&self) -> &[Arc<Image>] {
        &self.images
    }

    /// The sprite brush of a face for a writer that draws no textures: its colour, a
    /// texture as the image's mean colour, the palette.
    #[must_use]
    pub fn brush(&self, face: u32) -> Brush {
        match self.face(face) {
            FacePaint::Palette => Brush::Palette,
            FacePaint::Solid(colour) => Brush::Solid(*colour),
            FacePaint::Texture { image, .. } => Brush::Solid(self.images[*image].mean_colour()),
        }
    }

    /// Gives every visible sprite of `scene` whose face has a texture its exact texture
    /// brush ([`set_plane_textures`](crate::set_plane_textures) with the faces' uv maps),
    /// [`TextureId`] `i` being [`images`](Self::images)`[i]`; the other sprites keep theirs.
    /// `space` is the painter's `SpriteSpace::of_view(view)`. Returns how many sprites got
    /// a texture.
    pub fn set_textures(&self, scene: &mut Scene, space: &SpriteSpace) -> usize {
        crate::set_plane_textures(scene, space, |face, p| match self.face(face) {
            FacePaint::Texture { image, map } => Some((TextureId(*image as u32), map.uv(p))),
            _ => None,
        })
    }
}
