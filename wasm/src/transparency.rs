//! A certified order of a static mesh's triangles for a GPU that blends without sorting:
//! every certified order in one index buffer, and per frame the range of the viewer's
//! region (Chen, Sander, Nehab et al.'s depth-presorted triangle lists, with face-sort's
//! certificates in place of duplicated triangles).
//!
//! The GPU culls back faces; each order lists its region's pieces back faces included, so
//! a frame in a region without cycles is a range and nothing is uploaded. Regions whose
//! order holds small cycles are ordered per frame by [`Presorted`] (its per-cycle BSP
//! trees) into the scratch tail of the buffer, and so are views the certificate does not
//! cover (an eye nearer than its reach): those are drawn far to near by piece centroid and
//! counted, never silently.

use face_sort::{
    CullTest, DrawList, FallbackReason, Geometry, OrderStep, PresortOptions, Presorted, Viewer,
};
use glam::DVec3;

use crate::error::BindError;
use crate::input::Triangles;

// The tolerances of the GPU layout, together (relative, as face-sort's).

/// Width, in model sizes, up to which a piece is a sliver that the GPU does not draw: a
/// ten-thousandth of a pixel where the model spans a thousand.
const SLIVER_WIDTH: f64 = 1e-7;

/// Distance, in model sizes, within which a cut's corner lies on another piece's edge of
/// the same face and is inserted there (T-junctions closed).
const SEAM: f64 = 1e-9;

/// Twice a fan triangle's area, relative to its polygon's squared size, up to which the
/// triangle is degenerate (its corners on one line).
const COLLINEAR: f64 = 1e-9;

/// One certified order's place in the index buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LeafRange {
    /// First index.
    pub start: u32,
    /// Indices (three per triangle).
    pub count: u32,
    /// Whether the order holds cycles ordered per frame (then the range is unused).
    pub cycles: bool,
}

/// What a frame draws: a range of the index buffer, and whether its scratch tail changed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Frame {
    /// First index to draw.
    pub start: u32,
    /// Indices to draw.
    pub count: u32,
    /// Whether `indices()[scratch_start..scratch_start + count]` was rewritten (upload it).
    pub rewritten: bool,
    /// Why the view was outside the certificate (drawn by centroid, not exact), or `None`.
    pub fallback: Option<FallbackReason>,
}

/// The certificate of a mesh's triangles as GPU buffers (module docs).
pub struct Transparency {
    sorter: Presorted,
    centre: DVec3,
    /// Per piece, where its triangles' indices start in `piece_triangles` (one more entry
    /// than pieces).
    piece_start: Vec<u32>,
    /// Every piece's triangles (vertex indices), piece after piece.
    piece_triangles: Vec<u32>,
    /// Per piece of the cut geometry (not the cycles' fragments): its centroid (centred).
    centroids: Vec<DVec3>,
    positions: Vec<f32>,
    vertex_triangles: Vec<u32>,
    indices: Vec<u32>,
    leaves: Vec<LeafRange>,
    scratch_start: u32,
    /// The scratch tail as the next frame composes it (capacity reserved once).
    next: Vec<u32>,
    list: DrawList,
    by_depth: Vec<(f64, u32)>,
    last_scratch: Option<usize>,
    frames: u64,
    fallback_frames: u64,
}

/// Triangles covering a convex polygon (corners from vertex `first`) with none of zero
/// area: a fan from a corner whose fan has no degenerate triangle, else a fan from the
/// centroid (`centroid` is its vertex index). A closed T-junction leaves corners on the
/// line of an edge; a fan through them would hold slivers that a GPU's snapped vertices
/// can turn into double cover. A sliver left by cuts (no wider than `min_width`) gets no
/// triangle, for the same reason.
fn triangulate(
    corners: &[DVec3],
    first: u32,
    centroid: u32,
    min_width: f64,
    out: &mut Vec<u32>,
) -> bool {
    let n = corners.len();
    let scale = corners
        .iter()
        .map(|c| (*c - corners[0]).length_squared())
        .fold(0.0, f64::max);
    let flat = |a: DVec3, b: DVec3, c: DVec3| (b - a).cross(c - a).length() <= COLLINEAR * scale;
    let double_area: f64 = (1..n - 1)
        .map(|k| {
            (corners[k] - corners[0])
                .cross(corners[k + 1] - corners[0])
                .length()
        })
        .sum();
    if double_area <= min_width * scale.sqrt() {
        return false;
    }
    for apex in 0..n {
        let at = |k: usize| corners[(apex + k) % n];
        if (1..n - 1).all(|k| !flat(at(0), at(k), at(k + 1))) {
            for k in 1..n - 1 {
                out.extend_from_slice(&[
                    first + apex as u32,
                    first + ((apex + k) % n) as u32,
                    first + ((apex + k + 1) % n) as u32,
                ]);
            }
            return false;
        }
    }
    for k in 0..n {
        out.extend_from_slice(&[centroid, first + k as u32, first + ((k + 1) % n) as u32]);
    }
    true
}

impl Transparency {
    /// Certifies the triangles (model space of the mesh) for every viewer at least
    /// `min_eye_distance` times the bounding sphere's radius from its centre, within
    /// `max_build_ms` milliseconds.
    pub fn new(
        triangles: &Triangles,
        min_eye_distance: f64,
        max_build_ms: f64,
    ) -> Result<Self, BindError> {
        if !(max_build_ms.is_finite() && max_build_ms > 0.0) {
            return Err(BindError::argument(
                "maxBuildMs",
                format!("must be a positive number of milliseconds, got {max_build_ms}"),
            ));
        }
        let geometry = Geometry::with_exact_corners(&triangles.polygon_mesh()?)?;
        let started = web_time::Instant::now();
        let budget = std::time::Duration::from_secs_f64(max_build_ms / 1000.0);
        let options = PresortOptions {
            min_eye_distance,
            max_build_time: budget,
            ..PresortOptions::default()
        };
        let mut sorter = Presorted::try_new(&geometry, &options)?;
        if sorter.uncertified_regions() > 0 {
            // Cycles too large for the defaults (a soup of meshes passing through each
            // other): a GPU draws a per-frame order of a cycle as cheaply as a stored one,
            // so certify again with large cycles ordered per frame by their own BSP trees
            // rather than leave those regions to the fallback.
            let relaxed = PresortOptions {
                max_build_time: budget.saturating_sub(started.elapsed()),
                small_cycle_pieces: 512,
                soup_cuts_per_piece: f64::INFINITY,
                ..options
            };
            sorter = Presorted::try_new(&geometry, &relaxed)?;
        }
        Ok(Self::of(
            sorter,
            geometry.bounds().centre(),
            geometry.bounds().diagonal(),
        ))
    }

    /// A certificate that [`to_bytes`](Self::to_bytes) wrote for the same triangles (as a
    /// worker hands one to the page): validated, far quicker than certifying.
    pub fn from_bytes(triangles: &Triangles, bytes: &[u8]) -> Result<Self, BindError> {
        let geometry = Geometry::with_exact_corners(&triangles.polygon_mesh()?)?;
        let sorter = Presorted::from_bytes(bytes, &geometry)
            .map_err(|e| BindError::argument("bytes", e.to_string()))?;
        Ok(Self::of(
            sorter,
            geometry.bounds().centre(),
            geometry.bounds().diagonal(),
        ))
    }

    /// The certificate, versioned and compact ([`Presorted::to_bytes`]).
    pub fn to_bytes(&self) -> Vec<u8> {
        self.sorter.to_bytes()
    }

    fn of(sorter: Presorted, centre: DVec3, size: f64) -> Self {
        // Cuts divide faces: with their T-junctions closed the GPU covers each pixel of a
        // face once (no pinholes along a cut).
        let pieces = sorter.pieces().without_t_junctions(SEAM * size);
        let (mut piece_start, mut piece_triangles) = (vec![0u32], Vec::new());
        let (mut positions, mut vertex_triangles, mut centroids) =
            (Vec::new(), Vec::new(), Vec::new());
        let mut push_vertex = |at: DVec3, face: u32, positions: &mut Vec<f32>| {
            positions.extend_from_slice(&[at.x as f32, at.y as f32, at.z as f32]);
            vertex_triangles.push(face);
        };
        for p in 0..pieces.len() {
            let corners = pieces.corners(p);
            let first = (positions.len() / 3) as u32;
            for &c in corners {
                push_vertex(c + centre, pieces.face(p), &mut positions);
            }
            let centroid = corners.iter().copied().sum::<DVec3>() / corners.len().max(1) as f64;
            let centre_vertex = first + corners.len() as u32;
            if triangulate(
                corners,
                first,
                centre_vertex,
                SLIVER_WIDTH * size,
                &mut piece_triangles,
            ) {
                push_vertex(centroid + centre, pieces.face(p), &mut positions);
            }
            piece_start.push(piece_triangles.len() as u32);
            if p < sorter.cut_pieces() {
                centroids.push(centroid);
            }
        }
        let mut indices = Vec::new();
        let mut leaves = Vec::new();
        for order in sorter.leaf_orders() {
            let start = indices.len() as u32;
            let cycles = order.iter().any(|s| matches!(s, OrderStep::Core(_)));
            if !cycles {
                for step in order {
                    if let OrderStep::Piece(p) = step {
                        let p = p as usize;
                        indices.extend_from_slice(
                            &piece_triangles[piece_start[p] as usize..piece_start[p + 1] as usize],
                        );
                    }
                }
            }
            leaves.push(LeafRange {
                start,
                count: indices.len() as u32 - start,
                cycles,
            });
        }
        let scratch_start = indices.len() as u32;
        // The scratch tail: room for any list a frame composes (each piece at most once).
        let scratch = piece_triangles.len();
        indices.resize(indices.len() + scratch, 0);
        Transparency {
            sorter,
            centre,
            piece_start,
            piece_triangles,
            by_depth: Vec::with_capacity(centroids.len()),
            centroids,
            positions,
            vertex_triangles,
            indices,
            leaves,
            scratch_start,
            next: Vec::with_capacity(scratch),
            list: DrawList::new(),
            last_scratch: None,
            frames: 0,
            fallback_frames: 0,
        }
    }

    /// Vertex positions (x, y, z per vertex, model space): every piece's corners.
    pub fn positions(&self) -> &[f32] {
        &self.positions
    }

    /// Per vertex, the triangle (of the input) its piece comes from: for colours.
    pub fn vertex_triangles(&self) -> &[u32] {
        &self.vertex_triangles
    }

    /// The index buffer: every order without cycles, then the scratch tail.
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// Each certified order's range.
    pub fn leaves(&self) -> &[LeafRange] {
        &self.leaves
    }

    /// Where the scratch tail begins.
    pub fn scratch_start(&self) -> u32 {
        self.scratch_start
    }

    /// Frames so far, and those drawn by centroid outside the certificate.
    pub fn frames(&self) -> (u64, u64) {
        (self.frames, self.fallback_frames)
    }

    /// The range to draw for a viewer at the homogeneous point `(x, y, z, w)` of model
    /// space (an eye with `w = 1`, a direction toward the viewer with `w = 0`). Allocates
    /// nothing once the buffers have grown.
    pub fn frame(&mut self, viewer: [f64; 4]) -> Result<Frame, BindError> {
        let [x, y, z, w] = viewer;
        if !viewer.iter().all(|v| v.is_finite()) || (w == 0.0 && x == 0.0 && y == 0.0 && z == 0.0) {
            return Err(BindError::argument(
                "viewer",
                format!("{viewer:?} is not a point or direction"),
            ));
        }
        let viewer = if w == 0.0 {
            Viewer::Direction(DVec3::new(x, y, z).normalize())
        } else {
            Viewer::Eye(DVec3::new(x, y, z) / w - self.centre)
        };
        let cull = CullTest::back_faces_culled(viewer);
        self.frames += 1;
        let leaf = match self.sorter.leaf_for(&cull) {
            Ok(leaf) => leaf,
            Err(reason) => {
                self.fallback_frames += 1;
                self.by_centroid(viewer);
                return Ok(self.scratch(usize::MAX, Some(reason)));
            }
        };
        let range = self.leaves[leaf];
        if !range.cycles {
            return Ok(Frame {
                start: range.start,
                count: range.count,
                rewritten: false,
                fallback: None,
            });
        }
        self.sorter.sort_culled(&cull, &mut self.list);
        self.next.clear();
        for item in self.list.items() {
            let p = item.polygon as usize;
            let range = self.piece_start[p] as usize..self.piece_start[p + 1] as usize;
            self.next.extend_from_slice(&self.piece_triangles[range]);
        }
        Ok(self.scratch(leaf, None))
    }

    /// Every piece far to near by centroid, into `next`.
    fn by_centroid(&mut self, viewer: Viewer) {
        self.by_depth.clear();
        for (p, c) in self.centroids.iter().enumerate() {
            let nearness = match viewer {
                Viewer::Direction(d) => c.dot(d),
                Viewer::Eye(e) => -(e - *c).length(),
            };
            self.by_depth.push((nearness, p as u32));
        }
        self.by_depth.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        self.next.clear();
        for &(_, p) in &self.by_depth {
            let range =
                self.piece_start[p as usize] as usize..self.piece_start[p as usize + 1] as usize;
            self.next.extend_from_slice(&self.piece_triangles[range]);
        }
    }

    /// `next` into the scratch tail, rewritten only where it changed.
    fn scratch(&mut self, key: usize, fallback: Option<FallbackReason>) -> Frame {
        let start = self.scratch_start as usize;
        let tail = &mut self.indices[start..start + self.next.len()];
        let rewritten = self.last_scratch != Some(key) || tail != self.next.as_slice();
        if rewritten {
            tail.copy_from_slice(&self.next);
        }
        self.last_scratch = fallback.is_none().then_some(key);
        Frame {
            start: self.scratch_start,
            count: self.next.len() as u32,
            rewritten,
            fallback,
        }
    }
}
