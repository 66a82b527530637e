//! What each face is painted with: solid colours, textures, the ground grid, the palette.

use std::sync::Arc;

use tiny_skia::Pixmap;

use crate::grid::GroundGrid;
use sprite_compose::UvMap;

/// How one face is painted.
#[derive(Clone, Debug)]
pub enum Brush {
    /// One colour, sRGB with straight (not premultiplied) alpha.
    Solid([u8; 4]),
    /// A texture mapped through the face's affine uv map.
    Texture(TextureBrush),
    /// The procedural ground grid (for the face made by [`GroundGrid::quad`]).
    Grid(Arc<GroundGrid>),
}

/// A texture and the affine map from a face's plane to texture coordinates.
#[derive(Clone, Debug)]
pub struct TextureBrush {
    /// The texture (tiny-skia pixmaps are premultiplied RGBA).
    pub image: Arc<Pixmap>,
    /// Where each point of the face lands in the texture.
    pub map: UvMap,
}

/// Per-face brushes, with the golden-angle palette for faces that have none.
#[derive(Clone, Debug, Default)]
pub struct Style {
    faces: Vec<Option<Brush>>,
    default: Option<Brush>,
}

impl Style {
    /// Every face in its palette colour ([`face_sort::colours::golden_angle_colour`]).
    #[must_use]
    pub fn palette() -> Self {
        Style::default()
    }

    /// Every face in one colour (sRGB, straight alpha).
    #[must_use]
    pub fn solid(colour: [u8; 4]) -> Self {
        Style {
            faces: Vec::new(),
            default: Some(Brush::Solid(colour)),
        }
    }

    /// The brush of faces without their own brush (`None`: the palette).
    #[must_use]
    pub fn with_default(mut self, brush: Option<Brush>) -> Self {
        self.default = brush;
        self
    }

    /// Sets the brush of one face.
    pub fn set_face(&mut self, face: u32, brush: Brush) {
        let i = face as usize;
        if self.faces.len() <= i {
            self.faces.resize(i + 1, None);
        }
        self.faces[i] = Some(brush);
    }

    /// [`set_face`](Self::set_face), builder style.
    #[must_use]
    pub fn with_face(mut self, face: u32, brush: Brush) -> Self {
        self.set_face(face, brush);
        self
    }

    /// One more than the highest face with its own brush (0 when none has).
    #[must_use]
    pub fn face_slots(&self) -> usize {
        self.faces
            .iter()
            .rposition(Option::is_some)
            .map_or(0, |i| i + 1)
    }

    /// The brush of a face: its own, else the default; `None` means the palette colour.
    #[must_use]
    pub fn brush(&self, face: u32) -> Option<&Brush> {
        self.faces
            .get(face as usize)
            .and_then(Option::as_ref)
            .or(self.default.as_ref())
    }
}
