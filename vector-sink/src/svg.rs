//! The SVG writer: a scene's visible sprites as polygons in paint order.

use std::collections::HashMap;
use std::fmt::Write as _;

use glam::{DAffine2, DMat4, DVec2, DVec4};

use crate::hidden::{VectorShape, vector_shapes};
use crate::numbers::{hex, matrix_entry, pixel};
use crate::tolerance::{SVG_CELL_OVERLAP_PX, SVG_TEXTURE_MAX_CELLS, SVG_TEXTURE_PX};
use crate::{Brush, HiddenParts, Scene, SceneSprite, Visibility, id_colour, sprite_polygon};

/// Options of [`write_svg`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SvgOptions {
    /// Image width in pixels. Default: 256.
    pub width: u32,
    /// Image height in pixels. Default: 256.
    pub height: u32,
    /// Fill each face with its ID colour (CONVENTIONS.md) with `shape-rendering="crispEdges"`,
    /// no textures. Default: false.
    pub ids: bool,
    /// Background colour (`None`: transparent). Default: `None`.
    pub background: Option<[u8; 4]>,
    /// `href` of each texture, indexed by [`TextureId`](sprite_compose::TextureId) (a data URI or a
    /// path). Textured sprites whose texture has no entry use their fallback colour.
    /// Default: none.
    pub textures: Vec<String>,
    /// Extra SVG markup appended on top (e.g. [`outline_svg_path`](crate::outline_svg_path)).
    /// Default: empty.
    pub overlay: String,
    /// Width in pixels of a stroke in each solid polygon's own colour, which hides the
    /// hairlines of background that anti-aliased neighbours leave along shared edges
    /// (conflation). It also moves every visible boundary outward by half of it (silhouettes,
    /// intersection lines): 1.0 is the width that hides the hairlines (half a pixel still lets
    /// them through in resvg), and a measurement of colour boundaries wants 0. ID mode never
    /// strokes. A textured polygon (not cut by hidden-part removal) has its clip grown
    /// instead, each corner moved half the width away from its centre. Default: 1.
    pub seam_stroke: f64,
    /// Whether hidden parts are written ([`HiddenParts::Keep`], the painter's algorithm as
    /// is) or left out ([`HiddenParts::Remove`]: every polygon, or part of one, that opaque
    /// polygons in front cover; partly hidden polygons become even-odd paths). Default: keep.
    pub hidden: HiddenParts,
    /// Largest miss (pixels) of a textured cell's affine map against the exact projective
    /// one before the cell is cut finer; `f64::INFINITY` draws each texture with one affine
    /// map. Default: [`SVG_TEXTURE_PX`].
    pub texture_tolerance: f64,
}

impl SvgOptions {
    /// The defaults.
    pub const DEFAULT: SvgOptions = SvgOptions {
        width: 256,
        height: 256,
        ids: false,
        background: None,
        textures: Vec::new(),
        overlay: String::new(),
        seam_stroke: 1.0,
        hidden: HiddenParts::Keep,
        texture_tolerance: SVG_TEXTURE_PX,
    };

    /// Largest miss (pixels) of a textured cell's affine map.
    #[must_use]
    pub fn with_texture_tolerance(mut self, pixels: f64) -> Self {
        self.texture_tolerance = pixels;
        self
    }

    /// Markup drawn on top.
    #[must_use]
    pub fn with_overlay(mut self, overlay: String) -> Self {
        self.overlay = overlay;
        self
    }
}

crate::page::page_setters!(SvgOptions: size, ids, background, hidden, textures, seam_stroke);

impl Default for SvgOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The scene's visible sprites as an SVG document: one `<polygon>` per sprite in paint order
/// (textured sprites: an `<image>` under a `clip-path`), exactly the projected polygons.
///
/// Textures are placed with the affine map through three projected corners of the sprite's
/// square where that is exact (affine sprites under an orthographic root). Under a
/// projective map (perspective, projective quads; SVG has no projective image transform) the
/// square is cut into a grid of cells, each an `<image>` with the affine map nearest to the
/// exact one at its four projected corners (least squares) under a clip slightly larger than
/// the cell, fine enough that the map is off by at most [`SvgOptions::texture_tolerance`]
/// pixels (default [`SVG_TEXTURE_PX`]) at the cells'
/// corners (grid capped at
/// [`SVG_TEXTURE_MAX_CELLS`] per side).
#[must_use]
pub fn write_svg(scene: &Scene, options: &SvgOptions) -> String {
    let (w, h) = (options.width, options.height);
    let mut svg = String::new();
    let _ = write!(
        svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\""
    );
    if options.ids {
        svg.push_str(" shape-rendering=\"crispEdges\"");
    }
    svg.push_str(">\n");
    if let Some(bg) = options.background {
        let _ = writeln!(
            svg,
            "<rect width=\"{w}\" height=\"{h}\" fill=\"{}\"{}/>",
            hex(bg),
            opacity(bg)
        );
    }
    // Each texture once, in <defs>; textured cells <use> it.
    let shapes = vector_shapes(scene, options.ids, options.hidden);
    svg.push_str(&texture_defs(&shapes, options));
    // Colour mode: one class per brush colour; the attributes every shape shares sit on one
    // group.
    let (classes, rules) = colour_classes(&shapes, options);
    if !rules.is_empty() {
        let _ = writeln!(svg, "<style>{rules}</style>");
    }
    svg.push_str("<g fill-rule=\"evenodd\" clip-rule=\"evenodd\"");
    if !options.ids && options.seam_stroke > 0.0 {
        let _ = write!(
            svg,
            " stroke-width=\"{}\" stroke-linejoin=\"round\"",
            pixel(options.seam_stroke)
        );
    }
    svg.push_str(">\n");
    let mut clip_count = 0usize;
    for VectorShape {
        sprite,
        polygon,
        visible,
    } in shapes
    {
        // The element's geometry: the polygon, or the even-odd path of its visible parts.
        let shape = match &visible {
            Visibility::Parts(parts) => Shape::Path(path_data(parts)),
            _ => Shape::Polygon(points_attribute(&polygon)),
        };
        let texture = match sprite.brush {
            Brush::Texture { texture, uv, .. } if !options.ids => options
                .textures
                .get(texture.0 as usize)
                .map(|_| (texture.0, uv)),
            _ => None,
        };
        if let Some((id, uv)) = texture
            && let Some(cells) = texture_cells(scene.root(), sprite, uv, options.texture_tolerance)
        {
            clip_count += 1;
            let _ = write!(
                svg,
                "<clipPath id=\"c{clip_count}\">{}</clipPath><g clip-path=\"url(#c{clip_count})\">",
                match (&visible, options.seam_stroke > 0.0) {
                    // The same seam cover for textures: the clip polygon, each corner moved
                    // half the stroke width away from its centre.
                    (Visibility::Parts(_), _) | (_, false) => shape.element(""),
                    _ => Shape::Polygon(points_attribute(&dilate(
                        &polygon,
                        options.seam_stroke * 0.5
                    )))
                    .element(""),
                }
            );
            let single = cells.len() == 1;
            for (k, (cell, place)) in cells.iter().enumerate() {
                let m = place.to_cols_array();
                let image = format!(
                    "<use xlink:href=\"#t{id}\" transform=\"matrix({})\"/>",
                    m[..6]
                        .iter()
                        .map(|&v| matrix_entry(v))
                        .collect::<Vec<_>>()
                        .join(" ")
                );
                if single {
                    svg.push_str(&image);
                } else {
                    let _ = write!(
                        svg,
                        "<clipPath id=\"c{clip_count}-{k}\"><polygon points=\"{}\"/></clipPath><g clip-path=\"url(#c{clip_count}-{k})\">{image}</g>",
                        points_attribute(cell)
                    );
                }
            }
            svg.push_str("</g>\n");
            continue;
        }
        let paint = if options.ids {
            format!(" fill=\"{}\"", hex(id_colour(sprite.face)))
        } else {
            let colour = sprite.brush.solid_colour(sprite.face);
            format!(" class=\"{}\"", class_name(classes[&colour]))
        };
        let _ = writeln!(svg, "{}", shape.element(&paint));
    }
    svg.push_str("</g>\n");
    svg.push_str(&options.overlay);
    svg.push_str("</svg>\n");
    svg
}

/// `<defs>` holding each texture the shapes use, once (empty when none is used).
fn texture_defs(shapes: &[VectorShape<'_>], options: &SvgOptions) -> String {
    if options.ids {
        return String::new();
    }
    let used: std::collections::BTreeSet<u32> = shapes
        .iter()
        .filter_map(|s| match s.sprite.brush {
            Brush::Texture { texture, .. } => Some(texture.0),
            _ => None,
        })
        .filter(|&id| (id as usize) < options.textures.len())
        .collect();
    if used.is_empty() {
        return String::new();
    }
    let mut defs = String::from("<defs>");
    for &k in &used {
        let href = escape_attribute(&options.textures[k as usize]);
        let _ = write!(
            defs,
            "<image id=\"t{k}\" xlink:href=\"{href}\" width=\"1\" height=\"1\" preserveAspectRatio=\"none\"/>"
        );
    }
    defs.push_str("</defs>\n");
    defs
}

/// Colour mode: one CSS class per brush colour (fill, and the seam stroke of opaque ones),
/// with the rules that define them; nothing in ID mode.
fn colour_classes(
    shapes: &[VectorShape<'_>],
    options: &SvgOptions,
) -> (HashMap<[u8; 4], usize>, String) {
    let mut classes: HashMap<[u8; 4], usize> = HashMap::new();
    let mut rules = String::new();
    if options.ids {
        return (classes, rules);
    }
    for shape in shapes {
        let colour = shape.sprite.brush.solid_colour(shape.sprite.face);
        let next = classes.len();
        classes.entry(colour).or_insert_with(|| {
            let stroke = if options.seam_stroke > 0.0 && colour[3] == 255 {
                format!(";stroke:{}", hex(colour))
            } else {
                String::new()
            };
            let _ = write!(
                rules,
                ".{}{{fill:{}{}{stroke}}}",
                class_name(next),
                hex(colour),
                opacity_css(colour)
            );
            next
        });
    }
    (classes, rules)
}

/// The geometry of one written element.
enum Shape {
    /// `points` of a `<polygon>`.
    Polygon(String),
    /// `d` of an even-odd `<path>`.
    Path(String),
}

impl Shape {
    /// The element with extra attributes (each with a leading space).
    fn element(&self, attributes: &str) -> String {
        match self {
            Shape::Polygon(points) => format!("<polygon points=\"{points}\"{attributes}/>"),
            // fill-rule and clip-rule (even-odd) come from the enclosing group.
            Shape::Path(d) => format!("<path d=\"{d}\"{attributes}/>"),
        }
    }
}

/// Path data of shapes (each an outer contour and its holes), every contour closed.
fn path_data(shapes: &[Vec<Vec<DVec2>>]) -> String {
    let mut d = String::new();
    for contour in shapes.iter().flatten() {
        for (k, p) in contour.iter().enumerate() {
            let _ = write!(
                d,
                "{}{},{} ",
                if k == 0 { "M" } else { "L" },
                pixel(p.x),
                pixel(p.y)
            );
        }
        d.push_str("Z ");
    }
    d.truncate(d.trim_end().len());
    d
}

/// A short class name for class `k`: `c` and `k` in base 36.
fn class_name(k: usize) -> String {
    let digits = b"0123456789abcdefghijklmnopqrstuvwxyz";
    let mut n = k;
    let mut out = Vec::new();
    loop {
        out.push(digits[n % 36]);
        n /= 36;
        if n == 0 {
            break;
        }
    }
    out.push(b'c');
    out.reverse();
    String::from_utf8(out).unwrap_or_default()
}

/// `;fill-opacity:a` for a translucent colour, else nothing.
fn opacity_css(c: [u8; 4]) -> String {
    if c[3] == 255 {
        String::new()
    } else {
        format!(
            ";fill-opacity:{}",
            crate::numbers::significant(f64::from(c[3]) / 255.0, 4)
        )
    }
}

fn opacity(c: [u8; 4]) -> String {
    if c[3] == 255 {
        String::new()
    } else {
        format!(" fill-opacity=\"{:.4}\"", f64::from(c[3]) / 255.0)
    }
}

fn points_attribute(polygon: &[DVec2]) -> String {
    let mut s = String::new();
    for (k, p) in polygon.iter().enumerate() {
        if k > 0 {
            s.push(' ');
        }
        let _ = write!(s, "{},{}", pixel(p.x), pixel(p.y));
    }
    s
}

/// A polygon with each corner moved `by` pixels away from the corners' mean.
pub(crate) fn dilate(polygon: &[DVec2], by: f64) -> Vec<DVec2> {
    let centre = polygon.iter().copied().sum::<DVec2>() / polygon.len().max(1) as f64;
    polygon
        .iter()
        .map(|&p| p + (p - centre).normalize_or_zero() * by)
        .collect()
}

/// The texture of a sprite as cells: each a clip polygon in pixels and the affine map
/// texture space `[0,1]²` → pixels nearest the exact one at the cell's four projected
/// corners, the grid as fine as `tolerance` (pixels) asks. One cell (the whole square, no clip
/// of its own) when the projected map is affine. `None` when a corner of the square is not in
/// front of the eye or a map is singular.
pub(crate) fn texture_cells(
    root: &DMat4,
    sprite: &SceneSprite,
    uv: DAffine2,
    tolerance: f64,
) -> Option<Vec<(Vec<DVec2>, DAffine2)>> {
    let full = *root * sprite.transform.matrix;
    let at = |u: f64, v: f64| {
        let h = full * DVec4::new(u, v, 0.0, 1.0);
        (h.w > 0.0).then(|| DVec2::new(h.x / h.w, h.y / h.w))
    };
    let inverse_uv = uv.inverse();
    if !inverse_uv.is_finite() {
        return None;
    }
    // The cell [u0, u1] × [v0, v1]: its affine placement and the miss at its fourth corner.
    let cell = |u0: f64, v0: f64, u1: f64, v1: f64| {
        let (o, x, y, xy) = (at(u0, v0)?, at(u1, v0)?, at(u0, v1)?, at(u1, v1)?);
        // The affine map nearest (least squares) to the corners' images: it misses each of
        // them by a quarter of |o + xy − x − y|, the quad's departure from a parallelogram.
        let a = ((x - o) + (xy - y)) * 0.5;
        let b = ((y - o) + (xy - x)) * 0.5;
        let c = (o + x + y + xy) * 0.25 - (a + b) * 0.5;
        let square_to_pixels = DAffine2::from_cols(a, b, c)
            * DAffine2::from_cols(
                DVec2::new(1.0 / (u1 - u0), 0.0),
                DVec2::new(0.0, 1.0 / (v1 - v0)),
                DVec2::new(-u0 / (u1 - u0), -v0 / (v1 - v0)),
            );
        let place = square_to_pixels * inverse_uv;
        let miss = (o + xy - x - y).length() * 0.25;
        place
            .is_finite()
            .then_some((vec![o, x, xy, y], place, miss))
    };
    // The sprite's polygon (unit-square coordinates) bounds the cells worth writing.
    let polygon = sprite_polygon(sprite);
    let (mut lo, mut hi) = (polygon[0], polygon[0]);
    for p in &polygon {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let mut n = 1u32;
    loop {
        let step = 1.0 / f64::from(n);
        let range = |a: f64, b: f64| {
            let first = (((a / step).floor().max(0.0)) as u32).min(n - 1);
            let last = ((b / step).ceil() as u32).clamp(first + 1, n);
            first..last
        };
        let mut cells = Vec::new();
        let mut worst = 0.0f64;
        for j in range(lo.y, hi.y) {
            for i in range(lo.x, hi.x) {
                let (u0, v0) = (f64::from(i) * step, f64::from(j) * step);
                let (corners, place, miss) = cell(u0, v0, u0 + step, v0 + step)?;
                worst = worst.max(miss);
                cells.push((corners, place));
            }
        }
        if worst <= tolerance || n >= SVG_TEXTURE_MAX_CELLS {
            if n > 1 {
                for (corners, _) in &mut cells {
                    let centre = corners.iter().copied().sum::<DVec2>() / 4.0;
                    for p in corners.iter_mut() {
                        let away = (*p - centre).normalize_or_zero();
                        *p += away * SVG_CELL_OVERLAP_PX;
                    }
                }
            }
            return Some(cells);
        }
        n = (n * 2).min(SVG_TEXTURE_MAX_CELLS);
    }
}

/// `text` escaped for an XML attribute value in double quotes. Tabs and line breaks become
/// character references, so that a parser's attribute-value normalisation gives them back
/// as they were; a character that XML 1.0 does not allow at all (most C0 controls, U+FFFE,
/// U+FFFF) becomes U+FFFD, as no reference can carry it.
pub(crate) fn escape_attribute(text: &str) -> std::borrow::Cow<'_, str> {
    escape(text, |c| match c {
        '&' => Some("&amp;"),
        '<' => Some("&lt;"),
        '>' => Some("&gt;"),
        '"' => Some("&quot;"),
        '\'' => Some("&apos;"),
        '\t' => Some("&#9;"),
        '\n' => Some("&#10;"),
        '\r' => Some("&#13;"),
        '\u{0}'..='\u{1f}' | '\u{fffe}' | '\u{ffff}' => Some("\u{fffd}"),
        _ => None,
    })
}

/// `text` with each character that `replace` maps replaced; borrowed when none is.
pub(crate) fn escape(
    text: &str,
    replace: impl Fn(char) -> Option<&'static str>,
) -> std::borrow::Cow<'_, str> {
    if !text.chars().any(|c| replace(c).is_some()) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 16);
    for c in text.chars() {
        match replace(c) {
            Some(with) => out.push_str(with),
            None => out.push(c),
        }
    }
    std::borrow::Cow::Owned(out)
}
