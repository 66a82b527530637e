//! The spinning HTML page: a bake realised as one container per cell, a CSS animation
//! turning the model and keyframed visibility showing the cell of the current angle. No
//! script: the browser only composites, in the document order of the visible container.

use std::fmt::Write as _;
use std::sync::Arc;

use aspect_bake::{Bake, Spin};
use face_sort::Geometry;
use glam::{DMat3, DMat4, DVec2, DVec3};

use crate::numbers::hex;
use crate::{BakedSpriteTree, Materials, css_matrix3d, id_colour, perspective_matrix};

/// Options of [`write_spin_html`].
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct SpinOptions {
    /// Seconds per full turn. Default: 8.
    pub period_s: f64,
    /// Fill each face with its ID colour (CONVENTIONS.md) instead of the palette. Default:
    /// false.
    pub ids: bool,
    /// Page background. Default: none: black in ID mode, white otherwise (as every page
    /// and the PNG).
    pub background: Option<[u8; 4]>,
    /// What fills each face in colour mode (a texture as its mean colour), for the pages that
    /// draw a bake's pieces ([`write_culled_spin_html`](crate::write_culled_spin_html),
    /// [`write_canvas_spin_html`](crate::write_canvas_spin_html)). Default: none (the
    /// palette).
    pub materials: Option<Arc<Materials>>,
    /// Each element is laid out at this many times its extent at rest, so that the browser
    /// rasters it at least at screen resolution (as [`HtmlOptions::oversize`](crate::HtmlOptions)).
    /// Default: 4.
    pub oversize: f64,
    /// Orthographic roots get this perspective distance (pixels), as in
    /// [`HtmlOptions`](crate::HtmlOptions). Default: 1e8.
    pub orthographic_distance: f64,
    /// `Some(t)`: the page is paused at `t` seconds into the turn (every animation gets
    /// `animation-delay: −t s` and is paused), for screenshots. Default: `None` (it spins).
    pub paused_at_s: Option<f64>,
}

impl SpinOptions {
    /// The defaults.
    pub const DEFAULT: SpinOptions = SpinOptions {
        period_s: 8.0,
        ids: false,
        background: None,
        materials: None,
        oversize: 4.0,
        orthographic_distance: 1e8,
        paused_at_s: None,
    };
}

impl SpinOptions {
    /// Seconds per turn.
    #[must_use]
    pub fn with_period(mut self, seconds: f64) -> Self {
        self.period_s = seconds;
        self
    }

    /// Paused at `seconds` into the turn (`None`: spinning).
    #[must_use]
    pub fn with_paused_at(mut self, seconds: Option<f64>) -> Self {
        self.paused_at_s = seconds;
        self
    }
}

crate::page::page_setters!(SpinOptions: ids, background, materials);

impl Default for SpinOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The layout size (pixels) of an element that shows a sprite's unit square: its extent at
/// rest (the element is the whole square; a clip keeps part of it) times `oversize`, so
/// that the browser rasters it at least at screen resolution; at least 8.
pub(crate) fn layout_size(transform: &crate::SpriteTransform, oversize: f64) -> f64 {
    let (mut lo, mut hi) = (DVec2::splat(f64::MAX), DVec2::splat(f64::MIN));
    for uv in [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y] {
        let q = transform.apply(uv).truncate();
        lo = lo.min(q);
        hi = hi.max(q);
    }
    ((hi - lo).max_element().max(1.0) * oversize)
        .ceil()
        .max(8.0)
}

/// Percent of the turn at `degrees` of the animated parameter.
fn percent(degrees: f64) -> f64 {
    degrees / 360.0 * 100.0
}

/// The bake as a self-contained page that turns once per `period_s` (a full-period bake of
/// a yaw, pitch or roll [`Spin`]; `view` gives the sprite space: size and scale).
///
/// Each polygon's elements get one CSS class holding its transform
/// `matrix3d(T(O)·P·F A F) rotate3d(−F k, var(--a)) matrix3d(F B F·T(−O)·sprite)` — the
/// root transform of [`root_transform`](sprite_compose::root_transform) at `R(θ) = A·Rot(k, θ)·B`
/// with `F = diag(1, −1, 1)` (`F·Rot(k, θ)·F = Rot(−F k, θ)`) — where `--a` is a registered
/// custom property animated linearly from 0 to 360 degrees. Each cell is a container of its
/// draw list in paint order, visible (keyframes with `step-end` timing) only while the angle
/// is in the cell.
#[must_use]
pub fn write_spin_html(
    bake: &Bake,
    spin: &Spin,
    geometry: &Geometry,
    options: &SpinOptions,
) -> String {
    let view = spin.view_at(0.0);
    let graph = BakedSpriteTree::realise(bake, geometry, &view);
    let (w, h) = (view.width(), view.height());
    let origin = DVec3::new(f64::from(w) * 0.5, f64::from(h) * 0.5, 0.0);
    let (a, k, b) = spin.factors();
    let flip = DMat3::from_diagonal(DVec3::new(1.0, -1.0, 1.0));
    let projection = match view.projection() {
        face_sort::Projection::Orthographic => face_sort::Projection::Perspective {
            distance: options.orthographic_distance,
        },
        p => p,
    };
    let pre = DMat4::from_translation(origin)
        * perspective_matrix(projection)
        * DMat4::from_mat3(flip * a * flip);
    let post = DMat4::from_mat3(flip * b * flip) * DMat4::from_translation(-origin);
    let axis = -(flip * k);
    let pre_css = css_matrix3d(&pre);
    let rotate = format!("rotate3d({:e},{:e},{:e},var(--a))", axis.x, axis.y, axis.z);
    let period = options.period_s;
    let (delay, state) = match options.paused_at_s {
        Some(t) => (format!("{:e}s", -t), "paused"),
        None => ("0s".to_owned(), "running"),
    };
    let background = crate::page::background(options.background, options.ids);
    let mut page = crate::page::head("aspect-bake spin", w, h, background);
    let _ = write!(
        page,
        "@property --a{{syntax:'<angle>';inherits:true;initial-value:0deg}}\n\
         @keyframes turn{{from{{--a:0deg}}to{{--a:360deg}}}}\n\
         #scene{{position:absolute;left:0;top:0;width:{w}px;height:{h}px;\
         animation:turn {period}s linear {delay} infinite {state}}}\n\
         .cell{{position:absolute;left:0;top:0;visibility:hidden;\
         animation:{period}s step-end {delay} infinite {state}}}\n\
         .cell>div{{position:absolute;left:0;top:0;transform-origin:0 0}}\n",
    );
    // One class per polygon (its elements): transform, size, colour.
    let set = &bake.polygons();
    let mut elements: Vec<Vec<String>> = vec![Vec::new(); set.len()];
    for (p, out) in elements.iter_mut().enumerate() {
        let Some((transform, clip)) = graph.polygon_map(p as u32) else {
            continue;
        };
        let face = set.face(p);
        let colour = hex(if options.ids {
            id_colour(face)
        } else {
            graph.brush(face).solid_colour(face)
        });
        let size = layout_size(transform, options.oversize);
        let unscale = DMat4::from_scale(DVec3::new(1.0 / size, 1.0 / size, 1.0));
        let class = |page: &mut String, name: &str, extra: &str, m: &DMat4| {
            let _ = writeln!(
                page,
                ".{name}{{{extra}transform:{pre_css} {rotate} {}}}",
                css_matrix3d(&(post * *m))
            );
        };
        match clip {
            None => {
                let name = format!("p{p}");
                class(
                    &mut page,
                    &name,
                    &format!("width:{size}px;height:{size}px;background:{colour};"),
                    &(transform.matrix * unscale),
                );
                out.push(name);
            }
            Some(clip) => {
                // The writer's exact pieces: convex quads of the clip polygon, every edge an
                // element edge (no anti-aliased diagonals, so no seams between fragments).
                for (q, quad) in crate::html::clip_quads(clip).iter().enumerate() {
                    let name = format!("p{p}_{q}");
                    class(
                        &mut page,
                        &name,
                        &format!("width:{size}px;height:{size}px;background:{colour};"),
                        &(transform.matrix * *quad * unscale),
                    );
                    out.push(name);
                }
            }
        }
    }
    // Visibility keyframes per cell.
    let domain_lo = bake.domain().lo;
    for (c, cell) in bake.cells().iter().enumerate() {
        let (lo, hi) = (cell.range.lo - domain_lo, cell.range.hi - domain_lo);
        // (offset %, visible) in increasing offset; at equal offsets the later one holds.
        let mut keys: Vec<(f64, bool)> = if bake.cells().len() == 1 {
            vec![(0.0, true)]
        } else if hi > 360.0 {
            // Wraps: visible from lo to the end and from the start to hi − 360.
            vec![
                (0.0, true),
                (percent(hi - 360.0), false),
                (percent(lo), true),
            ]
        } else {
            vec![(0.0, false), (percent(lo), true), (percent(hi), false)]
        };
        keys.dedup_by(|later, earlier| {
            let same = later.0 == earlier.0;
            if same {
                earlier.1 = later.1;
            }
            same
        });
        let _ = write!(page, "@keyframes c{c}{{");
        for (offset, visible) in keys {
            let v = if visible { "visible" } else { "hidden" };
            let _ = write!(page, "{offset:e}%{{visibility:{v}}}");
        }
        let _ = writeln!(page, "}}\n#c{c}{{animation-name:c{c}}}");
    }
    page.push_str("</style></head><body><div id=\"scene\">\n");
    for (c, cell) in bake.cells().iter().enumerate() {
        let _ = write!(page, "<div id=\"c{c}\" class=\"cell\">");
        for &p in &cell.order {
            for class in &elements[p as usize] {
                let _ = write!(page, "<div class=\"{class}\"></div>");
            }
        }
        page.push_str("</div>\n");
    }
    page.push_str("</div></body></html>\n");
    page
}
