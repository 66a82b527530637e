//! Lines and points among faces: axes, wireframes, markers and annotations drawn exactly
//! where no face hides them.
//!
//! A line (or point) has no area, so it never hides a face; it only needs its visible parts:
//! [`visible_overlay`] clips every line exactly against the drawn pieces in front of it, in
//! closed form (the same interval test as the plotter edges, [`plot_edges`](crate::plot_edges)),
//! and the writers draw those parts **after** every face. That is the same picture as inserting
//! each line into the painter's order split at every face it passes behind, and it holds at
//! any zoom of a vector file. A line that lies on a face (a mesh edge as wireframe, a grid line
//! on the ground) names that face in [`Line::faces`]: the face never hides it, so it is drawn
//! on top rather than in a z-fight.

use glam::{DVec2, DVec3};

use face_sort::{Geometry, PolygonMesh, View};

use crate::occlusion::{Occluder, Occluders, Segment, weld};
use crate::tolerance::PLOT_SAME_CORNER;

/// A straight line in model space, stroked `width_px` pixels wide with butt ends.
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    /// Its ends (model space).
    pub ends: [DVec3; 2],
    /// Colour (sRGB, straight alpha).
    pub colour: [u8; 4],
    /// Stroke width in pixels.
    pub width_px: f64,
    /// Faces it lies on: their pieces whose plane holds both ends (within
    /// [`PLOT_SAME_CORNER`] of the model's diagonal) never hide it.
    pub faces: Vec<u32>,
}

/// A point in model space, drawn as a disc `radius_px` pixels wide.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// Where it is (model space).
    pub at: DVec3,
    /// Colour (sRGB, straight alpha).
    pub colour: [u8; 4],
    /// Disc radius in pixels.
    pub radius_px: f64,
    /// Faces it lies on (as for [`Line::faces`]).
    pub faces: Vec<u32>,
}

/// Lines and points to draw among a geometry's faces.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overlay {
    /// The lines.
    pub lines: Vec<Line>,
    /// The points.
    pub points: Vec<Point>,
}

impl Overlay {
    /// Every edge of `mesh` once (vertices at the same position are one vertex, so a uv seam
    /// gives one line), lying on the faces that share it.
    #[must_use]
    pub fn wireframe(mesh: &PolygonMesh, colour: [u8; 4], width_px: f64) -> Self {
        let ids = weld(mesh);
        let mut index: std::collections::HashMap<(u32, u32), usize> =
            std::collections::HashMap::new();
        let mut lines: Vec<Line> = Vec::new();
        for (face, corners) in mesh.faces().enumerate() {
            for k in 0..corners.len() {
                let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
                let (ia, ib) = (ids[a as usize], ids[b as usize]);
                if ia == ib {
                    continue;
                }
                let n = *index.entry((ia.min(ib), ia.max(ib))).or_insert_with(|| {
                    lines.push(Line {
                        ends: [mesh.positions()[a as usize], mesh.positions()[b as usize]],
                        colour,
                        width_px,
                        faces: Vec::new(),
                    });
                    lines.len() - 1
                });
                if !lines[n].faces.contains(&(face as u32)) {
                    lines[n].faces.push(face as u32);
                }
            }
        }
        Overlay {
            lines,
            points: Vec::new(),
        }
    }

    /// Every vertex of `mesh` once (welded as in [`wireframe`](Self::wireframe)), lying on
    /// the faces that use it.
    #[must_use]
    pub fn vertices(mesh: &PolygonMesh, colour: [u8; 4], radius_px: f64) -> Self {
        let ids = weld(mesh);
        let mut points: Vec<Point> = Vec::new();
        let mut first: Vec<Option<usize>> = vec![None; mesh.positions().len()];
        for (face, corners) in mesh.faces().enumerate() {
            for &c in corners {
                let id = ids[c as usize] as usize;
                let n = *first[id].get_or_insert_with(|| {
                    points.push(Point {
                        at: mesh.positions()[c as usize],
                        colour,
                        radius_px,
                        faces: Vec::new(),
                    });
                    points.len() - 1
                });
                if !points[n].faces.contains(&(face as u32)) {
                    points[n].faces.push(face as u32);
                }
            }
        }
        Overlay {
            lines: Vec::new(),
            points,
        }
    }

    /// This overlay with `other`'s lines and points added.
    #[must_use]
    pub fn with(mut self, other: Overlay) -> Self {
        self.lines.extend(other.lines);
        self.points.extend(other.points);
        self
    }
}

/// A visible part of a line, in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stroke {
    /// Its ends (pixels).
    pub ends: [DVec2; 2],
    /// The line's colour.
    pub colour: [u8; 4],
    /// The line's width (pixels).
    pub width_px: f64,
    /// Index of the line in [`Overlay::lines`].
    pub line: usize,
}

/// A visible point, in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dot {
    /// Centre (pixels).
    pub centre: DVec2,
    /// The point's colour.
    pub colour: [u8; 4],
    /// The point's radius (pixels).
    pub radius_px: f64,
    /// Index of the point in [`Overlay::points`].
    pub point: usize,
}

/// What a writer draws after the faces: the visible parts of an overlay.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DrawnOverlay {
    /// Visible line parts, lines in order.
    pub strokes: Vec<Stroke>,
    /// Visible points, in order.
    pub dots: Vec<Dot>,
}

/// The parts of `overlay` that the drawn pieces of `geometry` leave visible in `view`
/// (module docs). A point is visible when no drawn piece covers it; a point or line behind
/// the near plane is not drawn.
#[must_use]
pub fn visible_overlay(geometry: &Geometry, view: &View, overlay: &Overlay) -> DrawnOverlay {
    let centre = geometry.bounds().centre();
    let length = geometry.bounds().diagonal().max(f64::MIN_POSITIVE);
    let same_corner = PLOT_SAME_CORNER * length;
    let occluders = Occluders::new(geometry, view, &|_| true);
    let mut stamp = vec![u32::MAX; occluders.pieces.len()];
    let mut candidates = Vec::new();
    let mut covered = Vec::new();
    let mut tag = 0u32;
    let mut visible = |ends: [DVec3; 2], faces: &[u32]| -> Vec<[DVec2; 2]> {
        let Some(segment) = Segment::new(view, ends) else {
            return Vec::new();
        };
        occluders.candidates(&segment, tag, &mut stamp, &mut candidates);
        tag = tag.wrapping_add(1);
        covered.clear();
        for &k in &candidates {
            let piece = &occluders.pieces[k as usize];
            if !lies_on(piece, faces, &ends, same_corner)
                && let Some(interval) = segment.covered_by(piece, length)
            {
                covered.push(interval);
            }
        }
        uncovered(&segment, &ends, &mut covered)
            .into_iter()
            .filter_map(|[t0, t1]| {
                let at = |t: f64| view.project_view_point(view.to_view(ends[0].lerp(ends[1], t)));
                Some([at(t0)?, at(t1)?])
            })
            .collect()
    };
    let mut drawn = DrawnOverlay::default();
    for (n, line) in overlay.lines.iter().enumerate() {
        let ends = line.ends.map(|p| p - centre);
        for part in visible(ends, &line.faces) {
            drawn.strokes.push(Stroke {
                ends: part,
                colour: line.colour,
                width_px: line.width_px,
                line: n,
            });
        }
    }
    for (n, point) in overlay.points.iter().enumerate() {
        let at = point.at - centre;
        if let Some([centre_px, _]) = visible([at, at], &point.faces).first() {
            drawn.dots.push(Dot {
                centre: *centre_px,
                colour: point.colour,
                radius_px: point.radius_px,
                point: n,
            });
        }
    }
    drawn
}

/// The parts of a line (or point: equal ends) that `covered` leaves visible. A point is
/// covered or not (its intervals are all or nothing).
fn uncovered(segment: &Segment, ends: &[DVec3; 2], covered: &mut [[f64; 2]]) -> Vec<[f64; 2]> {
    if ends[0] != ends[1] {
        segment.visible_parts(covered)
    } else if covered.is_empty() {
        vec![[0.0, 1.0]]
    } else {
        Vec::new()
    }
}

/// Whether a line (or point) lies on `piece`: the piece's face is one it names and the
/// piece's plane holds its ends within `same_corner`.
fn lies_on(piece: &Occluder, faces: &[u32], ends: &[DVec3; 2], same_corner: f64) -> bool {
    faces.contains(&piece.face)
        && ends
            .iter()
            .all(|&e| piece.plane.signed_distance(e).abs() <= same_corner)
}

/// Where a visible part of a line, or a visible point, goes among translucent faces: see
/// [`overlay_in_order`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrderedPart {
    /// Index of the line in [`Overlay::lines`] (or of the point in [`Overlay::points`]).
    pub index: usize,
    /// The part as a parameter interval `[t0, t1]` of `ends[0] + t·(ends[1] − ends[0])`
    /// (`[0, 1]` for a point).
    pub t: [f64; 2],
    /// Paint it just before this face of the ordered geometry: the first, in paint order,
    /// of the translucent pieces in front of it. `None`: after every face.
    pub before: Option<u32>,
}

/// The parts of an overlay that stay visible among faces some of which are translucent, and
/// where each goes in the paint order.
///
/// `ordered` holds the polygons of an exact paint order, **face index = paint position**
/// (e.g. a sorter's draw list, one face per item, built with
/// [`Geometry::new_in_frame`](face_sort::Geometry::new_in_frame) in the overlay's frame).
/// A part hidden by an `opaque` piece is left out, as [`visible_overlay`] does. What
/// remains is cut where translucent pieces start or stop covering it, and each cut part is
/// painted just before the first translucent piece in front of it: the pieces behind it
/// overlap that piece on screen wherever they overlap the part, so an exact order already
/// paints them earlier. Painting faces and parts in that merged order is the picture of a
/// depth-sorted scene with every line split at every face.
#[must_use]
pub fn overlay_in_order(
    ordered: &Geometry,
    view: &View,
    overlay: &Overlay,
    opaque: &dyn Fn(u32) -> bool,
) -> (Vec<OrderedPart>, Vec<OrderedPart>) {
    let centre = ordered.bounds().centre();
    let length = ordered.bounds().diagonal().max(f64::MIN_POSITIVE);
    let same_corner = PLOT_SAME_CORNER * length;
    let occluders = Occluders::new(ordered, view, &|_| true);
    let mut stamp = vec![u32::MAX; occluders.pieces.len()];
    let (mut candidates, mut hiding, mut tinting) = (Vec::new(), Vec::new(), Vec::new());
    let mut tag = 0u32;
    let mut parts = |index: usize, ends: [DVec3; 2], faces: &[u32], out: &mut Vec<OrderedPart>| {
        let Some(segment) = Segment::new(view, ends) else {
            return;
        };
        occluders.candidates(&segment, tag, &mut stamp, &mut candidates);
        tag = tag.wrapping_add(1);
        hiding.clear();
        tinting.clear();
        for &k in &candidates {
            let piece = &occluders.pieces[k as usize];
            if !lies_on(piece, faces, &ends, same_corner)
                && let Some(interval) = segment.covered_by(piece, length)
            {
                if opaque(piece.face) {
                    hiding.push(interval);
                } else {
                    tinting.push((interval, piece.face));
                }
            }
        }
        for [a, b] in uncovered(&segment, &ends, &mut hiding) {
            let mut cuts: Vec<f64> = vec![a, b];
            if ends[0] != ends[1] {
                cuts.extend(
                    tinting
                        .iter()
                        .flat_map(|&([lo, hi], _)| [lo, hi])
                        .filter(|&t| t > a && t < b),
                );
            }
            cuts.sort_by(f64::total_cmp);
            cuts.dedup();
            for w in cuts.windows(2) {
                let mid = 0.5 * (w[0] + w[1]);
                let before = tinting
                    .iter()
                    .filter(|&&([lo, hi], _)| (ends[0] == ends[1]) || (lo <= mid && mid <= hi))
                    .map(|&(_, face)| face)
                    .min();
                match out.last_mut() {
                    Some(last)
                        if last.index == index && last.before == before && last.t[1] == w[0] =>
                    {
                        last.t[1] = w[1];
                    }
                    _ => out.push(OrderedPart {
                        index,
                        t: [w[0], w[1]],
                        before,
                    }),
                }
            }
        }
    };
    let (mut lines, mut points) = (Vec::new(), Vec::new());
    for (n, line) in overlay.lines.iter().enumerate() {
        parts(n, line.ends.map(|p| p - centre), &line.faces, &mut lines);
    }
    for (n, point) in overlay.points.iter().enumerate() {
        let at = point.at - centre;
        parts(n, [at, at], &point.faces, &mut points);
    }
    (lines, points)
}
