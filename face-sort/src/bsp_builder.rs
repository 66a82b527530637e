//! The BSP builder: chooses each node's splitter, splits the polygons that span it, and lays
//! the nodes and their fragments out in pre-order for [`BspTree`](crate::BspTree).

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use glam::DVec3;

use crate::ids::NodeId;
use crate::plane::{Plane, Side};
use crate::polygon::split_polygon;
use crate::{BspOptions, PolygonSet};

/// One node, in pre-order (node, front subtree, back subtree).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Node {
    /// Fragments lying in the node's plane: `[first, first + same)` face the plane's way,
    /// `[first + same, first + same + opposite)` face the other way.
    pub first: u32,
    pub same: u32,
    pub opposite: u32,
    pub front_child: NodeId,
    pub back_child: NodeId,
    /// Fragments in the front and back subtrees.
    pub front_size: u32,
    pub back_size: u32,
    /// A convex leaf: its `same` fragments need no order among themselves beyond "facing away
    /// first" (front faces of a convex set never overlap, nor do its back faces).
    pub leaf: bool,
}

/// Sets of at most this many polygons are tested for convexity (every polygon on or behind
/// every other's plane); a convex set becomes a leaf and is not split further.
const CONVEX_LEAF_MAX: usize = 48;

/// Sets of at least this many polygons also score one plane that is no polygon's: across
/// the widest axis of their centres, through the median. Face planes of a smooth surface
/// mostly cut off a few polygons each (a peel: trees thousands deep, builds growing far
/// faster than `n log n`); the median plane splits a large set in halves for a few splits.
/// Measured before the candidate pre-selection, 256 gave fewer fragments than 128, 512 and
/// 1,024 on spot and blub, and than 512 and no median plane on all four real models
/// (`docs/experiments/face-sort.md`).
const MEDIAN_CANDIDATE_MIN: usize = 256;

/// Sets of at most this many polygons score every one of them as a splitter.
const SMALL_SET: usize = 32;

/// Larger sets rank `PRESELECT` times [`BspOptions::candidates`] evenly spread candidates by
/// their score on `PRESELECT_SAMPLE` of their polygons, and score the best in full. With
/// [`SMALL_SET`], 1.751x fragments on spot instead of 1.831x for 12 candidates scored in full
/// (`docs/experiments/face-sort.md`).
const PRESELECT: usize = 4;

/// See [`PRESELECT`].
const PRESELECT_SAMPLE: usize = 16;

/// A finished build: the nodes in pre-order, their planes, and the fragments (each node's
/// own contiguous, in node order) with their pieces.
pub(crate) struct Built {
    pub nodes: Vec<Node>,
    pub planes: Vec<Plane>,
    pub fragments: PolygonSet,
    pub fragment_piece: Vec<u32>,
    /// The tree's depth.
    pub depth: usize,
}

/// Geometries of at least this many pieces build their tree on the threads
/// [`BspOptions::threads`] allows (one per core by default): the top nodes on one, then the
/// subtrees of at most [`SUBTREE_SHARE`] of the pieces side by side.
const PARALLEL_MIN_PIECES: usize = 4096;

/// See [`PARALLEL_MIN_PIECES`]: subtrees of at most `1 / SUBTREE_SHARE` of the pieces are
/// built side by side.
const SUBTREE_SHARE: usize = 16;

/// Builds the nodes over `pieces` with plane tolerance `tolerance`; `Err` when the tree
/// would hold more than `budget` fragments.
///
/// With several cores and enough pieces, the subtrees below the top nodes are built on
/// their own threads, each by a builder holding copies of its polygons numbered in the same
/// order: a subtree's choices depend only on its polygons, their order and their relative
/// numbering, so the tree is the same, bit for bit, on any number of cores (a test builds
/// it both ways).
pub(crate) fn build(
    pieces: &PolygonSet,
    tolerance: f64,
    options: &BspOptions,
    budget: usize,
) -> Result<Built, ()> {
    let threads = crate::workers::threads(options.threads);
    build_on(pieces, tolerance, options, budget, threads)
}

/// [`build`] on at most `threads` threads.
fn build_on(
    pieces: &PolygonSet,
    tolerance: f64,
    options: &BspOptions,
    budget: usize,
    threads: usize,
) -> Result<Built, ()> {
    let live = AtomicUsize::new(pieces.len());
    let mut top = Builder::new(pieces, tolerance, options, budget, &live);
    let root = Task::root((0..pieces.len() as u32).collect());
    let n = pieces.len();
    if threads < 2 || n < PARALLEL_MIN_PIECES {
        let depth = top.build_tasks(root, None)?;
        let mut built = top.finish(depth);
        fill_sizes(&mut built.nodes);
        return Ok(built);
    }
    let mut deferred = Vec::new();
    let top_depth = top.build_tasks(root, Some((n / SUBTREE_SHARE, &mut deferred)))?;
    let subtrees = build_subtrees(&top, &deferred, threads)?;
    let depth = (subtrees.iter().map(|sub| sub.depth)).fold(top_depth, usize::max);
    Ok(assemble(top.finish(top_depth), &subtrees, depth))
}

/// Builds each deferred task's subtree, largest first, on up to `threads` threads (the
/// calling one included; a thread that cannot be spawned leaves its share to the others).
fn build_subtrees(top: &Builder, deferred: &[Task], threads: usize) -> Result<Vec<Built>, ()> {
    let mut by_size: Vec<usize> = (0..deferred.len()).collect();
    by_size.sort_by_key(|&d| std::cmp::Reverse(deferred[d].polygons.len()));
    let (next, failed) = (AtomicUsize::new(0), AtomicBool::new(false));
    let work = || {
        let mut done = Vec::new();
        while !failed.load(Ordering::Relaxed) {
            let Some(&d) = by_size.get(next.fetch_add(1, Ordering::Relaxed)) else {
                break;
            };
            let built = top.build_subtree(&deferred[d]);
            failed.fetch_or(built.is_err(), Ordering::Relaxed);
            done.push((d, built));
        }
        done
    };
    let mut results: Vec<Option<Built>> = (0..deferred.len()).map(|_| None).collect();
    std::thread::scope(|scope| {
        let helpers: Vec<_> = (1..threads.min(deferred.len()))
            .filter_map(|_| std::thread::Builder::new().spawn_scoped(scope, work).ok())
            .collect();
        let mut done = work();
        for helper in helpers {
            match helper.join() {
                Ok(theirs) => done.extend(theirs),
                Err(panic) => std::panic::resume_unwind(panic),
            }
        }
        for (d, built) in done {
            results[d] = built.ok();
        }
    });
    results
        .into_iter()
        .collect::<Option<Vec<Built>>>()
        .ok_or(())
}

/// The tree in pre-order: the top nodes and, where a deferred task hangs, its subtree's
/// nodes (renumbered) and fragments.
fn assemble(top: Built, subtrees: &[Built], depth: usize) -> Built {
    enum Item {
        Top(u32),
        Subtree(usize),
    }
    let mut out = Built {
        nodes: Vec::with_capacity(
            top.nodes.len() + subtrees.iter().map(|s| s.nodes.len()).sum::<usize>(),
        ),
        planes: Vec::new(),
        fragments: PolygonSet::new(),
        fragment_piece: Vec::new(),
        depth,
    };
    let item_of = |child: NodeId| match child.get()? {
        c if c & DEFERRED != 0 => Some(Item::Subtree((c & !DEFERRED) as usize)),
        c => Some(Item::Top(c)),
    };
    // Each item with the slot of its parent's child pointer (`None`: the root).
    let mut stack = vec![(Item::Top(0), None, false)];
    while let Some((item, parent, is_front)) = stack.pop() {
        let index = out.nodes.len() as u32;
        if let Some(parent) = parent {
            let parent: &mut Node = &mut out.nodes[parent as usize];
            *(if is_front {
                &mut parent.front_child
            } else {
                &mut parent.back_child
            }) = NodeId::new(index);
        }
        match item {
            Item::Top(k) => {
                let node = top.nodes[k as usize];
                let first = out.fragments.len() as u32;
                for f in node.first..node.first + node.same + node.opposite {
                    out.push_fragment(&top.fragments, f as usize, top.fragment_piece[f as usize]);
                }
                out.planes.push(top.planes[k as usize]);
                out.nodes.push(Node {
                    first,
                    front_child: NodeId::NONE,
                    back_child: NodeId::NONE,
                    ..node
                });
                // Back pushed first: the front subtree comes first in pre-order.
                stack.extend(item_of(node.back_child).map(|c| (c, Some(index), false)));
                stack.extend(item_of(node.front_child).map(|c| (c, Some(index), true)));
            }
            Item::Subtree(d) => {
                let sub = &subtrees[d];
                let first = out.fragments.len() as u32;
                let moved = |c: NodeId| c.get().map_or(NodeId::NONE, |c| NodeId::new(c + index));
                out.nodes.extend(sub.nodes.iter().map(|node| Node {
                    first: node.first + first,
                    front_child: moved(node.front_child),
                    back_child: moved(node.back_child),
                    ..*node
                }));
                out.planes.extend_from_slice(&sub.planes);
                for (f, &piece) in sub.fragment_piece.iter().enumerate() {
                    out.push_fragment(&sub.fragments, f, piece);
                }
            }
        }
    }
    fill_sizes(&mut out.nodes);
    out
}

impl Built {
    /// Appends fragment `f` of `fragments`, a part of piece `piece`.
    fn push_fragment(&mut self, fragments: &PolygonSet, f: usize, piece: u32) {
        self.fragments
            .push(fragments.corners(f), fragments.face(f), *fragments.plane(f));
        self.fragment_piece.push(piece);
    }
}

/// Each node's front and back subtree sizes in fragments (children follow their parents in
/// pre-order).
fn fill_sizes(nodes: &mut [Node]) {
    let mut size = vec![0u32; nodes.len()];
    for k in (0..nodes.len()).rev() {
        let node = nodes[k];
        let child_size = |c: NodeId| c.get().map_or(0, |c| size[c as usize]);
        nodes[k].front_size = child_size(node.front_child);
        nodes[k].back_size = child_size(node.back_child);
        size[k] = node.same + node.opposite + nodes[k].front_size + nodes[k].back_size;
    }
}

/// Tag of a top node's child pointer that names a deferred task (its index), not a node.
const DEFERRED: u32 = 1 << 31;

struct Builder<'a> {
    work: PolygonSet,
    work_piece: Vec<u32>,
    /// Per work polygon, its corners' centre and its reach `[x, y, z, r + 2 · tolerance]`
    /// (`r` the largest distance of a corner from the centre), for [`side`](Self::side).
    work_sphere: Vec<[f64; 4]>,
    /// The splitter scoring's buffers: the polygons scored with their spheres, and which of
    /// them lie near the plane scored.
    scored: Vec<(u32, [f64; 4])>,
    near: Vec<u32>,
    /// The candidates scored in full, with their preliminary scores.
    chosen: Vec<(f64, u32)>,
    /// The nodes and fragments built so far.
    out: Built,
    tolerance: f64,
    options: BspOptions,
    corners_front: Vec<DVec3>,
    corners_back: Vec<DVec3>,
    /// Fragments the finished tree would hold so far: pieces plus one per two-sided split
    /// (shared by the builders of one tree).
    live: &'a AtomicUsize,
    /// Largest allowed `live`.
    budget: usize,
}

struct Task {
    polygons: Vec<u32>,
    /// The node whose child slot this task fills (`None`: the root).
    parent: Option<u32>,
    is_front: bool,
    depth: usize,
    /// Peels of `polygons` found while scoring an ancestor: each splits this set without
    /// a score of its own.
    peels: Vec<Peel>,
}

/// A candidate splitter that left every other polygon scored strictly on one side of its
/// plane (none on it, none cut): it still does for any subset of them.
#[derive(Clone, Copy, Debug)]
struct Peel {
    polygon: u32,
    /// Whether the others lie in front of its plane (else behind).
    rest_in_front: bool,
    /// Whether every polygon was scored (not a sample): then the sides are known without
    /// classifying again; a sampled peel is only likely one.
    exact: bool,
}

impl Task {
    /// The task of a whole tree over `polygons`.
    fn root(polygons: Vec<u32>) -> Vec<Task> {
        vec![Task {
            polygons,
            parent: None,
            is_front: false,
            depth: 1,
            peels: Vec::new(),
        }]
    }
}

impl<'a> Builder<'a> {
    /// A builder whose work polygons are `pieces`.
    fn new(
        pieces: &PolygonSet,
        tolerance: f64,
        options: &BspOptions,
        budget: usize,
        live: &'a AtomicUsize,
    ) -> Self {
        let mut builder = Builder::empty(tolerance, options, budget, live);
        for i in 0..pieces.len() {
            builder.push_work(
                pieces.corners(i),
                pieces.face(i),
                *pieces.plane(i),
                i as u32,
            );
        }
        builder
    }

    /// A builder with no work polygons.
    fn empty(tolerance: f64, options: &BspOptions, budget: usize, live: &'a AtomicUsize) -> Self {
        Builder {
            work: PolygonSet::new(),
            work_piece: Vec::new(),
            work_sphere: Vec::new(),
            scored: Vec::new(),
            near: Vec::new(),
            chosen: Vec::new(),
            out: Built {
                nodes: Vec::new(),
                planes: Vec::new(),
                fragments: PolygonSet::new(),
                fragment_piece: Vec::new(),
                depth: 0,
            },
            tolerance,
            options: *options,
            corners_front: Vec::new(),
            corners_back: Vec::new(),
            live,
            budget,
        }
    }

    /// The subtree of a deferred `task` of this builder, built by a builder of its own over
    /// copies of its polygons, numbered in this builder's order (so that ties between them
    /// fall the same way), its peels renumbered likewise.
    fn build_subtree(&self, task: &Task) -> Result<Built, ()> {
        let mut ids = task.polygons.clone();
        ids.sort_unstable();
        let mut sub = Builder::empty(self.tolerance, &self.options, self.budget, self.live);
        for &p in &ids {
            let p = p as usize;
            sub.push_work(
                self.work.corners(p),
                self.work.face(p),
                *self.work.plane(p),
                self.work_piece[p],
            );
        }
        let local = |p: u32| ids.binary_search(&p).ok().map(|i| i as u32);
        let root = Task {
            polygons: task.polygons.iter().filter_map(|&p| local(p)).collect(),
            parent: None,
            is_front: false,
            depth: task.depth,
            // Every peel is one of the task's polygons (`build_tasks` hands down only those
            // that the partition above put on the task's side).
            peels: (task.peels.iter())
                .filter_map(|peel| {
                    Some(Peel {
                        polygon: local(peel.polygon)?,
                        ..*peel
                    })
                })
                .collect(),
        };
        let depth = sub.build_tasks(vec![root], None)?;
        Ok(sub.finish(depth))
    }

    /// The built nodes and fragments, of a tree `depth` deep (subtree sizes not filled in:
    /// a subtree's are filled once, in the assembled tree).
    fn finish(self, depth: usize) -> Built {
        Built { depth, ..self.out }
    }

    /// Builds the nodes of `stack`'s tasks and below in pre-order, and returns the tree's
    /// depth; `Err` when the fragment budget is exceeded. With `defer`, tasks of at most
    /// `limit` polygons are not built but set aside (in the order met), their parents'
    /// child pointers naming them with [`DEFERRED`].
    fn build_tasks(
        &mut self,
        mut stack: Vec<Task>,
        mut defer: Option<(usize, &mut Vec<Task>)>,
    ) -> Result<usize, ()> {
        let mut max_depth = 0;
        while let Some(task) = stack.pop() {
            if task.polygons.is_empty() {
                continue;
            }
            let deferred = match &mut defer {
                Some((limit, deferred)) if task.polygons.len() <= *limit => Some(deferred),
                _ => None,
            };
            let index = match &deferred {
                Some(deferred) => DEFERRED | deferred.len() as u32,
                None => self.out.nodes.len() as u32,
            };
            if let Some(parent) = task.parent {
                let parent = &mut self.out.nodes[parent as usize];
                if task.is_front {
                    parent.front_child = NodeId::new(index);
                } else {
                    parent.back_child = NodeId::new(index);
                }
            }
            if let Some(deferred) = deferred {
                deferred.push(task);
                continue;
            }
            max_depth = max_depth.max(task.depth);
            if task.polygons.len() <= CONVEX_LEAF_MAX && self.is_convex(&task.polygons) {
                let first = self.out.fragments.len() as u32;
                for &p in &task.polygons {
                    let p = p as usize;
                    self.out.push_fragment(&self.work, p, self.work_piece[p]);
                }
                // A leaf has no plane of its own; keep the arrays aligned with a dummy.
                self.out
                    .planes
                    .push(*self.work.plane(task.polygons[0] as usize));
                self.out.nodes.push(Node {
                    first,
                    same: task.polygons.len() as u32,
                    opposite: 0,
                    front_child: NodeId::NONE,
                    back_child: NodeId::NONE,
                    front_size: 0,
                    back_size: 0,
                    leaf: true,
                });
                continue;
            }
            let mut peels = task.peels;
            let mut median = true;
            let (plane, same, opposite, front, back) = loop {
                let (splitter, plane, peel) = match peels.pop() {
                    Some(peel) => (
                        Some(peel.polygon),
                        *self.work.plane(peel.polygon as usize),
                        Some(peel),
                    ),
                    None => {
                        let (splitter, plane) =
                            self.choose_splitter(&task.polygons, &mut peels, median);
                        (splitter, plane, None)
                    }
                };
                let (same, opposite, front, back) = match peel {
                    // Every other polygon's side is known from the scoring: no classification.
                    Some(Peel {
                        exact: true,
                        rest_in_front,
                        ..
                    }) => {
                        let rest = task.polygons.iter().copied();
                        let rest: Vec<u32> = rest.filter(|&p| Some(p) != splitter).collect();
                        let (front, back) = if rest_in_front {
                            (rest, Vec::new())
                        } else {
                            (Vec::new(), rest)
                        };
                        (splitter.into_iter().collect(), Vec::new(), front, back)
                    }
                    _ => self.partition(&task.polygons, splitter, &plane)?,
                };
                // A median plane (scored on a sample) that leaves every polygon on one side
                // would be chosen again for the same set: take a face plane instead, which
                // always keeps at least its own polygon.
                let stuck = splitter.is_none()
                    && same.is_empty()
                    && opposite.is_empty()
                    && (front.is_empty() || back.is_empty());
                if !stuck {
                    break (plane, same, opposite, front, back);
                }
                median = false;
            };
            let first = self.out.fragments.len() as u32;
            for &p in same.iter().chain(&opposite) {
                let p = p as usize;
                self.out.push_fragment(&self.work, p, self.work_piece[p]);
            }
            self.out.planes.push(plane);
            self.out.nodes.push(Node {
                first,
                same: same.len() as u32,
                opposite: opposite.len() as u32,
                front_child: NodeId::NONE,
                back_child: NodeId::NONE,
                front_size: 0,
                back_size: 0,
                leaf: false,
            });
            // Back pushed first so that the front subtree is built (numbered) first: pre-order.
            // A peel leaves one side empty: the other inherits the remaining peels that went
            // to it. A peel scored on a sample may lie on this node's plane or have been cut
            // by it, as the partition (by the same classification) found: it is dropped then.
            let inherit = |mut peels: Vec<Peel>, side: Side| {
                peels.retain(|peel| self.side(&plane, peel.polygon) == side);
                peels
            };
            let (front_peels, back_peels) = if front.is_empty() {
                (Vec::new(), inherit(peels, Side::Back))
            } else if back.is_empty() {
                (inherit(peels, Side::Front), Vec::new())
            } else {
                (Vec::new(), Vec::new())
            };
            stack.push(Task {
                polygons: back,
                parent: Some(index),
                is_front: false,
                depth: task.depth + 1,
                peels: back_peels,
            });
            stack.push(Task {
                polygons: front,
                parent: Some(index),
                is_front: true,
                depth: task.depth + 1,
                peels: front_peels,
            });
        }
        Ok(max_depth)
    }

    /// The polygons on `plane` (facing its way, and the other way), in front of it and
    /// behind it, those spanning it split; `splitter` (if any) is on it by definition.
    /// `Err` when the splits exceed the fragment budget.
    #[allow(clippy::type_complexity)]
    fn partition(
        &mut self,
        polygons: &[u32],
        splitter: Option<u32>,
        plane: &Plane,
    ) -> Result<(Vec<u32>, Vec<u32>, Vec<u32>, Vec<u32>), ()> {
        let (mut same, mut opposite, mut front, mut back) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for &p in polygons {
            let side = if Some(p) == splitter {
                Side::On
            } else {
                self.side(plane, p)
            };
            match side {
                Side::On => {
                    if self.work.plane(p as usize).normal().dot(plane.normal()) >= 0.0 {
                        same.push(p);
                    } else {
                        opposite.push(p);
                    }
                }
                Side::Front => front.push(p),
                Side::Back => back.push(p),
                Side::Spanning => {
                    let (f, b) = self.split(p, plane);
                    if f.is_some() && b.is_some() {
                        let live = self.live.fetch_add(1, Ordering::Relaxed) + 1;
                        if live > self.budget {
                            return Err(());
                        }
                    }
                    front.extend(f);
                    back.extend(b);
                }
            }
        }
        Ok((same, opposite, front, back))
    }

    /// Splits work polygon `p` by `plane`; returns the new front and back polygon ids (a part
    /// of fewer than three corners is dropped, as Newell's `cut` drops it: change both
    /// together).
    fn split(&mut self, p: u32, plane: &Plane) -> (Option<u32>, Option<u32>) {
        self.corners_front.clear();
        self.corners_back.clear();
        split_polygon(
            self.work.corners(p as usize),
            plane,
            self.tolerance,
            &mut self.corners_front,
            &mut self.corners_back,
        );
        let face = self.work.face(p as usize);
        let own_plane = *self.work.plane(p as usize);
        let piece = self.work_piece[p as usize];
        let front = std::mem::take(&mut self.corners_front);
        let back = std::mem::take(&mut self.corners_back);
        let f = (front.len() >= 3).then(|| self.push_work(&front, face, own_plane, piece));
        let b = (back.len() >= 3).then(|| self.push_work(&back, face, own_plane, piece));
        (self.corners_front, self.corners_back) = (front, back);
        (f, b)
    }

    /// Adds a work polygon (a piece, or a fragment of piece `piece`) and its sphere.
    fn push_work(&mut self, corners: &[DVec3], face: u32, plane: Plane, piece: u32) -> u32 {
        let centre = corners.iter().copied().sum::<DVec3>() / corners.len() as f64;
        let radius = corners
            .iter()
            .map(|&c| c.distance(centre))
            .fold(0.0, f64::max);
        let reach = radius + 2.0 * self.tolerance;
        self.work_sphere.push([centre.x, centre.y, centre.z, reach]);
        self.work_piece.push(piece);
        self.work.push(corners, face, plane)
    }

    /// [`Plane::side_of_polygon`] of work polygon `p`, the same answer, mostly from its
    /// sphere alone: when the sphere's centre lies farther from `plane` than its radius plus
    /// twice the tolerance, every corner lies beyond the tolerance on the centre's side (one
    /// tolerance is the test's, the other far exceeds round-off, about `1e-16 · L` in centred
    /// coordinates). Most polygons lie far from most planes: the build's classifications
    /// then cost one dot product instead of one per corner.
    fn side(&self, plane: &Plane, p: u32) -> Side {
        let [x, y, z, reach] = self.work_sphere[p as usize];
        let d = plane.signed_distance(DVec3::new(x, y, z));
        if d > reach {
            Side::Front
        } else if d < -reach {
            Side::Back
        } else {
            plane.side_of_polygon(self.work.corners(p as usize), self.tolerance)
        }
    }

    /// Whether every polygon lies on or behind every other's plane.
    fn is_convex(&self, polygons: &[u32]) -> bool {
        polygons.iter().all(|&p| {
            let plane = self.work.plane(p as usize);
            polygons
                .iter()
                .all(|&q| q == p || matches!(self.side(plane, q), Side::Back | Side::On))
        })
    }

    /// The plane across the widest axis of the polygons' centres, through their median.
    fn median_plane(&self, polygons: &[u32]) -> Plane {
        let centre = |p: u32| {
            let [x, y, z, _] = self.work_sphere[p as usize];
            DVec3::new(x, y, z)
        };
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for &p in polygons {
            lo = lo.min(centre(p));
            hi = hi.max(centre(p));
        }
        let axis = (hi - lo).max_position();
        let mut along: Vec<f64> = polygons.iter().map(|&p| centre(p)[axis]).collect();
        let middle = along.len() / 2;
        let (_, &mut median, _) = along.select_nth_unstable_by(middle, f64::total_cmp);
        let mut normal = DVec3::ZERO;
        normal[axis] = 1.0;
        Plane::try_from_point_normal(normal * median, normal).expect("unit normal")
    }

    /// The best candidate splitter by score: evenly spread polygons of the set and, for
    /// large sets and with `median`, the median plane ([`MEDIAN_CANDIDATE_MIN`]); `None` for
    /// the median plane. The spheres are finite (a geometry's positions are), so each
    /// polygon scored lands in exactly one side's count, as in [`side`](Self::side).
    /// When the best is a peel (every other polygon scored strictly on one side of its plane),
    /// the other candidates that are peels too go to `peels`: each still is one for any
    /// subset, so the sets below split by them without scoring again.
    fn choose_splitter(
        &mut self,
        polygons: &[u32],
        peels: &mut Vec<Peel>,
        median: bool,
    ) -> (Option<u32>, Plane) {
        let n = polygons.len();
        if n <= 2 {
            return (Some(polygons[0]), *self.work.plane(polygons[0] as usize));
        }
        let candidates = self.options.candidates.max(1).min(n);
        let sample = self.options.score_sample.max(1).min(n);
        // The polygons scored, all of them or an evenly spread sample (`s · n / sample`),
        // with their spheres side by side (see `side`).
        let mut scored = std::mem::take(&mut self.scored);
        scored.clear();
        scored.extend((0..sample).map(|s| {
            let p = if sample == n {
                polygons[s]
            } else {
                polygons[(s * n) / sample]
            };
            (p, self.work_sphere[p as usize])
        }));
        let mut near = std::mem::take(&mut self.near);
        near.clear();
        near.resize(scored.len(), 0);
        // Per side (in `Side`'s order: front, back, on, spanning): first by the spheres alone
        // without a branch, then the polygons near the plane corner by corner.
        // On every `stride`-th polygon scored.
        let mut count = |plane: &Plane, candidate: Option<u32>, stride: usize| {
            let mut count = [0usize; 4];
            let mut nears = 0;
            let (normal, offset) = (plane.normal(), plane.offset());
            for (k, (_, [x, y, z, reach])) in scored.iter().enumerate().step_by(stride) {
                let d = normal.x * x + normal.y * y + normal.z * z - offset;
                count[0] += usize::from(d > *reach);
                count[1] += usize::from(d < -reach);
                near[nears] = k as u32;
                nears += usize::from(d.abs() <= *reach);
            }
            for &k in &near[..nears] {
                let p = scored[k as usize].0;
                if Some(p) != candidate {
                    let side = plane.side_of_polygon(self.work.corners(p as usize), self.tolerance);
                    count[side as usize] += 1;
                }
            }
            count
        };
        let score = |[front, back, _, splits]: [usize; 4]| {
            self.options.split_weight * splits as f64 + front.abs_diff(back) as f64
        };
        let mut best = (
            f64::INFINITY,
            Some(polygons[0]),
            *self.work.plane(polygons[0] as usize),
        );
        // The candidates: every polygon of a small set; otherwise the `candidates` best of
        // `PRESELECT` times as many evenly spread ones, ranked by their score on
        // `PRESELECT_SAMPLE` of the polygons scored (best first, ties by polygon).
        let mut chosen = std::mem::take(&mut self.chosen);
        chosen.clear();
        if n <= SMALL_SET {
            chosen.extend(polygons.iter().map(|&p| (0.0, p)));
        } else {
            let wide = (candidates * PRESELECT).min(n);
            let stride = (scored.len() / PRESELECT_SAMPLE).max(1);
            for c in 0..wide {
                let candidate = polygons[(c * n) / wide + (n / wide) / 2];
                let plane = *self.work.plane(candidate as usize);
                chosen.push((score(count(&plane, Some(candidate), stride)), candidate));
            }
            chosen.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            chosen.truncate(candidates);
        }
        for &(_, candidate) in &chosen {
            let plane = *self.work.plane(candidate as usize);
            let sides = count(&plane, Some(candidate), 1);
            if score(sides) < best.0 {
                best = (score(sides), Some(candidate), plane);
            }
            let [front, back, on, splits] = sides;
            if on == 0 && splits == 0 && (front == 0 || back == 0) {
                peels.push(Peel {
                    polygon: candidate,
                    rest_in_front: back == 0,
                    exact: sample == n,
                });
            }
        }
        if median && n >= MEDIAN_CANDIDATE_MIN {
            let plane = self.median_plane(polygons);
            let sides = count(&plane, None, 1);
            if score(sides) < best.0 {
                best = (score(sides), None, plane);
            }
        }
        // Only when the best is a peel; it is drawn from the list, the others stay.
        if peels.iter().any(|peel| Some(peel.polygon) == best.1) {
            peels.retain(|peel| Some(peel.polygon) != best.1);
        } else {
            peels.clear();
        }
        self.scored = scored;
        self.near = near;
        self.chosen = chosen;
        (best.1, best.2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tolerance::PLANE_SIDE;
    use crate::{Geometry, generate};

    /// The builder's sphere shortcut gives `side_of_polygon`'s answer, on planes through
    /// neighbouring pieces (corners on the plane), planes nudged by about the tolerance, and
    /// planes far from most pieces, on a model far from the origin (moved, then centred).
    #[test]
    fn sphere_classification_is_side_of_polygon() {
        let torus = generate::torus(400);
        let away = DVec3::new(1e6, -3e5, 2e6);
        let positions: Vec<DVec3> = torus.positions().iter().map(|&p| p + away).collect();
        let mesh = crate::PolygonMesh::new(positions, torus.faces()).expect("valid torus");
        let geometry = Geometry::new(&mesh).expect("valid torus");
        let tolerance = PLANE_SIDE * geometry.bounds().diagonal();
        let pieces = geometry.pieces();
        let live = AtomicUsize::new(0);
        let builder = Builder::new(pieces, tolerance, &BspOptions::DEFAULT, usize::MAX, &live);
        let mut shortcut = 0;
        for a in (0..pieces.len()).step_by(7) {
            let own = *pieces.plane(a);
            for nudge in [0.0, 0.5, 1.0, 1.5, 2.0, 3.0, -1.0, -2.5] {
                let offset = own.offset() + nudge * tolerance;
                let plane = Plane::try_from_point_normal(own.normal() * offset, own.normal())
                    .expect("unit normal");
                for b in 0..pieces.len() {
                    let exact = plane.side_of_polygon(pieces.corners(b), tolerance);
                    assert_eq!(
                        builder.side(&plane, b as u32),
                        exact,
                        "plane of {a}, piece {b}"
                    );
                    let [x, y, z, reach] = builder.work_sphere[b];
                    shortcut +=
                        usize::from(plane.signed_distance(DVec3::new(x, y, z)).abs() > reach);
                }
            }
        }
        // The shortcut decides most classifications: the test covers both of its branches.
        assert!(shortcut > 0, "no classification took the shortcut");
    }

    /// A tree built on two threads (top nodes, then subtrees side by side) is the tree built
    /// on one, bit for bit; a budget too small fails both ways.
    #[test]
    fn subtrees_built_side_by_side_give_the_same_tree() {
        let geometry = Geometry::new(&generate::torus(2400)).expect("valid torus");
        let pieces = geometry.pieces();
        assert!(
            pieces.len() >= PARALLEL_MIN_PIECES,
            "{} pieces",
            pieces.len()
        );
        let tolerance = PLANE_SIDE * geometry.bounds().diagonal();
        let options = BspOptions::DEFAULT;
        let one = build_on(pieces, tolerance, &options, usize::MAX, 1).expect("unbounded");
        let two = build_on(pieces, tolerance, &options, usize::MAX, 2).expect("unbounded");
        assert_eq!(one.depth, two.depth);
        assert_eq!(one.nodes, two.nodes);
        assert_eq!(one.planes, two.planes);
        assert_eq!(one.fragment_piece, two.fragment_piece);
        assert_eq!(one.fragments.len(), two.fragments.len());
        for f in 0..one.fragments.len() {
            assert_eq!(
                one.fragments.corners(f),
                two.fragments.corners(f),
                "fragment {f}"
            );
            assert_eq!(one.fragments.face(f), two.fragments.face(f), "fragment {f}");
        }
        // The torus splits: the subtrees hold fragments of their own.
        assert!(one.fragments.len() > pieces.len());
        let tight = pieces.len() + (one.fragments.len() - pieces.len()) / 2;
        for threads in [1, 2] {
            assert!(
                build_on(pieces, tolerance, &options, tight, threads).is_err(),
                "{threads} thread(s): {tight} fragments allowed, {} needed",
                one.fragments.len()
            );
        }
    }
}
