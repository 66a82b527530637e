//! A BSP tree built once per geometry and traversed per view: exact for any rigid mesh.

use std::sync::Arc;
use web_time::Instant;

use glam::DVec3;

use crate::bsp_builder::{self, Node};
use crate::fragment_merge::{FragmentMerge, MergeInput};
use crate::ids::NodeId;
use crate::plane::Plane;
use crate::t_junctions;
use crate::tolerance::PLANE_SIDE;
use crate::{BspError, DrawList, FaceSorter, Geometry, Newell, PolygonSet, SorterStats, View};

/// How the splitter of each node is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct BspOptions {
    /// Weight of one split against one unit of imbalance `|front − back|`. Default: 8.
    pub split_weight: f64,
    /// Candidate splitters scored per node among its polygons: the best of four times as many
    /// evenly spread ones, ranked on 16 of the node's polygons; every polygon of a node of at
    /// most 32. Nodes of 256 polygons or more also score one plane across their widest axis.
    /// Default: 12.
    pub candidates: usize,
    /// Polygons classified per candidate when scoring it (a deterministic sample on large
    /// nodes). Default: 1024.
    pub score_sample: usize,
    /// Fragment budget of the fallible builds ([`BspTree::try_build`], [`Bsp::try_new`],
    /// [`Bsp::new_or_fallback`]): a build that would hold more than
    /// `max(max_fragments_per_piece · pieces, min_fragment_budget)` fragments stops with
    /// [`BspError::FragmentBudget`]. Default: 16 (real models need about 2: spot 1.75,
    /// blub 1.80). The infallible [`BspTree::build`] and [`Bsp::new`] ignore it.
    pub max_fragments_per_piece: f64,
    /// Floor of the fragment budget, so that small scenes, whose worst case is quadratic
    /// (`n` crossing polygons can need about `n²/2` fragments), are not refused. Default: 4096.
    pub min_fragment_budget: usize,
    /// Threads a build of 4,096 pieces or more may use, the calling one included; 0: one per
    /// core ([`std::thread::available_parallelism`]). The tree is the same, bit for bit, on
    /// any number. Default: 0.
    pub threads: usize,
}

impl BspOptions {
    /// The defaults.
    pub const DEFAULT: BspOptions = BspOptions {
        split_weight: 8.0,
        candidates: 12,
        score_sample: 1024,
        max_fragments_per_piece: 16.0,
        min_fragment_budget: 4096,
        threads: 0,
    };

    /// The fragment budget for `pieces` pieces: `max(max_fragments_per_piece · pieces,
    /// min_fragment_budget)`, and never fewer than `pieces` (an unsplit tree always fits).
    #[must_use]
    pub fn fragment_budget(&self, pieces: usize) -> usize {
        let scaled = self.max_fragments_per_piece * pieces as f64;
        // `as` saturates: NaN gives 0, +inf gives usize::MAX.
        (scaled.ceil() as usize)
            .max(self.min_fragment_budget)
            .max(pieces)
    }
}

/// What [`Bsp::new_or_fallback`] builds when the BSP tree exceeds its fragment budget.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum BspFallback {
    /// Return the [`BspError`]: the caller decides.
    #[default]
    Error,
    /// Use [`Newell`] instead: exact as well, no tree, per-frame splits only where the view
    /// needs them (each frame's work is bounded by its own step budget).
    Newell,
}

impl Default for BspOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// An inner node as the per-view pass reads it: its plane row and its layout, 64 bytes.
#[derive(Clone, Copy, Debug)]
struct Inner {
    row: [f64; 4],
    /// Its index in `nodes` (and `base`).
    node: u32,
    first: u32,
    same: u32,
    opposite: u32,
    front_size: u32,
    back_size: u32,
    /// Child indices; `nodes.len()` (a spare `base` slot) when absent.
    front_child: u32,
    back_child: u32,
}

/// A convex leaf's fragments `first..first + count`, placed from its node's base.
#[derive(Clone, Copy, Debug)]
struct LeafRun {
    node: u32,
    first: u32,
    count: u32,
}

/// The immutable tree, shareable between views and threads (`Arc`).
#[derive(Debug)]
pub struct BspTree {
    /// The node planes (a leaf's is its first fragment's, unused).
    node_planes: Vec<Plane>,
    /// The pieces' planes, likewise, for the per-view cull pass.
    piece_rows: Vec<[f64; 4]>,
    /// Source face and piece of each fragment.
    fragment_face: Vec<[u32; 2]>,
    nodes: Vec<Node>,
    /// Fragments in pre-order: node by node, each node's own fragments contiguous.
    fragments: Arc<PolygonSet>,
    pieces: Arc<PolygonSet>,
    /// Per node, a sphere `[x, y, z, r]` (centred model space) around every fragment of its
    /// subtree, for skipping subtrees outside the image.
    spheres: Vec<[f64; 4]>,
    build_ms: f64,
    depth: usize,
    /// The inner nodes in pre-order and the leaves, for the per-view pass.
    inners: Vec<Inner>,
    leaf_runs: Vec<LeafRun>,
    /// Fragments proper: `fragments` holds them first, then a whole copy of every split
    /// piece, which [`FragmentMerge`] may draw instead of its fragments.
    fragment_count: usize,
    /// Per piece, the index of its whole copy in `fragments` (`None` when it is not split),
    /// and its number of fragments.
    whole: Vec<Option<u32>>,
    fragments_of: Vec<u32>,
    /// The model's diagonal `L`, for the merge's overlap tolerance.
    diagonal: f64,
}

/// Per node, a sphere around its subtree's fragments: the subtree's box, bottom up (children
/// follow their parents in `nodes`), then its centre and half diagonal.
fn subtree_spheres(nodes: &[Node], fragments: &PolygonSet) -> Vec<[f64; 4]> {
    let mut boxes = vec![(DVec3::INFINITY, DVec3::NEG_INFINITY); nodes.len()];
    for k in (0..nodes.len()).rev() {
        let node = &nodes[k];
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for f in node.first..node.first + node.same + node.opposite {
            for &c in fragments.corners(f as usize) {
                lo = lo.min(c);
                hi = hi.max(c);
            }
        }
        for child in [node.front_child, node.back_child]
            .into_iter()
            .filter_map(NodeId::get)
        {
            {
                let (clo, chi) = boxes[child as usize];
                lo = lo.min(clo);
                hi = hi.max(chi);
            }
        }
        boxes[k] = (lo, hi);
    }
    boxes
        .into_iter()
        .map(|(lo, hi)| {
            if lo.x > hi.x {
                return [0.0, 0.0, 0.0, -1.0]; // empty subtree
            }
            let c = (lo + hi) * 0.5;
            [c.x, c.y, c.z, (hi - lo).length() * 0.5]
        })
        .collect()
}

/// Where a sphere (centred model space, radius < 0 for an empty subtree) lies against the
/// image: `Some(false)` entirely outside it (with a margin of one pixel), `Some(true)`
/// entirely inside it, `None` across its border or reaching the near plane.
fn sphere_in_image(view: &View, sphere: &[f64; 4]) -> Option<bool> {
    if sphere[3] < 0.0 {
        return Some(false);
    }
    let (lo, hi) = view.project_sphere(DVec3::new(sphere[0], sphere[1], sphere[2]), sphere[3])?;
    let (w, h) = (f64::from(view.width()), f64::from(view.height()));
    if hi.x + 1.0 < 0.0 || hi.y + 1.0 < 0.0 || lo.x - 1.0 > w || lo.y - 1.0 > h {
        Some(false)
    } else if lo.x >= 0.0 && lo.y >= 0.0 && hi.x <= w && hi.y <= h {
        Some(true)
    } else {
        None
    }
}

/// Subtrees are culled only when the model's projected bound covers more than this many
/// times the image's area (a zoomed view), or reaches the near plane.
const ZOOMED_AREA: f64 = 2.0;

impl BspTree {
    /// Builds the tree over a geometry's pieces, in f64, with the plane tolerance
    /// [`PLANE_SIDE`]` · L`. Fragments are not bounded (the options' budget is ignored);
    /// [`BspTree::try_build`] bounds them.
    #[must_use]
    pub fn build(geometry: &Geometry, options: &BspOptions) -> Self {
        let tolerance = PLANE_SIDE * geometry.bounds().diagonal();
        match Self::build_bounded(
            Arc::clone(geometry.pieces()),
            tolerance,
            options,
            usize::MAX,
        ) {
            Ok(tree) => tree,
            // The fragment count cannot exceed usize::MAX: memory would run out first.
            Err(_) => unreachable!("an unbounded build has no budget to exceed"),
        }
    }

    /// Builds the tree like [`BspTree::build`], but stops with
    /// [`BspError::FragmentBudget`] as soon as it would hold more fragments than
    /// [`BspOptions::fragment_budget`] allows for the geometry's pieces. Memory and time
    /// stay proportional to the budget.
    ///
    /// # Errors
    /// [`BspError::FragmentBudget`] when the splits exceed the budget.
    pub fn try_build(geometry: &Geometry, options: &BspOptions) -> Result<Self, BspError> {
        let tolerance = PLANE_SIDE * geometry.bounds().diagonal();
        let pieces = Arc::clone(geometry.pieces());
        let budget = options.fragment_budget(pieces.len());
        Self::build_bounded(pieces, tolerance, options, budget)
    }

    /// Builds a tree holding at most `budget` fragments.
    fn build_bounded(
        pieces: Arc<PolygonSet>,
        tolerance: f64,
        options: &BspOptions,
        budget: usize,
    ) -> Result<Self, BspError> {
        let start = Instant::now();
        let mut builder =
            bsp_builder::build(&pieces, tolerance, options, budget).map_err(|()| {
                BspError::FragmentBudget {
                    pieces: pieces.len(),
                    budget,
                }
            })?;
        let depth = builder.depth;
        // Exporters hand fragments to other rasterisers: no T-junctions between siblings.
        builder.fragments =
            t_junctions::conform(&builder.fragments, &builder.fragment_piece, tolerance);
        let row = |p: &Plane| [p.normal().x, p.normal().y, p.normal().z, p.offset()];
        let piece_rows = pieces.planes().iter().map(row).collect();
        let fragment_face = (0..builder.fragments.len())
            .map(|i| [builder.fragments.face(i), builder.fragment_piece[i]])
            .collect();
        let spheres = subtree_spheres(&builder.nodes, &builder.fragments);
        let fragment_count = builder.fragments.len();
        let mut whole = vec![None; pieces.len()];
        let mut fragments_of = vec![0u32; pieces.len()];
        for &p in &builder.fragment_piece {
            fragments_of[p as usize] += 1;
        }
        for (p, &count) in fragments_of.iter().enumerate() {
            if count > 1 {
                whole[p] = Some(builder.fragments.push(
                    pieces.corners(p),
                    pieces.face(p),
                    *pieces.plane(p),
                ));
            }
        }
        let (inners, leaf_runs) = pass_layout(&builder.nodes, &builder.planes);
        let node_planes = builder.planes;
        Ok(BspTree {
            inners,
            leaf_runs,
            fragment_count,
            whole,
            fragments_of,
            // Every build's tolerance is `PLANE_SIDE · L`.
            diagonal: tolerance / PLANE_SIDE,
            piece_rows,
            node_planes,
            fragment_face,
            spheres,
            nodes: builder.nodes,
            fragments: Arc::new(builder.fragments),
            pieces,
            build_ms: start.elapsed().as_secs_f64() * 1e3,
            depth,
        })
    }

    /// The node planes, exactly those whose viewer side
    /// ([`Viewer::facing`](crate::Viewer::facing) of `[n, offset]`, `>= 0`) orders each
    /// node's children in [`Bsp`]'s sort (a leaf's plane orders nothing). For event
    /// computations along an animation (`aspect-bake`).
    #[must_use]
    pub fn node_planes(&self) -> &[Plane] {
        &self.node_planes
    }

    /// The pieces' planes, exactly those whose facing value decides culling and, within
    /// convex leaves, facing-away-first order in [`Bsp`]'s sort.
    #[must_use]
    pub fn piece_planes(&self) -> &[Plane] {
        self.pieces.planes()
    }

    /// Number of fragments (pieces, some cut in parts).
    #[must_use]
    pub fn fragment_count(&self) -> usize {
        self.fragment_count
    }

    /// Number of nodes.
    #[must_use]
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Longest root-to-leaf path, in nodes.
    #[must_use]
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// Build time in milliseconds.
    #[must_use]
    pub fn build_ms(&self) -> f64 {
        self.build_ms
    }

    /// The fragments (centred model space), in the tree's storage order, followed by a whole
    /// copy of every split piece (what `bsp-merged` draws instead of its fragments): its
    /// first [`fragment_count`](Self::fragment_count) polygons are the fragments.
    #[must_use]
    pub fn fragments(&self) -> &Arc<PolygonSet> {
        &self.fragments
    }

    /// Heap bytes of the tree.
    #[must_use]
    pub fn heap_bytes(&self) -> usize {
        self.node_planes.capacity() * size_of::<Plane>()
            + self.piece_rows.capacity() * size_of::<[f64; 4]>()
            + self.fragment_face.capacity() * 8
            + self.nodes.capacity() * size_of::<Node>()
            + self.fragments.heap_bytes()
            + self.whole.capacity() * 8
            + self.fragments_of.capacity() * 4
            + self.inners.capacity() * size_of::<Inner>()
            + self.leaf_runs.capacity() * size_of::<LeafRun>()
            + self.spheres.capacity() * size_of::<[f64; 4]>()
    }

    /// The inner nodes' plane rows `[nx, ny, nz, offset]`, in the numbering that
    /// [`order_for_sides`](Self::order_for_sides) reads (convex leaves need no side).
    pub(crate) fn inner_planes(&self) -> Vec<Plane> {
        (self.inners.iter())
            .map(|inner| self.node_planes[inner.node as usize])
            .collect()
    }

    /// Every fragment (indices into [`fragments`](Self::fragments)), back faces included, in
    /// the order [`Bsp`] gives a viewer on the front side of inner node `k`'s plane exactly
    /// when `in_front(k)`: a painter's order for every such viewer once back faces are culled
    /// (a convex leaf's front faces never overlap, so its fragments keep their stored order).
    pub(crate) fn order_for_sides(&self, in_front: &dyn Fn(usize) -> bool, out: &mut Vec<u32>) {
        out.clear();
        if self.nodes.is_empty() {
            return;
        }
        let mut inner_of = vec![0u32; self.nodes.len()];
        for (k, inner) in self.inners.iter().enumerate() {
            inner_of[inner.node as usize] = k as u32;
        }
        // Depth-first: a node to expand, or a run of fragments to emit.
        enum Task {
            Node(u32),
            Run(u32, u32),
        }
        let mut stack = vec![Task::Node(0)];
        while let Some(task) = stack.pop() {
            match task {
                Task::Run(first, count) => out.extend(first..first + count),
                Task::Node(k) => {
                    let node = &self.nodes[k as usize];
                    if node.leaf {
                        out.extend(node.first..node.first + node.same);
                        continue;
                    }
                    let front = in_front(inner_of[k as usize] as usize);
                    let own = Task::Run(node.first, node.same + node.opposite);
                    let (first, second) = if front {
                        (node.back_child, node.front_child)
                    } else {
                        (node.front_child, node.back_child)
                    };
                    // Pushed in reverse: `first` subtree, own fragments, `second` subtree.
                    if let Some(second) = second.get() {
                        stack.push(Task::Node(second));
                    }
                    stack.push(own);
                    if let Some(first) = first.get() {
                        stack.push(Task::Node(first));
                    }
                }
            }
        }
    }
}

/// The per-view pass's view of the nodes: inner nodes in pre-order with their planes, and the
/// leaves.
fn pass_layout(nodes: &[Node], planes: &[Plane]) -> (Vec<Inner>, Vec<LeafRun>) {
    let absent = nodes.len() as u32;
    let child = |c: NodeId| c.get().unwrap_or(absent);
    let (mut inners, mut leaves) = (Vec::new(), Vec::new());
    for (k, (node, plane)) in nodes.iter().zip(planes).enumerate() {
        if node.leaf {
            leaves.push(LeafRun {
                node: k as u32,
                first: node.first,
                count: node.same,
            });
        } else {
            let n = plane.normal();
            inners.push(Inner {
                row: [n.x, n.y, n.z, plane.offset()],
                node: k as u32,
                first: node.first,
                same: node.same,
                opposite: node.opposite,
                front_size: node.front_size,
                back_size: node.back_size,
                front_child: child(node.front_child),
                back_child: child(node.back_child),
            });
        }
    }
    (inners, leaves)
}

/// Exact back-to-front order from a BSP tree built once per geometry.
///
/// The tree ([`BspTree`]) is immutable and shared through an `Arc`, so any number of views or
/// threads can use one build. Per view, one linear pass over the inner nodes in pre-order and
/// one over the leaves place every fragment in its paint-order slot (no stack, no recursion,
/// no branch on the viewer's side: each node's subtree sizes are known at build time), each
/// slot marked drawn or culled by its piece's plane; a branch-free compaction keeps the drawn.
#[derive(Debug)]
pub struct Bsp {
    tree: Arc<BspTree>,
    base: Vec<u32>,
    /// Per slot of `scratch`, whether its fragment is drawn this frame.
    keep: Vec<u8>,
    piece_drawn: Vec<bool>,
    piece_facing: Vec<bool>,
    /// Per node, for the current frame: its subtree lies outside the image.
    node_culled: Vec<bool>,
    /// Per node, for the current frame: its subtree lies inside the image (no test below).
    node_inside: Vec<bool>,
    /// Every fragment's item in paint order, drawn or not (one slot per fragment, kept between
    /// frames); compacted in place to the drawn ones, which are copied out.
    scratch: Vec<crate::DrawItem>,
    /// The merge of split pieces drawn whole (`None`: fragments as the tree cut them).
    merge: Option<Box<FragmentMerge>>,
}

impl Bsp {
    /// Builds a tree with the default options.
    #[must_use]
    pub fn new(geometry: &Geometry) -> Self {
        Self::from_tree(Arc::new(BspTree::build(geometry, &BspOptions::DEFAULT)))
    }

    /// Builds a tree with `options`, its fragments bounded by the options' budget
    /// ([`BspTree::try_build`]).
    ///
    /// # Errors
    /// [`BspError::FragmentBudget`] when the splits exceed the budget.
    pub fn try_new(geometry: &Geometry, options: &BspOptions) -> Result<Self, BspError> {
        Ok(Self::from_tree(Arc::new(BspTree::try_build(
            geometry, options,
        )?)))
    }

    /// [`Bsp::try_new`], and when the tree exceeds its fragment budget, what `fallback`
    /// says: the error, or an exact [`Newell`] sorter (whose `name()` says `"newell"`, so
    /// callers can tell which one they got).
    ///
    /// # Errors
    /// [`BspError::FragmentBudget`] when the budget is exceeded and `fallback` is
    /// [`BspFallback::Error`].
    pub fn new_or_fallback(
        geometry: &Geometry,
        options: &BspOptions,
        fallback: BspFallback,
    ) -> Result<Box<dyn FaceSorter>, BspError> {
        match (Self::try_new(geometry, options), fallback) {
            (Ok(bsp), _) => Ok(Box::new(bsp)),
            (Err(_), BspFallback::Newell) => Ok(Box::new(Newell::new(geometry))),
            (Err(error), BspFallback::Error) => Err(error),
        }
    }

    /// A sorter over an existing (possibly shared) tree.
    #[must_use]
    pub fn from_tree(tree: Arc<BspTree>) -> Self {
        Bsp {
            base: vec![0; tree.nodes.len() + 1],
            keep: vec![0; tree.fragment_count],
            merge: None,
            piece_drawn: vec![false; tree.pieces.len()],
            piece_facing: vec![false; tree.pieces.len()],
            node_culled: vec![false; tree.nodes.len()],
            node_inside: vec![false; tree.nodes.len()],
            scratch: vec![
                crate::DrawItem {
                    polygon: 0,
                    face: 0,
                };
                tree.fragment_count
            ],
            tree,
        }
    }

    /// The tree.
    #[must_use]
    pub fn tree(&self) -> &Arc<BspTree> {
        &self.tree
    }

    /// This sorter drawing each split piece whole, per view, where nothing drawn between its
    /// fragments overlaps it on screen (`merge` true), or as the tree cut it (false, the
    /// default). Exact either way. Merged lists hold about as many items as the centroid
    /// sort's, for a per-view cost of many BSP traversals (figures in docs/bench.md):
    /// every sink pays per item, so exporters (SVG, PDF, HTML, plotters) gain; an animation
    /// whose sink is cheap per item may not. Only [`FaceSorter::sort`] merges (it needs the
    /// projection), not [`Bsp::sort_culled`]. The name becomes `"bsp-merged"`.
    #[must_use]
    pub fn with_fragment_merge(mut self, merge: bool) -> Self {
        self.merge = merge.then(|| Box::new(FragmentMerge::new(&self.tree.pieces)));
        self
    }
}

impl FaceSorter for Bsp {
    fn name(&self) -> &'static str {
        if self.merge.is_some() {
            "bsp-merged"
        } else {
            "bsp"
        }
    }

    fn sort(&mut self, view: &View, out: &mut DrawList) {
        self.sort_in_view(&view.cull_test(), Some(view), out);
    }

    fn stats(&self) -> SorterStats {
        SorterStats {
            build_ms: self.tree.build_ms,
            polygons: self.tree.fragment_count,
            cached_bytes: self.tree.heap_bytes()
                + self.base.capacity() * 4
                + self.keep.capacity()
                + self.piece_drawn.capacity()
                + self.piece_facing.capacity()
                + self.merge.as_ref().map_or(0, |m| m.heap_bytes()),
            depth: self.tree.depth,
            ..SorterStats::default()
        }
    }
}

impl Bsp {
    /// The painter's order for a viewer given by its cull test alone: the BSP needs no
    /// projection, only which side of each plane the viewer is on. With
    /// [`CullTest::transformed`](crate::CullTest::transformed) one tree serves every placement
    /// of its geometry (a scene's instances) without a rebuild.
    pub fn sort_culled(&mut self, cull: &crate::CullTest, out: &mut DrawList) {
        self.sort_in_view(cull, None, out);
    }

    /// Places every fragment in paint order: one pass over the inner nodes in pre-order, each
    /// placing its children's subtrees and its own fragments (facing away from the viewer
    /// first) from its subtree's start without a branch on the viewer's side, then one over
    /// the leaves. Each slot gets the fragment's item and whether it is drawn (its piece is,
    /// and with `FRUSTUM` its node is not culled). Fragments are read in storage order.
    ///
    /// With `away_first` (back faces are drawn), each convex leaf's fragments facing away
    /// from the viewer fill its slots from the start and those facing it from the end: its
    /// front faces never overlap, nor do its back faces, so either part may go in any order.
    fn place<const FRUSTUM: bool>(&mut self, point: DVec3, w: f64, away_first: bool) {
        let tree = &*self.tree;
        let (base, slots, keep) = (
            &mut self.base[..],
            &mut self.scratch[..],
            &mut self.keep[..],
        );
        let (culled, piece_drawn) = (&self.node_culled[..], &self.piece_drawn[..]);
        let piece_facing = &self.piece_facing[..];
        let shown = |node: u32| !FRUSTUM || !culled[node as usize];
        let mut put = |slot: u32, f: u32, shown: bool| {
            let [face, piece] = tree.fragment_face[f as usize];
            slots[slot as usize] = crate::DrawItem { polygon: f, face };
            keep[slot as usize] = u8::from(piece_drawn[piece as usize] & shown);
        };
        base[0] = 0;
        for inner in &tree.inners {
            let b = base[inner.node as usize];
            let t = u32::from(facing(&inner.row, point, w) >= 0.0);
            let own = inner.same + inner.opposite;
            // In front: back subtree, own (opposite, then same), front subtree; behind: front
            // subtree, own (same, then opposite), back subtree.
            base[inner.front_child as usize] = b + t * (inner.back_size + own);
            base[inner.back_child as usize] = b + (1 - t) * (inner.front_size + own);
            let own_base = b + t * inner.back_size + (1 - t) * inner.front_size;
            let shown = shown(inner.node);
            let same_base = own_base + t * inner.opposite;
            for j in 0..inner.same {
                put(same_base + j, inner.first + j, shown);
            }
            let opposite_base = own_base + (1 - t) * inner.same;
            for j in 0..inner.opposite {
                put(opposite_base + j, inner.first + inner.same + j, shown);
            }
        }
        for run in &tree.leaf_runs {
            let b = base[run.node as usize];
            let shown = shown(run.node);
            let fragments = run.first..run.first + run.count;
            if away_first {
                let (mut away, mut toward) = (b, b + run.count);
                for f in fragments {
                    let [_, piece] = tree.fragment_face[f as usize];
                    let faces_viewer = u32::from(piece_facing[piece as usize]);
                    toward -= faces_viewer;
                    put(if faces_viewer == 1 { toward } else { away }, f, shown);
                    away += 1 - faces_viewer;
                }
            } else {
                for (slot, f) in (b..).zip(fragments) {
                    put(slot, f, shown);
                }
            }
        }
    }

    /// The order for `cull`'s viewer; with `frustum`, subtrees whose bounding sphere lies
    /// outside the view's image are skipped (only when the whole tree's does not lie inside
    /// it: a model entirely in view pays nothing for the test).
    fn sort_in_view(&mut self, cull: &crate::CullTest, frustum: Option<&View>, out: &mut DrawList) {
        // A handle of its own, so that the passes below can borrow `self` mutably.
        let tree = Arc::clone(&self.tree);
        let tree = &*tree;
        // The view as given: the merge projects with it whether or not subtrees are culled.
        let frustum_view = frustum;
        // Frustum culling of subtrees, when a good part of the model may lie outside the
        // image: the model's projected bound covers more than twice the image, or reaches the
        // near plane. (A fitted view, whose bound just overlaps the border, would pay a pass
        // over the nodes for next to nothing.)
        let frustum = frustum.filter(|view| {
            tree.spheres.first().is_some_and(|root| {
                let image = f64::from(view.width()) * f64::from(view.height());
                match view.project_sphere(DVec3::new(root[0], root[1], root[2]), root[3]) {
                    None => true,
                    Some((lo, hi)) => {
                        let bound = (hi - lo).max(glam::DVec2::ZERO);
                        bound.x * bound.y > ZOOMED_AREA * image
                    }
                }
            })
        });
        let (point, w) = cull.viewer_point();
        let facing = |row: &[f64; 4]| facing(row, point, w);
        // Cull per piece: fragments share their piece's plane, and each is culled by it.
        let only_toward = cull.facing_rule() == Some((true, false));
        match cull.facing_rule() {
            Some((keep_toward, keep_away)) => {
                for ((drawn, toward), row) in self
                    .piece_drawn
                    .iter_mut()
                    .zip(&mut self.piece_facing)
                    .zip(&tree.piece_rows)
                {
                    let f = facing(row);
                    *toward = f > 0.0;
                    *drawn = (keep_toward & (f > 0.0)) | (keep_away & (f < 0.0));
                }
            }
            None => {
                for (i, plane) in tree.pieces.planes().iter().enumerate() {
                    self.piece_drawn[i] = cull.is_drawn(plane, tree.pieces.corners(i)[0]);
                    self.piece_facing[i] = cull.viewer.facing(plane) > 0.0;
                }
            }
        }
        if let Some(view) = frustum {
            // Parents come before their children: a culled parent culls its subtree.
            // Only subtrees whose sphere straddles the image's border are tested: one inside
            // holds only subtrees inside, one outside only subtrees outside.
            if let (Some(culled), Some(inside)) =
                (self.node_culled.first_mut(), self.node_inside.first_mut())
            {
                (*culled, *inside) = (false, false);
            }
            for k in 0..tree.nodes.len() {
                let (mut culled, mut inside) = (self.node_culled[k], self.node_inside[k]);
                let node = &tree.nodes[k];
                if !culled && !inside {
                    let side = sphere_in_image(view, &tree.spheres[k]);
                    (culled, inside) = (side == Some(false), side == Some(true));
                }
                self.node_culled[k] = culled;
                for child in [node.front_child, node.back_child]
                    .into_iter()
                    .filter_map(NodeId::get)
                {
                    self.node_culled[child as usize] = culled;
                    self.node_inside[child as usize] = inside;
                }
            }
        }
        if frustum.is_some() {
            self.place::<true>(point, w, !only_toward);
        } else {
            self.place::<false>(point, w, !only_toward);
        }
        out.begin(&tree.fragments);
        // Branch-free compaction in place: write every slot, advance past the drawn ones only.
        let items = &mut self.scratch;
        let mut drawn = 0;
        for (k, &keep) in self.keep.iter().enumerate() {
            items[drawn] = items[k];
            drawn += usize::from(keep);
        }
        match (&mut self.merge, frustum_view) {
            (Some(merge), Some(view)) => {
                let input = MergeInput {
                    pieces: &tree.pieces,
                    whole: &tree.whole,
                    fragments_of: &tree.fragments_of,
                    fragment_face: &tree.fragment_face,
                    diagonal: tree.diagonal,
                };
                merge.merge(view, &input, &items[..drawn], out.items_mut());
            }
            _ => out.items_mut().extend_from_slice(&items[..drawn]),
        }
    }
}

/// The viewer's facing value for a plane row `[nx, ny, nz, offset]` (positive in front of it)
/// from its homogeneous point `(point, w)`.
#[inline]
fn facing(row: &[f64; 4], point: DVec3, w: f64) -> f64 {
    row[0] * point.x + row[1] * point.y + row[2] * point.z - w * row[3]
}
