//! The HTML/CSS 3D writer: one element per sprite (or per triangle of a clipped sprite).

use std::fmt::Write as _;

use std::collections::HashMap;

use glam::{DAffine2, DMat3, DMat4, DVec2, DVec3, DVec4};

use crate::numbers::hex;
use crate::seams::{ScreenPolygons, SharedEdges, outset_polygon};
use crate::tolerance::{
    HTML_QUAD_WEIGHT_RATIO, HTML_SEAM_OUTSET_PX, HTML_SEAM_PX, HTML_SHARED_EDGE_PX,
    HTML_TEXTURE_MARGIN_PX,
};
use crate::{Brush, Scene, SceneSprite, id_colour, perspective_matrix};
use crate::{project_sprite, sprite_polygon};
use sprite_compose::tolerance::{SINGULAR_DET, UNDERFLOW_ABS};

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

/// How [`write_html`] draws a clipped sprite (triangle, n-gon, fragment).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum HtmlPieces {
    /// Plain boxes under projective `matrix3d`s, each a convex quad of the clip polygon: every
    /// edge is an element edge, composited without anti-aliasing (exact at pixel centres);
    /// plus thin strips over the edges a sprite shares with later fragments of its face,
    /// which fill the cracks Chromium leaves between layers.
    #[default]
    Quads,
    /// CSS border triangles (the earlier writer, kept for comparison): Chromium rasters their
    /// diagonal with anti-aliasing, so where two fragments of one face meet along diagonals
    /// the background shows through at single pixels.
    BorderTriangles,
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
    /// Page background. Default: none, which is white in colour mode (the browser's page, as
    /// raster-sink's PNG and the SVG and PDF writers) and black (ID 0) in ID mode.
    pub background: Option<[u8; 4]>,
    /// Each element is laid out at this many times its projected extent, so that the
    /// browser rasters it at least at screen resolution (smaller layers are filtered and bleed
    /// colour past their edges). Default: 4.
    pub oversize: f64,
    /// Orthographic roots get this perspective distance (pixels) so that Chromium treats the
    /// elements as 3D layers rastered at their own size. Default: 1e8.
    pub orthographic_distance: f64,
    /// How clipped sprites are drawn. Default: [`HtmlPieces::Quads`].
    pub pieces: HtmlPieces,
    /// `src` of each texture, indexed by [`TextureId`](sprite_compose::TextureId) (a data URI or a
    /// path relative to the page). Textured sprites whose texture has no entry, and every
    /// sprite in ID mode, use their fallback colour. Default: none.
    pub textures: Vec<String>,
    /// Lines and points drawn over the faces, in their own colours: the same SVG markup the
    /// SVG writer draws ([`overlay_svg`](crate::overlay_svg)), as an inline
    /// `<svg>` over the scene. Default: none.
    pub overlay: String,
}

impl HtmlOptions {
    /// The defaults.
    pub const DEFAULT: HtmlOptions = HtmlOptions {
        width: 256,
        height: 256,
        mode: HtmlMode::Flat,
        ids: false,
        background: None,
        oversize: 4.0,
        orthographic_distance: 1e8,
        pieces: HtmlPieces::Quads,
        textures: Vec::new(),
        overlay: String::new(),
    };

    /// Lines and points over the faces (SVG markup, e.g. `DrawnOverlay::to_svg`).
    #[must_use]
    pub fn with_overlay(mut self, overlay: String) -> Self {
        self.overlay = overlay;
        self
    }

    /// How clipped sprites are drawn.
    #[must_use]
    pub fn with_pieces(mut self, pieces: HtmlPieces) -> Self {
        self.pieces = pieces;
        self
    }

    /// Mode.
    #[must_use]
    pub fn with_mode(mut self, mode: HtmlMode) -> Self {
        self.mode = mode;
        self
    }
}

crate::page::page_setters!(HtmlOptions: size, ids, background, textures);

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
        s.push_str(&crate::numbers::matrix_entry(v));
    }
    s.push(')');
    s
}

/// The scene as a self-contained HTML page (no scripts; no external resources other than the
/// texture `src`s given).
///
/// A sprite without clip is one `div` (its unit square, scaled); a clipped sprite (triangle,
/// n-gon, fragment) is a few `div`s, convex quads of its clip polygon
/// ([`HtmlPieces::Quads`]), since `clip-path` under perspective is pathologically slow in
/// Chromium. A textured sprite (colour mode, its texture given in
/// [`HtmlOptions::textures`]) is one `div` of its whole unit square under the exact
/// (projective) `matrix3d`, holding an `<img>` placed by the brush's affine uv map in the
/// square's own plane, so the texture follows the homography exactly; its clip polygon, if
/// any, is a `clip-path` on an untransformed inner `div` (rastered into the element's layer,
/// anti-aliased, not the slow case).
///
/// Seams: in colour mode every opaque sprite reaches [`HTML_SEAM_OUTSET_PX`] pixels past
/// each edge it shares with another sprite ([`seams`](crate::seams), as raster-sink's PNG
/// does), and its quads overlap one another, so that no background shows between
/// anti-aliased neighbours; silhouettes stay where they are. In ID mode nothing grows: the
/// page is exact at pixel centres, with thin strips under the split lines between fragments
/// of one face instead.
#[must_use]
pub fn write_html(scene: &Scene, options: &HtmlOptions) -> String {
    let root = page_root(scene, options);
    // Flat pages: the root's perspective on the container (CSS `perspective` about the
    // principal point is CONVENTIONS.md's `w = 1 − z/d`), so each element carries only an
    // affine matrix.
    let flat = FlatRoot::of(&root);
    let head = page_head(options, &root, &flat);
    // The elements go to `body`; what repeats (colours, box sizes) becomes one class each,
    // written into the style sheet once the body is known.
    let mut page = String::new();
    let mut classes = Classes::default();
    let sprites: Vec<&SceneSprite> = scene.visible().map(|(_, s)| s).collect();
    let projections: Vec<Vec<DVec2>> = sprites
        .iter()
        .map(|s| project_sprite(scene.root(), s))
        .collect();
    let mut by_face: HashMap<u32, Vec<usize>> = HashMap::new();
    for (k, s) in sprites.iter().enumerate() {
        by_face.entry(s.face).or_default().push(k);
    }
    let seams = (!options.ids).then(|| Seams::of(&projections));
    for (index, sprite) in sprites.iter().copied().enumerate() {
        let projected = &projections[index];
        if projected.len() < 3 {
            continue;
        }
        let (mut lo, mut hi) = (projected[0], projected[0]);
        for p in projected {
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
            HtmlMode::Flat => flat.affine,
            HtmlMode::Preserve3d => DMat4::IDENTITY,
        };
        let texture = match sprite.brush {
            Brush::Texture { texture, uv, .. } if !options.ids => options
                .textures
                .get(texture.0 as usize)
                .map(|_| (texture.0, uv)),
            _ => None,
        };
        // A textured element is the sprite's whole unit square: its size follows the square's
        // projection (a fragment's can be far smaller), so the texture is rastered finely.
        let square_size = texture.and_then(|_| square_size(scene, sprite, options.oversize, size));
        // The element is the unit square grown by a margin of `e` (HTML_TEXTURE_MARGIN_PX in
        // pixels of the square), clipped to the sprite's polygon grown across its shared
        // edges: no edge of the element's box is an edge of the picture, so Chromium's
        // composited anti-aliasing of layer edges leaves no hairline between neighbouring
        // textured sprites.
        if let Some((id, uv)) = texture
            && let Some(size) = square_size
            && let Some(element) = textured_element(&TexturedSprite {
                sprite,
                outer,
                grown: seams
                    .as_ref()
                    .and_then(|seams| seams.grown(scene.root(), sprite, index)),
                texture: id,
                uv,
                size,
            })
        {
            page.push_str(&element);
            continue;
        }
        let opaque = options.ids || sprite.brush.solid_colour(sprite.face)[3] == 255;
        if opaque
            && let Some(grown) = seams
                .as_ref()
                .and_then(|seams| seams.grown(scene.root(), sprite, index))
            && let Some((to_square, clip)) = clipped_box(&grown, size)
        {
            let m = outer * sprite.transform.matrix * to_square * unscale;
            let _ = writeln!(
                page,
                "<div class=\"x {}\" style=\"transform:{}\"><div class=\"{}\" style=\"{clip}\"></div></div>",
                classes.of(format!("width:{size}px;height:{size}px")),
                css_matrix3d(&m),
                classes.of(format!("background:{colour}")),
            );
            continue;
        }
        match &sprite.clip {
            None => {
                let m = outer * sprite.transform.matrix * unscale;
                let _ = writeln!(
                    page,
                    "<div class=\"{} {}\" style=\"transform:{}\"></div>",
                    classes.of(format!("width:{size}px;height:{size}px")),
                    classes.of(format!("background:{colour}")),
                    css_matrix3d(&m)
                );
            }
            Some(clip) if options.pieces == HtmlPieces::BorderTriangles => {
                let place = outer * sprite.transform.matrix;
                border_triangles(&mut page, &mut classes, clip, place, size, &colour);
            }
            Some(clip) => {
                let later = (by_face
                    .get(&sprite.face)
                    .map_or(&[][..], Vec::as_slice)
                    .iter())
                .filter(|&&k| k > index)
                .map(|&k| projections[k].as_slice());
                // (Opaque sprites with shared edges grew across them above; these strips
                // fill ID pages' cracks.)
                let strips = if options.ids {
                    seam_strips(scene.root(), sprite, projected, later)
                } else {
                    Vec::new()
                };
                let quads = if opaque {
                    opaque_clip_quads(clip)
                } else {
                    clip_quads(clip)
                };
                for quad in quads.into_iter().chain(strips) {
                    let m = outer * sprite.transform.matrix * quad * unscale;
                    let _ = writeln!(
                        page,
                        "<div class=\"{} {}\" style=\"transform:{}\"></div>",
                        classes.of(format!("width:{size}px;height:{size}px")),
                        classes.of(format!("background:{colour}")),
                        css_matrix3d(&m)
                    );
                }
            }
        }
    }
    let mut out = head;
    out.push_str(&classes.rules());
    out.push_str("</style></head><body><div id=\"scene\">\n");
    out.push_str(&page);
    out.push_str("</div>\n");
    out.push_str(&overlay_element(options));
    out.push_str("</body></html>\n");
    out
}

/// `options.overlay` as an SVG over the whole page (nothing when it is empty).
fn overlay_element(options: &HtmlOptions) -> String {
    if options.overlay.is_empty() {
        return String::new();
    }
    let (w, h) = (options.width, options.height);
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" style=\"position:absolute;left:0;top:0\">{}</svg>\n",
        options.overlay
    )
}

/// The root the page draws with: the scene's, and for an orthographic one a huge
/// perspective about the frame centre (`options.orthographic_distance`; it changes nothing
/// visible).
fn page_root(scene: &Scene, options: &HtmlOptions) -> DMat4 {
    let root = *scene.root();
    if root.row(3) != DVec4::W {
        return root;
    }
    let origin = DVec3::new(
        f64::from(options.width) * 0.5,
        f64::from(options.height) * 0.5,
        0.0,
    );
    DMat4::from_translation(origin)
        * perspective_matrix(face_sort::Projection::Perspective {
            distance: options.orthographic_distance,
        })
        * DMat4::from_translation(-origin)
        * root
}

/// A clipped sprite as CSS border triangles ([`HtmlPieces::BorderTriangles`]): one
/// zero-size element per fan triangle of `clip`, under `place` (the element's matrix before
/// its unit square is scaled to `size` pixels).
fn border_triangles(
    page: &mut String,
    classes: &mut Classes,
    clip: &[DVec2],
    place: DMat4,
    size: f64,
    colour: &str,
) {
    let unscale = DMat4::from_scale(DVec3::new(1.0 / size, 1.0 / size, 1.0));
    for k in 1..clip.len().saturating_sub(1) {
        let (a, mut b, mut c) = (clip[0], clip[k], clip[k + 1]);
        if (b - a).perp_dot(c - a) < 0.0 {
            std::mem::swap(&mut b, &mut c);
        }
        let m = place * triangle_matrix(a, b, c) * unscale;
        let _ = writeln!(
            page,
            "<div class=\"{} {}\" style=\"transform:{}\"></div>",
            classes.of(format!(
                "width:0;height:0;border-style:solid;border-width:{size}px {size}px 0 0"
            )),
            classes.of(format!(
                "border-color:{colour} transparent transparent transparent"
            )),
            css_matrix3d(&m)
        );
    }
}

/// The page up to the element style rules: the document head, the body's size and
/// background (black in ID mode, else white, unless `options.background`), and the scene
/// container's perspective (flat pages) or root transform (`preserve-3d`).
fn page_head(options: &HtmlOptions, root: &DMat4, flat: &FlatRoot) -> String {
    let (w, h) = (options.width, options.height);
    let background = crate::page::background(options.background, options.ids);
    let mut page = crate::page::head("vector-sink", w, h, background);
    let _ = write!(
        page,
        "#scene{{position:absolute;left:0;top:0;width:{w}px;height:{h}px;{scene_style}}}\n\
     #scene>div{{position:absolute;left:0;top:0;transform-origin:0 0}}\n\
     .x{{overflow:hidden}}\n\
     .x>div{{position:absolute;left:0;top:0;width:100%;height:100%;overflow:hidden}}\n\
     .x i{{position:absolute;left:0;top:0;width:100%;height:100%;transform-origin:0 0;background-size:100% 100%}}\n\
     {texture_rules}",
        texture_rules = texture_rules(options),
        scene_style = match options.mode {
            HtmlMode::Flat => format!(
                "perspective:{}px;perspective-origin:{}px {}px",
                crate::numbers::matrix_entry(flat.distance),
                crate::numbers::pixel(flat.origin.x),
                crate::numbers::pixel(flat.origin.y)
            ),
            HtmlMode::Preserve3d => format!(
                "transform-style:preserve-3d;transform-origin:0 0;transform:{}",
                css_matrix3d(root)
            ),
        },
    );
    page
}

/// The size of a textured sprite's element: its whole unit square's projection (a
/// fragment's can be far smaller) times `oversize`, at least `size`; `None` when a corner is
/// behind the viewer or the extent is not finite.
fn square_size(scene: &Scene, sprite: &SceneSprite, oversize: f64, size: f64) -> Option<f64> {
    let full = *scene.root() * sprite.transform.matrix;
    let corners: Option<Vec<DVec2>> = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y]
        .iter()
        .map(|c| {
            let h = full * DVec4::new(c.x, c.y, 0.0, 1.0);
            (h.w > 0.0).then(|| DVec2::new(h.x / h.w, h.y / h.w))
        })
        .collect();
    let corners = corners?;
    let (lo, hi) = (corners.iter()).fold((corners[0], corners[0]), |(lo, hi), p| {
        (lo.min(*p), hi.max(*p))
    });
    let extent = (hi - lo).max_element();
    (extent.is_finite()).then(|| (extent.max(1.0) * oversize).ceil().max(size))
}

/// A textured sprite as [`textured_element`] writes it.
struct TexturedSprite<'a> {
    sprite: &'a SceneSprite,
    /// The flat page's affine part of the root (identity in `preserve-3d`).
    outer: DMat4,
    /// The sprite's polygon grown across its shared edges, if it has any.
    grown: Option<Vec<DVec2>>,
    texture: u32,
    uv: DAffine2,
    /// The element's size in pixels ([`square_size`]).
    size: f64,
}

/// One textured element: the unit square grown by a margin of `e`
/// ([`HTML_TEXTURE_MARGIN_PX`] in pixels of the square), clipped to the sprite's polygon
/// grown across its shared edges, holding the texture under its uv map. No edge of the
/// element's box is an edge of the picture, so Chromium's composited anti-aliasing of layer
/// edges leaves no hairline between neighbouring textured sprites. `None` when the uv map
/// has no placement.
fn textured_element(t: &TexturedSprite<'_>) -> Option<String> {
    let (size, sprite) = (t.size, t.sprite);
    let e = HTML_TEXTURE_MARGIN_PX / size;
    let grow =
        DAffine2::from_scale_angle_translation(DVec2::splat(1.0 + 2.0 * e), 0.0, DVec2::splat(-e));
    let place = image_placement(t.uv * grow, size)?;
    let unscale = DMat4::from_scale(DVec3::new(1.0 / size, 1.0 / size, 1.0));
    let box_to_square = DMat4::from_translation(DVec3::new(-e, -e, 0.0))
        * DMat4::from_scale(DVec3::new(1.0 + 2.0 * e, 1.0 + 2.0 * e, 1.0));
    let m = t.outer * sprite.transform.matrix * box_to_square * unscale;
    let dilated = t.grown.clone().unwrap_or_else(|| sprite_polygon(sprite));
    let clip = clip_path(
        dilated
            .iter()
            .map(|p| (*p + DVec2::splat(e)) / (1.0 + 2.0 * e)),
    );
    Some(format!(
        "<div class=\"x\" style=\"width:{size}px;height:{size}px;transform:{}\"><div style=\"{clip}\"><i class=\"t{}\" style=\"transform:{place}\"></i></div></div>\n",
        css_matrix3d(&m),
        t.texture
    ))
}

/// A perspective root `T(P₀) · P · A` split into the container's perspective (distance `d`
/// and origin `P₀`, which CSS applies as `T(P₀) · P · T(−P₀)`) and the affine rest
/// `T(P₀) · A` each element carries. The root's last row is `(0, 0, −1/d, 1) · A`
/// and `A`'s 3 × 3 part is a rotation, so `1/d` is that row's length in x, y, z; `P₀` follows
/// from the first two rows, whose rotation parts are orthogonal to the third.
struct FlatRoot {
    distance: f64,
    origin: DVec2,
    affine: DMat4,
}

impl FlatRoot {
    fn of(root: &DMat4) -> Self {
        let last = root.row(3);
        let inverse_d = last.truncate().length();
        let distance = 1.0 / inverse_d.max(UNDERFLOW_ABS);
        let third = -last.truncate() * distance; // A's third row, a unit vector
        let origin = DVec2::new(
            -distance * root.row(0).truncate().dot(third),
            -distance * root.row(1).truncate().dot(third),
        );
        let mut perspective = DMat4::IDENTITY;
        perspective.z_axis.w = -inverse_d;
        // CSS applies the container's perspective about its origin: T(P₀) · P · T(−P₀).
        let about = |m: DMat4| {
            DMat4::from_translation(origin.extend(0.0))
                * m
                * DMat4::from_translation(-origin.extend(0.0))
        };
        let affine = about(perspective.inverse()) * *root;
        FlatRoot {
            distance,
            origin,
            affine,
        }
    }
}

/// CSS classes for declarations that repeat: one short class per distinct declaration.
#[derive(Default)]
struct Classes {
    names: HashMap<String, usize>,
    order: Vec<String>,
}

impl Classes {
    /// The class of `declaration` (made on first use).
    fn of(&mut self, declaration: String) -> String {
        let next = self.order.len();
        let k = *self.names.entry(declaration.clone()).or_insert_with(|| {
            self.order.push(declaration);
            next
        });
        format!("k{k:x}")
    }

    /// The style rules of every class made.
    fn rules(&self) -> String {
        let mut out = String::new();
        for (k, declaration) in self.order.iter().enumerate() {
            let _ = writeln!(out, ".k{k:x}{{{declaration}}}");
        }
        out
    }
}

/// Thin quads (maps of the unit square, unit-square coordinates) reaching
/// [`HTML_SEAM_PX`] pixels to both sides of each edge of a clipped sprite that a later-drawn sprite of the
/// same face shares (a split line between fragments), over the shared stretch.
///
/// Chromium rasters layer edges in fixed point after float transforms, so two layers that
/// share an edge can leave a crack between them: a pixel centre 0.0016 px inside a fragment
/// showed the background (docs/html-fragment-crack.png). The strip is drawn with the earlier
/// fragment, under the later one, so it shows only where the later fragment leaves a crack;
/// whatever should cover the strip is drawn after it (it covers the earlier fragment's side
/// of the split line too).
fn seam_strips<'a>(
    root: &DMat4,
    sprite: &SceneSprite,
    projected: &[DVec2],
    later: impl Iterator<Item = &'a [DVec2]>,
) -> Vec<DMat4> {
    let later: Vec<&[DVec2]> = later.collect();
    if later.is_empty() {
        return Vec::new();
    }
    let Some((_, to_square)) = square_homography(root, sprite) else {
        return Vec::new();
    };
    let back = |p: DVec2| to_unit_square(&to_square, p);
    let n = projected.len();
    let area: f64 = (0..n)
        .map(|k| projected[k].perp_dot(projected[(k + 1) % n]))
        .sum();
    let mut out = Vec::new();
    for k in 0..n {
        let (p, q) = (projected[k], projected[(k + 1) % n]);
        let length = (q - p).length();
        if length <= HTML_SHARED_EDGE_PX {
            continue;
        }
        let along = (q - p) / length;
        // Outward normal: the polygon lies to the left of its edges when its area is positive
        // (in y-down pixels), to the right otherwise.
        let outward = if area > 0.0 {
            -along.perp()
        } else {
            along.perp()
        };
        for other in &later {
            let m = other.len();
            for j in 0..m {
                let (r, s) = (other[j], other[(j + 1) % m]);
                let off = |x: DVec2| along.perp_dot(x - p).abs();
                if off(r) > HTML_SHARED_EDGE_PX || off(s) > HTML_SHARED_EDGE_PX {
                    continue;
                }
                let (tr, ts) = (along.dot(r - p), along.dot(s - p));
                let (t0, t1) = (tr.min(ts).max(0.0), tr.max(ts).min(length));
                if t1 - t0 <= HTML_SHARED_EDGE_PX {
                    continue;
                }
                let (a, b) = (p + along * t0, p + along * t1);
                // Straddling the edge (its inner half over the sprite itself): an inner side
                // on the edge line would be rounded like the edge.
                let w = outward * HTML_SEAM_PX;
                let corners = [a - w, b - w, b + w, a + w];
                let square: Option<Vec<DVec2>> = corners.iter().map(|&c| back(c)).collect();
                if let Some(square) = square
                    && let Some(quad) = quad_matrix([square[0], square[1], square[2], square[3]])
                {
                    out.push(quad);
                }
            }
        }
    }
    out
}

/// The sprite's unit square → pixels as a 3×3 homography, and its inverse; `None` when
/// singular.
fn square_homography(root: &DMat4, sprite: &SceneSprite) -> Option<(DMat3, DMat3)> {
    let full = *root * sprite.transform.matrix;
    let plane = DMat3::from_cols(
        DVec3::new(full.x_axis.x, full.x_axis.y, full.x_axis.w),
        DVec3::new(full.y_axis.x, full.y_axis.y, full.y_axis.w),
        DVec3::new(full.w_axis.x, full.w_axis.y, full.w_axis.w),
    );
    (plane.determinant().abs() > UNDERFLOW_ABS).then(|| (plane, plane.inverse()))
}

/// A pixel mapped back to unit-square coordinates; `None` at infinity.
fn to_unit_square(to_square: &DMat3, p: DVec2) -> Option<DVec2> {
    let h = *to_square * DVec3::new(p.x, p.y, 1.0);
    let s = DVec2::new(h.x / h.z, h.y / h.z);
    (h.z.abs() > UNDERFLOW_ABS && s.is_finite()).then_some(s)
}

/// The sprites' projected polygons and which of their edges another sprite shares, for the
/// seam outset of colour pages.
struct Seams {
    polygons: ScreenPolygons,
    shared: SharedEdges,
}

impl Seams {
    fn of(projections: &[Vec<DVec2>]) -> Self {
        let mut polygons = ScreenPolygons::default();
        polygons.clear();
        for p in projections {
            polygons.push(p);
        }
        let mut shared = SharedEdges::default();
        shared.compute(&polygons);
        Seams { polygons, shared }
    }

    /// Sprite `index`'s polygon (unit-square coordinates) grown [`HTML_SEAM_OUTSET_PX`]
    /// pixels across the edges it shares; `None` when it shares none, or when a grown corner
    /// cannot be mapped back onto the sprite's plane.
    fn grown(&self, root: &DMat4, sprite: &SceneSprite, index: usize) -> Option<Vec<DVec2>> {
        let flags = self.shared.flags(self.polygons.edges(index));
        if !flags.contains(&true) {
            return None;
        }
        let (_, to_square) = square_homography(root, sprite)?;
        let mut grown = Vec::new();
        outset_polygon(
            self.polygons.polygon(index),
            flags,
            HTML_SEAM_OUTSET_PX,
            &mut grown,
        );
        grown
            .iter()
            .map(|&p| to_unit_square(&to_square, p))
            .collect()
    }
}

/// CSS `matrix(…)` placing an `<img>` that fills a `size`-pixel box (texture space `[0,1]²`
/// scaled by `size`) where the uv map `uv` (unit square → texture) puts it: `size · uv⁻¹ /
/// size`. `None` when the uv map is singular.
fn image_placement(uv: DAffine2, size: f64) -> Option<String> {
    let l = uv.matrix2;
    if l.determinant().powi(2)
        <= SINGULAR_DET * l.x_axis.length_squared() * l.y_axis.length_squared()
    {
        return None;
    }
    let inverse = uv.inverse();
    let (a, b) = (inverse.matrix2.x_axis, inverse.matrix2.y_axis);
    let t = inverse.translation * size;
    let values = [a.x, a.y, b.x, b.y, t.x, t.y];
    values.iter().all(|v| v.is_finite()).then(|| {
        let mut s = String::from("matrix(");
        for (k, v) in values.iter().enumerate() {
            let _ = write!(s, "{}{v:e}", if k > 0 { "," } else { "" });
        }
        s.push(')');
        s
    })
}

/// Convex quads (as maps of the unit square, in the sprite's unit-square coordinates) whose
/// union is the convex polygon `clip`, each a plain box under a projective `matrix3d`.
///
/// Every edge is an element edge, which Chromium composites without anti-aliasing under
/// `--disable-composited-antialiasing`: a border triangle's diagonal is rastered with
/// anti-aliasing instead, and where two fragments of one face meet along such diagonals the
/// background showed through at single pixels (docs/html-border-seam.png). Consecutive fan
/// triangles pair into quads `(c0, ck, ck+1, ck+2)` (overlapping the previous one when the
/// count is odd); a lone triangle is cut into three quads at its centroid and edge midpoints.
/// Quads whose homography is ill-conditioned fall back to their two triangles' cuts (whose
/// corner weights always differ by exactly 3×: each is an affine image of one fixed quad).
pub(crate) fn clip_quads(clip: &[DVec2]) -> Vec<DMat4> {
    let mut out = Vec::new();
    let n = clip.len();
    if n < 3 {
        return out;
    }
    let triangles = n - 2;
    if triangles == 1 {
        triangle_quads(clip[0], clip[1], clip[2], &mut out);
        return out;
    }
    let mut k = 1;
    while k < n - 1 {
        // The quad starting at fan triangle k; the last one steps back by one when the count
        // of fan triangles is odd (it then overlaps its predecessor, same face and colour).
        let start = if k + 2 < n { k } else { n - 3 };
        let corners = [clip[0], clip[start], clip[start + 1], clip[start + 2]];
        if let Some(m) = quad_matrix(corners) {
            out.push(m);
        } else {
            triangle_quads(corners[0], corners[1], corners[2], &mut out);
            triangle_quads(corners[0], corners[2], corners[3], &mut out);
        }
        k += 2;
    }
    out
}

/// [`clip_quads`] for an opaque sprite, which may overlap itself: a lone triangle is two
/// quads instead of three, the trapezoid `(a, b, m_bc, m_ca)` and the parallelogram
/// `(m_ab, m_bc, c, m_ca)` (`m` the edge midpoints), overlapping on the medial triangle. Both
/// are well-shaped whenever the triangle has area, their union is the triangle (what the
/// trapezoid leaves, the triangle `(m_ca, m_bc, c)`, lies in the parallelogram), and each
/// one's inner edges lie inside the other.
pub(crate) fn opaque_clip_quads(clip: &[DVec2]) -> Vec<DMat4> {
    if let [a, b, c] = *clip {
        let mut out = Vec::new();
        opaque_triangle_quads(a, b, c, &mut out);
        return out;
    }
    clip_quads(clip)
}

/// A colour page's opaque sprite as one element: the box of `polygon` (unit-square
/// coordinates) grown by a margin of [`HTML_TEXTURE_MARGIN_PX`] (in pixels of a `size`-pixel
/// element), clipped back to `polygon`. Returns the map from the element's unit box to the
/// sprite's unit square and the element's `clip-path` declaration; `None` when the polygon has
/// no area. No edge of the element's box is an edge of the picture, and the sprite's polygon is
/// one clip, so no edge inside the sprite is drawn at all: only the grown outline is
/// anti-aliased, where it lies under its neighbours.
fn clipped_box(polygon: &[DVec2], size: f64) -> Option<(DMat4, String)> {
    let (mut lo, mut hi) = (*polygon.first()?, polygon[0]);
    for p in polygon {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let span = hi - lo;
    if !(span.min_element() > 0.0 && span.is_finite()) {
        return None;
    }
    let e = HTML_TEXTURE_MARGIN_PX / size;
    let to_square = DMat4::from_translation(lo.extend(0.0))
        * DMat4::from_scale(span.extend(1.0))
        * DMat4::from_translation(DVec3::new(-e, -e, 0.0))
        * DMat4::from_scale(DVec3::new(1.0 + 2.0 * e, 1.0 + 2.0 * e, 1.0));
    let clip = clip_path(
        polygon
            .iter()
            .map(|p| ((*p - lo) / span + DVec2::splat(e)) / (1.0 + 2.0 * e)),
    );
    Some((to_square, clip))
}

/// `clip-path:polygon(…)` through `points`, given in the element's unit box.
fn clip_path(points: impl Iterator<Item = DVec2>) -> String {
    let mut c = String::from("clip-path:polygon(");
    for (k, b) in points.enumerate() {
        let _ = write!(
            c,
            "{}{}% {}%",
            if k > 0 { "," } else { "" },
            crate::numbers::significant(b.x * 100.0, 6),
            crate::numbers::significant(b.y * 100.0, 6)
        );
    }
    c.push(')');
    c
}

/// A triangle as [`opaque_clip_quads`] draws it: two overlapping quads, or, when one of them
/// is ill-shaped, three quads meeting at its centroid.
fn opaque_triangle_quads(a: DVec2, b: DVec2, c: DVec2, out: &mut Vec<DMat4>) {
    let (ab, bc, ca) = ((a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5);
    if let (Some(p), Some(q)) = (quad_matrix([a, b, bc, ca]), quad_matrix([ab, bc, c, ca])) {
        out.extend([p, q]);
    } else {
        triangle_quads(a, b, c, out);
    }
}

/// The triangle `(a, b, c)` as three quads meeting at its centroid (corner, edge midpoint,
/// centroid, edge midpoint): convex, well-shaped whenever the triangle has area.
fn triangle_quads(a: DVec2, b: DVec2, c: DVec2, out: &mut Vec<DMat4>) {
    let g = (a + b + c) / 3.0;
    let (ab, bc, ca) = ((a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5);
    for corners in [[a, ab, g, ca], [b, bc, g, ab], [c, ca, g, bc]] {
        if let Some(m) = quad_matrix(corners) {
            out.push(m);
        }
    }
}

/// The projective map of the unit square taking `(0,0), (1,0), (1,1), (0,1)` to the corners
/// of a convex quad (unit-square coordinates), or `None` when the quad is degenerate or its
/// projective weights at the corners differ by more than [`HTML_QUAD_WEIGHT_RATIO`] (a quad
/// with a vanishing edge: Chromium dropped such layers whole).
fn quad_matrix(p: [DVec2; 4]) -> Option<DMat4> {
    let d1 = p[1] - p[2];
    let d2 = p[3] - p[2];
    let s = p[0] - p[1] + p[2] - p[3];
    let det = d1.perp_dot(d2);
    let scale = (p[2] - p[0])
        .length_squared()
        .max((p[3] - p[1]).length_squared());
    if det.abs() <= SINGULAR_DET.sqrt() * scale || !det.is_finite() {
        return None;
    }
    let g = s.perp_dot(d2) / det;
    let h = d1.perp_dot(s) / det;
    // Weights at the four corners: 1, 1 + g, 1 + g + h, 1 + h (positive for a convex quad).
    let weights = [1.0, 1.0 + g, 1.0 + g + h, 1.0 + h];
    let (lo, hi) = weights.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), w| {
        (lo.min(*w), hi.max(*w))
    });
    if !(lo > 0.0 && hi <= HTML_QUAD_WEIGHT_RATIO * lo) {
        return None;
    }
    let u = p[1] - p[0] + p[1] * g;
    let v = p[3] - p[0] + p[3] * h;
    Some(DMat4::from_cols(
        DVec4::new(u.x, u.y, 0.0, g),
        DVec4::new(v.x, v.y, 0.0, h),
        DVec4::Z,
        DVec4::new(p[0].x, p[0].y, 0.0, 1.0),
    ))
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

/// One CSS rule per texture, `.t<k>`, holding its image once for the whole page.
fn texture_rules(options: &HtmlOptions) -> String {
    if options.ids {
        return String::new();
    }
    let mut rules = String::new();
    for (k, src) in options.textures.iter().enumerate() {
        let _ = writeln!(
            rules,
            ".t{k}{{background-image:url(\"{}\")}}",
            escape_css_string(src)
        );
    }
    rules
}

/// `text` escaped for a double-quoted CSS string: quotes, backslashes, `<` (so that no
/// `</style>` can end the style element) and every character the HTML parser reports in a
/// style element (controls, NUL, noncharacters) as CSS hex escapes. NUL, which CSS reads as
/// U+FFFD, is written as U+FFFD.
fn escape_css_string(text: &str) -> std::borrow::Cow<'_, str> {
    let needs = |c: char| {
        matches!(c, '"' | '\\' | '<' | '\u{0}'..='\u{1f}' | '\u{7f}'..='\u{9f}')
            || is_noncharacter(c)
    };
    if !text.chars().any(needs) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 16);
    for c in text.chars() {
        if needs(c) {
            let code = if c == '\u{0}' { 0xfffd } else { u32::from(c) };
            let _ = write!(out, "\\{code:x} ");
        } else {
            out.push(c);
        }
    }
    std::borrow::Cow::Owned(out)
}

/// A Unicode noncharacter (U+FDD0 to U+FDEF, and the last two code points of every plane).
fn is_noncharacter(c: char) -> bool {
    let code = u32::from(c);
    (0xfdd0..=0xfdef).contains(&code) || code & 0xfffe == 0xfffe
}

#[cfg(test)]
mod tests {

    #[test]
    fn a_flat_root_splits_into_the_container_perspective_and_an_affine_rest() {
        use face_sort::{Bounds, View};
        let bounds = Bounds {
            min: DVec3::splat(-1.0),
            max: DVec3::splat(1.0),
        };
        for view in [
            View::fit(&bounds, 300, 200)
                .with_yaw_pitch_roll(35.0, 25.0, -10.0)
                .with_perspective(300.0),
            View::fit(&bounds, 300, 200)
                .with_yaw_pitch_roll(-70.0, 5.0, 0.0)
                .with_perspective(450.0)
                .with_view_offset(DVec3::new(0.3, -0.2, -0.7))
                .with_principal_point(170.0, 80.0),
        ] {
            let root = sprite_compose::root_transform(&view);
            let flat = FlatRoot::of(&root);
            assert!((flat.affine.row(3) - DVec4::W).abs().max_element() < 1e-12);
            let mut perspective = DMat4::IDENTITY;
            perspective.z_axis.w = -1.0 / flat.distance;
            let o = flat.origin.extend(0.0);
            let again = DMat4::from_translation(o)
                * perspective
                * DMat4::from_translation(-o)
                * flat.affine;
            assert!(again.abs_diff_eq(root, 1e-9), "{again} vs {root}");
            assert!((flat.origin - view.principal_point()).length() < 1e-9);
        }
    }

    use super::*;

    /// Whether `p` is inside the image of the unit square under `m` (2D part), by inverting
    /// the homography; `None` when `p` is within `margin` of that image's boundary.
    fn in_quad(m: &DMat4, p: DVec2, margin: f64) -> Option<bool> {
        let corners = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y].map(|c| {
            let h = *m * DVec4::new(c.x, c.y, 0.0, 1.0);
            DVec2::new(h.x / h.w, h.y / h.w)
        });
        let sides: Vec<f64> = (0..4)
            .map(|k| {
                let (a, b) = (corners[k], corners[(k + 1) % 4]);
                (b - a).perp_dot(p - a) / (b - a).length()
            })
            .collect();
        if sides.iter().any(|s| s.abs() <= margin) {
            return None;
        }
        Some(sides.iter().all(|s| *s > 0.0) || sides.iter().all(|s| *s < 0.0))
    }

    fn in_polygon(poly: &[DVec2], p: DVec2, margin: f64) -> Option<bool> {
        let n = poly.len();
        let sides: Vec<f64> = (0..n)
            .map(|k| {
                let (a, b) = (poly[k], poly[(k + 1) % n]);
                (b - a).perp_dot(p - a) / (b - a).length()
            })
            .collect();
        if sides.iter().any(|s| s.abs() <= margin) {
            return None;
        }
        Some(sides.iter().all(|s| *s > 0.0))
    }

    #[test]
    fn opaque_triangles_are_two_quads_covering_exactly_the_triangle() {
        let triangles = [
            [
                DVec2::new(0.1, 0.1),
                DVec2::new(0.9, 0.2),
                DVec2::new(0.3, 0.8),
            ],
            [
                DVec2::new(0.0, 0.0),
                DVec2::new(1.0, 0.0),
                DVec2::new(0.5, 0.01),
            ],
            [
                DVec2::new(0.2, 0.9),
                DVec2::new(0.95, 0.5),
                DVec2::new(0.1, 0.1),
            ],
        ];
        for t in triangles {
            let ccw = if (t[1] - t[0]).perp_dot(t[2] - t[0]) > 0.0 {
                t.to_vec()
            } else {
                vec![t[0], t[2], t[1]]
            };
            let quads = opaque_clip_quads(&t);
            assert_eq!(quads.len(), 2);
            for i in 0..=60 {
                for j in 0..=60 {
                    let p = DVec2::new(f64::from(i) / 60.0, f64::from(j) / 60.0);
                    let Some(inside) = in_polygon(&ccw, p, 1e-9) else {
                        continue;
                    };
                    let Some(sides): Option<Vec<bool>> =
                        quads.iter().map(|q| in_quad(q, p, 1e-9)).collect()
                    else {
                        continue; // on a quad's edge line: not a clean sample
                    };
                    assert_eq!(inside, sides.contains(&true), "{p} in {t:?}");
                }
            }
        }
    }

    #[test]
    fn clip_quads_cover_exactly_the_polygon() {
        // Counter-clockwise convex polygons of 3 to 8 corners (regular, squashed, rotated),
        // one with a near-collinear corner.
        let mut polygons: Vec<Vec<DVec2>> = (3..=8)
            .map(|n| {
                (0..n)
                    .map(|k| {
                        let a = 0.3 + std::f64::consts::TAU * f64::from(k) / f64::from(n);
                        DVec2::new(0.5 + 0.45 * a.cos(), 0.5 + 0.2 * a.sin())
                    })
                    .collect()
            })
            .collect();
        polygons.push(vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(0.5, 1e-13),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.2, 0.7),
        ]);
        for poly in &polygons {
            let quads = clip_quads(poly);
            assert!(!quads.is_empty());
            let steps = 97;
            for i in 0..=steps {
                for j in 0..=steps {
                    let p = DVec2::new(f64::from(i), f64::from(j)) / f64::from(steps);
                    let Some(inside) = in_polygon(poly, p, 1e-9) else {
                        continue;
                    };
                    let hits: Vec<Option<bool>> =
                        quads.iter().map(|m| in_quad(m, p, 1e-9)).collect();
                    if hits.contains(&None) {
                        continue; // on an inner edge
                    }
                    let covered = hits.contains(&Some(true));
                    assert_eq!(covered, inside, "{} corners, at {p}", poly.len());
                }
            }
        }
    }

    #[test]
    fn quad_matrix_maps_the_corners() {
        let p = [
            DVec2::new(0.1, 0.2),
            DVec2::new(0.9, 0.1),
            DVec2::new(0.7, 0.8),
            DVec2::new(0.2, 0.6),
        ];
        let m = quad_matrix(p).expect("convex quad");
        for (c, want) in [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y].iter().zip(p) {
            let h = m * DVec4::new(c.x, c.y, 0.0, 1.0);
            let got = DVec2::new(h.x / h.w, h.y / h.w);
            assert!((got - want).length() < 1e-12, "{got} vs {want}");
        }
        assert!(quad_matrix([DVec2::ZERO, DVec2::X, DVec2::X * 2.0, DVec2::Y * 0.0]).is_none());
    }
}
