//! The colour raster on tiny-skia: render steps, brushes, shading, seams, supersampling.

use std::path::Path;

use face_sort::glam::{DVec2, DVec3};
use face_sort::{DrawItem, DrawList, Projection, View};
use tiny_skia::{
    FillRule, FilterQuality, Paint, PathBuilder, Pattern, Pixmap, PremultipliedColorU8, Shader,
    SpreadMode, Transform,
};

use crate::fill::for_each_span;
use crate::grid::GridShader;
use crate::ids::id_to_rgb;
use crate::project::{Projector, is_degenerate};
use crate::seams::{ScreenPolygons, SharedEdges, outset_polygon};
use crate::style::{Brush, Style, TextureBrush, golden_angle_colour};
use crate::{MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, RasterError};

/// A brush that replaces every face's own brush in a draw step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Override {
    /// Each face's brush from the [`Style`].
    #[default]
    None,
    /// Everything in one colour (sRGB, straight alpha).
    Solid([u8; 4]),
    /// Each face in its ID colour (face index + 1 as 24-bit RGB, opaque), as in ID images.
    /// Drawn by tiny-skia, so not exact at shared edges: use
    /// [`render_ids`](crate::render_ids) for measurements.
    IdColours,
    /// Each face in its palette colour ([`golden_angle_colour`]).
    Palette,
}

/// A directional light for flat Lambert shading: each face's colour is multiplied by
/// `ambient + (1 − ambient) · max(0, n · l)`, `n` its unit normal turned toward the viewer,
/// `l` the unit direction toward the light, both in view space (x right, y up, z toward the
/// viewer).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Direction toward the light, view space (need not be unit length).
    pub direction: DVec3,
    /// Light every face receives, 0..=1.
    pub ambient: f64,
}

impl Light {
    /// The Lambert factor `ambient + (1 − ambient) · max(0, n · l)` of a surface whose unit
    /// normal (view space, turned toward the viewer) is `normal`.
    #[must_use]
    pub fn factor(&self, normal: DVec3) -> f64 {
        let l = self.direction.normalize_or_zero();
        let ambient = self.ambient.clamp(0.0, 1.0);
        ambient + (1.0 - ambient) * normal.dot(l).max(0.0)
    }

    /// Light from the upper left front, ambient 0.3.
    pub const DEFAULT: Light = Light {
        direction: DVec3::new(-0.4, 0.6, 1.0),
        ambient: 0.3,
    };

    /// The [`factor`](Self::factor) of a face seen in `view` whose model-space normal (any
    /// length) is `normal`, turned toward the viewer along the view axis. Used for whole
    /// faces (sprite brushes); the raster shades each drawn piece by its own plane.
    #[must_use]
    pub fn facing_factor(&self, view: &View, normal: DVec3) -> f64 {
        let mut n = view.to_view(normal.normalize_or_zero());
        if n.z < 0.0 {
            n = -n;
        }
        self.factor(n)
    }
}

/// Multiplies the colour channels of a straight-alpha colour by a shading factor (alpha
/// unchanged), rounding to bytes.
#[must_use]
pub fn shade_colour(colour: [u8; 4], factor: f64) -> [u8; 4] {
    let m = |c: u8| (f64::from(c) * factor).round().clamp(0.0, 255.0) as u8;
    [m(colour[0]), m(colour[1]), m(colour[2]), colour[3]]
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

/// One step of a render: a small ordered list a caller may change (see [`default_steps`]).
#[derive(Clone, Copy)]
pub enum Step<'a> {
    /// Fill the canvas with a colour (sRGB, straight alpha).
    Clear([u8; 4]),
    /// Draw the list's items in order, those the filter keeps, with an optional override.
    Draw {
        /// Keeps an item when it returns true; `None` keeps all.
        filter: Option<&'a dyn Fn(DrawItem) -> bool>,
        /// Replaces the style's brushes.
        brush: Override,
    },
    /// Box-filter the supersampled canvas down to the output size (no-op without
    /// supersampling). Later draw steps draw at the output size.
    Resolve,
}

impl std::fmt::Debug for Step<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Step::Clear(c) => f.debug_tuple("Clear").field(c).finish(),
            Step::Draw { filter, brush } => f
                .debug_struct("Draw")
                .field("filter", &filter.is_some())
                .field("brush", brush)
                .finish(),
            Step::Resolve => f.write_str("Resolve"),
        }
    }
}

/// The steps [`render_colour`] runs: clear to the background, draw everything with the
/// options' override brush, resolve.
#[must_use]
pub fn default_steps(options: &RasterOptions) -> [Step<'static>; 3] {
    [
        Step::Clear(options.background),
        Step::Draw {
            filter: None,
            brush: options.brush_override,
        },
        Step::Resolve,
    ]
}

/// Renders a draw list in colour: [`default_steps`] through [`run_steps`].
pub fn render_colour(
    view: &View,
    list: &DrawList,
    style: &Style,
    options: &RasterOptions,
) -> Result<Pixmap, RasterError> {
    run_steps(view, list, style, options, &default_steps(options))
}

/// Checks an image size against [`MAX_IMAGE_SIDE`] and [`MAX_IMAGE_PIXELS`] and creates the
/// pixmap (tiny-skia aborts the process on huge sizes, so this check comes first).
pub fn new_pixmap(width: u64, height: u64) -> Result<Pixmap, RasterError> {
    let error = || RasterError::ImageSize {
        width,
        height,
        max_side: MAX_IMAGE_SIDE,
        max_pixels: MAX_IMAGE_PIXELS,
    };
    if width == 0
        || height == 0
        || width > u64::from(MAX_IMAGE_SIDE)
        || height > u64::from(MAX_IMAGE_SIDE)
        || width * height > MAX_IMAGE_PIXELS
    {
        return Err(error());
    }
    Pixmap::new(width as u32, height as u32).ok_or_else(error)
}

/// Runs render steps on a fresh canvas of the view's size times the supersampling factor
/// and returns the canvas (resolved or not, as the steps left it).
pub fn run_steps(
    view: &View,
    list: &DrawList,
    style: &Style,
    options: &RasterOptions,
    steps: &[Step<'_>],
) -> Result<Pixmap, RasterError> {
    let factor = options.supersample;
    if !(1..=MAX_SUPERSAMPLE).contains(&factor) {
        return Err(RasterError::InvalidOption {
            option: "supersample",
            message: format!("{factor} is not in 1..={MAX_SUPERSAMPLE}"),
        });
    }
    if !(1..=MAX_TEXTURE_SUBDIVISION).contains(&options.texture_subdivision) {
        return Err(RasterError::InvalidOption {
            option: "texture_subdivision",
            message: format!(
                "{} is not in 1..={MAX_TEXTURE_SUBDIVISION}",
                options.texture_subdivision
            ),
        });
    }
    if !(options.seam_outset.is_finite() && (0.0..=4.0).contains(&options.seam_outset)) {
        return Err(RasterError::InvalidOption {
            option: "seam_outset",
            message: format!("{} is not in 0..=4 pixels", options.seam_outset),
        });
    }
    let mut canvas = new_pixmap(
        u64::from(view.width()) * u64::from(factor),
        u64::from(view.height()) * u64::from(factor),
    )?;
    let mut current = factor;
    let mut painter = Painter::default();
    for step in steps {
        match *step {
            Step::Clear(colour) => {
                let [r, g, b, a] = colour;
                canvas.fill(tiny_skia::Color::from_rgba8(r, g, b, a));
            }
            Step::Draw { filter, brush } => {
                painter.draw(
                    &mut canvas,
                    current,
                    view,
                    list,
                    style,
                    options,
                    filter,
                    brush,
                )?;
            }
            Step::Resolve => {
                if current > 1 {
                    canvas = resolve(&canvas, current)?;
                    current = 1;
                }
            }
        }
    }
    Ok(canvas)
}

/// Box-filters a pixmap down by an integer factor.
fn resolve(canvas: &Pixmap, factor: u32) -> Result<Pixmap, RasterError> {
    let (w, h) = (canvas.width() / factor, canvas.height() / factor);
    let mut out = new_pixmap(u64::from(w), u64::from(h))?;
    let src = canvas.data();
    let stride = canvas.width() as usize * 4;
    let k = factor as usize;
    let n = (k * k) as u32;
    let dst = out.data_mut();
    for y in 0..h as usize {
        for x in 0..w as usize {
            let mut sum = [0u32; 4];
            for sy in 0..k {
                let row = (y * k + sy) * stride + x * k * 4;
                for sx in 0..k {
                    for c in 0..4 {
                        sum[c] += u32::from(src[row + sx * 4 + c]);
                    }
                }
            }
            let o = (y * w as usize + x) * 4;
            for c in 0..4 {
                dst[o + c] = ((sum[c] + n / 2) / n) as u8;
            }
        }
    }
    Ok(out)
}

/// Writes a pixmap as an 8-bit RGBA PNG (un-premultiplied).
pub fn save_png(pixmap: &Pixmap, path: impl AsRef<Path>) -> Result<(), RasterError> {
    let path = path.as_ref();
    let data = pixmap.encode_png().map_err(|e| RasterError::Png {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    std::fs::write(path, data).map_err(|source| RasterError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Reusable state of a draw step.
#[derive(Default)]
struct Painter {
    projector: Projector,
    polygons: ScreenPolygons,
    items: Vec<DrawItem>,
    shared: SharedEdges,
    outset: Vec<DVec2>,
    sub: Vec<DVec2>,
    sub_shared: Vec<bool>,
    tri3: Vec<DVec3>,
}

fn paint_for(colour: [u8; 4], anti_alias: bool) -> Paint<'static> {
    let mut paint = Paint::default();
    let [r, g, b, a] = colour;
    paint.set_color_rgba8(r, g, b, a);
    paint.anti_alias = anti_alias;
    paint
}

/// A closed tiny-skia path through pixel-space points; `None` when tiny-skia finds it empty.
#[must_use]
pub fn polygon_path(points: &[DVec2]) -> Option<tiny_skia::Path> {
    let mut builder = PathBuilder::new();
    for (i, p) in points.iter().enumerate() {
        if i == 0 {
            builder.move_to(p.x as f32, p.y as f32);
        } else {
            builder.line_to(p.x as f32, p.y as f32);
        }
    }
    builder.close();
    builder.finish()
}

fn fill(canvas: &mut Pixmap, points: &[DVec2], paint: &Paint<'_>) {
    if let Some(path) = polygon_path(points) {
        canvas.fill_path(&path, paint, FillRule::Winding, Transform::identity(), None);
    }
}

/// The affine transform taking texture pixels `tex` to screen points `screen` (three pairs
/// chosen among the polygon's corners for the largest uv area); `None` when degenerate.
fn texture_transform(screen: &[DVec2], tex: &[DVec2]) -> Option<Transform> {
    let n = screen.len().min(tex.len());
    let (mut best, mut pick) = (0.0, None);
    for j in 1..n {
        for k in j + 1..n {
            let area = (tex[j] - tex[0]).perp_dot(tex[k] - tex[0]).abs();
            if area > best {
                best = area;
                pick = Some((j, k));
            }
        }
    }
    let (j, k) = pick?;
    let (t1, t2) = (tex[j] - tex[0], tex[k] - tex[0]);
    let (s1, s2) = (screen[j] - screen[0], screen[k] - screen[0]);
    let det = t1.perp_dot(t2);
    // A = S · T⁻¹ with T = [t1 t2], S = [s1 s2] as columns.
    let inv = [t2.y / det, -t2.x / det, -t1.y / det, t1.x / det]; // rows of T⁻¹
    let a00 = s1.x * inv[0] + s2.x * inv[2];
    let a01 = s1.x * inv[1] + s2.x * inv[3];
    let a10 = s1.y * inv[0] + s2.y * inv[2];
    let a11 = s1.y * inv[1] + s2.y * inv[3];
    let tx = screen[0].x - (a00 * tex[0].x + a01 * tex[0].y);
    let ty = screen[0].y - (a10 * tex[0].x + a11 * tex[0].y);
    let values = [a00, a10, a01, a11, tx, ty];
    if !values.iter().all(|v| v.is_finite()) {
        return None;
    }
    Some(Transform::from_row(
        a00 as f32, a10 as f32, a01 as f32, a11 as f32, tx as f32, ty as f32,
    ))
}

impl Painter {
    #[expect(
        clippy::too_many_arguments,
        reason = "one internal call site, all distinct"
    )]
    fn draw(
        &mut self,
        canvas: &mut Pixmap,
        factor: u32,
        view: &View,
        list: &DrawList,
        style: &Style,
        options: &RasterOptions,
        filter: Option<&dyn Fn(DrawItem) -> bool>,
        brush_override: Override,
    ) -> Result<(), RasterError> {
        let k = f64::from(factor);
        self.polygons.clear();
        self.items.clear();
        for &item in list.items() {
            if filter.is_some_and(|f| !f(item)) {
                continue;
            }
            if !self.projector.project(view, list.corners(item)) {
                continue;
            }
            for p in self.projector.points.iter_mut() {
                *p *= k;
            }
            self.polygons.push(&self.projector.points);
            self.items.push(item);
        }
        let seams = options.anti_alias && options.seam_outset > 0.0;
        if seams {
            self.shared.compute(&self.polygons);
        }
        let (cw, ch) = (canvas.width(), canvas.height());
        for i in 0..self.items.len() {
            let item = self.items[i];
            let start = self.polygons.starts[i];
            let points = self.polygons.polygon(i);
            let flags = if seams {
                &self.shared.shared[start..start + points.len()]
            } else {
                &[][..]
            };
            let outset = if seams { options.seam_outset } else { 0.0 };
            let light = options
                .shading
                .map_or(1.0, |light| lambert(view, list, item, &light));
            let brush = match brush_override {
                Override::None => style.brush(item.face),
                _ => None,
            };
            let colour = match brush_override {
                Override::Solid(c) => Some(c),
                Override::IdColours => {
                    let [r, g, b] = id_to_rgb(item.face.wrapping_add(1));
                    Some([r, g, b, 255])
                }
                Override::Palette => Some(golden_angle_colour(item.face)),
                Override::None => match brush {
                    None => Some(golden_angle_colour(item.face)),
                    Some(Brush::Solid(c)) => Some(*c),
                    _ => None,
                },
            };
            let shading_applies = !matches!(brush_override, Override::IdColours);
            if let Some(colour) = colour {
                let colour = if shading_applies {
                    shade_colour(colour, light)
                } else {
                    colour
                };
                outset_polygon(points, flags, outset, &mut self.outset);
                fill(canvas, &self.outset, &paint_for(colour, options.anti_alias));
                continue;
            }
            match brush {
                Some(Brush::Grid(grid)) => {
                    let shader = GridShader::new(grid, view, k);
                    let data = canvas.pixels_mut();
                    for_each_span(points, cw, ch, |y, x0, x1| {
                        for x in x0..x1 {
                            let src = shader.shade(x, y);
                            if src[3] <= 0.0 {
                                continue;
                            }
                            let px = &mut data[(y * cw + x) as usize];
                            *px = blend_over(*px, src);
                        }
                    });
                }
                Some(Brush::Texture(texture)) => {
                    self.draw_textured(canvas, k, view, list, item, i, texture, options, light);
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// Draws one textured polygon, whole or subdivided.
    #[expect(
        clippy::too_many_arguments,
        reason = "one internal call site, all distinct"
    )]
    fn draw_textured(
        &mut self,
        canvas: &mut Pixmap,
        k: f64,
        view: &View,
        list: &DrawList,
        item: DrawItem,
        index: usize,
        texture: &TextureBrush,
        options: &RasterOptions,
        light: f64,
    ) {
        let seams = options.anti_alias && options.seam_outset > 0.0;
        let outset = if seams { options.seam_outset } else { 0.0 };
        let start = self.polygons.starts[index];
        let n_points = self.polygons.starts[index + 1] - start;
        let size = DVec2::new(
            f64::from(texture.image.width()),
            f64::from(texture.image.height()),
        );
        let corners = list.corners(item);
        let n = options.texture_subdivision;
        // Whole polygon: one transform. Near-clipped polygons (other corner count) are also
        // drawn whole, from the clipped screen polygon and their 3D corners' uvs.
        let clipped = n_points != corners.len();
        let mut parts: Vec<(Vec<DVec3>, Vec<bool>)> = Vec::new();
        if n <= 1 || clipped {
            let flags = if seams {
                self.shared.shared[start..start + n_points].to_vec()
            } else {
                vec![false; n_points]
            };
            parts.push((corners.to_vec(), flags));
        } else {
            subdivide(corners, n, |tri, boundary| {
                let flags = (0..3)
                    .map(|e| match boundary[e] {
                        None => true,
                        Some(edge) => seams && self.shared.shared[start + edge],
                    })
                    .collect();
                parts.push((tri.to_vec(), flags));
            });
        }
        for (part, flags) in &parts {
            let screen: Vec<DVec2> = if clipped {
                self.polygons.polygon(index).to_vec()
            } else {
                self.tri3.clear();
                self.tri3.extend_from_slice(part);
                if !self.projector.project(view, &self.tri3) {
                    continue;
                }
                self.projector.points.iter().map(|p| *p * k).collect()
            };
            if is_degenerate(&screen) {
                continue;
            }
            // Texture pixel coordinates of the 3D corners (for a clipped polygon: the screen
            // points are back-projected onto its plane instead).
            let tex: Vec<DVec2> = if clipped {
                screen
                    .iter()
                    .map(|s| texture.map.uv(unproject(view, list, item, *s / k)) * size)
                    .collect()
            } else {
                part.iter().map(|&p| texture.map.uv(p) * size).collect()
            };
            self.sub_shared.clear();
            self.sub_shared.extend_from_slice(flags);
            outset_polygon(
                &screen,
                &self.sub_shared,
                if seams { outset } else { 0.0 },
                &mut self.sub,
            );
            let Some(transform) = texture_transform(&screen, &tex) else {
                continue;
            };
            let mut paint = Paint {
                shader: Pattern::new(
                    Pixmap::as_ref(&texture.image),
                    SpreadMode::Repeat,
                    options.texture_quality,
                    1.0,
                    transform,
                ),
                ..Paint::default()
            };
            paint.anti_alias = options.anti_alias;
            fill(canvas, &self.sub, &paint);
            if light < 1.0 {
                let darken = ((1.0 - light) * 255.0).round().clamp(0.0, 255.0) as u8;
                let mut shadow = paint_for([0, 0, 0, darken], options.anti_alias);
                shadow.shader = Shader::SolidColor(tiny_skia::Color::from_rgba8(0, 0, 0, darken));
                fill(canvas, &self.sub, &shadow);
            }
        }
    }
}

/// Splits a convex polygon's fan triangles into `n × n` sub-triangles each; calls
/// `emit(triangle, boundary)` where `boundary[e]` is the polygon edge (corner index of its
/// start) that sub-triangle edge `e` lies on, or `None` for an internal edge.
fn subdivide(corners: &[DVec3], n: u32, mut emit: impl FnMut(&[DVec3; 3], [Option<usize>; 3])) {
    let m = corners.len();
    let nf = f64::from(n);
    for t in 1..m - 1 {
        let (a, b, c) = (corners[0], corners[t], corners[t + 1]);
        // Fan triangle edges: a→b is polygon edge 0 only for t == 1; b→c is polygon edge t;
        // c→a is polygon edge m−1 only for the last triangle.
        let edge_ab = (t == 1).then_some(0);
        let edge_bc = Some(t);
        let edge_ca = (t == m - 2).then_some(m - 1);
        let point = |i: u32, j: u32| {
            // Barycentric grid: i steps toward b, j toward c.
            a + (b - a) * (f64::from(i) / nf) + (c - a) * (f64::from(j) / nf)
        };
        for j in 0..n {
            for i in 0..n - j {
                // Upward triangle (i, j), (i+1, j), (i, j+1).
                let tri = [point(i, j), point(i + 1, j), point(i, j + 1)];
                let boundary = [
                    if j == 0 { edge_ab } else { None },
                    if i + j + 1 == n { edge_bc } else { None },
                    if i == 0 { edge_ca } else { None },
                ];
                emit(&tri, boundary);
                if i + j + 1 < n {
                    // Downward triangle (i+1, j), (i+1, j+1), (i, j+1): all internal.
                    let tri = [point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)];
                    emit(&tri, [None, None, None]);
                }
            }
        }
    }
}

/// The point of an item's plane (centred model space) seen at view pixel `p`.
fn unproject(view: &View, list: &DrawList, item: DrawItem, p: DVec2) -> DVec3 {
    let caster = face_sort::PixelRays::new(view);
    let (n, offset) = crate::truth::view_plane(view, list.plane(item));
    let (o, d) = caster.ray(p);
    let t = (offset - n.dot(o)) / n.dot(d);
    view.rotation().transpose() * (o + d * t)
}

/// Lambert factor of an item under a light.
fn lambert(view: &View, list: &DrawList, item: DrawItem, light: &Light) -> f64 {
    let mut n = view.to_view(list.plane(item).normal());
    let toward_viewer = match view.projection() {
        Projection::Orthographic => n.z,
        Projection::Perspective { .. } => {
            let eye = view.eye_in_view().unwrap_or(DVec3::Z);
            let v0 = list
                .corners(item)
                .first()
                .map_or(DVec3::ZERO, |&c| view.to_view(c));
            n.dot(eye - v0)
        }
    };
    if toward_viewer < 0.0 {
        n = -n;
    }
    light.factor(n)
}

/// `src` (premultiplied, 0..1) over `dst`.
fn blend_over(dst: PremultipliedColorU8, src: [f64; 4]) -> PremultipliedColorU8 {
    let inv = 1.0 - src[3];
    let c = |s: f64, d: u8| (s * 255.0 + f64::from(d) * inv).round().clamp(0.0, 255.0) as u8;
    let a = c(src[3], dst.alpha());
    let (r, g, b) = (
        c(src[0], dst.red()).min(a),
        c(src[1], dst.green()).min(a),
        c(src[2], dst.blue()).min(a),
    );
    PremultipliedColorU8::from_rgba(r, g, b, a).unwrap_or(dst)
}
