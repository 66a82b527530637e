//! Cutting pieces that pass through each other, once, so that every remaining pair has one
//! occlusion relation wherever their projections overlap.

use glam::DVec3;

use crate::{Plane, PolygonSet, split_polygon};

/// One polygon being cut: corners (centred model space), source face, plane.
#[derive(Clone)]
struct Piece {
    corners: Vec<DVec3>,
    face: u32,
    plane: Plane,
}

/// Axis-aligned box of a polygon.
fn bounds(corners: &[DVec3]) -> (DVec3, DVec3) {
    corners.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &c| (lo.min(c), hi.max(c)),
    )
}

/// Whether the corners lie strictly on both sides of the plane (beyond `tolerance`).
fn spans(plane: &Plane, corners: &[DVec3], tolerance: f64) -> bool {
    let (mut front, mut back) = (false, false);
    for &c in corners {
        let d = plane.signed_distance(c);
        front |= d > tolerance;
        back |= d < -tolerance;
    }
    front && back
}

/// The interval, along direction `u`, of the points where a convex polygon meets a plane
/// that it spans.
fn cut_interval(plane: &Plane, corners: &[DVec3], u: DVec3) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (k, &a) in corners.iter().enumerate() {
        let b = corners[(k + 1) % corners.len()];
        let (da, db) = (plane.signed_distance(a), plane.signed_distance(b));
        let mut take = |p: DVec3| {
            let t = p.dot(u);
            lo = lo.min(t);
            hi = hi.max(t);
        };
        if da == 0.0 {
            take(a);
        }
        if (da > 0.0 && db < 0.0) || (da < 0.0 && db > 0.0) {
            take(a + (b - a) * (da / (da - db)));
        }
    }
    (lo, hi)
}

/// Whether two convex polygons pass through each other: each spans the other's plane and
/// the segments where each meets the other's plane overlap by more than `tolerance`, or meet
/// (within `tolerance`) elsewhere than at a corner they share.
fn cross(a: &Piece, b: &Piece, tolerance: f64) -> bool {
    if !spans(&b.plane, &a.corners, tolerance) || !spans(&a.plane, &b.corners, tolerance) {
        return false;
    }
    let Some(u) = a.plane.normal().cross(b.plane.normal()).try_normalize() else {
        return false;
    };
    let (a0, a1) = cut_interval(&b.plane, &a.corners, u);
    let (b0, b1) = cut_interval(&a.plane, &b.corners, u);
    let overlap = a1.min(b1) - a0.max(b0);
    // Touching at a shared corner is harmless (a single common point keeps one relation
    // over each connected overlap); touching anywhere else is treated as crossing.
    overlap > tolerance
        || (overlap >= -tolerance && !a.corners.iter().any(|c| b.corners.contains(c)))
}

/// For each piece, one other piece that it passes through (the first found), if any.
fn first_crossings(pieces: &[Piece], tolerance: f64) -> Vec<Option<usize>> {
    // Boxes sorted by their low x (ties by index), stored in that order, so that the sweep
    // along x reads them one after another.
    let mut boxes: Vec<(DVec3, DVec3, usize)> = pieces
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let (lo, hi) = bounds(&p.corners);
            (lo, hi, i)
        })
        .collect();
    boxes.sort_unstable_by(|a, b| a.0.x.total_cmp(&b.0.x).then(a.2.cmp(&b.2)));
    let mut partner = vec![None; pieces.len()];
    for (k, &(lo_i, hi_i, i)) in boxes.iter().enumerate() {
        for &(lo_j, hi_j, j) in &boxes[k + 1..] {
            if lo_j.x > hi_i.x + tolerance {
                break;
            }
            let overlap = lo_i.cmple(hi_j + tolerance).all() && lo_j.cmple(hi_i + tolerance).all();
            if overlap && cross(&pieces[i], &pieces[j], tolerance) {
                partner[i].get_or_insert(j);
                partner[j].get_or_insert(i);
            }
        }
    }
    partner
}

/// Cutting pieces that pass through each other would make more pieces than allowed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("cutting crossing pieces would make {pieces} pieces (budget {budget})")]
pub struct TooManyPieces {
    /// Pieces when stopping.
    pub pieces: usize,
    /// The budget.
    pub budget: usize,
}

/// Rounds of cutting before giving up (each round cuts every crossing pair once; real models
/// need one or two).
const MAX_ROUNDS: usize = 64;

/// The pieces of `set` with every pair that passes through each other cut along one of the
/// two planes, repeated until no pair crosses; with the number of cuts. Two pieces cross when
/// each spans the other's plane (beyond `tolerance`, a length) and the segments where each
/// meets the other's plane overlap, or meet anywhere but at a corner they share. Afterwards
/// every pair of pieces has one occlusion relation wherever their projections overlap,
/// which orders baked for many views need. At most `max_pieces` pieces come out.
///
/// # Errors
/// [`TooManyPieces`] beyond `max_pieces` or after 64 rounds (real models need one or two).
pub fn split_crossing(
    set: &PolygonSet,
    tolerance: f64,
    max_pieces: usize,
) -> Result<(PolygonSet, usize), TooManyPieces> {
    let mut pieces: Vec<Piece> = (0..set.len())
        .map(|i| Piece {
            corners: set.corners(i).to_vec(),
            face: set.face(i),
            plane: *set.plane(i),
        })
        .collect();
    let mut cuts = 0;
    let (mut front, mut back) = (Vec::new(), Vec::new());
    for round in 0.. {
        if round == MAX_ROUNDS {
            return Err(TooManyPieces {
                pieces: pieces.len(),
                budget: max_pieces,
            });
        }
        let partner = first_crossings(&pieces, tolerance);
        if partner.iter().all(Option::is_none) {
            break;
        }
        let mut next = Vec::with_capacity(pieces.len() + partner.len());
        for (i, piece) in pieces.iter().enumerate() {
            // A piece is cut by its partner's plane; of a crossing pair only the one with the
            // lower index is cut in this round (the other may be cut by a third piece).
            let cut_by = partner[i].filter(|&j| i < j || partner[j] != Some(i));
            let Some(j) = cut_by else {
                next.push(piece.clone());
                continue;
            };
            front.clear();
            back.clear();
            split_polygon(
                &piece.corners,
                &pieces[j].plane,
                tolerance,
                &mut front,
                &mut back,
            );
            for part in [&front, &back] {
                if part.len() >= 3 {
                    next.push(Piece {
                        corners: part.clone(),
                        ..*piece
                    });
                }
            }
            cuts += 1;
        }
        if next.len() > max_pieces {
            return Err(TooManyPieces {
                pieces: next.len(),
                budget: max_pieces,
            });
        }
        pieces = next;
    }
    let mut out = PolygonSet::new();
    for p in &pieces {
        out.push(&p.corners, p.face, p.plane);
    }
    Ok((out, cuts))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(z: f64, rotate: bool) -> Vec<DVec3> {
        let c = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        c.iter()
            .map(|&(x, y)| {
                if rotate {
                    DVec3::new(x, z, y)
                } else {
                    DVec3::new(x, y, z)
                }
            })
            .collect()
    }

    #[test]
    fn crossing_squares_are_cut_once() {
        let mut set = PolygonSet::new();
        for (k, rotate) in [false, true].into_iter().enumerate() {
            let corners = square(0.0, rotate);
            let plane = Plane::try_from_polygon(&corners).unwrap();
            set.push(&corners, k as u32, plane);
        }
        let (out, cuts) = split_crossing(&set, 4e-12, 100).unwrap();
        assert_eq!(cuts, 1);
        assert_eq!(out.len(), 3);
        // Parallel squares do not cross.
        let mut apart = PolygonSet::new();
        for z in [0.0, 1.0] {
            let corners = square(z, false);
            apart.push(&corners, 0, Plane::try_from_polygon(&corners).unwrap());
        }
        assert_eq!(split_crossing(&apart, 4e-12, 100).unwrap().1, 0);
        assert_eq!(
            split_crossing(&set, 4e-12, 2).err(),
            Some(TooManyPieces {
                pieces: 3,
                budget: 2
            })
        );
    }
}
