//! The ground grid: a face in the scene with a procedural, level-of-detail line brush.

use face_sort::glam::{DVec2, DVec3};
use face_sort::{Bounds, View};

use face_sort::PixelRays;

use crate::tolerance::UNDERFLOW_ABS;

/// A square grid on the model's ground plane `y = bounds.min.y`, centred under the model.
///
/// Add [`quad`](Self::quad) to the mesh as one more face (so it is culled, sorted and split
/// like any other), and paint that face with [`Brush::Grid`](crate::Brush::Grid). Adding it
/// changes the mesh bounds and hence the view's centre and fit: build the view from the
/// bounds of the mesh *with* the grid.
///
/// The brush draws anti-aliased lines `cell` apart, every tenth line thicker. Lines are
/// kept in screen pixels wide; where the cells of a decade get denser than
/// [`FULL_DETAIL_PX`](Self::FULL_DETAIL_PX) pixels that decade fades out (fully gone at
/// [`MIN_SPACING_PX`](Self::MIN_SPACING_PX)) and the next decade takes over, so there is no
/// moiré far away. Opacity falls off toward the grid's extent and at grazing view angles.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct GroundGrid {
    /// Centre of the grid on the ground plane (model space).
    pub origin: DVec3,
    /// Side length of the square grid (model units).
    pub size: f64,
    /// Cell size (model units). Default: `size / 20`.
    pub cell: f64,
    /// Colour of thin lines, sRGB with straight alpha. Default: `[90, 90, 90, 200]`.
    pub thin: [u8; 4],
    /// Colour of every tenth line, sRGB with straight alpha. Default: `[40, 40, 40, 255]`.
    pub thick: [u8; 4],
    /// Width of thin lines in pixels. Default: 1.
    pub thin_width: f64,
    /// Width of thick lines in pixels. Default: 2.
    pub thick_width: f64,
    /// Fraction of the half-size where the fade toward the extent starts. Default: 0.6.
    pub fade_start: f64,
    /// `|cos|` of the angle between a pixel ray and the ground normal below which the grid
    /// starts to fade; fully transparent at a fifth of it. Default: 0.3.
    pub grazing_fade: f64,
}

impl GroundGrid {
    /// Line spacing (pixels) below which a decade of lines is invisible.
    pub const MIN_SPACING_PX: f64 = 2.0;
    /// Line spacing (pixels) from which a decade is fully visible (10× the minimum).
    pub const FULL_DETAIL_PX: f64 = 20.0;

    /// A grid `size` units wide under a model with these bounds, cells `size / 20`.
    #[must_use]
    pub fn new(bounds: &Bounds, size: f64) -> Self {
        let c = bounds.centre();
        GroundGrid {
            origin: DVec3::new(c.x, bounds.min.y, c.z),
            size,
            cell: size / 20.0,
            thin: [90, 90, 90, 200],
            thick: [40, 40, 40, 255],
            thin_width: 1.0,
            thick_width: 2.0,
            fade_start: 0.6,
            grazing_fade: 0.3,
        }
    }

    /// Cell size (model units).
    #[must_use]
    pub fn with_cell(mut self, cell: f64) -> Self {
        self.cell = cell;
        self
    }

    /// Thin and thick line colours (sRGB, straight alpha).
    #[must_use]
    pub fn with_colours(mut self, thin: [u8; 4], thick: [u8; 4]) -> Self {
        self.thin = thin;
        self.thick = thick;
        self
    }

    /// Thin and thick line widths in pixels.
    #[must_use]
    pub fn with_line_widths(mut self, thin: f64, thick: f64) -> Self {
        self.thin_width = thin;
        self.thick_width = thick;
        self
    }

    /// Where the fade toward the extent starts (fraction of the half-size).
    #[must_use]
    pub fn with_fade_start(mut self, fade_start: f64) -> Self {
        self.fade_start = fade_start;
        self
    }

    /// Grazing-angle fade threshold (`|cos|` of ray to ground normal).
    #[must_use]
    pub fn with_grazing_fade(mut self, grazing_fade: f64) -> Self {
        self.grazing_fade = grazing_fade;
        self
    }

    /// The grid's face: four corners (model space) counter-clockwise seen from above, so its
    /// front faces +Y.
    #[must_use]
    pub fn quad(&self) -> [DVec3; 4] {
        let h = self.size * 0.5;
        let o = self.origin;
        [
            o + DVec3::new(-h, 0.0, h),
            o + DVec3::new(h, 0.0, h),
            o + DVec3::new(h, 0.0, -h),
            o + DVec3::new(-h, 0.0, -h),
        ]
    }
}

/// Per-view precomputation of the grid shader.
pub(crate) struct GridShader<'a> {
    grid: &'a GroundGrid,
    caster: PixelRays,
    /// Ground normal (+Y) in view space.
    normal: DVec3,
    /// Ground plane offset in view space (`normal · v = offset`).
    offset: f64,
    view: View,
    /// Ground origin in centred model space.
    origin: DVec3,
    /// Canvas pixels per view pixel (supersampling factor).
    factor: f64,
    thin: [f64; 4],
    thick: [f64; 4],
}

fn unit_colour(c: [u8; 4]) -> [f64; 4] {
    c.map(|v| f64::from(v) / 255.0)
}

fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl<'a> GridShader<'a> {
    pub(crate) fn new(grid: &'a GroundGrid, view: &View, factor: f64) -> Self {
        let origin = grid.origin - view.centre();
        let (normal, offset) = view.plane_to_view(DVec3::Y, origin.y);
        GridShader {
            grid,
            caster: PixelRays::new(view),
            normal,
            offset,
            view: *view,
            origin,
            factor,
            thin: unit_colour(grid.thin),
            thick: unit_colour(grid.thick),
        }
    }

    /// Ground coordinates (model units from the grid origin, x and z) where the ray through
    /// canvas point `p` meets the ground, and `|cos|` of its angle to the ground normal.
    fn ground(&self, p: DVec2) -> Option<(DVec2, f64)> {
        let (o, d) = self.caster.ray(p / self.factor);
        let denom = self.normal.dot(d);
        if denom == 0.0 {
            return None;
        }
        let t = (self.offset - self.normal.dot(o)) / denom;
        let v = o + d * t;
        let m = self.view.to_centred(v) - self.origin;
        let cos = (denom / d.length()).abs();
        m.is_finite().then_some((DVec2::new(m.x, m.z), cos))
    }

    /// Premultiplied RGBA (0..1) of the grid at canvas pixel `(x, y)`.
    pub(crate) fn shade(&self, x: u32, y: u32) -> [f64; 4] {
        let p = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
        let (Some((g, cos)), Some((gx, _)), Some((gy, _))) = (
            self.ground(p),
            self.ground(p + DVec2::X),
            self.ground(p + DVec2::Y),
        ) else {
            return [0.0; 4];
        };
        let grid = self.grid;
        let half = grid.size * 0.5;
        let extent = g.x.abs().max(g.y.abs()) / half;
        let fade = (1.0 - smoothstep(grid.fade_start, 1.0, extent))
            * smoothstep(grid.grazing_fade * 0.2, grid.grazing_fade, cos);
        if fade <= 0.0 || grid.cell.is_nan() || grid.cell <= 0.0 {
            return [0.0; 4];
        }
        // Footprint of one pixel in ground units, per ground axis (like GLSL fwidth).
        let (dx, dy) = (gx - g, gy - g);
        let fw = DVec2::new(dx.x.abs() + dy.x.abs(), dx.y.abs() + dy.y.abs())
            .max(DVec2::splat(UNDERFLOW_ABS));
        let footprint = fw.x.max(fw.y);
        let finest = ((GroundGrid::MIN_SPACING_PX * footprint / grid.cell)
            .log10()
            .floor()
            + 1.0)
            .max(0.0);
        if !finest.is_finite() || finest > 300.0 {
            return [0.0; 4];
        }
        let visibility = |spacing: f64| {
            ((spacing / footprint / GroundGrid::MIN_SPACING_PX).log10()
                / (GroundGrid::FULL_DETAIL_PX / GroundGrid::MIN_SPACING_PX).log10())
            .clamp(0.0, 1.0)
        };
        let coverage = |spacing: f64, width: f64| {
            let axis = |u: f64, fw: f64| {
                let r = u / spacing;
                let d = (r - r.round()).abs() * spacing / fw;
                (0.5 * width + 0.5 - d).clamp(0.0, 1.0)
            };
            axis(g.x, fw.x).max(axis(g.y, fw.y))
        };
        let s0 = grid.cell * 10f64.powf(finest);
        let v0 = visibility(s0);
        let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
        let mid: [f64; 4] = std::array::from_fn(|i| lerp(self.thin[i], self.thick[i], v0));
        let layers = [
            (s0, self.thin, grid.thin_width, v0),
            (
                s0 * 10.0,
                mid,
                lerp(grid.thin_width, grid.thick_width, v0),
                1.0,
            ),
            (s0 * 100.0, self.thick, grid.thick_width, 1.0),
        ];
        let mut out = [0.0f64; 4];
        for (spacing, colour, width, vis) in layers {
            let a = coverage(spacing, width) * vis * colour[3] * fade;
            if a <= 0.0 {
                continue;
            }
            for c in 0..3 {
                out[c] = colour[c] * a + out[c] * (1.0 - a);
            }
            out[3] = a + out[3] * (1.0 - a);
        }
        out
    }
}
