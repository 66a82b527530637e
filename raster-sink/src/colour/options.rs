//! Options of the colour raster: the override brush, `RasterOptions` and their limits.

use tiny_skia::FilterQuality;

use super::shading::Light;

/// A brush that replaces every face's own brush in a draw step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Override {
    /// Each face's brush from the [`Style`](crate::Style).
    #[default]
    None,
    /// Everything in one colour (sRGB, straight alpha).
    Solid([u8; 4]),
    /// Each face in its ID colour (face index + 1 as 24-bit RGB, opaque), as in ID images.
    /// Drawn by tiny-skia, so not exact at shared edges: use
    /// [`render_ids`](crate::render_ids) for measurements.
    IdColours,
    /// Each face in its palette colour ([`face_sort::colours::golden_angle_colour`]).
    Palette,
}

/// Options of the colour raster.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct RasterOptions {
    /// Anti-aliased polygon edges. Default: true.
    pub anti_alias: bool,
    /// Background colour (sRGB, straight alpha) of the clear step. Default: opaque white.
    pub background: [u8; 4],
    /// How far (pixels of the drawing canvas) each polygon's fill is pushed out across the
    /// edges it shares with another drawn polygon, so that anti-aliased neighbours leave no
    /// hairline of background (see the crate docs). 0 turns it off; only used with
    /// anti-aliasing. Default: 0.5.
    pub seam_outset: f64,
    /// Flat Lambert shading. Default: `None` (unlit colours).
    pub shading: Option<Light>,
    /// Draw at `supersample ×` the size and box-filter down (1 = off). Default: 1.
    pub supersample: u32,
    /// Brush that replaces the style in the default draw step. Default: [`Override::None`].
    pub brush_override: Override,
    /// Each textured polygon is cut into `n × n` pieces per fan triangle, each with its own
    /// affine texture transform, so that perspective distorts the texture less (1 = off).
    /// Default: 1.
    pub texture_subdivision: u32,
    /// Texture filtering. Default: bilinear.
    pub texture_quality: FilterQuality,
}

impl RasterOptions {
    /// The defaults.
    pub const DEFAULT: RasterOptions = RasterOptions {
        anti_alias: true,
        background: [255, 255, 255, 255],
        seam_outset: 0.5,
        shading: None,
        supersample: 1,
        brush_override: Override::None,
        texture_subdivision: 1,
        texture_quality: FilterQuality::Bilinear,
    };

    /// Anti-aliasing on or off.
    #[must_use]
    pub fn with_anti_alias(mut self, on: bool) -> Self {
        self.anti_alias = on;
        self
    }
    /// Background colour.
    #[must_use]
    pub fn with_background(mut self, colour: [u8; 4]) -> Self {
        self.background = colour;
        self
    }
    /// Seam outset in canvas pixels (0 = off).
    #[must_use]
    pub fn with_seam_outset(mut self, pixels: f64) -> Self {
        self.seam_outset = pixels;
        self
    }
    /// Flat Lambert shading.
    #[must_use]
    pub fn with_shading(mut self, light: Option<Light>) -> Self {
        self.shading = light;
        self
    }
    /// Supersampling factor (1 = off).
    #[must_use]
    pub fn with_supersample(mut self, factor: u32) -> Self {
        self.supersample = factor;
        self
    }
    /// Override brush of the default draw step.
    #[must_use]
    pub fn with_brush_override(mut self, brush: Override) -> Self {
        self.brush_override = brush;
        self
    }
    /// Texture subdivision `n` (1 = off).
    #[must_use]
    pub fn with_texture_subdivision(mut self, n: u32) -> Self {
        self.texture_subdivision = n;
        self
    }
    /// Texture filtering.
    #[must_use]
    pub fn with_texture_quality(mut self, quality: FilterQuality) -> Self {
        self.texture_quality = quality;
        self
    }
}

impl Default for RasterOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Largest supersampling factor.
pub const MAX_SUPERSAMPLE: u32 = 16;
/// Largest texture subdivision.
pub const MAX_TEXTURE_SUBDIVISION: u32 = 64;
