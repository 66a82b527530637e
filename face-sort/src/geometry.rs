//! A mesh prepared for ordering: planar convex pieces in centred model space.

use std::sync::Arc;

use glam::DVec3;

use crate::plane::{Plane, newell_normal};
use crate::polygon_set::PolygonSet;
use crate::tolerance::{
    CONVEXITY, DEGENERATE_AREA, MAX_EXTENT_ABS, MAX_IMAGE_EXTENT_PX, MIN_EXTENT_ABS,
    MIN_IMAGE_EXTENT_PX, ON_PLANE, PLANARITY, SAME_CORNER_ROUNDING, SLIVER,
};
use crate::{Bounds, MeshError, PolygonMesh};

/// A mesh cut into **pieces**, the units every sorter, the oracle and the truth work on
/// (CONVENTIONS.md): a planar face is one piece; a non-planar face is the fan of triangles
/// `(0, 1, 2), (0, 2, 3), …`, each a piece keeping the face's index. Pieces without area
/// are dropped, and so are slivers narrower than [`SLIVER`]` · D` (a millionth of their
/// length), whose planes f64 does not know well enough to order them.
///
/// Planar faces are snapped onto their fitted plane (a move of at most `1e-6 · D`), so that
/// every piece is planar and its plane is the one the truth uses. Corners already within
/// [`ON_PLANE`]` · L` of it (round-off: typically every corner of a triangle) keep their bits,
/// so that neighbours keep sharing them.
#[derive(Clone, Debug)]
pub struct Geometry {
    pieces: Arc<PolygonSet>,
    bounds: Bounds,
    face_count: usize,
    non_planar_faces: usize,
    dropped_pieces: usize,
    /// Per piece, its connected part (faces sharing a mesh vertex are connected), numbered
    /// densely from 0 in piece order.
    piece_part: Arc<[u32]>,
    part_count: usize,
}

impl Geometry {
    /// Cuts `mesh` into pieces. Errors when no piece has area, or when the mesh's size is
    /// outside what f64 orders exactly ([`MeshError::ExtentOutOfRange`]).
    pub fn new(mesh: &PolygonMesh) -> Result<Self, MeshError> {
        let bounds = mesh.bounds().ok_or(MeshError::Empty)?;
        Self::new_in_frame(mesh, bounds)
    }

    /// Whether `view` belongs to this geometry and its numbers are usable. Its centre must be
    /// the geometry's centre, the origin of the pieces' (centred) coordinates; views from
    /// [`Camera::view`](crate::Camera::view) and `View::fit(&geometry.bounds(), ..)` are. The
    /// `View` builders take any number; this is where a caller's view is checked before
    /// sorting: every number finite, the image not empty, the scale (the model's image
    /// between [`MIN_IMAGE_EXTENT_PX`] and [`MAX_IMAGE_EXTENT_PX`] across), the perspective
    /// eye distance and the cull margin in their ranges. A view that passes is sorted exactly.
    ///
    /// # Errors
    /// [`CameraError::CentreMismatch`](crate::CameraError::CentreMismatch),
    /// [`CameraError::NotFinite`](crate::CameraError::NotFinite),
    /// [`CameraError::EmptyImage`](crate::CameraError::EmptyImage) and
    /// [`CameraError::Lens`](crate::CameraError::Lens) naming the number out of range.
    pub fn check_view(&self, view: &crate::View) -> Result<(), crate::CameraError> {
        use crate::CameraError;
        let finite = |ok: bool, what: &'static str| {
            if ok {
                Ok(())
            } else {
                Err(CameraError::NotFinite { what })
            }
        };
        finite(view.rotation().is_finite(), "view rotation")?;
        finite(view.scale().is_finite(), "view scale")?;
        finite(view.view_offset().is_finite(), "view offset")?;
        finite(view.principal_point().is_finite(), "principal point")?;
        finite(view.cull_margin().is_finite(), "cull margin")?;
        if view.width() == 0 || view.height() == 0 {
            return Err(CameraError::EmptyImage {
                width: view.width(),
                height: view.height(),
            });
        }
        if view.scale() <= 0.0 {
            return Err(CameraError::Lens {
                what: "view scale",
                value: view.scale(),
            });
        }
        let extent = view.scale() * view.diagonal();
        if !(MIN_IMAGE_EXTENT_PX..=MAX_IMAGE_EXTENT_PX).contains(&extent) {
            return Err(CameraError::Lens {
                what: "model's image size in pixels (view scale times diagonal)",
                value: extent,
            });
        }
        if !(0.0..90.0).contains(&view.cull_margin()) {
            return Err(CameraError::Lens {
                what: "cull margin in degrees",
                value: view.cull_margin(),
            });
        }
        if let crate::Projection::Perspective { distance } = view.projection() {
            finite(distance.is_finite(), "perspective eye distance")?;
            if distance <= 0.0 {
                return Err(CameraError::Lens {
                    what: "perspective eye distance",
                    value: distance,
                });
            }
        }
        let (view_centre, centre) = (view.centre(), self.bounds.centre());
        if view_centre == centre {
            Ok(())
        } else {
            Err(CameraError::CentreMismatch {
                view: view_centre,
                geometry: centre,
            })
        }
    }

    /// Cuts `mesh` into pieces centred on `frame`'s centre, with `frame` as the bounds that
    /// views are fitted to and tolerances are relative to, instead of the mesh's own: for
    /// a part of a larger scene (a [`SceneSorter`](crate::SceneSorter)'s clusters, or its
    /// flattened reference) whose draw lists must share the scene's coordinates.
    pub fn new_in_frame(mesh: &PolygonMesh, frame: Bounds) -> Result<Self, MeshError> {
        Self::build(mesh, frame, true)
    }

    /// Like [`new`](Self::new), but every piece keeps the file's corners bit for bit: a
    /// planar face whose corners lie off its plane by more than rounding (which `new` snaps
    /// onto the plane, by up to `1e-6` of the face's size) is cut into its fan of triangles
    /// instead. Neighbouring pieces then share their corners exactly, so no two pieces cross
    /// or twist about a shared edge by the snapping; what needs pairs of pieces to meet
    /// exactly (aspect-bake's picture bakes) wants this. The difference from `new`'s pieces
    /// is below the ambiguity of the error metric (depths within `1e-6 · L`).
    pub fn with_exact_corners(mesh: &PolygonMesh) -> Result<Self, MeshError> {
        let bounds = mesh.bounds().ok_or(MeshError::Empty)?;
        Self::build(mesh, bounds, false)
    }

    fn build(mesh: &PolygonMesh, frame: Bounds, snap: bool) -> Result<Self, MeshError> {
        if mesh.face_count() == 0 {
            return Err(MeshError::Empty);
        }
        let bounds = frame;
        let diagonal = bounds.diagonal();
        if diagonal > 0.0 && !(MIN_EXTENT_ABS..=MAX_EXTENT_ABS).contains(&diagonal) {
            // The largest side, not the diagonal: its square may have overflowed. `as`
            // saturates should the side itself be infinite.
            let side = (bounds.max - bounds.min).max_element();
            let exponent = side.log10().floor() as i32;
            return Err(MeshError::ExtentOutOfRange { exponent });
        }
        let centre = bounds.centre();
        let on_plane = ON_PLANE * diagonal;
        let same_corner = SAME_CORNER_ROUNDING * diagonal;
        let mut pieces = PolygonSet::new();
        let mut corners: Vec<DVec3> = Vec::new();
        let mut non_planar_faces = 0;
        let mut dropped_pieces = 0;
        for (face, list) in mesh.faces().enumerate() {
            corners.clear();
            corners.extend(list.iter().map(|&i| mesh.positions()[i as usize] - centre));
            // A corner repeated next to itself, or within rounding of it, adds an edge of no
            // length (or of a direction only rounding decides), which every test on edges
            // (separating lines, clipping) would have to treat apart: the piece keeps one.
            let same = |a: &DVec3, b: &DVec3| a.distance(*b) <= same_corner;
            corners.dedup_by(|a, b| same(a, b));
            while corners.len() > 1 && same(&corners[0], &corners[corners.len() - 1]) {
                corners.pop();
            }
            if corners.len() < 3 {
                dropped_pieces += 1;
                continue;
            }
            let size = largest_distance(&corners);
            let plane = Plane::try_from_polygon(&corners);
            let planar = plane.is_some_and(|p| {
                corners.iter().all(|&c| {
                    let d = p.signed_distance(c).abs();
                    d <= PLANARITY * size && (snap || d <= on_plane)
                })
            });
            match plane {
                Some(plane) if planar => {
                    if newell_normal(&corners).length() <= SLIVER * size * size {
                        dropped_pieces += 1;
                        continue;
                    }
                    // A corner already on the plane (to round-off) keeps its bits, so that
                    // neighbours keep sharing it.
                    for c in corners.iter_mut() {
                        if plane.signed_distance(*c).abs() > on_plane {
                            *c = plane.project_point(*c);
                        }
                    }
                    if repeats_a_corner(&corners)
                        || !is_convex(&corners, newell_normal(&corners).normalize(), size)
                    {
                        return Err(MeshError::NonConvex { face });
                    }
                    pieces.push(&corners, face as u32, plane);
                }
                _ => {
                    // The fan is the surface of a non-planar face; it must not cover itself.
                    // It does when the face repeats a corner out of turn (`[a, b, c, b, d]`
                    // fans into a triangle and its reverse), or folds onto itself with no
                    // net area while its fan has area.
                    let least = DEGENERATE_AREA * size * size;
                    let fan_has_area = (1..corners.len() - 1).any(|k| {
                        newell_normal(&[corners[0], corners[k], corners[k + 1]]).length() > least
                    });
                    if fan_has_area
                        && (repeats_a_corner(&corners) || newell_normal(&corners).length() <= least)
                    {
                        return Err(MeshError::NonConvex { face });
                    }
                    non_planar_faces += 1;
                    for k in 1..corners.len() - 1 {
                        let tri = [corners[0], corners[k], corners[k + 1]];
                        let tri_size = largest_distance(&tri);
                        let normal = newell_normal(&tri);
                        match Plane::try_from_polygon(&tri) {
                            Some(p) if normal.length() > SLIVER * tri_size * tri_size => {
                                pieces.push(&tri, face as u32, p);
                            }
                            _ => dropped_pieces += 1,
                        }
                    }
                }
            }
        }
        if pieces.is_empty() {
            return Err(MeshError::Empty);
        }
        let (piece_part, part_count) = parts_of(mesh, &pieces);
        Ok(Geometry {
            pieces: Arc::new(pieces),
            bounds,
            face_count: mesh.face_count(),
            non_planar_faces,
            dropped_pieces,
            piece_part: piece_part.into(),
            part_count,
        })
    }

    /// A geometry of ready pieces (planar, convex, centred on `bounds`' centre), for a part
    /// of another geometry that a sorter orders apart (a [`Presorted`](crate::Presorted) cycle).
    pub(crate) fn from_pieces(pieces: PolygonSet, bounds: Bounds) -> Self {
        let n = pieces.len();
        Geometry {
            face_count: n,
            pieces: Arc::new(pieces),
            bounds,
            non_planar_faces: 0,
            dropped_pieces: 0,
            piece_part: vec![0; n].into(),
            part_count: 1,
        }
    }

    /// The pieces (centred model space).
    #[must_use]
    pub fn pieces(&self) -> &Arc<PolygonSet> {
        &self.pieces
    }

    /// Bounds of the source mesh (model space).
    #[must_use]
    pub fn bounds(&self) -> Bounds {
        self.bounds
    }

    /// Number of faces of the source mesh.
    #[must_use]
    pub fn face_count(&self) -> usize {
        self.face_count
    }

    /// Faces that were not planar and became fans of triangles.
    #[must_use]
    pub fn non_planar_faces(&self) -> usize {
        self.non_planar_faces
    }

    /// Faces or fan triangles dropped for having no area or being slivers ([`SLIVER`]).
    #[must_use]
    pub fn dropped_pieces(&self) -> usize {
        self.dropped_pieces
    }

    /// Connected parts of the mesh (faces that share a vertex index are in one part).
    #[must_use]
    pub fn part_count(&self) -> usize {
        self.part_count
    }

    /// Per piece, its part (`0..part_count()`, numbered in piece order).
    #[must_use]
    pub fn piece_parts(&self) -> &[u32] {
        &self.piece_part
    }
}

/// Each piece's connected part, by union of the vertex indices of each face (one pass over
/// the mesh's corners), and the number of parts that have pieces.
fn parts_of(mesh: &PolygonMesh, pieces: &PolygonSet) -> (Vec<u32>, usize) {
    fn root(parent: &mut [u32], mut i: u32) -> u32 {
        while parent[i as usize] != i {
            parent[i as usize] = parent[parent[i as usize] as usize];
            i = parent[i as usize];
        }
        i
    }
    let mut parent: Vec<u32> = (0..mesh.positions().len() as u32).collect();
    for face in mesh.faces() {
        let first = root(&mut parent, face[0]);
        for &v in &face[1..] {
            let r = root(&mut parent, v);
            if r != first {
                let (lo, hi) = (first.min(r), first.max(r));
                parent[hi as usize] = lo;
            }
        }
    }
    let faces: Vec<u32> = mesh.faces().map(|f| f[0]).collect();
    let mut number = vec![u32::MAX; parent.len()];
    let mut count = 0;
    let parts = (0..pieces.len())
        .map(|i| {
            let r = root(&mut parent, faces[pieces.face(i) as usize]) as usize;
            if number[r] == u32::MAX {
                number[r] = count;
                count += 1;
            }
            number[r]
        })
        .collect();
    (parts, count as usize)
}

fn largest_distance(corners: &[DVec3]) -> f64 {
    if corners.len() > 32 {
        // Bounding-box diagonal: within a factor √3 of the largest distance, and O(n).
        return Bounds::from_points(corners.iter().copied())
            .map_or(0.0, |b| (b.max - b.min).length());
    }
    let mut best: f64 = 0.0;
    for (i, a) in corners.iter().enumerate() {
        for b in &corners[i + 1..] {
            best = best.max(a.distance_squared(*b));
        }
    }
    best.sqrt()
}

/// Whether a corner occurs twice (neighbouring repeats are already removed): the polygon then
/// crosses or retraces itself.
fn repeats_a_corner(corners: &[DVec3]) -> bool {
    // Faces may have up to 65,536 corners: compare sorted bit patterns, not every pair. Corners
    // are finite, and `+ 0.0` makes `-0.0` equal to `0.0` as `==` has it.
    let mut bits: Vec<[u64; 3]> = corners
        .iter()
        .map(|c| (*c + DVec3::ZERO).to_array().map(f64::to_bits))
        .collect();
    bits.sort_unstable();
    bits.windows(2).any(|w| w[0] == w[1])
}

/// Whether a planar polygon with this unit normal is convex (straight corners and repeated
/// neighbours allowed) and goes round exactly once ([`CONVEXITY`]). Edges shorter than
/// `CONVEXITY · D` are left out: their direction is rounding.
fn is_convex(corners: &[DVec3], normal: DVec3, size: f64) -> bool {
    let short = CONVEXITY * size;
    let mut ring: Vec<DVec3> = Vec::with_capacity(corners.len());
    for &c in corners {
        if ring.last().is_none_or(|&p| p.distance(c) > short) {
            ring.push(c);
        }
    }
    while ring.len() > 1 && ring[0].distance(ring[ring.len() - 1]) <= short {
        ring.pop();
    }
    let n = ring.len();
    if n < 4 {
        return true;
    }
    let eps = CONVEXITY * size * size;
    let mut turning = 0.0;
    for i in 0..n {
        let e1 = ring[i] - ring[(i + n - 1) % n];
        let e2 = ring[(i + 1) % n] - ring[i];
        let turn = e1.cross(e2).dot(normal);
        // A turn back along the edge (a spike of no width) is not convex either, though its
        // cross product is zero.
        if turn < -eps || (turn <= eps && e1.dot(e2) < 0.0) {
            return false;
        }
        turning += turn.atan2(e1.dot(e2));
    }
    (turning - std::f64::consts::TAU).abs() < 0.5
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit triangle and a triangle `1e8` long and `width` wide, far along `x`.
    fn with_sliver(width: f64) -> Geometry {
        let mesh = PolygonMesh::new(
            [
                DVec3::ZERO,
                DVec3::X,
                DVec3::Y,
                DVec3::new(0.0, 0.0, 1.0),
                DVec3::new(0.0, width, 1.0),
                DVec3::new(1e8, 0.0, 1.0),
            ],
            [[0u32, 1, 2], [3, 5, 4]],
        )
        .unwrap();
        Geometry::new(&mesh).unwrap()
    }

    #[test]
    fn a_sliver_is_dropped_and_counted() {
        // Width over length `4e-7` and `4e-5`: one side of `SLIVER = 1e-6` each.
        let thin = with_sliver(40.0);
        assert_eq!((thin.pieces().len(), thin.dropped_pieces()), (1, 1));
        let kept = with_sliver(4000.0);
        assert_eq!((kept.pieces().len(), kept.dropped_pieces()), (2, 0));
    }
}
