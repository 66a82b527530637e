//! Texture mapping: each textured polygon (or each piece of its subdivided fan) gets one
//! affine tiny-skia `Pattern` transform from its corners' uvs.

use face_sort::glam::{DVec2, DVec3};
use face_sort::{DrawItem, DrawList, View};
use tiny_skia::{Paint, Pattern, Pixmap, Shader, SpreadMode, Transform};

use super::blend::{fill, paint_for};
use super::painter::{DrawContext, Painter};
use crate::project::is_degenerate;
use crate::style::TextureBrush;
use sprite_compose::seams::outset_polygon;

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
    /// Draws one textured polygon (item `item`, the step's polygon `index`), whole or
    /// subdivided, darkened by the shading factor `light`.
    pub(super) fn draw_textured(
        &mut self,
        canvas: &mut Pixmap,
        context: DrawContext<'_>,
        item: DrawItem,
        index: usize,
        texture: &TextureBrush,
        light: f64,
    ) {
        let DrawContext {
            view,
            list,
            options,
            factor,
            ..
        } = context;
        let k = f64::from(factor);
        let seams = options.anti_alias && options.seam_outset > 0.0;
        let outset = if seams { options.seam_outset } else { 0.0 };
        let edges = self.polygons.edges(index);
        let n_points = edges.len();
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
                self.shared.flags(edges.clone()).to_vec()
            } else {
                vec![false; n_points]
            };
            parts.push((corners.to_vec(), flags));
        } else {
            subdivide(corners, n, |tri, boundary| {
                let flags = (0..3)
                    .map(|e| match boundary[e] {
                        None => true,
                        Some(edge) => seams && self.shared.flags(edges.clone())[edge],
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
    view.to_centred(o + d * t)
}
