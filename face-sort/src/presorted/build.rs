//! Building the region tree: certify a region's order, or split the region.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use web_time::Instant;

use super::occlusion::{OcclusionTest, PieceBounds, may_ever_hide, may_face};
use super::partial::{Graph, Partial};
use super::region::Region;
use super::region_order::{MIN_LEAN, RegionOrder, Setting, lean, region_order};
use super::{CORE, Leaf, Node, NodeKind, PresortError, PresortOptions, PresortProgress};
use crate::tolerance::PLANE_SIDE;
use crate::{BspOptions, BspTree, Geometry, PolygonSet};

/// What the build hands to the sorter.
pub(super) struct Built {
    pub nodes: Vec<Node>,
    pub leaves: Vec<Leaf>,
    /// The pieces, then every core's fragments.
    pub shared: Arc<PolygonSet>,
    pub cores: Vec<Core>,
    pub near: f64,
    pub pair_tests: usize,
    pub candidate_pairs: usize,
    /// Cuts made by [`crate::split_crossing`].
    pub cuts: usize,
    /// Threads the octants were certified on.
    pub threads: usize,
}

impl Built {
    /// No certificate at all: every view falls back (a build that stopped on a budget).
    pub fn uncovered(geometry: &Geometry) -> Built {
        Built {
            nodes: Vec::new(),
            leaves: Vec::new(),
            shared: Arc::clone(geometry.pieces()),
            cores: Vec::new(),
            near: f64::INFINITY,
            pair_tests: 0,
            candidate_pairs: 0,
            cuts: 0,
            threads: 1,
        }
    }
}

/// A set of pieces a leaf cannot order once for all its viewers (a cycle among them, left at
/// the deepest split): ordered per frame by a BSP tree of their own.
pub(super) struct Core {
    pub tree: Arc<BspTree>,
    /// Index in the shared set of the tree's first fragment.
    pub offset: u32,
    /// Face of each of the tree's pieces (the tree numbers them by position in the core).
    pub faces: Vec<u32>,
    pub pieces: usize,
    /// The core's pieces: ascending indices into the pieces (what a saved certificate keeps).
    pub set: Vec<u32>,
}

struct Builder<'a> {
    geometry: &'a Geometry,
    setting: &'a Setting<'a>,
    pieces: &'a PolygonSet,
    bounds: &'a [PieceBounds],
    options: &'a PresortOptions,
    tolerance: f64,
    /// Pairs the regions' orders looked at ([`RegionOrder::candidates`]).
    candidates: usize,
    /// Where ordered regions are counted and told.
    report: Option<&'a Report<'a>>,
    /// This builder's regions: its octant's root first.
    nodes: Vec<Node>,
    leaves: Vec<Leaf>,
    cores: Vec<Core>,
    core_sets: Vec<Vec<u32>>,
    pair_tests: usize,
    started: Instant,
}

/// Every pair that can ever need an order, as adjacency lists (`a` before `b`): the pieces
/// split into ranges scanned side by side on `threads` threads.
/// Adjacency lists: where each piece's targets start, and the targets.
type Adjacency = (Vec<u32>, Vec<u32>);

pub(super) fn pairs_ever(
    pieces: &PolygonSet,
    tolerance: f64,
    max_pairs: usize,
    threads: usize,
) -> Result<Adjacency, PresortError> {
    let n = pieces.len();
    let chunk = n.div_ceil(threads.max(1)).max(1);
    let parts: Vec<Result<Adjacency, PresortError>> =
        crate::workers::map(n.div_ceil(chunk), threads, |k| {
            let first = k * chunk;
            let mut counts = Vec::with_capacity(chunk);
            let mut targets = Vec::new();
            for a in first..(first + chunk).min(n) {
                let before = targets.len();
                for b in 0..n {
                    if a != b && may_ever_hide(pieces, a, b, tolerance) {
                        if targets.len() >= max_pairs {
                            return Err(PresortError::PairBudget { limit: max_pairs });
                        }
                        targets.push(b as u32);
                    }
                }
                counts.push((targets.len() - before) as u32);
            }
            Ok((counts, targets))
        });
    let mut start = Vec::with_capacity(n + 1);
    start.push(0u32);
    let mut all = Vec::new();
    for part in parts {
        let (counts, targets) = part?;
        if all.len() + targets.len() > max_pairs {
            return Err(PresortError::PairBudget { limit: max_pairs });
        }
        for c in counts {
            start.push(start.last().expect("starts at 0") + c);
        }
        all.extend(targets);
    }
    Ok((start, all))
}

pub(super) fn build(
    geometry: &Geometry,
    options: &PresortOptions,
    progress: &(dyn Fn(PresortProgress) + Sync),
) -> Result<Built, PresortError> {
    let radius = geometry.bounds().diagonal() * 0.5;
    let near = options.min_eye_distance * radius;
    let tolerance = PLANE_SIDE * geometry.bounds().diagonal();
    // Pieces that pass through each other hide each other from every side: cut them once.
    let (pieces, cuts) = crate::split_crossing(
        geometry.pieces(),
        tolerance,
        options.max_pieces.max(geometry.pieces().len()),
    )
    .map_err(PresortError::Pieces)?;
    let octants = Region::octants(near);
    if cuts as f64 > options.soup_cuts_per_piece * geometry.pieces().len() as f64 {
        // A soup of crossing polygons: its cycles hold from every side, so every region
        // would be left to the whole BSP after costing its tests. Leave them all at once.
        return Ok(Built {
            nodes: octants
                .map(|region| Node {
                    region,
                    kind: NodeKind::Uncertified,
                })
                .to_vec(),
            leaves: Vec::new(),
            shared: Arc::new(pieces),
            cores: Vec::new(),
            near,
            pair_tests: 0,
            candidate_pairs: 0,
            cuts,
            threads: 1,
        });
    }
    let pieces = &pieces;
    let n = pieces.len();
    let threads = crate::workers::threads(options.threads).min(8);
    if n <= ONE_ORDER_PIECES
        && let Some(built) = one_order(geometry, pieces, options, (near, tolerance), threads, cuts)?
    {
        return Ok(built);
    }
    let bounds = PieceBounds::of(pieces);
    let setting = Setting {
        pieces,
        bounds: &bounds,
        radius,
        tolerance,
        max_pairs: options.max_pairs,
    };
    let started = Instant::now();
    let report = Report {
        done: AtomicUsize::new(0),
        total: octants
            .iter()
            .map(|o| top_regions(o, radius, options.max_depth, 0))
            .sum(),
        progress,
    };
    // Each octant is certified on its own, the octants shared out among the threads.
    let next = std::sync::atomic::AtomicUsize::new(0);
    let built: Vec<Vec<(usize, Result<Builder<'_>, PresortError>)>> =
        crate::workers::map(threads, threads, |_| {
            let mut done = Vec::new();
            loop {
                let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                if k >= octants.len() {
                    return done;
                }
                let mut builder = Builder::new(geometry, &setting, options, started);
                builder.report = Some(&report);
                let result = builder.octant(octants[k]).map(|kind| {
                    builder.nodes[0].kind = kind;
                    builder
                });
                done.push((k, result));
            }
        });
    let mut by_octant: Vec<Option<Builder<'_>>> = (0..octants.len()).map(|_| None).collect();
    for (k, result) in built.into_iter().flatten() {
        by_octant[k] = Some(result?);
    }
    let parts: Vec<Builder<'_>> = by_octant
        .into_iter()
        .map(|b| b.expect("every octant was built"))
        .collect();
    (report.progress)(PresortProgress {
        done: report.total,
        total: report.total,
    });
    let candidate_pairs = parts.iter().map(|b| b.candidates).sum();
    let (nodes, leaves, mut cores, pair_tests) = merge_octants(parts);

    let shared = share_cores(pieces, &mut cores);
    Ok(Built {
        nodes,
        leaves,
        shared: Arc::new(shared),
        cores,
        near,
        pair_tests,
        candidate_pairs,
        cuts,
        threads,
    })
}

/// The build's count of ordered regions, and whom to tell.
struct Report<'a> {
    done: AtomicUsize,
    total: usize,
    progress: &'a (dyn Fn(PresortProgress) + Sync),
}

/// How many regions below `region` (at `depth`) [`Builder::top`] orders from all their
/// pieces: itself, or its quarters' when it does not see the geometry from one side.
fn top_regions(region: &Region, radius: f64, max_depth: usize, depth: usize) -> usize {
    if lean(&region.grown(), radius) >= MIN_LEAN {
        1
    } else if depth < max_depth {
        region
            .split_directions()
            .iter()
            .map(|q| top_regions(q, radius, max_depth, depth + 1))
            .sum()
    } else {
        0
    }
}

/// Models with at most this many pieces are checked for one order that serves every view
/// (a scan of every pair, quadratic); larger ones are certified by regions only.
pub(super) const ONE_ORDER_PIECES: usize = 8192;

/// One order for every view, when the pairs that may ever need an order (necessary for every
/// viewer, orthographic or perspective, wherever the eye) have no cycle; `None` when they
/// have one or are more than the budget allows.
fn one_order(
    geometry: &Geometry,
    pieces: &PolygonSet,
    options: &PresortOptions,
    (near, tolerance): (f64, f64),
    threads: usize,
    cuts: usize,
) -> Result<Option<Built>, PresortError> {
    let n = pieces.len();
    let Ok((start, targets)) = pairs_ever(pieces, tolerance, options.max_pairs, threads) else {
        return Ok(None);
    };
    let candidate_pairs = targets.len();
    let components = Graph::from_lists(start, targets).components(&vec![true; n]);
    if components.iter().any(|c| c.len() > 1) {
        return Ok(None);
    }
    let order: Vec<u32> = components.into_iter().map(|c| c[0]).collect();
    let octants = Region::octants(near);
    let setting = Setting {
        pieces,
        bounds: &[],
        radius: geometry.bounds().diagonal() * 0.5,
        tolerance,
        max_pairs: options.max_pairs,
    };
    let mut builder = Builder::new(geometry, &setting, options, Instant::now());
    builder.leaf(
        octants[0],
        &Partial {
            order,
            blocks: Vec::new(),
        },
    )?;
    Ok(Some(Built {
        nodes: octants
            .map(|region| Node {
                region,
                kind: NodeKind::Leaf(0),
            })
            .to_vec(),
        leaves: builder.leaves,
        shared: Arc::new(pieces.clone()),
        cores: Vec::new(),
        near: 0.0,
        pair_tests: 0,
        candidate_pairs,
        cuts,
        threads,
    }))
}

/// The octants' builders as one tree: the eight roots first (so that the octant of a
/// direction is its root's index), then each octant's other regions, leaves and cores,
/// renumbered; with the pair tests they made.
fn merge_octants(parts: Vec<Builder<'_>>) -> (Vec<Node>, Vec<Leaf>, Vec<Core>, usize) {
    let mut nodes: Vec<Node> = Vec::new();
    let (mut leaves, mut cores) = (Vec::new(), Vec::new());
    let mut pair_tests = 0;
    let mut node_offsets = Vec::with_capacity(parts.len());
    let mut offset = parts.len();
    for part in &parts {
        node_offsets.push(offset);
        offset += part.nodes.len() - 1;
    }
    for part in &parts {
        nodes.push(part.nodes[0]);
    }
    for (k, part) in parts.into_iter().enumerate() {
        let (leaf_offset, core_offset) = (leaves.len() as u32, cores.len() as u32);
        let local = |i: u32| -> u32 {
            if i == 0 {
                k as u32
            } else {
                (node_offsets[k] + i as usize - 1) as u32
            }
        };
        let renumber = |kind: NodeKind| match kind {
            NodeKind::Leaf(l) => NodeKind::Leaf(l + leaf_offset),
            NodeKind::Directions { first } => NodeKind::Directions {
                first: local(first),
            },
            NodeKind::Distance { mid, first } => NodeKind::Distance {
                mid,
                first: local(first),
            },
            NodeKind::Uncertified => NodeKind::Uncertified,
        };
        nodes[k].kind = renumber(part.nodes[0].kind);
        for node in &part.nodes[1..] {
            nodes.push(Node {
                region: node.region,
                kind: renumber(node.kind),
            });
        }
        for mut leaf in part.leaves {
            for step in &mut leaf.pieces {
                if *step & CORE != 0 {
                    *step = CORE | ((*step & !CORE) + core_offset);
                }
            }
            leaves.push(leaf);
        }
        cores.extend(part.cores);
        pair_tests += part.pair_tests;
    }
    (nodes, leaves, cores, pair_tests)
}

impl<'a> Builder<'a> {
    /// A builder with no regions yet; its budget of time runs from `started`.
    fn new(
        geometry: &'a Geometry,
        setting: &'a Setting<'a>,
        options: &'a PresortOptions,
        started: Instant,
    ) -> Self {
        Builder {
            geometry,
            setting,
            pieces: setting.pieces,
            bounds: setting.bounds,
            options,
            tolerance: setting.tolerance,
            candidates: 0,
            report: None,
            nodes: Vec::new(),
            leaves: Vec::new(),
            cores: Vec::new(),
            core_sets: Vec::new(),
            pair_tests: 0,
            started,
        }
    }

    /// Certifies one octant (its root is this builder's node 0).
    fn octant(&mut self, region: Region) -> Result<NodeKind, PresortError> {
        self.nodes.push(Node {
            region,
            kind: NodeKind::Leaf(u32::MAX),
        });
        self.top(region, 0)
    }

    /// Certifies `region` (at `depth`, its node pushed) from all its pieces: ordered by
    /// [`region_order`] when its viewers see the geometry from one side, else split into
    /// quarters that are (or left uncertified when no split is left).
    fn top(&mut self, region: Region, depth: usize) -> Result<NodeKind, PresortError> {
        self.check_time()?;
        let grown = region.grown();
        if lean(&grown, self.setting.radius) < MIN_LEAN {
            return Ok(if self.may_split(depth) {
                self.split(region, false, depth, &mut |b, child, d| b.top(child, d))?
            } else {
                NodeKind::Uncertified
            });
        }
        let mut test = OcclusionTest::new(self.pieces, self.bounds, grown);
        let facing = self.facing(&grown, &test);
        let started = self.started;
        let limit = self.options.max_build_time;
        let check_time = move || {
            if started.elapsed() > limit {
                return Err(PresortError::TimeBudget { limit });
            }
            Ok(())
        };
        let RegionOrder {
            partial,
            open_edges,
            tests,
            candidates,
        } = region_order(self.setting, &mut test, &facing, &grown, &check_time)?;
        self.pair_tests += tests;
        self.candidates += candidates;
        if let Some(report) = self.report {
            let done = report.done.fetch_add(1, Ordering::Relaxed) + 1;
            (report.progress)(PresortProgress {
                done: done.min(report.total),
                total: report.total,
            });
        }
        self.settle(region, partial, &open_edges, usize::MAX, depth)
    }

    /// Whether a region at `depth` may still be split (depth and node budgets).
    fn may_split(&self, depth: usize) -> bool {
        depth < self.options.max_depth && 8 * (self.nodes.len() + 4) <= self.options.max_nodes
    }

    /// Splits `region` (at `depth`) by distance or into quarters of directions, certifying
    /// each child with `child`.
    fn split(
        &mut self,
        region: Region,
        by_distance: bool,
        depth: usize,
        child: &mut dyn FnMut(&mut Self, Region, usize) -> Result<NodeKind, PresortError>,
    ) -> Result<NodeKind, PresortError> {
        let children: Vec<Region> = if by_distance {
            region.split_distance().to_vec()
        } else {
            region.split_directions().to_vec()
        };
        let first = self.nodes.len() as u32;
        for c in &children {
            self.nodes.push(Node {
                region: *c,
                kind: NodeKind::Leaf(u32::MAX),
            });
        }
        for (k, c) in children.iter().enumerate() {
            let kind = child(self, *c, depth + 1)?;
            self.nodes[first as usize + k].kind = kind;
        }
        Ok(if by_distance {
            NodeKind::Distance {
                mid: region.distance_split(),
                first,
            }
        } else {
            NodeKind::Directions { first }
        })
    }

    /// [`PresortError::TimeBudget`] once the build has run longer than its budget.
    fn check_time(&self) -> Result<(), PresortError> {
        if self.started.elapsed() > self.options.max_build_time {
            return Err(PresortError::TimeBudget {
                limit: self.options.max_build_time,
            });
        }
        Ok(())
    }

    fn facing(&self, grown: &Region, test: &OcclusionTest<'_>) -> Vec<bool> {
        (0..self.pieces.len())
            .map(|i| may_face(self.pieces, i, grown, test.hull(), self.tolerance))
            .collect()
    }

    /// Certifies an order for `region`, or splits it. `parent` is the parent's partial
    /// order, `candidates` the pairs it kept inside its open blocks: only those can still
    /// form a cycle here (a cycle among this region's pairs is one among the parent's, whose
    /// pairs include these), and every other pair the region keeps the parent kept too, so
    /// the parent's order already respects it.
    fn certify(
        &mut self,
        region: Region,
        parent: &Partial,
        candidates: &[(u32, u32)],
        depth: usize,
    ) -> Result<NodeKind, PresortError> {
        self.check_time()?;
        let grown = region.grown();
        let mut test = OcclusionTest::new(self.pieces, self.bounds, grown);
        let facing = self.facing(&grown, &test);
        let mut edges = Vec::new();
        for &(a, b) in candidates {
            let (ai, bi) = (a as usize, b as usize);
            if facing[ai] && facing[bi] {
                self.pair_tests += 1;
                if test.may_hide(ai, bi) {
                    edges.push((a, b));
                }
            }
        }
        let (partial, open_edges) = parent.refined(&facing, &edges);
        self.settle(region, partial, &open_edges, parent.open_pieces(), depth)
    }

    /// Stores `partial` as the order of `region` (at `depth`, below a region whose cycles
    /// held `parent_open` pieces), or splits the region, passing on the pairs inside its
    /// cycles (`open_edges`).
    fn settle(
        &mut self,
        region: Region,
        partial: Partial,
        open_edges: &[(u32, u32)],
        parent_open: usize,
        depth: usize,
    ) -> Result<NodeKind, PresortError> {
        let small = partial
            .blocks
            .iter()
            .all(|b| b.len() <= self.options.small_cycle_pieces);
        // Splitting helps while it opens cycles: when the pieces left in cycles are as many as
        // in the parent's, the cycles hold from every side of the region (pieces that touch
        // along a cut, cyclic overlaps of crossing soups) and more regions only cost memory.
        let open = partial.open_pieces();
        let stalled = depth > 0 && open >= parent_open;
        if depth >= 2 && !small && 4 * open > partial.order.len() {
            return Ok(NodeKind::Uncertified);
        }
        if small || stalled {
            // Acyclic, or the cycles left are ordered per frame by BSP trees of their own.
            return Ok(NodeKind::Leaf(self.leaf(region, &partial)?));
        }
        if self.may_split(depth) {
            let by_distance = !region.orthographic_only()
                && region.angular_radius() < parallax(&region, self.geometry);
            return self.split(region, by_distance, depth, &mut |b, child, d| {
                b.certify(child, &partial, open_edges, d)
            });
        }
        // The deepest split: the open blocks are ordered per frame.
        Ok(NodeKind::Leaf(self.leaf(region, &partial)?))
    }

    /// Stores a leaf: the pieces of `partial` in order, each open block as one core.
    fn leaf(&mut self, region: Region, partial: &Partial) -> Result<u32, PresortError> {
        let n = partial.order.len();
        let mut leaf = Leaf {
            region,
            edges: region.edge_normals(),
            pieces: Vec::with_capacity(n),
        };
        let mut blocks = partial.blocks.iter().peekable();
        let mut i = 0;
        while i < n {
            if let Some(block) = blocks.next_if(|b| b.start as usize == i) {
                let set: Vec<u32> =
                    partial.order[block.start as usize..block.end as usize].to_vec();
                let core = self.core(&set)?;
                leaf.pieces.push(CORE | core);
                i = block.end as usize;
                continue;
            }
            leaf.pieces.push(partial.order[i]);
            i += 1;
        }
        leaf.pieces.shrink_to_fit();
        self.leaves.push(leaf);
        Ok(self.leaves.len() as u32 - 1)
    }

    /// A core's BSP tree (shared by leaves holding the same set).
    fn core(&mut self, set: &[u32]) -> Result<u32, PresortError> {
        let mut set = set.to_vec();
        set.sort_unstable();
        let set = &set[..];
        if let Some(k) = self.core_sets.iter().position(|s| s == set) {
            return Ok(k as u32);
        }
        self.cores
            .push(Core::of(self.pieces, set, self.geometry.bounds())?);
        self.core_sets.push(set.to_vec());
        Ok(self.cores.len() as u32 - 1)
    }
}

impl Core {
    /// The core of the pieces `set` (ascending indices into `pieces`): a BSP tree of their
    /// own, in a geometry with `bounds` (the whole geometry's, for its tolerances).
    pub fn of(
        pieces: &PolygonSet,
        set: &[u32],
        bounds: crate::Bounds,
    ) -> Result<Core, PresortError> {
        let mut own = PolygonSet::new();
        for (k, &p) in set.iter().enumerate() {
            let p = p as usize;
            own.push(pieces.corners(p), k as u32, *pieces.plane(p));
        }
        let geometry = Geometry::from_pieces(own, bounds);
        let tree =
            BspTree::try_build(&geometry, &BspOptions::default()).map_err(PresortError::Core)?;
        Ok(Core {
            tree: Arc::new(tree),
            offset: 0,
            faces: set.iter().map(|&p| pieces.face(p as usize)).collect(),
            pieces: set.len(),
            set: set.to_vec(),
        })
    }
}

/// The shared set: `pieces`, then each core's fragments (setting each core's offset).
pub(super) fn share_cores(pieces: &PolygonSet, cores: &mut [Core]) -> PolygonSet {
    let mut shared = pieces.clone();
    for core in cores {
        core.offset = shared.len() as u32;
        let fragments = core.tree.fragments();
        for f in 0..fragments.len() {
            let face = core.faces[fragments.face(f) as usize];
            shared.push(fragments.corners(f), face, *fragments.plane(f));
        }
    }
    shared
}

/// How far the direction toward a piece turns as the eye moves across the region's
/// distances: `asin(r / near) − asin(r / far)` for the geometry's radius `r`.
fn parallax(region: &Region, geometry: &Geometry) -> f64 {
    let r = geometry.bounds().diagonal() * 0.5;
    let angle = |t: f64| {
        if t.is_finite() {
            (r / t).min(1.0).asin()
        } else {
            0.0
        }
    };
    angle(region.near) - angle(region.far)
}
