//! The crate's own exact pixel-centre fill in f64, used for ID images, the truth and the grid.
//!
//! # Fill rule
//! A pixel `(x, y)` is covered by a polygon when its centre `(x + 0.5, y + 0.5)` is inside.
//! Centres exactly on an edge follow a top-left rule: an edge crossing is computed from the
//! edge's endpoints ordered by `y` (so two polygons sharing an edge compute bit-identical
//! crossings), rows use edges half-open in `y` (`y_min ≤ y_c < y_max`, horizontal edges never
//! count) and a row's span is half-open in `x` (`x_left ≤ x_c < x_right`). Two polygons
//! that share an edge therefore never both cover, nor both miss, a centre on it.

use glam::DVec2;

/// Calls `span(row, x_start, x_end)` for every row of pixels whose centres the convex polygon
/// `points` (pixel coordinates, either winding) covers, with the covered columns
/// `x_start..x_end` (never empty), clipped to a `width × height` image.
///
/// Non-finite points make the polygon draw nothing. Slightly non-convex input (round-off)
/// is filled between its leftmost and rightmost crossing on each row.
pub fn for_each_span(
    points: &[DVec2],
    width: u32,
    height: u32,
    mut span: impl FnMut(u32, u32, u32),
) {
    if points.len() < 3 || !points.iter().all(|p| p.is_finite()) {
        return;
    }
    let (mut y_min, mut y_max) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in points {
        y_min = y_min.min(p.y);
        y_max = y_max.max(p.y);
    }
    let first_row = first_index_at_or_after(y_min, height);
    let end_row = first_index_at_or_after(y_max, height);
    let n = points.len();
    for row in first_row..end_row {
        let yc = f64::from(row) + 0.5;
        let (mut left, mut right) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..n {
            let (mut a, mut b) = (points[i], points[(i + 1) % n]);
            if a.y == b.y {
                continue;
            }
            if a.y > b.y {
                std::mem::swap(&mut a, &mut b);
            }
            if a.y <= yc && yc < b.y {
                let x = a.x + (yc - a.y) * ((b.x - a.x) / (b.y - a.y));
                left = left.min(x);
                right = right.max(x);
            }
        }
        if left < right {
            let x0 = first_index_at_or_after(left, width);
            let x1 = first_index_at_or_after(right, width);
            if x0 < x1 {
                span(row, x0, x1);
            }
        }
    }
}

/// The first pixel index `i` in `0..=limit` whose centre `i + 0.5` is at or after `coordinate`.
#[inline]
fn first_index_at_or_after(coordinate: f64, limit: u32) -> u32 {
    let i = (coordinate - 0.5).ceil();
    if i <= 0.0 {
        0
    } else if i >= f64::from(limit) {
        limit
    } else {
        i as u32
    }
}

/// Calls `pixel(x, y)` for every pixel of a `width × height` image whose centre lies closer
/// than `radius` to the segment `a`–`b` (pixel coordinates). Each pixel is reported once.
pub fn for_each_pixel_near_segment(
    a: DVec2,
    b: DVec2,
    radius: f64,
    width: u32,
    height: u32,
    mut pixel: impl FnMut(u32, u32),
) {
    if !(a.is_finite() && b.is_finite()) || radius <= 0.0 {
        return;
    }
    let r2 = radius * radius;
    let d = b - a;
    let len2 = d.length_squared();
    let first_row = first_index_at_or_after(a.y.min(b.y) - radius, height);
    let end_row = first_index_at_or_after(a.y.max(b.y) + radius, height);
    for row in first_row..end_row {
        let yc = f64::from(row) + 0.5;
        // x range of the segment's points within `radius` of this row, widened by `radius`.
        let (lo, hi) = if d.y.abs() > 0.0 {
            let t0 = (yc - radius - a.y) / d.y;
            let t1 = (yc + radius - a.y) / d.y;
            let (t0, t1) = (t0.min(t1).clamp(0.0, 1.0), t0.max(t1).clamp(0.0, 1.0));
            let (x0, x1) = (a.x + d.x * t0, a.x + d.x * t1);
            (x0.min(x1) - radius, x0.max(x1) + radius)
        } else {
            (a.x.min(b.x) - radius, a.x.max(b.x) + radius)
        };
        let x0 = first_index_at_or_after(lo, width);
        let x1 = first_index_at_or_after(hi, width)
            .saturating_add(1)
            .min(width);
        for x in x0..x1 {
            let p = DVec2::new(f64::from(x) + 0.5, yc);
            let t = if len2 > 0.0 {
                ((p - a).dot(d) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            if (a + d * t).distance_squared(p) < r2 {
                pixel(x, row);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_on_pixel_centres_follows_top_left_rule() {
        // Corners exactly on centres 1.5 and 3.5: left/top centres are in, right/bottom out.
        let sq = [
            DVec2::new(1.5, 1.5),
            DVec2::new(3.5, 1.5),
            DVec2::new(3.5, 3.5),
            DVec2::new(1.5, 3.5),
        ];
        let mut spans = Vec::new();
        for_each_span(&sq, 8, 8, |y, a, b| spans.push((y, a, b)));
        assert_eq!(spans, [(1, 1, 3), (2, 1, 3)]);
    }

    #[test]
    fn segment_band_is_within_radius() {
        let mut hits = Vec::new();
        for_each_pixel_near_segment(
            DVec2::new(0.0, 2.5),
            DVec2::new(10.0, 2.5),
            0.75,
            10,
            6,
            |x, y| hits.push((x, y)),
        );
        assert_eq!(hits.len(), 10);
        assert!(hits.iter().all(|&(_, y)| y == 2));
    }
}
