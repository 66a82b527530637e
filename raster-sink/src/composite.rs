//! The per-pixel compositing reference for translucent faces: what a renderer that sorts
//! every pixel's fragments (an A-buffer) shows, to judge a painter's order of translucent
//! faces, which only an exact order gets right.

use face_sort::glam::DVec2;
use face_sort::{Geometry, PixelRays, Projection, View};

use crate::fill::{for_each_pixel_near_segment, for_each_span};
use crate::project::Projector;
use crate::tolerance::{DEPTH_GAP, EDGE_MARGIN_PX};
use crate::truth::view_plane;

/// The composited colour of every pixel centre, and where it is unambiguous.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CompositeTruth {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major straight RGBA: every fragment at the pixel centre composited far to near
    /// (source-over, premultiplied, in sRGB values, each layer rounded to 8 bits, as an
    /// 8-bit canvas such as tiny-skia's stores it) over the background.
    pub rgba: Vec<[u8; 4]>,
    /// Row-major: at least [`EDGE_MARGIN_PX`] from every projected edge of every drawn piece,
    /// and no two fragments change places within [`EDGE_MARGIN_PX`] of the centre (their
    /// depths over that square, sampled at its corners and the centre, stay more than
    /// [`DEPTH_GAP`]` · L` apart): pixels by an interpenetration line, where a rasteriser's
    /// fill rule decides, are not judged.
    pub unambiguous: Vec<bool>,
    /// Row-major number of fragments composited at each pixel centre.
    pub layers: Vec<u16>,
}

impl CompositeTruth {
    /// The largest channel difference (sRGB, 0–255) a correct 8-bit compositing of pixel `k`
    /// may show against [`rgba`](Self::rgba): 2, plus one for every four layers (each layer
    /// is rounded to 8 bits, and canvases round their blends in their own ways).
    #[must_use]
    pub fn tolerance(&self, k: usize) -> u8 {
        (2 + self.layers[k] / 4).min(255) as u8
    }
}

/// Composites, per pixel centre, every piece of `geometry` the view draws, far to near,
/// each in `colour(face)` (straight sRGB RGBA), over `background`.
///
/// Cost: one fill per piece; memory about 16 bytes per fragment.
#[must_use]
pub fn composite_truth(
    view: &View,
    geometry: &Geometry,
    colour: impl Fn(u32) -> [u8; 4],
    background: [u8; 4],
) -> CompositeTruth {
    let (width, height) = (view.width(), view.height());
    let n_pixels = width as usize * height as usize;
    let stride = width as usize;
    // (pixel, depth toward the viewer at the centre, face, lowest and highest depth over
    // the pixel's ±EDGE_MARGIN_PX square)
    let mut fragments: Vec<(u32, f64, u32, f64, f64)> = Vec::new();
    let mut near_edge = vec![false; n_pixels];
    let caster = PixelRays::new(view);
    let cull = view.cull_test();
    let pieces = geometry.pieces();
    let mut projector = Projector::default();
    let near_z = match view.projection() {
        Projection::Orthographic => f64::INFINITY,
        Projection::Perspective { distance } => {
            (1.0 - face_sort::tolerance::NEAR_W) * distance / view.scale()
        }
    };
    for i in 0..pieces.len() {
        let corners = pieces.corners(i);
        let plane = pieces.plane(i);
        if !cull.is_drawn(plane, corners[0]) || !projector.project(view, corners) {
            continue;
        }
        let face = pieces.face(i);
        let (n, offset) = view_plane(view, plane);
        let (mut z_lo, mut z_hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for &c in corners {
            let z = view.to_view(c).z;
            z_lo = z_lo.min(z);
            z_hi = z_hi.max(z);
        }
        z_hi = z_hi.min(near_z);
        let points = &projector.points;
        for_each_span(points, width, height, |y, x0, x1| {
            let yc = f64::from(y) + 0.5;
            for x in x0..x1 {
                let depth = |dx: f64, dy: f64| {
                    let z = caster.depth(DVec2::new(f64::from(x) + 0.5 + dx, yc + dy), n, offset);
                    if z.is_nan() {
                        z_hi
                    } else {
                        z.clamp(z_lo, z_hi)
                    }
                };
                let z = depth(0.0, 0.0);
                let m = EDGE_MARGIN_PX;
                let (mut lo, mut hi) = (z, z);
                for (dx, dy) in [(-m, -m), (m, -m), (-m, m), (m, m)] {
                    let d = depth(dx, dy);
                    lo = lo.min(d);
                    hi = hi.max(d);
                }
                fragments.push(((y as usize * stride + x as usize) as u32, z, face, lo, hi));
            }
        });
        let m = points.len();
        for e in 0..m {
            for_each_pixel_near_segment(
                points[e],
                points[(e + 1) % m],
                EDGE_MARGIN_PX,
                width,
                height,
                |x, y| near_edge[y as usize * stride + x as usize] = true,
            );
        }
    }
    // Far to near per pixel: depth grows toward the viewer.
    fragments.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let gap = DEPTH_GAP * view.diagonal();
    let mut rgba = vec![background; n_pixels];
    let mut unambiguous: Vec<bool> = near_edge.iter().map(|&e| !e).collect();
    let mut layers = vec![0u16; n_pixels];
    let mut start = 0;
    while start < fragments.len() {
        let pixel = fragments[start].0;
        let end = start
            + fragments[start..]
                .iter()
                .take_while(|f| f.0 == pixel)
                .count();
        let mut out = premultiply(background);
        for k in start..end {
            // Sorted by centre depth: the nearer one's lowest depth must clear the farther
            // one's highest over the whole square.
            if k > start && fragments[k].3 - fragments[k - 1].4 <= gap {
                unambiguous[pixel as usize] = false;
            }
            // Each layer lands in 8-bit channels, as a canvas stores it.
            out =
                over(premultiply(colour(fragments[k].2)), out).map(|v| (v * 255.0).round() / 255.0);
        }
        rgba[pixel as usize] = demultiply(out);
        layers[pixel as usize] = (end - start).min(usize::from(u16::MAX)) as u16;
        start = end;
    }
    CompositeTruth {
        width,
        height,
        rgba,
        unambiguous,
        layers,
    }
}

fn premultiply(c: [u8; 4]) -> [f32; 4] {
    let a = f32::from(c[3]) / 255.0;
    [
        f32::from(c[0]) / 255.0 * a,
        f32::from(c[1]) / 255.0 * a,
        f32::from(c[2]) / 255.0 * a,
        a,
    ]
}

/// Source over destination, premultiplied.
fn over(src: [f32; 4], dst: [f32; 4]) -> [f32; 4] {
    let k = 1.0 - src[3];
    [
        src[0] + dst[0] * k,
        src[1] + dst[1] * k,
        src[2] + dst[2] * k,
        src[3] + dst[3] * k,
    ]
}

fn demultiply(c: [f32; 4]) -> [u8; 4] {
    if c[3] <= 0.0 {
        return [0, 0, 0, 0];
    }
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    [
        byte(c[0] / c[3]),
        byte(c[1] / c[3]),
        byte(c[2] / c[3]),
        byte(c[3]),
    ]
}
