//! A flat arena of planar convex polygons, each tagged with its source face and plane.

use glam::DVec3;

use crate::plane::Plane;

/// Planar convex polygons stored flat: one vertex buffer, one start offset per polygon.
///
/// Vertices are in **centred model space**: model coordinates minus the view centre `c`
/// (CONVENTIONS.md), computed in f64, so that models far from the origin keep precision.
///
/// # Guarantees
/// Every polygon has at least 3 corners and a plane; the source face index is the face's
/// position in the input mesh.
#[derive(Clone, Debug, Default)]
pub struct PolygonSet {
    vertices: Vec<DVec3>,
    starts: Vec<u32>,
    faces: Vec<u32>,
    planes: Vec<Plane>,
}

impl PolygonSet {
    /// An empty set.
    #[must_use]
    pub fn new() -> Self {
        PolygonSet {
            vertices: Vec::new(),
            starts: vec![0],
            faces: Vec::new(),
            planes: Vec::new(),
        }
    }

    /// Number of polygons.
    #[inline]
    #[must_use]
    pub fn len(&self) -> usize {
        self.faces.len()
    }

    /// Whether the set has no polygon.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty()
    }

    /// Corners of polygon `i` (centred model space).
    #[inline]
    #[must_use]
    pub fn corners(&self, i: usize) -> &[DVec3] {
        &self.vertices[self.starts[i] as usize..self.starts[i + 1] as usize]
    }

    /// Source face of polygon `i`.
    #[inline]
    #[must_use]
    pub fn face(&self, i: usize) -> u32 {
        self.faces[i]
    }

    /// Plane of polygon `i` (the plane of the piece it was cut from).
    #[inline]
    #[must_use]
    pub fn plane(&self, i: usize) -> &Plane {
        &self.planes[i]
    }

    /// Every plane, indexed like the polygons.
    #[must_use]
    pub fn planes(&self) -> &[Plane] {
        &self.planes
    }

    /// Appends a polygon (at least 3 corners) and returns its index.
    pub fn push(&mut self, corners: &[DVec3], face: u32, plane: Plane) -> u32 {
        debug_assert!(corners.len() >= 3);
        if self.starts.is_empty() {
            self.starts.push(0);
        }
        self.vertices.extend_from_slice(corners);
        self.starts.push(self.vertices.len() as u32);
        self.faces.push(face);
        self.planes.push(plane);
        (self.faces.len() - 1) as u32
    }

    /// Removes every polygon, keeping the capacity.
    pub fn clear(&mut self) {
        self.vertices.clear();
        self.starts.clear();
        self.starts.push(0);
        self.faces.clear();
        self.planes.clear();
    }

    /// Total number of stored corners.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }

    /// Heap bytes in use (capacity), for memory reports.
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        self.vertices.capacity() * size_of::<DVec3>()
            + self.starts.capacity() * 4
            + self.faces.capacity() * 4
            + self.planes.capacity() * size_of::<Plane>()
    }
}
