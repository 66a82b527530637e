//! The bench's and the fuzzer's view of `raster-sink`: truth and pixel error.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::Result;
use face_sort::glam::{DVec2, DVec3};
use face_sort::{DrawList, Geometry, View};
pub use raster_sink::Truth;
use raster_sink::tiny_skia::Pixmap;
use raster_sink::{Brush, Light, RasterOptions, Style, TextureBrush, UvMap};

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

/// Colour options of `render`.
#[derive(Clone, Debug)]
pub struct ColourOptions {
    /// Anti-aliased edges.
    pub anti_alias: bool,
    /// Flat Lambert shading.
    pub shade: bool,
    /// Face index of the ground grid's quad, and the grid, when there is one.
    pub grid: Option<(u32, raster_sink::GroundGrid)>,
    /// A texture for meshes with uvs but no material texture (the demo's spot).
    pub texture: Option<PathBuf>,
}

/// Paints `list` in order with raster-sink in the colours of [`face_style`].
pub fn render_colour(
    view: &View,
    geometry: &Geometry,
    list: &DrawList,
    mesh: &obj_quads::Mesh,
    options: &ColourOptions,
) -> Result<Pixmap> {
    let style = face_style(geometry, mesh, options)?;
    let raster_options = RasterOptions::DEFAULT
        .with_anti_alias(options.anti_alias)
        .with_shading(options.shade.then_some(Light::DEFAULT));
    raster_sink::render_colour(view, list, &style, &raster_options)
        .map_err(|e| anyhow::anyhow!("raster: {e}"))
}

/// The sprite brush closest to a raster brush, for the SVG and HTML writers: solid colours
/// as they are, a texture as its mean colour, the ground grid transparent; with `shading`,
/// solid colours are flat-shaded for this view (`normal`: the face's model-space normal).
pub fn sprite_brush(
    style: &Style,
    face: u32,
    shading: Option<(&View, DVec3)>,
) -> sprite_compose::Brush {
    let shaded = |colour: [u8; 4]| match shading {
        Some((view, normal)) => {
            let mut n = view.to_view(normal.normalize_or_zero());
            if n.z < 0.0 {
                n = -n;
            }
            let k = Light::DEFAULT.factor(n);
            let c = |v: u8| (f64::from(v) * k).round().clamp(0.0, 255.0) as u8;
            [c(colour[0]), c(colour[1]), c(colour[2]), colour[3]]
        }
        None => colour,
    };
    match style.brush(face) {
        Some(Brush::Solid(colour)) => sprite_compose::Brush::Solid(shaded(*colour)),
        Some(Brush::Texture(texture)) => {
            sprite_compose::Brush::Solid(shaded(mean_colour(&texture.image)))
        }
        Some(Brush::Grid(_)) => sprite_compose::Brush::Solid([0, 0, 0, 0]),
        _ => sprite_compose::Brush::Palette,
    }
}

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

/// Per-face brushes: material textures (or `options.texture`) where the mesh has uvs,
/// material diffuse colours, else the golden-angle palette; the ground grid on its face.
pub fn face_style(
    geometry: &Geometry,
    mesh: &obj_quads::Mesh,
    options: &ColourOptions,
) -> Result<Style> {
    let mut style = Style::palette();
    let mut textures: HashMap<PathBuf, Option<Arc<Pixmap>>> = HashMap::new();
    let mut load = |path: &Path| -> Result<Option<Arc<Pixmap>>> {
        if let Some(t) = textures.get(path) {
            return Ok(t.clone());
        }
        let image = Pixmap::load_png(path)
            .map(Arc::new)
            .map_err(|e| anyhow::anyhow!("texture {}: {e}", path.display()));
        // A missing or unreadable material texture falls back to the diffuse colour (with
        // a warning); an explicitly requested one is an error.
        let image = match image {
            Ok(image) => Some(image),
            Err(e) if options.texture.as_deref() == Some(path) => return Err(e),
            Err(e) => {
                eprintln!("warning: {e:#}; using the diffuse colour");
                None
            }
        };
        textures.insert(path.to_owned(), image.clone());
        Ok(image)
    };
    let centre = geometry.bounds().centre();
    let positions = mesh.positions();
    for face in 0..mesh.face_count() {
        let material = mesh
            .face_material(face)
            .and_then(|m| mesh.materials().get(m as usize));
        let texture_path = material
            .and_then(|m| m.texture.clone())
            .or_else(|| options.texture.clone());
        let brush = match (texture_path, mesh.face_uvs(face), mesh.face(face)) {
            (Some(path), Some(uvs), Some(indices)) => load(&path)?.and_then(|image| {
                let corners: Vec<DVec3> = indices
                    .iter()
                    .map(|&i| positions[i as usize] - centre)
                    .collect();
                let uvs: Vec<DVec2> = uvs
                    .iter()
                    .map(|uv| DVec2::new(f64::from(uv.x), 1.0 - f64::from(uv.y)))
                    .collect();
                UvMap::fit(&corners, &uvs).map(|map| Brush::Texture(TextureBrush { image, map }))
            }),
            _ => None,
        };
        let brush = brush.or_else(|| {
            material.map(|m| {
                let c = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
                Brush::Solid([
                    c(m.diffuse[0]),
                    c(m.diffuse[1]),
                    c(m.diffuse[2]),
                    c(m.diffuse[3]),
                ])
            })
        });
        if let Some(brush) = brush {
            style.set_face(face as u32, brush);
        }
    }
    if let Some((face, grid)) = &options.grid {
        style.set_face(*face, Brush::Grid(Arc::new(grid.clone())));
    }
    Ok(style)
}

/// Writes a colour image as PNG.
pub fn save_colour(pixmap: &Pixmap, path: &Path) -> Result<()> {
    raster_sink::save_png(pixmap, path).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
}
