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
