//! Fragments of one piece without T-junctions between them.
//!
//! A BSP cuts a piece into fragments that tile it, and cuts those again: a later cut puts a
//! new corner on a seam that the fragment across it does not have (a T-junction). Two
//! polygons whose shared boundary is one edge on one side and two on the other are rounded
//! differently by a rasteriser with finite precision (resvg's works in 1/64 px): a pixel
//! centre hundredths of a pixel from the seam can fall in neither, and shows what lies
//! behind (a pinhole). With every such corner inserted into the edge it lies on, the two
//! sides share their edges exactly and any consistent rasteriser covers each pixel once.

use glam::DVec3;

use crate::polygon::edges;
use crate::polygon_set::PolygonSet;

impl PolygonSet {
    /// These polygons with the T-junctions between polygons of the same face closed: each
    /// corner of one that lies inside an edge of another of the same face (within
    /// `tolerance` of the edge's line, farther than `tolerance` from its ends) is inserted
    /// there. Order, faces and planes are kept and corners copied bit for bit, so a
    /// rasteriser with finite precision (a GPU, a vector renderer) covers each pixel of a
    /// face once where cuts divide it. A tolerance of [`PLANE_SIDE`](crate::tolerance::PLANE_SIDE)
    /// times the model's size is what the sorters use.
    #[must_use]
    pub fn without_t_junctions(&self, tolerance: f64) -> PolygonSet {
        let faces: Vec<u32> = (0..self.len()).map(|i| self.face(i)).collect();
        conform(self, &faces, tolerance)
    }
}

/// `fragments` with, in every fragment, each corner of another fragment of the same piece
/// (`piece_of`) that lies inside one of its edges (within `tolerance` of the edge's line,
/// farther than `tolerance` from its ends) inserted there, in order along the edge, corners
/// within `tolerance` of each other once. Faces, planes and the fragments' order are kept;
/// corners are copied bit for bit. Seams between fragments of different pieces (a cut corner
/// on a mesh edge whose neighbour was not cut there) are left as they are: they lie on piece
/// edges, which CONVENTIONS.md's 0.75 px margin keeps out of the pixel error.
pub(crate) fn conform(fragments: &PolygonSet, piece_of: &[u32], tolerance: f64) -> PolygonSet {
    // Fragments grouped by piece, in fragment order within each.
    let mut by_piece: Vec<u32> = (0..fragments.len() as u32).collect();
    by_piece.sort_by_key(|&f| piece_of[f as usize]);
    let mut corners_of: Vec<Vec<DVec3>> = (0..fragments.len())
        .map(|f| fragments.corners(f).to_vec())
        .collect();
    let mut on_edge: Vec<(f64, DVec3)> = Vec::new();
    let mut boxes: Vec<(DVec3, DVec3)> = Vec::new();
    let mut touching: Vec<usize> = Vec::new();
    for group in by_piece.chunk_by(|&a, &b| piece_of[a as usize] == piece_of[b as usize]) {
        if group.len() < 2 {
            continue;
        }
        // Boxes grown by the tolerance: only fragments whose boxes touch can share a seam.
        boxes.clear();
        boxes.extend(group.iter().map(|&f| {
            let corners = fragments.corners(f as usize);
            let lo = corners.iter().fold(DVec3::INFINITY, |lo, &c| lo.min(c));
            let hi = corners.iter().fold(DVec3::NEG_INFINITY, |hi, &c| hi.max(c));
            (lo - tolerance, hi + tolerance)
        }));
        for (i, &f) in group.iter().enumerate() {
            let own = fragments.corners(f as usize);
            let (lo, hi) = boxes[i];
            touching.clear();
            touching.extend((0..group.len()).filter(|&j| {
                let (other_lo, other_hi) = boxes[j];
                j != i && lo.cmple(other_hi).all() && other_lo.cmple(hi).all()
            }));
            let mut conformed = Vec::with_capacity(own.len());
            for (a, b) in edges(own) {
                conformed.push(a);
                let along = b - a;
                let length_squared = along.length_squared();
                on_edge.clear();
                for &j in &touching {
                    for &c in fragments.corners(group[j] as usize) {
                        let t = (c - a).dot(along) / length_squared;
                        let off_line = (c - (a + along * t)).length();
                        let inside = t > 0.0 && t < 1.0;
                        let apart = a.distance(c) > tolerance && b.distance(c) > tolerance;
                        if inside && apart && off_line <= tolerance {
                            on_edge.push((t, c));
                        }
                    }
                }
                on_edge.sort_by(|x, y| x.0.total_cmp(&y.0));
                // One corner per point: two siblings cut by one plane compute its corner on
                // their shared seam from opposite ends, a rounding apart, and both inserted
                // would make an edge of no length in any direction (a reflex turn).
                on_edge.dedup_by(|x, y| x.1.distance(y.1) <= tolerance);
                conformed.extend(on_edge.iter().map(|&(_, c)| c));
            }
            corners_of[f as usize] = conformed;
        }
    }
    let mut out = PolygonSet::new();
    for (f, corners) in corners_of.iter().enumerate() {
        out.push(corners, fragments.face(f), *fragments.plane(f));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plane::Plane;

    fn p(x: f64, y: f64) -> DVec3 {
        DVec3::new(x, y, 0.0)
    }

    /// A unit square (face 7) cut in two by x = 0.5, then its right half cut by y = 0.5:
    /// the left half, and the lower and upper right quarters, whose shared corner on the
    /// seam is `(0.5, 0.5)` for the lower and `upper_corner` for the upper one.
    fn cut_square(upper_corner: DVec3) -> PolygonSet {
        let plane = Plane::try_from_polygon(&[p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)]).unwrap();
        let mut fragments = PolygonSet::new();
        let left = [p(0.0, 0.0), p(0.5, 0.0), p(0.5, 1.0), p(0.0, 1.0)];
        let lower = [p(0.5, 0.0), p(1.0, 0.0), p(1.0, 0.5), p(0.5, 0.5)];
        let upper = [upper_corner, p(1.0, 0.5), p(1.0, 1.0), p(0.5, 1.0)];
        for corners in [&left, &lower, &upper] {
            fragments.push(corners, 7, plane);
        }
        fragments
    }

    /// The left half gains the corner (0.5, 0.5) on its right edge, which both right
    /// quarters have.
    #[test]
    fn a_corner_on_a_siblings_edge_is_inserted() {
        let mut fragments = cut_square(p(0.5, 0.5));
        // Another piece's fragment with a corner on the left half's edge: not inserted.
        let plane = *fragments.plane(0);
        fragments.push(&[p(0.5, 0.25), p(2.0, 0.0), p(2.0, 1.0)], 8, plane);
        let conformed = conform(&fragments, &[0, 0, 0, 1], 1e-12);
        assert_eq!(
            conformed.corners(0),
            &[
                p(0.0, 0.0),
                p(0.5, 0.0),
                p(0.5, 0.5),
                p(0.5, 1.0),
                p(0.0, 1.0)
            ]
        );
        for f in 1..4 {
            assert_eq!(conformed.corners(f), fragments.corners(f));
            assert_eq!(conformed.face(f), fragments.face(f));
        }
    }

    /// Two siblings cut by one plane put its corner on their shared seam a rounding apart:
    /// the fragment across gets one of them, not both (an edge of no length between them
    /// could turn any way).
    #[test]
    fn corners_a_rounding_apart_are_inserted_once() {
        let fragments = cut_square(p(0.5, 0.5 + 1e-16));
        let conformed = conform(&fragments, &[0, 0, 0], 1e-12);
        assert_eq!(conformed.corners(0).len(), 5);
        assert_eq!(conformed.corners(0)[2], p(0.5, 0.5));
    }
}
