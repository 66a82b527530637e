//! What every page shares: one background rule, and faces filled from the materials.

use sprite_compose::Materials;

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
