//! The truth for lines and points among faces: what a viewer sees along each line, judged
//! like faces are (away from edges), to check a drawing of them
//! (`sprite_compose::visible_overlay` or any other).
//!
//! Independent of how the drawing was made: every line is sampled every
//! [`OVERLAY_STEP_PX`] along its projection, and a ray from the viewer through each sample is
//! tested against every drawn piece (point in its projected polygon, then the depth where
//! the ray meets its plane). A sample is judged only where the answer is clear at
//! [`EDGE_MARGIN_PX`]-like distances: no nearer piece's outline within [`OVERLAY_JUDGE_PX`]
//! of it, the same answer [`OVERLAY_JUDGE_PX`] before and after along the line (a line
//! passing through a face turns hidden where it crosses the plane, with no outline nearby),
//! and not within [`OVERLAY_JUDGE_PX`] of the line's ends.

use face_sort::glam::{DVec2, DVec3};
use face_sort::{Geometry, Plane, ProjectionScratch, View, Viewer};
use sprite_compose::{DrawnOverlay, Overlay};

use crate::tolerance::{OVERLAY_DEPTH, OVERLAY_EDGE_ON, OVERLAY_JUDGE_PX, OVERLAY_STEP_PX};

#[cfg(doc)]
use crate::tolerance::EDGE_MARGIN_PX;

const EDGE_ON: f64 = OVERLAY_EDGE_ON;

/// What a viewer sees at one point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Seen {
    /// No drawn piece in front of it.
    Visible,
    /// A drawn piece is in front of it, clearly.
    Hidden,
    /// Too close to call at the judging distance.
    Ambiguous,
}

/// A drawn piece, projected.
struct Piece {
    corners: Vec<DVec2>,
    plane: Plane,
}

/// The drawn pieces of a geometry in a view, to ask what a viewer sees.
pub struct OverlayTruth {
    view: View,
    pieces: Vec<Piece>,
    centre: DVec3,
    length: f64,
}

/// How a drawing of lines and points compares with the truth.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct OverlayError {
    /// Samples judged (lines) and points judged.
    pub judged: usize,
    /// Of those, the ones the truth finds hidden.
    pub hidden: usize,
    /// Judged samples or points drawn where hidden, or not drawn where visible.
    pub wrong: usize,
    /// Up to eight wrong samples, described.
    pub examples: Vec<String>,
}

impl OverlayTruth {
    /// The truth of `geometry`'s drawn pieces (the view's cull mode) in `view`.
    #[must_use]
    pub fn new(view: &View, geometry: &Geometry) -> Self {
        let set = geometry.pieces();
        let cull = view.cull_test();
        let mut scratch = ProjectionScratch::default();
        let mut pieces = Vec::new();
        for i in 0..set.len() {
            let plane = set.plane(i);
            if !cull.is_drawn(plane, set.corners(i)[0]) {
                continue;
            }
            let mut corners = Vec::new();
            view.project_polygon(set.corners(i), &mut corners, &mut scratch);
            if corners.len() >= 3 {
                pieces.push(Piece {
                    corners,
                    plane: *plane,
                });
            }
        }
        OverlayTruth {
            view: *view,
            pieces,
            centre: geometry.bounds().centre(),
            length: geometry.bounds().diagonal(),
        }
    }

    /// What a viewer sees at model point `p` (not centred).
    #[must_use]
    pub fn seen(&self, p: DVec3) -> Seen {
        let x = p - self.centre;
        let Some(s) = self.view.project_view_point(self.view.to_view(x)) else {
            return Seen::Ambiguous;
        };
        let tol = OVERLAY_DEPTH * self.length;
        let mut ambiguous = false;
        for piece in &self.pieces {
            let inside = signed_distance(&piece.corners, s);
            if inside <= -OVERLAY_JUDGE_PX {
                continue;
            }
            // How much nearer the viewer the piece's plane is than `x`, along the ray.
            let gap = match self.view.viewer() {
                Viewer::Direction(d) => {
                    let nd = piece.plane.normal().dot(d);
                    if nd.abs() < EDGE_ON {
                        ambiguous = true;
                        continue;
                    }
                    -piece.plane.signed_distance(x) / nd
                }
                Viewer::Eye(e) => {
                    let ray = x - e;
                    let nr = piece.plane.normal().dot(ray);
                    if nr.abs() < EDGE_ON * ray.length() {
                        ambiguous = true;
                        continue;
                    }
                    (1.0 + piece.plane.signed_distance(e) / nr) * ray.length()
                }
            };
            if gap > tol && inside >= OVERLAY_JUDGE_PX {
                return Seen::Hidden;
            }
            // Nearer, but its outline is close. (A piece whose plane holds the point within
            // the tolerance does not hide it: the faces a line lies on.)
            if gap > tol {
                ambiguous = true;
            }
        }
        if ambiguous {
            Seen::Ambiguous
        } else {
            Seen::Visible
        }
    }

    /// Compares a drawing of `overlay` with the truth: every line sampled every
    /// [`OVERLAY_STEP_PX`] (a sample is drawn when a stroke of that line passes within 1e-6
    /// of it, relative to the line's projected length), every point judged once (drawn when
    /// it has a dot).
    #[must_use]
    pub fn compare(&self, overlay: &Overlay, drawn: &DrawnOverlay) -> OverlayError {
        let mut error = OverlayError::default();
        let project = |p: DVec3| {
            self.view
                .project_view_point(self.view.to_view(p - self.centre))
        };
        let judge =
            |error: &mut OverlayError, seen: Seen, shown: bool, what: &dyn Fn() -> String| {
                if seen == Seen::Ambiguous {
                    return;
                }
                error.judged += 1;
                error.hidden += usize::from(seen == Seen::Hidden);
                if shown != (seen == Seen::Visible) {
                    error.wrong += 1;
                    if error.examples.len() < 8 {
                        error.examples.push(what());
                    }
                }
            };
        for (n, line) in overlay.lines.iter().enumerate() {
            let [pa, pb] = line.ends;
            let (Some(a), Some(b)) = (project(pa), project(pb)) else {
                continue;
            };
            let len = a.distance(b);
            if len < 2.0 * OVERLAY_JUDGE_PX {
                continue;
            }
            // Screen parameter → line parameter (perspective: through w).
            let (wa, wb) = (
                self.view
                    .w_of_view_point(self.view.to_view(pa - self.centre)),
                self.view
                    .w_of_view_point(self.view.to_view(pb - self.centre)),
            );
            let at = |s: f64| pa.lerp(pb, s * wa / (s * wa + (1.0 - s) * wb));
            let steps = (len / OVERLAY_STEP_PX).ceil() as usize;
            let step = OVERLAY_JUDGE_PX / len;
            for k in 0..steps {
                let s = (k as f64 + 0.5) / steps as f64;
                if s * len < OVERLAY_JUDGE_PX || (1.0 - s) * len < OVERLAY_JUDGE_PX {
                    continue;
                }
                let seen = self.seen(at(s));
                let seen = if self.seen(at(s - step)) == seen && self.seen(at(s + step)) == seen {
                    seen
                } else {
                    Seen::Ambiguous
                };
                let p = a.lerp(b, s);
                let shown = drawn.strokes.iter().filter(|st| st.line == n).any(|st| {
                    let [u, v] = st.ends;
                    let uv = v - u;
                    let q = ((p - u).dot(uv) / uv.length_squared().max(f64::MIN_POSITIVE))
                        .clamp(0.0, 1.0);
                    (u + uv * q).distance(p) <= 1e-6 * len.max(1.0)
                });
                judge(&mut error, seen, shown, &|| {
                    format!("line {n} at s = {s:.4}: truth {seen:?}, drawn {shown}")
                });
            }
        }
        for (n, point) in overlay.points.iter().enumerate() {
            let seen = self.seen(point.at);
            let shown = drawn.dots.iter().any(|d| d.point == n);
            judge(&mut error, seen, shown, &|| {
                format!("point {n}: truth {seen:?}, drawn {shown}")
            });
        }
        error
    }
}

/// Signed distance (pixels) from `p` to a convex polygon's outline: positive inside.
fn signed_distance(poly: &[DVec2], p: DVec2) -> f64 {
    let n = poly.len();
    let area: f64 = (0..n).map(|k| poly[k].perp_dot(poly[(k + 1) % n])).sum();
    let mut inside = f64::INFINITY;
    let mut outside = f64::INFINITY;
    let mut is_inside = true;
    for k in 0..n {
        let (q, r) = (poly[k], poly[(k + 1) % n]);
        let e = r - q;
        let d = area.signum() * e.perp_dot(p - q) / e.length();
        is_inside &= d > 0.0;
        inside = inside.min(d);
        let t = ((p - q).dot(e) / e.length_squared()).clamp(0.0, 1.0);
        outside = outside.min((q + e * t).distance(p));
    }
    if is_inside { inside } else { -outside }
}
