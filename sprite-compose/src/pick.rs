//! Picking and selection outlines on the projected polygons of a frame.

use face_sort::{Box2, DrawItem, DrawList, ProjectionScratch, View, signed_area_2d};
use glam::DVec2;

use crate::tolerance::{EDGE_PARAMETER, OUTLINE_PROBE_PX, PARALLEL_EDGES, SAME_POINT_PX};

/// The drawn polygons of one frame projected to pixels, in paint order (back to front).
#[derive(Clone, Debug, Default)]
pub struct ProjectedFrame {
    points: Vec<DVec2>,
    starts: Vec<usize>,
    items: Vec<DrawItem>,
    boxes: Vec<Box2>,
}

impl ProjectedFrame {
    /// Projects every item of `list` under `view` (near-plane clipped; items with nothing in
    /// front of the near plane are left out).
    #[must_use]
    pub fn new(view: &View, list: &DrawList) -> Self {
        let mut frame = ProjectedFrame {
            starts: vec![0],
            ..Default::default()
        };
        let mut scratch = ProjectionScratch::default();
        let mut polygon = Vec::new();
        for &item in list.items() {
            view.project_polygon(list.corners(item), &mut polygon, &mut scratch);
            if polygon.len() < 3 {
                continue;
            }
            frame.points.extend_from_slice(&polygon);
            frame.starts.push(frame.points.len());
            frame.items.push(item);
            frame.boxes.push(Box2::from_points(&polygon));
        }
        frame
    }

    /// Number of polygons.
    #[must_use]
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// Whether nothing is drawn.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Polygon `i` (paint order) in pixels.
    #[must_use]
    pub fn polygon(&self, i: usize) -> &[DVec2] {
        &self.points[self.starts[i]..self.starts[i + 1]]
    }

    /// The draw item of polygon `i`.
    #[must_use]
    pub fn item(&self, i: usize) -> DrawItem {
        self.items[i]
    }

    /// Index (paint order) of the topmost polygon containing `point` (pixels; a pixel's centre
    /// is `(x + 0.5, y + 0.5)`), testing front to back with an exact point-in-convex-polygon
    /// test (boundary points count as inside).
    #[must_use]
    pub fn pick_index(&self, point: DVec2) -> Option<usize> {
        (0..self.items.len()).rev().find(|&i| {
            let b = &self.boxes[i];
            point.x >= b.min.x
                && point.x <= b.max.x
                && point.y >= b.min.y
                && point.y <= b.max.y
                && contains(self.polygon(i), point)
        })
    }

    /// The topmost draw item at `point`.
    #[must_use]
    pub fn pick(&self, point: DVec2) -> Option<DrawItem> {
        self.pick_index(point).map(|i| self.items[i])
    }

    /// The outline of the visible parts of the faces for which `selected(face)` holds: the
    /// segments (pixels) between a point whose topmost face is selected and one whose is not.
    /// Candidate edges are the projected edges near the selection, split where other edges
    /// cross them; each piece is kept when the probes [`OUTLINE_PROBE_PX`] to its two sides
    /// disagree. Collinear pieces of one edge are merged.
    #[must_use]
    pub fn selection_outline(&self, selected: impl Fn(u32) -> bool) -> Vec<[DVec2; 2]> {
        let mut area = Box2::EMPTY;
        for i in 0..self.len() {
            if selected(self.items[i].face) {
                area.min = area.min.min(self.boxes[i].min);
                area.max = area.max.max(self.boxes[i].max);
            }
        }
        if area.min.x > area.max.x {
            return Vec::new();
        }
        let near = |b: &Box2| {
            b.min.x <= area.max.x
                && b.max.x >= area.min.x
                && b.min.y <= area.max.y
                && b.max.y >= area.min.y
        };
        let mut edges: Vec<[DVec2; 2]> = Vec::new();
        for i in (0..self.len()).filter(|&i| near(&self.boxes[i])) {
            let poly = self.polygon(i);
            for k in 0..poly.len() {
                edges.push([poly[k], poly[(k + 1) % poly.len()]]);
            }
        }
        let is_selected = |p: DVec2| self.pick(p).is_some_and(|item| selected(item.face));
        let mut out: Vec<[DVec2; 2]> = Vec::new();
        let mut cuts: Vec<f64> = Vec::new();
        for (e, &[a, b]) in edges.iter().enumerate() {
            let d = b - a;
            let length = d.length();
            if length <= 0.0 {
                continue;
            }
            let normal = DVec2::new(-d.y, d.x) / length * OUTLINE_PROBE_PX;
            cuts.clear();
            cuts.extend([0.0, 1.0]);
            for (f, &[c, g]) in edges.iter().enumerate() {
                if f != e
                    && let Some(t) = crossing(a, b, c, g)
                {
                    cuts.push(t);
                }
            }
            cuts.sort_unstable_by(f64::total_cmp);
            let mut open: Option<DVec2> = None;
            for w in cuts.windows(2) {
                if w[1] - w[0] <= EDGE_PARAMETER {
                    continue;
                }
                let m = a + d * (0.5 * (w[0] + w[1]));
                let boundary = is_selected(m + normal) != is_selected(m - normal);
                match (boundary, open) {
                    (true, None) => open = Some(a + d * w[0]),
                    (false, Some(start)) => {
                        out.push([start, a + d * w[0]]);
                        open = None;
                    }
                    _ => {}
                }
            }
            if let Some(start) = open {
                out.push([start, b]);
            }
        }
        dedup_segments(&mut out);
        out
    }
}

/// Removes segments that repeat another one (shared edges of neighbouring polygons).
fn dedup_segments(segments: &mut Vec<[DVec2; 2]>) {
    let mut kept: Vec<[DVec2; 2]> = Vec::with_capacity(segments.len());
    for s in segments.iter() {
        let dup = kept.iter().any(|k| {
            ((k[0] - s[0]).length() < SAME_POINT_PX && (k[1] - s[1]).length() < SAME_POINT_PX)
                || ((k[0] - s[1]).length() < SAME_POINT_PX
                    && (k[1] - s[0]).length() < SAME_POINT_PX)
        });
        if !dup {
            kept.push(*s);
        }
    }
    *segments = kept;
}

/// Parameter along `a→b` where segment `c→g` crosses it (or touches it with an end point).
fn crossing(a: DVec2, b: DVec2, c: DVec2, g: DVec2) -> Option<f64> {
    let r = b - a;
    let s = g - c;
    let denom = r.perp_dot(s);
    if denom.abs() <= PARALLEL_EDGES * r.length_squared().max(s.length_squared()) {
        return None;
    }
    let t = (c - a).perp_dot(s) / denom;
    let u = (c - a).perp_dot(r) / denom;
    let eps = EDGE_PARAMETER;
    ((-eps..=1.0 + eps).contains(&t) && (-eps..=1.0 + eps).contains(&u) && t > 0.0 && t < 1.0)
        .then_some(t)
}

/// Whether a convex polygon (either winding) contains `p` (boundary included).
#[must_use]
pub fn contains(polygon: &[DVec2], p: DVec2) -> bool {
    let orientation = signed_area_2d(polygon);
    if orientation == 0.0 {
        return false;
    }
    let n = polygon.len();
    (0..n).all(|k| {
        let a = polygon[k];
        let b = polygon[(k + 1) % n];
        (b - a).perp_dot(p - a) * orientation >= 0.0
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contains_either_winding() {
        let sq = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        assert!(contains(&sq, DVec2::splat(0.5)));
        let rev: Vec<DVec2> = sq.iter().rev().copied().collect();
        assert!(contains(&rev, DVec2::splat(0.5)));
        assert!(!contains(&sq, DVec2::new(1.5, 0.5)));
    }
}
