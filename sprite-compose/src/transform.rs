//! Per-piece sprite transforms: the unit square mapped onto a face in sprite space.

use face_sort::{Geometry, View};
use glam::{DMat4, DVec2, DVec3, DVec4};

use crate::tolerance::{HOMOGRAPHY_W, PARALLELOGRAM, SINGULAR_DET, UNDERFLOW_ABS};

/// Where sprites live before the root transform: **rest pixel space**.
///
/// A centred model point `p − c` sits at `O + F · s · (p − c)` with `O = (W/2, H/2, 0)`,
/// `F = diag(1, −1, 1)` (pixel y points down) and `s` the view's scale. With identity rotation
/// and orthographic projection this is exactly the pixel position of CONVENTIONS.md, so the
/// root transform only has to rotate about `O` and apply perspective.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpriteSpace {
    /// Frame centre `O = (W/2, H/2, 0)` in pixels.
    pub origin: DVec3,
    /// Scale `s`, pixels per model unit.
    pub scale: f64,
}

impl SpriteSpace {
    /// The sprite space of a view (its scale and image size).
    #[must_use]
    pub fn of_view(view: &View) -> Self {
        SpriteSpace {
            origin: DVec3::new(
                f64::from(view.width()) * 0.5,
                f64::from(view.height()) * 0.5,
                0.0,
            ),
            scale: view.scale(),
        }
    }

    /// Sprite-space position of a centred model point.
    #[inline]
    #[must_use]
    pub fn point(&self, centred: DVec3) -> DVec3 {
        let q = centred * self.scale;
        self.origin + DVec3::new(q.x, -q.y, q.z)
    }

    /// Sprite-space direction of a model-space normal (not normalised).
    #[inline]
    #[must_use]
    pub fn normal(&self, normal: DVec3) -> DVec3 {
        DVec3::new(normal.x, -normal.y, normal.z)
    }
}

/// How a sprite's unit square reaches its face.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MapKind {
    /// Affine: a parallelogram quad, a triangle (half the square), or the bounding rectangle
    /// of an n-gon (with a clip polygon).
    Affine,
    /// Projective: the homography of the unit square onto a general planar quad.
    Projective,
}

/// The fixed transform of one sprite: a 4×4 matrix acting on `(u, v, z, 1)` (column vectors,
/// CSS `matrix3d` order via [`DMat4::to_cols_array`]) that maps the unit square `z = 0` onto a
/// face in [`SpriteSpace`].
///
/// The square's corners `(0,0), (1,0), (1,1), (0,1)` go to a quad's corners `0, 3, 2, 1`, so
/// that the square's front (CSS: `+z` toward the viewer with `y` down) is the face's front
/// (counter-clockwise from outside). The third column is the face's front normal, so
/// `backface-visibility: hidden` culls like CONVENTIONS.md's counter-clockwise front.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpriteTransform {
    /// The matrix.
    pub matrix: DMat4,
    /// Affine or projective.
    pub kind: MapKind,
}

impl SpriteTransform {
    /// Sprite-space homogeneous image of a unit-square point.
    #[inline]
    #[must_use]
    pub fn apply_homogeneous(&self, uv: DVec2) -> DVec4 {
        self.matrix * DVec4::new(uv.x, uv.y, 0.0, 1.0)
    }

    /// Sprite-space image of a unit-square point (after the projective divide).
    #[inline]
    #[must_use]
    pub fn apply(&self, uv: DVec2) -> DVec3 {
        let h = self.apply_homogeneous(uv);
        h.truncate() / h.w
    }

    /// Unit-square coordinates of a sprite-space point on the face's plane (least squares
    /// for points slightly off the plane).
    #[must_use]
    pub fn unit_coords(&self, point: DVec3) -> DVec2 {
        // X · (g u + h v + k) = A u + B v + C  ⇔  u (A − g X) + v (B − h X) = k X − C.
        let m = &self.matrix;
        let a = m.x_axis.truncate() - m.x_axis.w * point;
        let b = m.y_axis.truncate() - m.y_axis.w * point;
        let r = m.w_axis.w * point - m.w_axis.truncate();
        solve_2x2_least_squares(a, b, r).unwrap_or(DVec2::ZERO)
    }
}

/// Solves `u a + v b = r` in the least-squares sense; `None` when `a` and `b` are parallel.
fn solve_2x2_least_squares(a: DVec3, b: DVec3, r: DVec3) -> Option<DVec2> {
    let (aa, ab, bb) = (a.dot(a), a.dot(b), b.dot(b));
    let det = aa * bb - ab * ab;
    if !det.is_finite() || det.abs() <= UNDERFLOW_ABS || det.abs() <= SINGULAR_DET * aa * bb {
        return None;
    }
    let (ar, br) = (a.dot(r), b.dot(r));
    let out = DVec2::new((ar * bb - ab * br) / det, (aa * br - ab * ar) / det);
    out.is_finite().then_some(out)
}

/// The transform of one piece, and the clip polygon (unit-square coordinates) when the piece is
/// not the whole square.
#[derive(Clone, Debug, PartialEq)]
pub struct PieceMap {
    /// The transform.
    pub transform: SpriteTransform,
    /// `None` for a quad (the whole square); otherwise the piece's corners in unit-square
    /// coordinates, in the piece's corner order.
    pub clip: Option<Vec<DVec2>>,
}

/// Builds the map of one planar convex piece (corners in centred model space, with the piece's
/// unit normal). `None` when the piece is degenerate in sprite space.
#[must_use]
pub fn piece_map(space: &SpriteSpace, corners: &[DVec3], normal: DVec3) -> Option<PieceMap> {
    let n = space.normal(normal).try_normalize()?;
    let p: Vec<DVec3> = corners.iter().map(|&c| space.point(c)).collect();
    let map = match p.len() {
        0..=2 => return None,
        3 => {
            // (0,0) → P0, (1,0) → P2, (0,1) → P1: the triangle is the square's half u + v ≤ 1.
            let transform = affine(p[0], p[2] - p[0], p[1] - p[0], n)?;
            PieceMap {
                transform,
                clip: Some(vec![DVec2::ZERO, DVec2::Y, DVec2::X]),
            }
        }
        4 => match quad(&p, n) {
            Some(transform) => PieceMap {
                transform,
                clip: None,
            },
            None => bounding_rectangle(&p, n)?,
        },
        _ => bounding_rectangle(&p, n)?,
    };
    map.transform.matrix.is_finite().then_some(map)
}

/// The unit-square map onto `origin + u·a + v·b`, third column the front normal.
fn affine(origin: DVec3, a: DVec3, b: DVec3, n: DVec3) -> Option<SpriteTransform> {
    let cross = a.cross(b);
    if !cross.is_finite() || cross.length() <= 0.0 {
        return None;
    }
    let size = cross.length().sqrt();
    Some(SpriteTransform {
        matrix: DMat4::from_cols(
            a.extend(0.0),
            b.extend(0.0),
            (n * size).extend(0.0),
            origin.extend(1.0),
        ),
        kind: MapKind::Affine,
    })
}

/// The exact map of a planar quad: affine for a parallelogram, else the homography.
/// `None` for a quad that is not strictly convex (the homography would cross `w = 0`).
fn quad(p: &[DVec3], n: DVec3) -> Option<SpriteTransform> {
    // Square corners (0,0),(1,0),(1,1),(0,1) → Q0..Q3 = P0, P3, P2, P1.
    let q = [p[0], p[3], p[2], p[1]];
    let diagonal = (q[2] - q[0]).length().max((q[3] - q[1]).length());
    let residual = q[0] + q[2] - q[1] - q[3];
    if residual.length() <= PARALLELOGRAM * diagonal {
        return affine(q[0], q[1] - q[0], q[3] - q[0], n);
    }
    // X(u,v) = (A u + B v + C) / (g u + h v + 1) with C = Q0, A = (1+g) Q1 − Q0,
    // B = (1+h) Q3 − Q0 and X(1,1) = Q2: g (Q2 − Q1) + h (Q2 − Q3) = Q1 + Q3 − Q0 − Q2.
    let gh = solve_2x2_least_squares(q[2] - q[1], q[2] - q[3], -residual)?;
    let (g, h) = (gh.x, gh.y);
    // Convex quads keep w = g u + h v + 1 > 0 on the whole square (check its corners).
    let w_min = [1.0, 1.0 + g, 1.0 + h, 1.0 + g + h]
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    if !w_min.is_finite() || w_min <= HOMOGRAPHY_W {
        return None;
    }
    let a = q[1] * (1.0 + g) - q[0];
    let b = q[3] * (1.0 + h) - q[0];
    let size = (q[1] - q[0]).cross(q[3] - q[0]).length().sqrt();
    if !size.is_finite() || size <= 0.0 {
        return None;
    }
    Some(SpriteTransform {
        matrix: DMat4::from_cols(
            a.extend(g),
            b.extend(h),
            (n * size).extend(0.0),
            q[0].extend(1.0),
        ),
        kind: MapKind::Projective,
    })
}

/// An affine map onto the polygon's bounding rectangle in its plane, plus the clip polygon.
fn bounding_rectangle(p: &[DVec3], n: DVec3) -> Option<PieceMap> {
    // v runs along P0 → P1 (as for quads), u = v × n so that u × v = n (front).
    let e_v = (p[1] - p[0]).try_normalize()?;
    let e_u = e_v.cross(n).try_normalize()?;
    let coords: Vec<DVec2> = p
        .iter()
        .map(|&x| DVec2::new((x - p[0]).dot(e_u), (x - p[0]).dot(e_v)))
        .collect();
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for c in &coords {
        lo = lo.min(*c);
        hi = hi.max(*c);
    }
    let extent = hi - lo;
    if !extent.is_finite() || extent.x <= 0.0 || extent.y <= 0.0 {
        return None;
    }
    let transform = affine(
        p[0] + e_u * lo.x + e_v * lo.y,
        e_u * extent.x,
        e_v * extent.y,
        n,
    )?;
    let clip = coords.iter().map(|&c| (c - lo) / extent).collect();
    Some(PieceMap {
        transform,
        clip: Some(clip),
    })
}

/// The maps of every piece of a geometry, built once per geometry, scale and image size.
#[derive(Clone, Debug)]
pub struct PieceMaps {
    space: SpriteSpace,
    maps: Vec<Option<PieceMap>>,
    degenerate: usize,
}

impl PieceMaps {
    /// Builds the map of every piece of `geometry` in the sprite space of `view`.
    #[must_use]
    pub fn new(geometry: &Geometry, view: &View) -> Self {
        let space = SpriteSpace::of_view(view);
        let pieces = geometry.pieces();
        let maps: Vec<Option<PieceMap>> = (0..pieces.len())
            .map(|i| piece_map(&space, pieces.corners(i), pieces.plane(i).normal()))
            .collect();
        let degenerate = maps.iter().filter(|m| m.is_none()).count();
        PieceMaps {
            space,
            maps,
            degenerate,
        }
    }

    /// The sprite space the maps were built in.
    #[must_use]
    pub fn space(&self) -> &SpriteSpace {
        &self.space
    }

    /// The map of piece `piece`; `None` when it is degenerate (skipped).
    #[must_use]
    pub fn get(&self, piece: usize) -> Option<&PieceMap> {
        self.maps.get(piece).and_then(Option::as_ref)
    }

    /// Number of pieces.
    #[must_use]
    pub fn len(&self) -> usize {
        self.maps.len()
    }

    /// Whether there are no pieces.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.maps.is_empty()
    }

    /// Pieces skipped because no map could be built (degenerate in sprite space). Pieces
    /// without area were already dropped by [`Geometry`] (see
    /// [`Geometry::dropped_pieces`]).
    #[must_use]
    pub fn degenerate(&self) -> usize {
        self.degenerate
    }

    /// How many maps are affine and how many projective.
    #[must_use]
    pub fn kind_counts(&self) -> (usize, usize) {
        let mut counts = (0, 0);
        for m in self.maps.iter().flatten() {
            match m.transform.kind {
                MapKind::Affine => counts.0 += 1,
                MapKind::Projective => counts.1 += 1,
            }
        }
        counts
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn space() -> SpriteSpace {
        SpriteSpace {
            origin: DVec3::new(128.0, 128.0, 0.0),
            scale: 10.0,
        }
    }

    fn check_corners(map: &PieceMap, space: &SpriteSpace, corners: &[DVec3]) {
        match &map.clip {
            None => {
                let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
                let order = [0, 3, 2, 1];
                for (uv, &k) in square.iter().zip(&order) {
                    let got = map.transform.apply(*uv);
                    let want = space.point(corners[k]);
                    assert!((got - want).length() < 1e-9, "{got} vs {want}");
                }
            }
            Some(clip) => {
                assert_eq!(clip.len(), corners.len());
                for (uv, c) in clip.iter().zip(corners) {
                    assert!(
                        uv.cmpge(DVec2::splat(-1e-12)).all()
                            && uv.cmple(DVec2::splat(1.0 + 1e-12)).all()
                    );
                    let got = map.transform.apply(*uv);
                    assert!((got - space.point(*c)).length() < 1e-9);
                }
            }
        }
    }

    #[test]
    fn parallelogram_is_affine_and_exact() {
        let c = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 1.0),
            DVec3::new(3.0, 1.0, 1.0),
            DVec3::new(1.0, 1.0, 0.0),
        ];
        let n = face_sort::newell_normal(&c).normalize();
        let map = piece_map(&space(), &c, n).unwrap();
        assert_eq!(map.transform.kind, MapKind::Affine);
        check_corners(&map, &space(), &c);
    }

    #[test]
    fn general_quad_is_projective_and_exact() {
        let c = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(3.0, 0.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(0.5, 2.0, 0.0),
        ];
        let map = piece_map(&space(), &c, DVec3::Z).unwrap();
        assert_eq!(map.transform.kind, MapKind::Projective);
        check_corners(&map, &space(), &c);
        // Straight lines stay straight and the inverse is exact.
        let x = map.transform.apply(DVec2::new(0.3, 0.7));
        let back = map.transform.unit_coords(x);
        assert!((back - DVec2::new(0.3, 0.7)).length() < 1e-12);
        // Front normal: u × v along the (flipped) face normal.
        let m = map.transform.matrix;
        let front = m.x_axis.truncate().cross(m.y_axis.truncate());
        assert!(front.dot(m.z_axis.truncate()) > 0.0);
        assert!(front.z > 0.0, "a +Z face faces the CSS viewer (+z)");
    }

    #[test]
    fn triangle_and_ngon_get_clip_polygons() {
        let tri = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let map = piece_map(&space(), &tri, DVec3::Z).unwrap();
        check_corners(&map, &space(), &tri);
        let hex: Vec<DVec3> = (0..6)
            .map(|k| {
                let a = f64::from(k) * std::f64::consts::TAU / 6.0;
                DVec3::new(a.cos(), a.sin(), 0.5 * a.cos())
            })
            .collect();
        let n = face_sort::newell_normal(&hex).normalize();
        let map = piece_map(&space(), &hex, n).unwrap();
        assert_eq!(map.transform.kind, MapKind::Affine);
        check_corners(&map, &space(), &hex);
    }

    #[test]
    fn degenerate_pieces_are_skipped() {
        let flat = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        assert!(piece_map(&space(), &flat, DVec3::Z).is_none());
    }
}
