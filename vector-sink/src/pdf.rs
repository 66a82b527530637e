//! The PDF writer: a scene's visible sprites as filled vector paths in paint order, through
//! `pdf-writer`.

use std::collections::HashMap;
use std::sync::Arc;

use glam::{DAffine2, DVec2};

use pdf_writer::types::{LineCapStyle, LineJoinStyle};
use pdf_writer::{Content, Filter, Finish, Name, Pdf, Rect, Ref};

use crate::hidden::{VectorShape, vector_shapes};
use crate::svg::{dilate, texture_cells};
use crate::tolerance::{SPLASH_ORDER_MARGIN, SVG_TEXTURE_PX};
use crate::{Brush, DrawnOverlay, HiddenParts, Image, Scene, Visibility, id_colour};

/// Options of [`write_pdf`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct PdfOptions {
    /// Image width in pixels. Default: 256.
    pub width: u32,
    /// Image height in pixels. Default: 256.
    pub height: u32,
    /// PDF points per pixel: the page is `width · points_per_pixel` wide. Default: 1 (one
    /// pixel to one point, so that a rasteriser at 72 dpi gives back the image size).
    pub points_per_pixel: f64,
    /// Fill each sprite with its face's ID colour (CONVENTIONS.md). Default: false.
    pub ids: bool,
    /// Background colour (`None`: none, the page stays transparent). Default: `None`.
    pub background: Option<[u8; 4]>,
    /// Width in pixels of a stroke in each opaque solid polygon's own colour (hides the
    /// hairlines that anti-aliasing viewers leave along shared edges; textured polygons have
    /// their clip grown by half of it instead); never in ID mode. Default: 1, as in SVG.
    pub seam_stroke: f64,
    /// Keep or remove hidden parts (as [`SvgOptions::hidden`](crate::SvgOptions::hidden)).
    /// Default: keep.
    pub hidden: HiddenParts,
    /// Lines and points drawn after the faces, in their own colours (their visible parts,
    /// [`visible_overlay`](sprite_compose::visible_overlay)), in ID mode too. Default: none.
    pub overlay: Option<DrawnOverlay>,
    /// The images of [`Brush::Texture`] sprites, indexed by [`TextureId`](sprite_compose::TextureId)
    /// (e.g. [`Materials::images`](crate::Materials::images)): each written once as an image
    /// XObject (deflated RGB, with a soft mask when it has alpha) and drawn per sprite under
    /// its clip by the exact affine map, cut into cells under perspective as the SVG writer
    /// does. A textured sprite without its image is filled with its fallback colour.
    /// Default: none.
    pub images: Vec<Arc<Image>>,
    /// Largest distance (pixels) between a textured cell's affine map and the exact
    /// projective one. Default: [`SVG_TEXTURE_PX`].
    pub texture_tolerance: f64,
}

impl PdfOptions {
    /// The defaults.
    pub const DEFAULT: PdfOptions = PdfOptions {
        width: 256,
        height: 256,
        points_per_pixel: 1.0,
        ids: false,
        background: None,
        seam_stroke: 1.0,
        hidden: HiddenParts::Keep,
        overlay: None,
        images: Vec::new(),
        texture_tolerance: SVG_TEXTURE_PX,
    };

    /// The images of textured sprites, indexed by texture id.
    #[must_use]
    pub fn with_images(mut self, images: Vec<Arc<Image>>) -> Self {
        self.images = images;
        self
    }

    /// Lines and points drawn after the faces.
    #[must_use]
    pub fn with_overlay(mut self, overlay: DrawnOverlay) -> Self {
        self.overlay = Some(overlay);
        self
    }

    /// Points per pixel.
    #[must_use]
    pub fn with_points_per_pixel(mut self, points: f64) -> Self {
        self.points_per_pixel = points;
        self
    }
}

crate::page::page_setters!(PdfOptions: size, ids, background, hidden, seam_stroke);

impl Default for PdfOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The scene's visible sprites as a one-page PDF: one filled path per sprite in paint order
/// (the even-odd visible parts under [`HiddenParts::Remove`]), in DeviceRGB, the page the image
/// size times [`PdfOptions::points_per_pixel`]. Textured sprites are filled with their fallback
/// colour; translucent colours are written opaque (no transparency group).
#[must_use]
pub fn write_pdf(scene: &Scene, options: &PdfOptions) -> Vec<u8> {
    let (catalog, pages, page, content_id) = (Ref::new(1), Ref::new(2), Ref::new(3), Ref::new(4));
    let scale = options.points_per_pixel;
    let (w, h) = (
        f64::from(options.width) * scale,
        f64::from(options.height) * scale,
    );
    let mut content = Content::new();
    // Pixel space (y down) onto the page (y up).
    content.transform([scale as f32, 0.0, 0.0, -scale as f32, 0.0, h as f32]);
    if let Some(bg) = options.background {
        fill_colour(&mut content, bg);
        content
            .rect(0.0, 0.0, options.width as f32, options.height as f32)
            .fill_nonzero();
    }
    content.set_line_join(LineJoinStyle::RoundJoin);
    let mut tiles = UsedTiles::default();
    for VectorShape {
        sprite,
        polygon,
        visible,
    } in vector_shapes(scene, options.ids, options.hidden)
    {
        if let Brush::Texture { texture, uv, .. } = sprite.brush
            && !options.ids
            && let Some(image) = options.images.get(texture.0 as usize)
            && let Some(cells) = texture_cells(scene.root(), sprite, uv, options.texture_tolerance)
        {
            content.save_state();
            let outline: Vec<DVec2> = match &visible {
                Visibility::Parts(parts) => parts.iter().flatten().flatten().copied().collect(),
                // The seam cover of the SVG writer: the clip grown by half the stroke.
                _ if options.seam_stroke > 0.0 => dilate(&polygon, options.seam_stroke * 0.5),
                _ => polygon.clone(),
            };
            match &visible {
                Visibility::Parts(parts) => {
                    for contour in parts.iter().flatten() {
                        trace(&mut content, contour);
                    }
                }
                _ => trace(&mut content, &outline),
            }
            content.clip_even_odd().end_path();
            let single = cells.len() == 1;
            for (cell, place) in &cells {
                content.save_state();
                if !single {
                    trace(&mut content, cell);
                    content.clip_nonzero().end_path();
                }
                let (width, height) = (image.width(), image.height());
                let under = tiles_under(width, height, *place, &outline, (!single).then_some(cell));
                for tile in under.flat_map(|t| t.strips_for_splash(*place, width, height)) {
                    let name = tiles.name(texture.0, tile);
                    // Image space is the unit square with the image's first row at the top
                    // (y = 1): the tile's (s, row) is image space (s, 1 − row).
                    let m = (*place * tile.to_texture(width, height)).to_cols_array();
                    content.save_state();
                    content.transform([
                        m[0] as f32,
                        m[1] as f32,
                        -m[2] as f32,
                        -m[3] as f32,
                        (m[2] + m[4]) as f32,
                        (m[3] + m[5]) as f32,
                    ]);
                    content.x_object(Name(name.as_bytes()));
                    content.restore_state();
                }
                content.restore_state();
            }
            content.restore_state();
            continue;
        }
        let colour = if options.ids {
            id_colour(sprite.face)
        } else {
            sprite.brush.solid_colour(sprite.face)
        };
        fill_colour(&mut content, colour);
        match &visible {
            Visibility::Parts(parts) => {
                for contour in parts.iter().flatten() {
                    trace(&mut content, contour);
                }
            }
            _ => trace(&mut content, &polygon),
        }
        let stroke = !options.ids && options.seam_stroke > 0.0 && colour[3] == 255;
        if stroke {
            let [r, g, b] = unit_rgb(colour);
            content
                .set_stroke_rgb(r, g, b)
                .set_line_width(options.seam_stroke as f32)
                .fill_even_odd_and_stroke();
        } else {
            content.fill_even_odd();
        }
    }
    if let Some(overlay) = &options.overlay {
        draw_overlay(&mut content, overlay);
    }

    let mut pdf = Pdf::new();
    pdf.catalog(catalog).pages(pages);
    pdf.pages(pages).kids([page]).count(1);
    let mut page_writer = pdf.page(page);
    page_writer
        .media_box(Rect::new(0.0, 0.0, w as f32, h as f32))
        .parent(pages)
        .contents(content_id);
    {
        let mut resources = page_writer.resources();
        let mut objects = resources.x_objects();
        for (k, _) in tiles.used.iter().enumerate() {
            objects.pair(Name(tile_name(k).as_bytes()), tile_ref(k));
        }
    }
    page_writer.finish();
    // The content stream deflated, as PDF producers do: paths compress several times.
    let deflated = deflate(&content.finish());
    pdf.stream(content_id, &deflated)
        .filter(Filter::FlateDecode);
    for (k, &(texture, tile)) in tiles.used.iter().enumerate() {
        if let Some(image) = options.images.get(texture as usize) {
            write_tile(&mut pdf, tile_ref(k), image, tile);
        }
    }
    pdf.finish()
}

/// Texels along each side of a texture tile, before its one-texel apron.
const TILE_TEXELS: u32 = 64;

/// A tile of a texture: the texels `[x0, x1) × [y0, y1)`, the core `TILE_TEXELS`-square cell
/// `(tx, ty)` of the texture's grid grown by one texel on each side (within the texture), so
/// that neighbouring tiles overlap and their smoothed edges lie under each other.
///
/// Each textured cell draws only the tiles under it, never the whole texture: a PDF viewer
/// scales an image XObject to its full device size before clipping it, so a sprite showing a
/// few texels made poppler scale the whole texture. (The blank sprites poppler left were
/// another cause: see [`Tile::strips_for_splash`].)
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct Tile {
    x0: u32,
    y0: u32,
    x1: u32,
    y1: u32,
}

impl Tile {
    /// The tile at grid cell `(tx, ty)` of a `width × height` texture.
    fn at(tx: u32, ty: u32, width: u32, height: u32) -> Tile {
        Tile::around(
            [tx * TILE_TEXELS, ty * TILE_TEXELS],
            [
                ((tx + 1) * TILE_TEXELS).min(width),
                ((ty + 1) * TILE_TEXELS).min(height),
            ],
            width,
            height,
        )
    }

    /// The core texels `[lo, hi)` with their one-texel apron, within the texture.
    fn around(lo: [u32; 2], hi: [u32; 2], width: u32, height: u32) -> Tile {
        Tile {
            x0: lo[0].saturating_sub(1),
            y0: lo[1].saturating_sub(1),
            x1: (hi[0] + 1).min(width),
            y1: (hi[1] + 1).min(height),
        }
    }

    /// The tile's core texels (without the apron), `([x0, y0], [x1, y1])`.
    fn core(self, width: u32, height: u32) -> ([u32; 2], [u32; 2]) {
        let inner = |lo: u32, hi: u32, size: u32| {
            (
                if lo == 0 { 0 } else { lo + 1 },
                if hi == size { size } else { hi - 1 },
            )
        };
        let (x0, x1) = inner(self.x0, self.x1, width);
        let (y0, y1) = inner(self.y0, self.y1, height);
        ([x0, y0], [x1.max(x0 + 1), y1.max(y0 + 1)])
    }

    /// The tile as strips that poppler's Splash rasteriser draws: Splash fills an image's
    /// parallelogram from its top corner down, taking the neighbour corner with the smaller
    /// `x` as the left edge. Where both neighbours lie on one side of the top corner and the
    /// steeper edge reaches further in `x`, that guess is wrong and Splash draws nothing
    /// (measured: about one in ten random parallelograms, the holes of the textured spot's
    /// PDF). Cutting the longer edge into strips shortens it until the guess is right; the
    /// strips keep one-texel aprons. Other viewers draw the strips as they drew the tile.
    fn strips_for_splash(self, place: DAffine2, width: u32, height: u32) -> Vec<Tile> {
        let edges = |t: Tile| {
            let m = place * t.to_texture(width, height);
            (m.matrix2.x_axis, m.matrix2.y_axis)
        };
        let (a, b) = edges(self);
        let Some(columns) = splash_misorders(a, b) else {
            return vec![self];
        };
        let (lo, hi) = self.core(width, height);
        let axis = usize::from(!columns);
        let texels = hi[axis] - lo[axis];
        let mut n = 2u32;
        loop {
            let n_now = n.min(texels);
            let strips: Vec<Tile> = (0..n_now)
                .map(|k| {
                    let (mut s_lo, mut s_hi) = (lo, hi);
                    s_lo[axis] = lo[axis] + texels * k / n_now;
                    s_hi[axis] = lo[axis] + texels * (k + 1) / n_now;
                    Tile::around(s_lo, s_hi, width, height)
                })
                .collect();
            let fine = strips.iter().all(|&t| {
                let (a, b) = edges(t);
                splash_misorders(a, b).is_none()
            });
            if fine || n_now == texels {
                return strips;
            }
            n *= 2;
        }
    }

    /// The map from the tile's unit square `(s, row)` (row 0 at its first row) to texture
    /// space `[0,1]²` of a `width × height` texture.
    fn to_texture(self, width: u32, height: u32) -> DAffine2 {
        let (w, h) = (f64::from(width), f64::from(height));
        DAffine2::from_cols(
            DVec2::new(f64::from(self.x1 - self.x0) / w, 0.0),
            DVec2::new(0.0, f64::from(self.y1 - self.y0) / h),
            DVec2::new(f64::from(self.x0) / w, f64::from(self.y0) / h),
        )
    }
}

/// Whether Splash can misjudge which side is left for the parallelogram with edge vectors `a`
/// and `b` (pixels, `y` down; see [`Tile::strips_for_splash`]): `Some(true)` when shortening
/// `a` (the image's columns axis) puts it right, `Some(false)` when shortening `b` does.
fn splash_misorders(a: DVec2, b: DVec2) -> Option<bool> {
    // The edges from the top corner point down.
    let down = |v: DVec2| if v.y < 0.0 { -v } else { v };
    let (p, q) = (down(a), down(b));
    // A horizontal edge (one section) or neighbours on both sides are judged right.
    if p.y <= 0.0 || q.y <= 0.0 || p.x * q.x <= 0.0 {
        return None;
    }
    let (p_slope, q_slope) = (p.x / p.y, q.x / q.y);
    let by_x = p.x - q.x;
    let close = by_x.abs() <= SPLASH_ORDER_MARGIN * p.x.abs().max(q.x.abs());
    // Shortening the steeper edge (smaller |dx/dy|) moves its far corner towards the top
    // corner's `x`, which is the side Splash needs it on: left of the other edge's corner
    // when both go right, right of it when both go left.
    (close || by_x * (p_slope - q_slope) < 0.0).then_some(p_slope.abs() <= q_slope.abs())
}

/// The tiles of a `width × height` texture placed by `place` (texture space → pixels) that
/// the pixels of `outline` (and of `cell`, when given) can show: the texels within the
/// bounds of both, mapped back to texture space, plus one texel for smoothing.
fn tiles_under(
    width: u32,
    height: u32,
    place: DAffine2,
    outline: &[DVec2],
    cell: Option<&Vec<DVec2>>,
) -> impl Iterator<Item = Tile> {
    let (w, h) = (f64::from(width), f64::from(height));
    let to_texels = DAffine2::from_scale(DVec2::new(w, h)) * place.inverse();
    let bounds = |points: &[DVec2]| {
        points
            .iter()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                let t = to_texels.transform_point2(*p);
                (lo.min(t), hi.max(t))
            })
    };
    let (mut lo, mut hi) = bounds(outline);
    if let Some(cell) = cell {
        let (clo, chi) = bounds(cell);
        lo = lo.max(clo);
        hi = hi.min(chi);
    }
    // A map that cannot be inverted shows nothing measurable: draw every tile.
    if !(lo.is_finite() && hi.is_finite()) {
        (lo, hi) = (DVec2::ZERO, DVec2::new(w, h));
    }
    let grid = |a: f64, b: f64, texels: u32| {
        let last = texels.div_ceil(TILE_TEXELS).max(1) - 1;
        let index = |x: f64| ((x / f64::from(TILE_TEXELS)).floor().max(0.0) as u32).min(last);
        let (first, end) = (index(a - 1.0), index(b + 1.0));
        first..=end.max(first)
    };
    let (xs, ys) = (grid(lo.x, hi.x, width), grid(lo.y, hi.y, height));
    let empty = hi.x < lo.x || hi.y < lo.y;
    ys.flat_map(move |ty| xs.clone().map(move |tx| Tile::at(tx, ty, width, height)))
        .filter(move |_| !empty)
}

/// The texture tiles a page draws, in order of first use; tile `k` is image XObject
/// `tile_ref(k)` named `tile_name(k)`, its soft mask (if any) the object after it.
#[derive(Default)]
struct UsedTiles {
    used: Vec<(u32, Tile)>,
    index: HashMap<(u32, Tile), usize>,
}

impl UsedTiles {
    /// The resource name of `tile` of texture `texture`, numbering it on first use.
    fn name(&mut self, texture: u32, tile: Tile) -> String {
        let next = self.used.len();
        let k = *self.index.entry((texture, tile)).or_insert(next);
        if k == next {
            self.used.push((texture, tile));
        }
        tile_name(k)
    }
}

/// The resource name of the page's `k`-th texture tile.
fn tile_name(k: usize) -> String {
    format!("T{k}")
}

/// The object of the page's `k`-th texture tile (objects 1-4 are the catalog, page tree,
/// page and content; each tile takes two, the image and its soft mask).
fn tile_ref(k: usize) -> Ref {
    Ref::new(5 + 2 * i32::try_from(k).unwrap_or(i32::MAX / 2 - 3))
}

/// A tile of an image as a deflated RGB image XObject at `id`, with a deflated soft mask at
/// the next object number when any of its pixels is not opaque.
fn write_tile(pdf: &mut Pdf, id: Ref, image: &Image, tile: Tile) {
    let rgba = image.rgba();
    let row = image.width() as usize * 4;
    let texels = || {
        (tile.y0..tile.y1).flat_map(move |y| {
            let start = y as usize * row;
            rgba[start + tile.x0 as usize * 4..start + tile.x1 as usize * 4].chunks_exact(4)
        })
    };
    let rgb: Vec<u8> = texels().flat_map(|p| [p[0], p[1], p[2]]).collect();
    let alpha: Vec<u8> = texels().map(|p| p[3]).collect();
    let mask = alpha
        .iter()
        .any(|&a| a < 255)
        .then(|| Ref::new(id.get() + 1));
    let size = (tile.x1 - tile.x0, tile.y1 - tile.y0);
    write_samples(pdf, id, &rgb, size, false, mask);
    if let Some(mask) = mask {
        write_samples(pdf, mask, &alpha, size, true, None);
    }
}

/// One deflated 8-bit image XObject of RGB (or, `gray`, one-channel) samples, smoothed
/// when scaled as raster-sink's bilinear texture sampling is, with an optional soft mask.
fn write_samples(
    pdf: &mut Pdf,
    id: Ref,
    samples: &[u8],
    (width, height): (u32, u32),
    gray: bool,
    mask: Option<Ref>,
) {
    let deflated = deflate(samples);
    let mut xobject = pdf.image_xobject(id, &deflated);
    xobject.filter(Filter::FlateDecode);
    xobject.width(width as i32);
    xobject.height(height as i32);
    if gray {
        xobject.color_space().device_gray();
    } else {
        xobject.color_space().device_rgb();
    }
    xobject.bits_per_component(8);
    xobject.interpolate(true);
    if let Some(mask) = mask {
        xobject.s_mask(mask);
    }
    xobject.finish();
}

/// zlib-deflated bytes, for FlateDecode streams.
fn deflate(bytes: &[u8]) -> Vec<u8> {
    miniz_oxide::deflate::compress_to_vec_zlib(bytes, 6)
}

/// Strokes (butt caps) then dots (four cubic Béziers each, within 3e-4 of the radius).
fn draw_overlay(content: &mut Content, overlay: &DrawnOverlay) {
    content.set_line_cap(LineCapStyle::ButtCap);
    for stroke in &overlay.strokes {
        let [r, g, b] = unit_rgb(stroke.colour);
        let [a, c] = stroke.ends;
        content
            .set_stroke_rgb(r, g, b)
            .set_line_width(stroke.width_px as f32)
            .move_to(a.x as f32, a.y as f32)
            .line_to(c.x as f32, c.y as f32)
            .stroke();
    }
    // Control distance of a quarter circle: 4/3 · tan(π/8).
    const K: f64 = 0.552_284_749_830_793_4;
    for dot in &overlay.dots {
        fill_colour(content, dot.colour);
        let (c, r) = (dot.centre, dot.radius_px);
        let p = |x: f64, y: f64| ((c.x + x * r) as f32, (c.y + y * r) as f32);
        let start = p(1.0, 0.0);
        content.move_to(start.0, start.1);
        for [(x1, y1), (x2, y2), (x3, y3)] in [
            [(1.0, K), (K, 1.0), (0.0, 1.0)],
            [(-K, 1.0), (-1.0, K), (-1.0, 0.0)],
            [(-1.0, -K), (-K, -1.0), (0.0, -1.0)],
            [(K, -1.0), (1.0, -K), (1.0, 0.0)],
        ] {
            let (a, b, e) = (p(x1, y1), p(x2, y2), p(x3, y3));
            content.cubic_to(a.0, a.1, b.0, b.1, e.0, e.1);
        }
        content.close_path().fill_nonzero();
    }
}

fn trace(content: &mut Content, contour: &[glam::DVec2]) {
    let Some(first) = contour.first() else {
        return;
    };
    content.move_to(first.x as f32, first.y as f32);
    for p in &contour[1..] {
        content.line_to(p.x as f32, p.y as f32);
    }
    content.close_path();
}

fn unit_rgb(c: [u8; 4]) -> [f32; 3] {
    [c[0], c[1], c[2]].map(|v| f32::from(v) / 255.0)
}

fn fill_colour(content: &mut Content, c: [u8; 4]) {
    let [r, g, b] = unit_rgb(c);
    content.set_fill_rgb(r, g, b);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Splash's choice of left edge, modelled from its corner order (corners `o`, `o + b`,
    /// `o + a + b`, `o + a`; the top one's two neighbours; the one of smaller `x` taken as
    /// left) against the true left edge (the smaller `dx/dy`): whether they agree.
    fn splash_guesses_right(a: DVec2, b: DVec2) -> bool {
        let corners = [DVec2::ZERO, b, a + b, a];
        let top = (0..4)
            .min_by(|&i, &j| corners[i].y.total_cmp(&corners[j].y))
            .unwrap_or(0);
        let (n1, n3) = (corners[(top + 1) % 4], corners[(top + 3) % 4]);
        let t = corners[top];
        if (n1.y - t.y).abs() < 1e-9 || (n3.y - t.y).abs() < 1e-9 {
            return true;
        }
        let slope = |n: DVec2| (n.x - t.x) / (n.y - t.y);
        (n1.x < n3.x) == (slope(n1) < slope(n3))
    }

    #[test]
    fn the_parallelogram_that_left_holes_is_cut_until_splash_guesses_right() {
        // A tile's edges at spot's snout (yaw -100, pitch 10): Splash drew nothing.
        let (a, b) = (DVec2::new(13.63, 1.52), DVec2::new(-28.16, -47.63));
        assert!(!splash_guesses_right(a, b));
        assert_eq!(splash_misorders(a, b), Some(false));
        let tile = Tile::at(1, 1, 256, 256);
        let place = DAffine2::from_cols(a * 4.0, b * 4.0, DVec2::new(100.0, 100.0));
        let strips = tile.strips_for_splash(place, 256, 256);
        assert!(strips.len() > 1);
        for s in &strips {
            let m = place * s.to_texture(256, 256);
            assert!(splash_guesses_right(m.matrix2.x_axis, m.matrix2.y_axis));
            assert_eq!((s.x0, s.x1), (tile.x0, tile.x1), "cut along the rows only");
        }
        // The strips' cores tile the tile's core.
        let rows: u32 = strips
            .iter()
            .map(|s| s.core(256, 256).1[1] - s.core(256, 256).0[1])
            .sum();
        assert_eq!(rows, TILE_TEXELS);
    }

    #[test]
    fn every_strip_of_random_parallelograms_is_one_splash_draws() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut cut = 0;
        for _ in 0..2000 {
            let a = DVec2::new(next(), next()) * 40.0;
            let b = DVec2::new(next(), next()) * 40.0;
            if a.perp_dot(b).abs() < 50.0 {
                continue;
            }
            let tile = Tile::at(0, 0, 64, 64);
            let place = DAffine2::from_cols(a, b, DVec2::ZERO);
            let strips = tile.strips_for_splash(place, 64, 64);
            cut += usize::from(strips.len() > 1);
            for s in strips {
                let m = place * s.to_texture(64, 64);
                assert!(
                    splash_guesses_right(m.matrix2.x_axis, m.matrix2.y_axis),
                    "a {a}, b {b}: strip {s:?}"
                );
            }
        }
        assert!(cut > 50, "only {cut} parallelograms needed cutting");
    }

    #[test]
    fn tiles_under_a_small_outline_are_few_and_cover_its_texels() {
        let (width, height) = (512, 384);
        // Texture space onto pixels: the texture 3000 px across, turned 30°.
        let place = DAffine2::from_scale_angle_translation(
            DVec2::splat(3000.0),
            0.5,
            DVec2::new(-900.0, -1400.0),
        );
        let outline = [
            DVec2::new(100.0, 100.0),
            DVec2::new(140.0, 110.0),
            DVec2::new(115.0, 150.0),
        ];
        let tiles: Vec<Tile> = tiles_under(width, height, place, &outline, None).collect();
        assert!(
            !tiles.is_empty() && tiles.len() < 6,
            "{} tiles",
            tiles.len()
        );
        let to_texels = DAffine2::from_scale(DVec2::new(512.0, 384.0)) * place.inverse();
        for p in outline {
            let t = to_texels.transform_point2(p);
            assert!(
                tiles.iter().any(|k| {
                    f64::from(k.x0) <= t.x
                        && t.x <= f64::from(k.x1)
                        && f64::from(k.y0) <= t.y
                        && t.y <= f64::from(k.y1)
                }),
                "texel {t} of corner {p} is in no tile"
            );
        }
    }
}
