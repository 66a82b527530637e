//! The narrow input of the crate: positions plus face index lists.

use glam::DVec3;

use crate::MeshError;

/// Largest number of corners one face may have.
pub const MAX_FACE_CORNERS: usize = 1 << 16;

/// A polygon mesh as the sorters need it: positions and faces (index lists, any arity ≥ 3,
/// each convex and, for ordering, planar or else treated as a fan of triangles).
///
/// # Guarantees
/// Every face has at least 3 corners, every index is in range, and every position is finite.
#[derive(Clone, Debug, Default)]
pub struct PolygonMesh {
    positions: Vec<DVec3>,
    indices: Vec<u32>,
    offsets: Vec<u32>,
}

impl PolygonMesh {
    /// Validates and builds a mesh from positions (`[f32; 3]`, `[f64; 3]`, glam vectors or,
    /// with the `mint` feature, mint points: whatever [`Point3`](crate::Point3) converts,
    /// owned or borrowed as arrays) and faces (lists of position indices). Face order is
    /// kept: face `i` is the `i`-th list.
    pub fn new<P, F, I>(positions: impl IntoIterator<Item = P>, faces: F) -> Result<Self, MeshError>
    where
        P: Into<crate::Point3>,
        F: IntoIterator<Item = I>,
        I: AsRef<[u32]>,
    {
        let positions: Vec<DVec3> = positions.into_iter().map(|p| p.into().0).collect();
        if let Some(vertex) = positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinitePosition { vertex });
        }
        let mut indices = Vec::new();
        let mut offsets = vec![0u32];
        for (face, list) in faces.into_iter().enumerate() {
            let list = list.as_ref();
            if list.len() < 3 || list.len() > MAX_FACE_CORNERS {
                return Err(MeshError::BadArity {
                    face,
                    corners: list.len(),
                });
            }
            if let Some(&index) = list.iter().find(|&&i| i as usize >= positions.len()) {
                return Err(MeshError::IndexOutOfRange {
                    face,
                    index,
                    positions: positions.len(),
                });
            }
            indices.extend_from_slice(list);
            let end = u32::try_from(indices.len()).map_err(|_| MeshError::TooLarge)?;
            offsets.push(end);
        }
        Ok(PolygonMesh {
            positions,
            indices,
            offsets,
        })
    }

    /// Vertex positions in model space.
    #[must_use]
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// Number of faces.
    #[must_use]
    pub fn face_count(&self) -> usize {
        self.offsets.len() - 1
    }

    /// The index list of face `face`.
    ///
    /// # Panics
    /// When `face >= self.face_count()`.
    #[must_use]
    pub fn face(&self, face: usize) -> &[u32] {
        &self.indices[self.offsets[face] as usize..self.offsets[face + 1] as usize]
    }

    /// Every face's index list, in order.
    pub fn faces(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        (0..self.face_count()).map(|f| self.face(f))
    }

    /// Bounds of every vertex that a face uses (CONVENTIONS.md), `None` for a mesh without faces.
    #[must_use]
    pub fn bounds(&self) -> Option<Bounds> {
        Bounds::from_points(self.indices.iter().map(|&i| self.positions[i as usize]))
    }
}

/// Axis-aligned bounds: centre `c` and diagonal `L` as CONVENTIONS.md defines them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// Smallest corner.
    pub min: DVec3,
    /// Largest corner.
    pub max: DVec3,
}

impl Bounds {
    /// The bounds of `points`; `None` when there are none.
    #[must_use]
    pub fn from_points(points: impl IntoIterator<Item = DVec3>) -> Option<Self> {
        let mut it = points.into_iter();
        let first = it.next()?;
        let (mut min, mut max) = (first, first);
        for p in it {
            min = min.min(p);
            max = max.max(p);
        }
        Some(Bounds { min, max })
    }

    /// Midpoint of the box: the centre `c` of the view.
    #[must_use]
    pub fn centre(&self) -> DVec3 {
        (self.min + self.max) * 0.5
    }

    /// Length of the box's diagonal, `L`. Never zero: a single point gets `L = 1`.
    #[must_use]
    pub fn diagonal(&self) -> f64 {
        let l = (self.max - self.min).length();
        if l > 0.0 { l } else { 1.0 }
    }
}
