//! xtask's use of `raster-sink`: pixel error for the bench and the fuzzer, and the render
//! command's style. Materials are resolved by sprite-compose (`Materials::resolve`),
//! raster brushes, shading and their sprite projection by raster-sink
//! (`Style::from_resolved`, `Style::sprite_brushes`); this module only adds the command
//! line's choices (a texture for the demo, the ground grid) and reports warnings.

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::Result;
use face_sort::{DrawList, Geometry, View};
pub use raster_sink::Truth;
use raster_sink::{Brush, GroundGrid, MaterialOptions, Style};
use sprite_compose::Materials;

/// Wrong and unambiguous pixel counts of one draw list.
#[derive(Clone, Copy, Debug, Default)]
pub struct ErrorCounts {
    /// Unambiguous pixels.
    pub pixels: u64,
    /// Of those, painted with the wrong face.
    pub wrong: u64,
}

/// The z-buffer truth of a view (`None` if the image would be empty).
pub fn truth(view: &View, geometry: &Geometry) -> Option<Truth> {
    Some(raster_sink::truth(view, geometry))
}

/// The pixel error of `list` painted under `view`, against `truth`.
pub fn pixel_error(view: &View, list: &DrawList, truth: &Truth) -> ErrorCounts {
    let painted = raster_sink::render_ids(view, list);
    let e = raster_sink::pixel_error(&painted, truth);
    ErrorCounts {
        pixels: e.pixels as u64,
        wrong: e.wrong as u64,
    }
}

/// The render command's per-face brushes: the mesh's materials resolved once
/// (sprite-compose's `Materials`, with `texture` for faces with uvs and no texture of their
/// own), as raster brushes with the ground grid on its face, and as they are for the vector
/// writers. Material textures that fail to load are reported and fall back to the diffuse
/// colour.
pub fn face_style(
    geometry: &Geometry,
    mesh: &obj_quads::Mesh,
    texture: Option<PathBuf>,
    grid: Option<&(u32, GroundGrid)>,
) -> Result<(Style, Materials)> {
    let mut options = MaterialOptions::DEFAULT;
    options.texture = texture;
    let materials = Materials::resolve(mesh, geometry.bounds().centre(), &options)
        .map_err(|e| anyhow::anyhow!("texture {e}"))?;
    for warning in materials.warnings() {
        eprintln!("warning: {warning}");
    }
    let mut style = Style::from_resolved(&materials).map_err(|e| anyhow::anyhow!("{e}"))?;
    if let Some((face, grid)) = grid {
        style.set_face(*face, Brush::Grid(Arc::new(grid.clone())));
    }
    Ok((style, materials))
}
