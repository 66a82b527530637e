//! The PDF writer: a scene's visible sprites as filled vector paths in paint order, through
//! `pdf-writer`.

use std::sync::Arc;

use pdf_writer::types::{LineCapStyle, LineJoinStyle};
use pdf_writer::{Content, Filter, Finish, Name, Pdf, Rect, Ref};

use crate::hidden::{VectorShape, vector_shapes};
use crate::svg::{dilate, texture_cells};
use crate::tolerance::SVG_TEXTURE_PX;
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
    /// [`visible_overlay`](crate::visible_overlay)), in ID mode too. Default: none.
    pub overlay: Option<DrawnOverlay>,
    /// The images of [`Brush::Texture`] sprites, indexed by [`TextureId`](crate::TextureId)
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

    /// Image size in pixels.
    #[must_use]
    pub fn with_size(mut self, width: u32, height: u32) -> Self {
        self.width = width;
        self.height = height;
        self
    }

    /// Points per pixel.
    #[must_use]
    pub fn with_points_per_pixel(mut self, points: f64) -> Self {
        self.points_per_pixel = points;
        self
    }

    /// ID colours mode.
    #[must_use]
    pub fn with_ids(mut self, ids: bool) -> Self {
        self.ids = ids;
        self
    }

    /// Background colour.
    #[must_use]
    pub fn with_background(mut self, background: Option<[u8; 4]>) -> Self {
        self.background = background;
        self
    }

    /// Seam stroke width in pixels (0: off).
    #[must_use]
    pub fn with_seam_stroke(mut self, width: f64) -> Self {
        self.seam_stroke = width;
        self
    }

    /// Keep or remove hidden parts.
    #[must_use]
    pub fn with_hidden(mut self, hidden: HiddenParts) -> Self {
        self.hidden = hidden;
        self
    }
}

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
    // Image XObjects in use, by texture id: (name, object).
    let mut used: Vec<Option<Ref>> = vec![None; options.images.len()];
    let mut next_ref = 5;
    for VectorShape {
        sprite,
        polygon,
        visible,
    } in vector_shapes(scene, options.ids, options.hidden)
    {
        if let Brush::Texture { texture, uv, .. } = sprite.brush
            && !options.ids
            && let Some(slot) = used.get_mut(texture.0 as usize)
            && let Some(cells) = texture_cells(scene.root(), sprite, uv, options.texture_tolerance)
        {
            if slot.is_none() {
                *slot = Some(Ref::new(next_ref));
                next_ref += 2; // the image and its soft mask
            }
            content.save_state();
            match &visible {
                Visibility::Parts(parts) => {
                    for contour in parts.iter().flatten() {
                        trace(&mut content, contour);
                    }
                }
                // The seam cover of the SVG writer: the clip grown by half the stroke.
                _ if options.seam_stroke > 0.0 => {
                    trace(&mut content, &dilate(&polygon, options.seam_stroke * 0.5));
                }
                _ => trace(&mut content, &polygon),
            }
            content.clip_even_odd().end_path();
            let single = cells.len() == 1;
            for (cell, place) in &cells {
                content.save_state();
                if !single {
                    trace(&mut content, cell);
                    content.clip_nonzero().end_path();
                }
                // Image space is the unit square with the image's first row at the top
                // (y = 1): texture (u, v) with v down is image space (u, 1 − v).
                let m = place.to_cols_array();
                content.transform([
                    m[0] as f32,
                    m[1] as f32,
                    -m[2] as f32,
                    -m[3] as f32,
                    (m[2] + m[4]) as f32,
                    (m[3] + m[5]) as f32,
                ]);
                content.x_object(Name(image_name(texture.0).as_bytes()));
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
        for (k, slot) in used.iter().enumerate() {
            if let Some(id) = slot {
                objects.pair(Name(image_name(k as u32).as_bytes()), *id);
            }
        }
    }
    page_writer.finish();
    // The content stream deflated, as PDF producers do: paths compress several times.
    let deflated = deflate(&content.finish());
    pdf.stream(content_id, &deflated)
        .filter(Filter::FlateDecode);
    for (image, slot) in options.images.iter().zip(&used) {
        if let Some(id) = slot {
            write_image(&mut pdf, *id, image);
        }
    }
    pdf.finish()
}

/// The resource name of texture `k`'s image.
fn image_name(k: u32) -> String {
    format!("Im{k}")
}

/// An image as a deflated RGB image XObject at `id`, with a deflated soft mask at the next
/// object number when any pixel is not opaque.
fn write_image(pdf: &mut Pdf, id: Ref, image: &Image) {
    let rgba = image.rgba();
    let rgb: Vec<u8> = rgba
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    let alpha: Vec<u8> = rgba.chunks_exact(4).map(|p| p[3]).collect();
    let mask = alpha
        .iter()
        .any(|&a| a < 255)
        .then(|| Ref::new(id.get() + 1));
    let size = (image.width(), image.height());
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
