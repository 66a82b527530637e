//! [`Presorted`]: orders certified over regions of views, looked up per frame.
//!
//! # What is certified
//! The sphere of directions toward the viewer is cut into spherical triangles (the eight
//! octants, each split into four by its edge midpoints as often as needed), and the eye
//! distances from the geometry's centre into ranges from
//! [`PresortOptions::min_eye_distance`] outward (the farthest range reaching ∞ also holds
//! the orthographic views of its directions). For each region, a pair of pieces
//! "`A` before `B`" is kept when `B` may hide part of `A` from some viewer of the region
//! while both face that viewer (the test and its proof are in `occlusion.rs`: three convex
//! cones of directions with a common interior point). When the kept pairs have no cycle, any
//! topological order of the pieces that may face the region's viewers is exact for every
//! viewer in it, once back faces are culled: two drawn pieces that overlap on screen with
//! positive area are a kept pair, so the one behind comes first. Otherwise the region is
//! split, and at the deepest split each cycle (a strongly connected set of kept pairs) is
//! drawn in its slot by a BSP tree of its own pieces, which orders any view exactly: the
//! condensation of the kept pairs is a DAG, and nothing outside a set can need to go between
//! two of its pieces (it would belong to the set).
//!
//! When the pairs that may ever need an order have no cycle at all, one order serves every
//! view, orthographic or perspective, wherever the eye
//! ([`Presorted::one_order_for_every_view`]).
//!
//! No view is sampled: a region's certificate holds at every viewer in it. Regions are grown
//! by [`PRESORT_GROWTH`](crate::tolerance::PRESORT_GROWTH) before they are certified, so that
//! a viewer rounding places on the wrong side of a boundary is still covered.
//!
//! # Per frame
//! Find the region of the viewer (the last frame's first), then one pass over its order,
//! keeping the pieces that face the viewer. Views the certificate does not cover are ordered by
//! a BSP tree of the whole geometry (built once), and [`Presorted::fallback_frames`] counts them:
//! - an eye nearer the centre than [`PresortOptions::min_eye_distance`];
//! - a cull mode other than back faces with no margin (the certificate assumes exactly the
//!   pieces facing the viewer are drawn);
//! - a region whose cycles still hold more than a quarter of its pieces two splits below its
//!   octant: per-frame BSP trees of such cycles would cost as much as the whole one;
//! - every view of a soup of crossing polygons ([`PresortOptions::soup_cuts_per_piece`]).
//!
//! [`Presorted::last_fallback`] says why the last frame fell back ([`FallbackReason`]), and
//! [`Presorted::refusal`] why a build of [`Presorted::new`] stopped.
//!
//! # Cost
//! Each region is ordered from a far-to-near rank of its pieces, testing only the pairs that
//! may be kept against that rank (spatial neighbours in a thin slab of depth, found by a grid)
//! and then the pairs that ranks repairing it turn (`region_order.rs`, with the proof):
//! near `n log n` a region, for regions whose viewers see the geometry from one side (the
//! octants are quartered first when their eyes come near). A sub-region tests only the pairs
//! inside its parent's cycles. Models of at most 8,192 pieces are first scanned for one order
//! that serves every view (every pair, quadratic). [`PresortOptions::max_pairs`] bounds the
//! pairs a region looks at, [`PresortOptions::max_build_time`] the whole.

//! # Kept on disk
//! [`Presorted::to_bytes`] writes the region tree, the orders and the cores' piece sets,
//! nothing the geometry gives; [`Presorted::from_bytes`] checks them against the geometry
//! and builds the cores' trees again (the format and its checks are in `bytes.rs`).

mod build;
mod bytes;
mod certified;
mod cones;
mod occlusion;
mod partial;
mod region;
mod region_order;

use std::sync::Arc;
use std::time::Duration;
use web_time::Instant;

use glam::DVec3;

use crate::{
    Bsp, BspError, CullTest, DrawList, FaceSorter, Geometry, PolygonSet, SorterStats, View, Viewer,
};
pub use bytes::{FORMAT_VERSION as PRESORT_FORMAT_VERSION, PresortLoadError};
pub use certified::{
    CertifiedOrders, CertifiedOrdersError, CertifiedRegion, CoreOrders, MAX_CORE_PLANES, OrderStep,
};
use region::Region;

/// Tag of a leaf step that draws a core (a cycle ordered per frame) instead of a piece.
const CORE: u32 = 1 << 31;

/// Limits and choices of a [`Presorted`] build.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PresortOptions {
    /// Perspective eyes at least this far from the geometry's centre, in bounding-sphere
    /// radii (half the bounding-box diagonal), are certified; nearer ones fall back to the
    /// BSP. Must be above 1. Orthographic views are always certified.
    pub min_eye_distance: f64,
    /// Splits of a region below its octant before its cycles are left to per-frame BSP trees.
    pub max_depth: usize,
    /// Most regions in the tree.
    pub max_nodes: usize,
    /// A region whose open cycles all have at most this many pieces is not split further:
    /// the cycles are ordered per frame by BSP trees of their own.
    pub small_cycle_pieces: usize,
    /// Most pairs of pieces one region may look at (those its grid puts forward, those a
    /// new rank turns, and every pair inside its cycles); [`PresortError::PairBudget`]
    /// beyond. The scan for one order that serves every view (models of at most 8,192
    /// pieces) stops at this many pairs too, and is then left out.
    pub max_pairs: usize,
    /// Longest build ([`PresortError::TimeBudget`] beyond).
    pub max_build_time: Duration,
    /// A geometry whose pieces cut each other more than this many times per piece (a soup of
    /// crossing polygons, not a surface) is left uncertified at once: its cycles would hold
    /// from every side.
    pub soup_cuts_per_piece: f64,
    /// Threads the build may use (octants are certified side by side); 0: one per core
    /// ([`std::thread::available_parallelism`]). The result is the same on any number.
    pub threads: usize,
    /// Most pieces after cutting those that pass through each other (at least the
    /// geometry's pieces; [`PresortError::Pieces`] beyond).
    pub max_pieces: usize,
}

impl Default for PresortOptions {
    fn default() -> Self {
        PresortOptions {
            min_eye_distance: 1.5,
            max_depth: 6,
            max_nodes: 20_000,
            small_cycle_pieces: 8,
            max_pairs: 50_000_000,
            max_build_time: Duration::from_secs(120),
            max_pieces: 1 << 22,
            soup_cuts_per_piece: 0.5,
            threads: 0,
        }
    }
}

/// How far a [`Presorted`] build has come: of the regions it orders from all their pieces
/// (quarters of octants, or whole octants; most of the work), how many are done.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PresortProgress {
    /// Regions ordered so far.
    pub done: usize,
    /// Regions to order in all.
    pub total: usize,
}

/// Why a [`Presorted`] build stopped.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PresortError {
    /// A region would look at more pairs than the budget allows.
    #[error(
        "more than {limit} pairs of pieces to look at in one region (PresortOptions::max_pairs)"
    )]
    PairBudget {
        /// The budget.
        limit: usize,
    },
    /// The build ran longer than its budget.
    #[error("the presort build ran longer than {limit:?} (PresortOptions::max_build_time)")]
    TimeBudget {
        /// The budget.
        limit: Duration,
    },
    /// Cutting pieces that pass through each other made too many.
    #[error(transparent)]
    Pieces(crate::TooManyPieces),
    /// A cycle's BSP tree could not be built.
    #[error("the BSP tree of a cycle: {0}")]
    Core(BspError),
    /// `min_eye_distance` is not above 1.
    #[error("min_eye_distance must be a number above 1, not {0}")]
    EyeDistance(f64),
}

/// Why a [`Presorted`] frame was ordered by the whole BSP instead of a certified order
/// (exactness is kept either way; only the per-frame cost differs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum FallbackReason {
    /// The build stopped on a budget or a cycle's tree ([`Presorted::refusal`] says which):
    /// no view is certified.
    Refused,
    /// A perspective eye nearer the centre than [`PresortOptions::min_eye_distance`] (or a
    /// viewer that is not a finite eye or direction).
    EyeTooNear,
    /// A cull mode other than back faces with no margin.
    CullMode,
    /// The viewer's region was left uncertified: its cycles hold too many of its pieces, or
    /// the geometry is a soup of crossing polygons.
    UncertifiedRegion,
}

impl std::fmt::Display for FallbackReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            FallbackReason::Refused => "the build was refused",
            FallbackReason::EyeTooNear => "the eye is nearer than min_eye_distance",
            FallbackReason::CullMode => "the cull mode is not back faces without a margin",
            FallbackReason::UncertifiedRegion => "the view's region is uncertified",
        })
    }
}

/// A node of the region tree.
#[derive(Clone, Copy, Debug)]
struct Node {
    region: Region,
    kind: NodeKind,
}

#[derive(Clone, Copy, Debug)]
enum NodeKind {
    /// Index into the leaves.
    Leaf(u32),
    /// Four children from `first`, as [`Region::split_directions`] orders them.
    Directions { first: u32 },
    /// Two children from `first`: eyes nearer than `mid`, then the rest.
    Distance { mid: f64, first: u32 },
    /// A region whose cycles hold too many of its pieces: ordered by the whole BSP.
    Uncertified,
}

/// One certified order: piece indices (or `CORE | k`); the per-frame pass reads each piece's
/// face and plane from the shared set.
#[derive(Clone, Debug)]
struct Leaf {
    region: Region,
    /// `region.edge_normals()`, for the per-frame test whether the viewer is still inside.
    edges: [DVec3; 3],
    pieces: Vec<u32>,
}

/// Exact per frame by looking up an order certified for a region of views (module docs).
///
/// Build it from [`Geometry::with_exact_corners`] where planar faces have corners off their
/// plane: pieces that share corners bit for bit meet without slivers of overlap, which would
/// otherwise form cycles that only per-frame BSP trees can order.
pub struct Presorted {
    shared: Arc<PolygonSet>,
    nodes: Vec<Node>,
    leaves: Vec<Leaf>,
    cores: Vec<build::Core>,
    core_sorters: Vec<Bsp>,
    core_list: DrawList,
    near: f64,
    fallback: Bsp,
    last_leaf: Option<u32>,
    last_fallback: Option<FallbackReason>,
    fallback_frames: usize,
    refusal: Option<PresortError>,
    threads: usize,
    build_ms: f64,
    pair_tests: usize,
    candidate_pairs: usize,
    cuts: usize,
    /// The geometry's fingerprint and piece count (a saved certificate names them).
    fingerprint: u64,
    geometry_pieces: usize,
    /// Pieces after cutting those that pass through each other (the shared set's first).
    pieces: usize,
}

impl std::fmt::Debug for Presorted {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Presorted")
            .field("regions", &self.nodes.len())
            .field("orders", &self.leaves.len())
            .field("cores", &self.cores.len())
            .finish_non_exhaustive()
    }
}

impl Presorted {
    /// Builds with [`PresortOptions::default`]; on a budget error, every view falls back to
    /// the BSP, and says so: [`refusal`](Self::refusal) holds the error,
    /// [`last_fallback`](Self::last_fallback) is [`FallbackReason::Refused`] after every frame
    /// and [`fallback_frames`](Self::fallback_frames) counts them. Use
    /// [`try_new`](Self::try_new) to handle the error instead.
    #[must_use]
    pub fn new(geometry: &Geometry) -> Self {
        Self::with_options(geometry, &PresortOptions::default())
    }

    /// [`new`](Self::new) with `options`: on an error, every view falls back to the BSP and
    /// says so ([`refusal`](Self::refusal), [`FallbackReason::Refused`]).
    #[must_use]
    pub fn with_options(geometry: &Geometry, options: &PresortOptions) -> Self {
        Self::try_new(geometry, options).unwrap_or_else(|error| {
            let mut sorter =
                Self::assemble(geometry, build::Built::uncovered(geometry), Instant::now());
            sorter.refusal = Some(error);
            sorter
        })
    }

    /// Builds the region tree and the orders.
    ///
    /// # Errors
    /// A budget of `options` exceeded, or a cycle's BSP tree failing to build.
    pub fn try_new(geometry: &Geometry, options: &PresortOptions) -> Result<Self, PresortError> {
        Self::try_new_with_progress(geometry, options, &|_| {})
    }

    /// [`try_new`](Self::try_new), telling `progress` (from the build's threads) each time a
    /// region has been ordered from all its pieces; the last call has `done == total`.
    ///
    /// # Errors
    /// As [`try_new`](Self::try_new).
    pub fn try_new_with_progress(
        geometry: &Geometry,
        options: &PresortOptions,
        progress: &(dyn Fn(PresortProgress) + Sync),
    ) -> Result<Self, PresortError> {
        if !(options.min_eye_distance > 1.0 && options.min_eye_distance.is_finite()) {
            return Err(PresortError::EyeDistance(options.min_eye_distance));
        }
        let start = Instant::now();
        let built = build::build(geometry, options, progress)?;
        Ok(Self::assemble(geometry, built, start))
    }

    /// The sorter over what the build made (and the fallback BSP, built here), its build
    /// time counted from `start`.
    fn assemble(geometry: &Geometry, built: build::Built, start: Instant) -> Self {
        let fallback = Bsp::new(geometry);
        let pieces = built
            .cores
            .first()
            .map_or(built.shared.len(), |c| c.offset as usize);
        let core_sorters = built
            .cores
            .iter()
            .map(|c| Bsp::from_tree(Arc::clone(&c.tree)))
            .collect();
        Presorted {
            shared: built.shared,
            nodes: built.nodes,
            leaves: built.leaves,
            cores: built.cores,
            core_sorters,
            core_list: DrawList::new(),
            near: built.near,
            fallback,
            last_leaf: None,
            last_fallback: None,
            fallback_frames: 0,
            refusal: None,
            threads: built.threads,
            build_ms: start.elapsed().as_secs_f64() * 1e3,
            pair_tests: built.pair_tests,
            candidate_pairs: built.candidate_pairs,
            cuts: built.cuts,
            fingerprint: bytes::fingerprint(geometry.pieces()),
            geometry_pieces: geometry.pieces().len(),
            pieces,
        }
    }

    /// Regions in the tree (inner ones included).
    #[must_use]
    pub fn regions(&self) -> usize {
        self.nodes.len()
    }

    /// Certified orders (leaf regions).
    #[must_use]
    pub fn orders(&self) -> usize {
        self.leaves.len()
    }

    /// Whether one order serves every view covered by back-face culling, orthographic or
    /// perspective, wherever the eye: the pairs that may ever need an order (the plane-side
    /// test, necessary for every viewer) have no cycle. Then there is no region to look up.
    #[must_use]
    pub fn one_order_for_every_view(&self) -> bool {
        self.leaves.len() == 1 && self.near == 0.0
    }

    /// Regions left uncertified (their cycles hold too many pieces): views in them are
    /// ordered by the whole BSP.
    #[must_use]
    pub fn uncertified_regions(&self) -> usize {
        self.nodes
            .iter()
            .filter(|n| matches!(n.kind, NodeKind::Uncertified))
            .count()
    }

    /// Cycles left to per-frame BSP trees, and the pieces in them (over all orders).
    #[must_use]
    pub fn cores(&self) -> (usize, usize) {
        (self.cores.len(), self.cores.iter().map(|c| c.pieces).sum())
    }

    /// Pairs of pieces the build looked at (those its regions' grids put forward, those
    /// repaired ranks turned that may need a test, and those inside cycles; for one order
    /// that serves every view, the pairs that can ever need an order), and the pair-region
    /// tests it made.
    #[must_use]
    pub fn pairs(&self) -> (usize, usize) {
        (self.candidate_pairs, self.pair_tests)
    }

    /// Cuts made once, before certifying, in pieces that pass through each other.
    #[must_use]
    pub fn cuts(&self) -> usize {
        self.cuts
    }

    /// Frames so far that the certificate did not cover (ordered by the whole BSP).
    #[must_use]
    pub fn fallback_frames(&self) -> usize {
        self.fallback_frames
    }

    /// Whether the last frame fell back to the whole BSP.
    #[must_use]
    pub fn last_frame_fell_back(&self) -> bool {
        self.last_fallback.is_some()
    }

    /// Why the last frame fell back to the whole BSP (`None`: it was certified).
    #[must_use]
    pub fn last_fallback(&self) -> Option<FallbackReason> {
        self.last_fallback
    }

    /// The error that stopped the build of [`new`](Self::new) (`None` when it finished).
    #[must_use]
    pub fn refusal(&self) -> Option<&PresortError> {
        self.refusal.as_ref()
    }

    /// Threads the build used (1 when it certified nothing or one order serves every view).
    #[must_use]
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// The leaf whose region holds the viewer, or why the certificate does not cover it.
    fn locate(&mut self, cull: &CullTest) -> Result<u32, FallbackReason> {
        if self.refusal.is_some() || self.nodes.is_empty() {
            return Err(FallbackReason::Refused);
        }
        if cull.facing_rule() != Some((true, false)) {
            return Err(FallbackReason::CullMode);
        }
        let (u, t) = match cull.viewer {
            Viewer::Direction(d) => (d, f64::INFINITY),
            Viewer::Eye(e) => {
                let t = e.length();
                (e / t, t)
            }
        };
        if t.is_nan() || t < self.near || !u.is_finite() {
            return Err(FallbackReason::EyeTooNear);
        }
        if let Some(leaf) = self.last_leaf
            && self.leaf_holds(leaf, u, t)
        {
            return Ok(leaf);
        }
        let mut node = Region::octant_of(u);
        loop {
            match self.nodes[node].kind {
                NodeKind::Leaf(leaf) => {
                    self.last_leaf = Some(leaf);
                    return Ok(leaf);
                }
                NodeKind::Directions { first } => {
                    node = first as usize + self.nodes[node].region.child_holding(u);
                }
                NodeKind::Distance { mid, first } => {
                    node = first as usize + usize::from(t >= mid);
                }
                NodeKind::Uncertified => {
                    self.last_leaf = None;
                    return Err(FallbackReason::UncertifiedRegion);
                }
            }
        }
    }

    /// Whether the last leaf's region holds the viewer (a quick test before the descent).
    fn leaf_holds(&self, leaf: u32, u: DVec3, t: f64) -> bool {
        let leaf = &self.leaves[leaf as usize];
        leaf.region.holds_distance(t) && leaf.edges.iter().all(|e| e.dot(u) >= 0.0)
    }
}

impl Presorted {
    /// The order for a viewer given by its cull test alone (no projection is needed): with
    /// [`CullTest::transformed`] one sorter serves every placement of its geometry, as a
    /// scene's instances do. Views the certificate does not cover fall back to the BSP.
    pub fn sort_culled(&mut self, cull: &CullTest, out: &mut DrawList) {
        self.sort_in(cull, None, out);
    }

    fn sort_in(&mut self, cull: &CullTest, view: Option<&View>, out: &mut DrawList) {
        let leaf = match self.locate(cull) {
            Ok(leaf) => leaf,
            Err(reason) => {
                self.fallback_frames += 1;
                self.last_fallback = Some(reason);
                match view {
                    Some(view) => self.fallback.sort(view, out),
                    None => self.fallback.sort_culled(cull, out),
                }
                return;
            }
        };
        self.last_fallback = None;
        let cull = *cull;
        let (point, w) = cull.viewer_point();
        out.begin(&self.shared);
        let leaf = &self.leaves[leaf as usize];
        let planes = self.shared.planes();
        for &piece in &leaf.pieces {
            if piece & CORE != 0 {
                let k = (piece & !CORE) as usize;
                self.core_sorters[k].sort_culled(&cull, &mut self.core_list);
                let core = &self.cores[k];
                for item in self.core_list.items() {
                    out.push(core.offset + item.polygon, core.faces[item.face as usize]);
                }
            } else {
                let plane = &planes[piece as usize];
                if plane.normal().dot(point) - w * plane.offset() > 0.0 {
                    out.push(piece, self.shared.face(piece as usize));
                }
            }
        }
    }
}

impl FaceSorter for Presorted {
    fn name(&self) -> &'static str {
        "presorted"
    }

    fn sort(&mut self, view: &View, out: &mut DrawList) {
        self.sort_in(&view.cull_test(), Some(view), out);
    }

    fn stats(&self) -> SorterStats {
        let leaf_bytes: usize = self.leaves.iter().map(|l| l.pieces.capacity() * 4).sum();
        SorterStats {
            build_ms: self.build_ms,
            polygons: self.shared.len(),
            cached_bytes: leaf_bytes
                + self.nodes.capacity() * std::mem::size_of::<Node>()
                + self.shared.heap_bytes()
                + self.fallback.stats().cached_bytes,
            cycles: self.cores.len(),
            orders: self.leaves.len(),
            fallback_frames: self.fallback_frames,
            fallback: self.last_fallback,
            ..SorterStats::default()
        }
    }
}
