//! One draw step: project the items, find shared edges for the seam outset, and paint each
//! polygon with its brush (solid, palette, ID colour, grid or texture).

use face_sort::glam::{DVec2, DVec3};
use face_sort::{DrawItem, DrawList, View};
use tiny_skia::Pixmap;

use super::blend::{blend_over, fill, paint_for};
use super::options::{Override, RasterOptions};
use super::shading::{lambert, shade_colour};
use crate::RasterError;
use crate::fill::for_each_span;
use crate::grid::GridShader;
use crate::project::Projector;
use crate::style::{Brush, Style};
use face_sort::colours::{golden_angle_colour, id_colour};
use sprite_compose::seams::{ScreenPolygons, SharedEdges, outset_polygon};

/// What a draw step paints and how: the same for every polygon of the step.
#[derive(Clone, Copy)]
pub(super) struct DrawContext<'a> {
    /// The camera.
    pub view: &'a View,
    /// The items, in paint order.
    pub list: &'a DrawList,
    /// Per-face brushes.
    pub style: &'a Style,
    /// Raster options.
    pub options: &'a RasterOptions,
    /// Canvas pixels per output pixel (the supersampling factor still in force).
    pub factor: u32,
}

/// Reusable state of a draw step.
#[derive(Default)]
pub(super) struct Painter {
    pub(super) projector: Projector,
    pub(super) polygons: ScreenPolygons,
    items: Vec<DrawItem>,
    pub(super) shared: SharedEdges,
    outset: Vec<DVec2>,
    pub(super) sub: Vec<DVec2>,
    pub(super) sub_shared: Vec<bool>,
    pub(super) tri3: Vec<DVec3>,
}

impl Painter {
    /// Draws the context's items that `filter` keeps, each with its brush or the override.
    pub(super) fn draw(
        &mut self,
        canvas: &mut Pixmap,
        context: DrawContext<'_>,
        filter: Option<&dyn Fn(DrawItem) -> bool>,
        brush_override: Override,
    ) -> Result<(), RasterError> {
        let DrawContext {
            view,
            list,
            style,
            options,
            factor,
        } = context;
        let k = f64::from(factor);
        self.polygons.clear();
        self.items.clear();
        let test = view.cull_test();
        for &item in list.items() {
            if filter.is_some_and(|f| !f(item)) || !list.paints(item, &test) {
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
            let points = self.polygons.polygon(i);
            let flags = if seams {
                self.shared.flags(self.polygons.edges(i))
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
                Override::IdColours => Some(id_colour(item.face)),
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
                    self.draw_textured(canvas, context, item, i, texture, light);
                }
                _ => {}
            }
        }
        Ok(())
    }
}
