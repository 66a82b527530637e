//! What every page shares: one head, one background rule, and faces filled from the
//! materials.

use sprite_compose::Materials;

/// The start of every page: the document head up to its style sheet's first rule, a body of
/// `width` × `height` pixels on `background` with no margin and no scroll bars. The caller
/// writes its own rules, then closes the style sheet and the head.
pub(crate) fn head(title: &str, width: u32, height: u32, background: [u8; 4]) -> String {
    format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{title}</title><style>\n\
         html,body{{margin:0;padding:0;overflow:hidden;width:{width}px;height:{height}px;background:{}}}\n",
        crate::numbers::hex(background)
    )
}

/// A page's background: `explicit`, else black in ID mode (ID 0: no face) and white
/// otherwise, the PNG's background too.
pub(crate) fn background(explicit: Option<[u8; 4]>, ids: bool) -> [u8; 4] {
    explicit.unwrap_or(if ids {
        [0, 0, 0, 255]
    } else {
        [255, 255, 255, 255]
    })
}

/// A face's fill from `materials` (a texture as its mean colour; the palette where there are
/// none or the face has no material).
pub(crate) fn face_colour(materials: Option<&Materials>, face: u32) -> [u8; 4] {
    materials.map_or_else(
        || sprite_compose::Brush::Palette.solid_colour(face),
        |m| m.brush(face).solid_colour(face),
    )
}

/// The setters the pages' options share, written once: `page_setters!(SvgOptions: size,
/// ids, background)` gives `SvgOptions` those `with_…` setters, each of the same field and
/// meaning in every options type.
macro_rules! page_setters {
    ($options:ty: $($setter:ident),+ $(,)?) => {
        impl $options {
            $(crate::page::page_setters!(@$setter);)+
        }
    };
    (@size) => {
        /// Image size in pixels.
        #[must_use]
        pub fn with_size(mut self, width: u32, height: u32) -> Self {
            self.width = width;
            self.height = height;
            self
        }
    };
    (@ids) => {
        /// ID colours (CONVENTIONS.md) instead of the faces' paint.
        #[must_use]
        pub fn with_ids(mut self, ids: bool) -> Self {
            self.ids = ids;
            self
        }
    };
    (@background) => {
        /// The background (`None`: the writer's default, which its `background` field
        /// documents).
        #[must_use]
        pub fn with_background(mut self, background: Option<[u8; 4]>) -> Self {
            self.background = background;
            self
        }
    };
    (@hidden) => {
        /// What becomes of the parts opaque faces in front hide ([`HiddenParts`](crate::HiddenParts)).
        #[must_use]
        pub fn with_hidden(mut self, hidden: crate::HiddenParts) -> Self {
            self.hidden = hidden;
            self
        }
    };
    (@textures) => {
        /// The `src` of each texture, indexed by `TextureId` (a data URI or a link).
        #[must_use]
        pub fn with_textures(mut self, textures: Vec<String>) -> Self {
            self.textures = textures;
            self
        }
    };
    (@seam_stroke) => {
        /// Seam stroke width in pixels (0: off).
        #[must_use]
        pub fn with_seam_stroke(mut self, width: f64) -> Self {
            self.seam_stroke = width;
            self
        }
    };
    (@materials) => {
        /// Faces filled from `materials` in colour mode (a texture as its mean colour).
        #[must_use]
        pub fn with_materials(mut self, materials: &crate::Materials) -> Self {
            self.materials = Some(std::sync::Arc::new(materials.clone()));
            self
        }
    };
}
pub(crate) use page_setters;
