//! Vector files of triangles through a WebGL camera: the exact SVG (sprite-compose's
//! `Export`) and the visible edges for pen plotters.

use face_sort::Geometry;
use sprite_compose::{Materials, PlotOptions, plot_edges};
use vector_sink::{Export, HiddenParts, SvgOptions, write_svg};

use crate::error::BindError;
use crate::input::{self, Triangles};

/// A camera as JS hands it over: view and projection matrices (column-major), the image
/// size, and which faces are drawn.
#[derive(Clone, Copy, Debug)]
pub struct CameraArgs<'a> {
    /// `camera.matrixWorldInverse.elements`.
    pub view: &'a [f64],
    /// `camera.projectionMatrix.elements`.
    pub projection: &'a [f64],
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// `"back"`, `"front"` or `"none"`.
    pub cull: &'a str,
}

impl CameraArgs<'_> {
    /// The view of `geometry` through this camera.
    fn view_of(&self, geometry: &Geometry) -> Result<face_sort::View, BindError> {
        input::view(
            geometry,
            self.view,
            self.projection,
            self.width,
            self.height,
            input::cull_mode(self.cull)?,
        )
    }
}

/// What the SVG holds of what cannot be seen.
fn hidden_parts(hidden: &str) -> Result<HiddenParts, BindError> {
    match hidden {
        "remove" => Ok(HiddenParts::Remove),
        "keep" => Ok(HiddenParts::Keep),
        other => Err(BindError::argument(
            "hidden",
            format!("must be \"remove\" or \"keep\", not {other:?}"),
        )),
    }
}

/// The exact SVG of the triangles in their colours (or, with `ids`, in the ID colours of
/// CONVENTIONS.md: triangle index + 1 as 24-bit RGB, no background). Hidden parts are
/// removed (`"remove"`) or kept (`"keep"`); removal treats every face as opaque, so it is
/// refused when a colour is translucent.
pub fn svg(
    triangles: &Triangles,
    colours: &[u8],
    camera: CameraArgs<'_>,
    hidden: &str,
    ids: bool,
) -> Result<String, BindError> {
    let hidden = hidden_parts(hidden)?;
    let model = triangles.coloured_model(colours)?;
    if hidden == HiddenParts::Remove
        && !ids
        && let Some(k) = colours.chunks_exact(4).position(|c| c[3] < 255)
    {
        return Err(BindError::argument(
            "hidden",
            format!(
                "\"remove\" hides what lies behind, but triangle {k} is translucent: use \"keep\""
            ),
        ));
    }
    let geometry = Geometry::new(&triangles.polygon_mesh()?)?;
    let view = camera.view_of(&geometry)?;
    let export = Export::new(&geometry, view).with_hidden(hidden);
    if ids {
        let options = SvgOptions::DEFAULT
            .with_size(camera.width, camera.height)
            .with_hidden(hidden)
            .with_ids(true)
            .with_background(None);
        return Ok(write_svg(export.scene(), &options));
    }
    let materials = Materials::of(&model, &geometry)
        .map_err(|e| BindError::argument("colours", e.to_string()))?;
    Ok(export.with_materials(&materials).svg())
}

/// The visible edges (outlines, creases at least `crease_deg` apart, intersection lines)
/// as SVG strokes `stroke_px` wide.
pub fn plot_svg(
    triangles: &Triangles,
    camera: CameraArgs<'_>,
    crease_deg: f64,
    stroke_px: f64,
) -> Result<String, BindError> {
    if !(0.0..=180.0).contains(&crease_deg) {
        return Err(BindError::argument(
            "crease",
            format!("must be an angle in 0..=180 degrees, got {crease_deg}"),
        ));
    }
    if !(stroke_px.is_finite() && stroke_px > 0.0) {
        return Err(BindError::argument(
            "stroke",
            format!("must be a positive width in pixels, got {stroke_px}"),
        ));
    }
    let mesh = triangles.polygon_mesh()?;
    let geometry = Geometry::new(&mesh)?;
    let view = camera.view_of(&geometry)?;
    let plot = plot_edges(
        &mesh,
        &geometry,
        &view,
        &PlotOptions::DEFAULT.with_crease_deg(crease_deg),
    );
    Ok(vector_sink::plot_svg(&plot, stroke_px))
}
