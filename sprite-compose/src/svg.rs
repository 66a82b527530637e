//! The SVG writer: a scene's visible sprites as polygons in paint order.

use std::fmt::Write as _;

use face_sort::tolerance::NEAR_W;
use glam::{DAffine2, DMat4, DVec2, DVec4};

use crate::hidden::{VectorShape, vector_shapes};
use crate::{Brush, HiddenParts, Scene, SceneSprite, Visibility, id_colour};

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
    /// `href` of each texture, indexed by [`TextureId`](crate::TextureId) (a data URI or a
    /// path). Textured sprites whose texture has no entry use their fallback colour.
    /// Default: none.
    pub textures: Vec<String>,
    /// Extra SVG markup appended on top (e.g. [`outline_svg_path`](crate::outline_svg_path)).
    /// Default: empty.
    pub overlay: String,
    /// Width in pixels of a stroke in each solid polygon's own colour, which hides the
    /// hairlines of background that anti-aliased neighbours leave along shared edges
    /// (conflation). It also moves every visible boundary outward by half of it (silhouettes,
    /// intersection lines), so it is off by default: an export for people to look at wants
    /// 1.0 (half a pixel still lets hairlines through in resvg), a measurement wants 0.
    /// ID mode never strokes. Default: 0.
    pub seam_stroke: f64,
    /// Whether hidden parts are written ([`HiddenParts::Keep`], the painter's algorithm as
    /// is) or left out ([`HiddenParts::Remove`]: every polygon, or part of one, that opaque
    /// polygons in front cover; partly hidden polygons become even-odd paths). Default: keep.
    pub hidden: HiddenParts,
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
        seam_stroke: 0.0,
        hidden: HiddenParts::Keep,
    };

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

    /// Image size.
    #[must_use]
    pub fn with_size(mut self, width: u32, height: u32) -> Self {
        self.width = width;
        self.height = height;
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

    /// Texture `href`s by texture index.
    #[must_use]
    pub fn with_textures(mut self, textures: Vec<String>) -> Self {
        self.textures = textures;
        self
    }

    /// Markup drawn on top.
    #[must_use]
    pub fn with_overlay(mut self, overlay: String) -> Self {
        self.overlay = overlay;
        self
    }
}

impl Default for SvgOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// `#rrggbb` of a colour.
pub(crate) fn hex(c: [u8; 4]) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// The unit-square polygon a sprite shows: its clip, or the square (corners `0, 1, 2, 3` of a
/// quad).
pub(crate) fn sprite_polygon(sprite: &SceneSprite) -> Vec<DVec2> {
    match &sprite.clip {
        Some(clip) => clip.clone(),
        None => vec![DVec2::ZERO, DVec2::Y, DVec2::ONE, DVec2::X],
    }
}

/// Projects a sprite's polygon to pixels through `root · transform`, clipping it against the
/// near plane `w ≥ NEAR_W` (CONVENTIONS.md) in homogeneous coordinates. Empty when nothing is
/// in front of the near plane.
#[must_use]
pub fn project_sprite(root: &DMat4, sprite: &SceneSprite) -> Vec<DVec2> {
    let matrix = sprite.transform.matrix;
    let full = *root * matrix;
    // Homogeneous (unit-square) points; the near test W − NEAR_W · w_sprite ≥ 0 is linear.
    let lifted: Vec<DVec4> = sprite_polygon(sprite)
        .iter()
        .map(|uv| DVec4::new(uv.x, uv.y, 0.0, 1.0))
        .collect();
    let near = |p: DVec4| (full * p).w - NEAR_W * (matrix * p).w;
    let mut kept: Vec<DVec4> = Vec::with_capacity(lifted.len() + 2);
    let n = lifted.len();
    for k in 0..n {
        let (a, b) = (lifted[k], lifted[(k + 1) % n]);
        let (da, db) = (near(a), near(b));
        if da >= 0.0 {
            kept.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let t = da / (da - db);
            kept.push(a + (b - a) * t);
        }
    }
    if kept.len() < 3 {
        return Vec::new();
    }
    kept.iter()
        .map(|&p| {
            let h = full * p;
            DVec2::new(h.x / h.w, h.y / h.w)
        })
        .collect()
}

/// The scene's visible sprites as an SVG document: one `<polygon>` per sprite in paint order
/// (textured sprites: an `<image>` under a `clip-path`), exactly the projected polygons.
///
/// Textures are placed with the affine map through three projected corners of the sprite's
/// square: exact for affine sprites under an orthographic root, an approximation under
/// perspective or for projective sprites (SVG has no projective image transform).
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
    let mut clip_count = 0usize;
    for VectorShape {
        sprite,
        polygon,
        visible,
    } in vector_shapes(scene, options.ids, options.hidden)
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
                .map(|href| (href, uv)),
            _ => None,
        };
        if let Some((href, uv)) = texture
            && let Some(place) = texture_placement(scene.root(), sprite, uv)
        {
            clip_count += 1;
            let m = place.to_cols_array();
            let _ = writeln!(
                svg,
                "<clipPath id=\"c{clip_count}\">{}</clipPath><g clip-path=\"url(#c{clip_count})\"><image href=\"{href}\" xlink:href=\"{href}\" width=\"1\" height=\"1\" preserveAspectRatio=\"none\" transform=\"matrix({} {} {} {} {} {})\"/></g>",
                shape.element(""),
                m[0],
                m[1],
                m[2],
                m[3],
                m[4],
                m[5]
            );
            continue;
        }
        let colour = if options.ids {
            id_colour(sprite.face)
        } else {
            sprite.brush.solid_colour(sprite.face)
        };
        let stroke = if !options.ids && options.seam_stroke > 0.0 && colour[3] == 255 {
            format!(
                " stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\"",
                hex(colour),
                options.seam_stroke
            )
        } else {
            String::new()
        };
        let paint = format!(" fill=\"{}\"{}{stroke}", hex(colour), opacity(colour));
        let _ = writeln!(svg, "{}", shape.element(&paint));
    }
    svg.push_str(&options.overlay);
    svg.push_str("</svg>\n");
    svg
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
            Shape::Path(d) => {
                format!("<path d=\"{d}\" fill-rule=\"evenodd\" clip-rule=\"evenodd\"{attributes}/>")
            }
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
                fmt(p.x),
                fmt(p.y)
            );
        }
        d.push_str("Z ");
    }
    d.truncate(d.trim_end().len());
    d
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
        let _ = write!(s, "{},{}", fmt(p.x), fmt(p.y));
    }
    s
}

/// Shortest text that keeps 1e-4 px.
fn fmt(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

/// Texture space `[0,1]²` → pixels, through the sprite's unit square (affine through the
/// projections of `(0,0)`, `(1,0)`, `(0,1)`).
fn texture_placement(root: &DMat4, sprite: &SceneSprite, uv: DAffine2) -> Option<DAffine2> {
    let full = *root * sprite.transform.matrix;
    let at = |u: f64, v: f64| {
        let h = full * DVec4::new(u, v, 0.0, 1.0);
        (h.w > 0.0).then(|| DVec2::new(h.x / h.w, h.y / h.w))
    };
    let (o, x, y) = (at(0.0, 0.0)?, at(1.0, 0.0)?, at(0.0, 1.0)?);
    let square_to_pixels = DAffine2::from_cols(x - o, y - o, o);
    let inverse_uv = uv.inverse();
    let place = square_to_pixels * inverse_uv;
    place.is_finite().then_some(place)
}
