//! The HTML/CSS 3D writer: one element per sprite (or per triangle of a clipped sprite).

use std::fmt::Write as _;

use glam::{DMat4, DVec2, DVec3, DVec4};

use crate::svg::{hex, project_sprite};
use crate::tolerance::UNDERFLOW_ABS;
use crate::{Scene, id_colour, perspective_matrix};

/// How the page orders faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum HtmlMode {
    /// Every element carries its full `matrix3d` (root included) and the document order is
    /// the painter's order: the browser only composites.
    #[default]
    Flat,
    /// The root transform sits on a `transform-style: preserve-3d` container and the sprites'
    /// own transforms on its children, so the browser orders the faces itself (a peer to
    /// compare against).
    Preserve3d,
}

/// Options of [`write_html`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct HtmlOptions {
    /// Page width in pixels. Default: 256.
    pub width: u32,
    /// Page height in pixels. Default: 256.
    pub height: u32,
    /// Flat or preserve-3d. Default: flat.
    pub mode: HtmlMode,
    /// Fill each face with its ID colour (CONVENTIONS.md). Default: false.
    pub ids: bool,
    /// Page background. Default: black (ID 0).
    pub background: [u8; 4],
    /// Each element is laid out at this many times its projected extent, so that the
    /// browser rasters it at least at screen resolution (smaller layers are filtered and bleed
    /// colour past their edges). Default: 4.
    pub oversize: f64,
    /// Orthographic roots get this perspective distance (pixels) so that Chromium treats the
    /// elements as 3D layers rastered at their own size. Default: 1e8.
    pub orthographic_distance: f64,
}

impl HtmlOptions {
    /// The defaults.
    pub const DEFAULT: HtmlOptions = HtmlOptions {
        width: 256,
        height: 256,
        mode: HtmlMode::Flat,
        ids: false,
        background: [0, 0, 0, 255],
        oversize: 4.0,
        orthographic_distance: 1e8,
    };

    /// Page size.
    #[must_use]
    pub fn with_size(mut self, width: u32, height: u32) -> Self {
        self.width = width;
        self.height = height;
        self
    }

    /// Mode.
    #[must_use]
    pub fn with_mode(mut self, mode: HtmlMode) -> Self {
        self.mode = mode;
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
    pub fn with_background(mut self, background: [u8; 4]) -> Self {
        self.background = background;
        self
    }
}

impl Default for HtmlOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// CSS `matrix3d(…)` of a matrix (column-major, as CSS expects).
#[must_use]
pub fn css_matrix3d(m: &DMat4) -> String {
    let mut s = String::from("matrix3d(");
    for (k, v) in m.to_cols_array().iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        let v = if v.abs() < UNDERFLOW_ABS { 0.0 } else { *v };
        let _ = write!(s, "{v:e}");
    }
    s.push(')');
    s
}

/// The scene as a self-contained HTML page (no scripts, no external resources).
///
/// A sprite without clip is one `div` (its unit square, scaled); a clipped sprite (triangle,
/// n-gon, fragment) is a fan of CSS border triangles, since `clip-path` under perspective is
/// pathologically slow in Chromium. Textured sprites use their fallback colour.
#[must_use]
pub fn write_html(scene: &Scene, options: &HtmlOptions) -> String {
    let (w, h) = (options.width, options.height);
    let origin = DVec3::new(f64::from(w) * 0.5, f64::from(h) * 0.5, 0.0);
    let mut root = *scene.root();
    if root.row(3) == DVec4::W {
        // Orthographic: a huge perspective about the frame centre (changes nothing visible).
        root = DMat4::from_translation(origin)
            * perspective_matrix(face_sort::Projection::Perspective {
                distance: options.orthographic_distance,
            })
            * DMat4::from_translation(-origin)
            * root;
    }
    let mut page = String::new();
    let _ = write!(
        page,
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>sprite-compose</title><style>\n\
         html,body{{margin:0;padding:0;overflow:hidden;width:{w}px;height:{h}px;background:{bg}}}\n\
         #scene{{position:absolute;left:0;top:0;width:{w}px;height:{h}px;{scene_style}}}\n\
         #scene>div{{position:absolute;left:0;top:0;transform-origin:0 0}}\n\
         .t{{width:0;height:0;border-style:solid}}\n\
         </style></head><body><div id=\"scene\">\n",
        bg = hex(options.background),
        scene_style = match options.mode {
            HtmlMode::Flat => String::new(),
            HtmlMode::Preserve3d => format!(
                "transform-style:preserve-3d;transform-origin:0 0;transform:{}",
                css_matrix3d(&root)
            ),
        },
    );
    for (_, sprite) in scene.visible() {
        let projected = project_sprite(scene.root(), sprite);
        if projected.len() < 3 {
            continue;
        }
        let (mut lo, mut hi) = (projected[0], projected[0]);
        for p in &projected {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        let extent = (hi - lo).max_element().max(1.0);
        let size = (extent * options.oversize).ceil().max(8.0);
        let colour = hex(if options.ids {
            id_colour(sprite.face)
        } else {
            sprite.brush.solid_colour(sprite.face)
        });
        let unscale = DMat4::from_scale(DVec3::new(1.0 / size, 1.0 / size, 1.0));
        let outer = match options.mode {
            HtmlMode::Flat => root,
            HtmlMode::Preserve3d => DMat4::IDENTITY,
        };
        match &sprite.clip {
            None => {
                let m = outer * sprite.transform.matrix * unscale;
                let _ = writeln!(
                    page,
                    "<div style=\"width:{size}px;height:{size}px;background:{colour};transform:{}\"></div>",
                    css_matrix3d(&m)
                );
            }
            Some(clip) => {
                for k in 1..clip.len().saturating_sub(1) {
                    let (a, mut b, mut c) = (clip[0], clip[k], clip[k + 1]);
                    if (b - a).perp_dot(c - a) < 0.0 {
                        std::mem::swap(&mut b, &mut c);
                    }
                    let corner = triangle_matrix(a, b, c);
                    let m = outer * sprite.transform.matrix * corner * unscale;
                    let _ = writeln!(
                        page,
                        "<div class=\"t\" style=\"border-width:{size}px {size}px 0 0;border-color:{colour} transparent transparent transparent;transform:{}\"></div>",
                        css_matrix3d(&m)
                    );
                }
            }
        }
    }
    page.push_str("</div></body></html>\n");
    page
}

/// The unit-square map taking `(0,0) → a`, `(1,0) → b`, `(0,1) → c` (unit-square coordinates).
fn triangle_matrix(a: DVec2, b: DVec2, c: DVec2) -> DMat4 {
    DMat4::from_cols(
        DVec4::new(b.x - a.x, b.y - a.y, 0.0, 0.0),
        DVec4::new(c.x - a.x, c.y - a.y, 0.0, 0.0),
        DVec4::Z,
        DVec4::new(a.x, a.y, 0.0, 1.0),
    )
}
