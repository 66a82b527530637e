//! Event sources: what a sorter's draw list depends on, as event functions along a spin.

use std::cmp::{Ordering, Reverse};
use std::collections::BinaryHeap;
use std::f64::consts::TAU;
use std::sync::Arc;

use face_sort::{Bsp, BspTree, Centroid, FaceSorter, Geometry, Plane, PolygonSet};
use glam::DVec3;

use crate::BakeError;
use crate::axis::Spin;
use crate::event::{EventFn, Roots};
use crate::rows::Row;
use crate::tolerance::SAME_ROOT_RAD;

/// A sign change of an event function at `theta` (radians).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event {
    /// Where, radians.
    pub theta: f64,
    /// The function that changes sign there.
    pub function: EventFn,
}

/// A sorter whose draw list, along a [`Spin`], changes only where one of finitely many event
/// functions changes sign. The bake evaluates [`sorter`](Self::sorter) once inside each
/// interval between consecutive events.
pub trait EventSource: Sync {
    /// The sorter's name (`"bsp"`, `"centroid"`).
    fn name(&self) -> &'static str;

    /// The polygons the sorter's draw lists refer to (its shared set).
    fn polygons(&self) -> &Arc<PolygonSet>;

    /// A fresh live sorter (one per thread).
    fn sorter(&self) -> Box<dyn FaceSorter>;

    /// Appends every sign change in `[start, end)` (radians, `end − start ≤ 2π`), in any
    /// order. At most `max_events`.
    ///
    /// # Errors
    /// [`BakeError::EventBudget`] when there would be more than `max_events`.
    fn events(
        &self,
        spin: &Spin,
        start: f64,
        end: f64,
        max_events: usize,
        out: &mut Vec<Event>,
    ) -> Result<(), BakeError>;

    /// Every sign condition of the sorter as a [`Row`], for two-axis bakes
    /// ([`crate::bake_two_axes`]). At most `max_events`.
    ///
    /// # Errors
    /// [`BakeError::EventBudget`] beyond `max_events`; [`BakeError::Unsupported`] by default.
    fn rows(&self, max_events: usize, out: &mut Vec<Row>) -> Result<(), BakeError> {
        let _ = (max_events, out);
        Err(BakeError::Unsupported {
            sorter: self.name(),
        })
    }
}

/// Pushes the sign changes of `f` in `[start, end)`.
fn push_roots(f: EventFn, start: f64, end: f64, out: &mut Vec<Event>) {
    if let Roots::Two { down, up } = f.roots() {
        for root in [down, up] {
            let t = crate::event::reduce(root, start);
            if t < end {
                out.push(Event {
                    theta: t,
                    function: f,
                });
            }
        }
    }
}

fn budget(events: usize, max_events: usize) -> Result<(), BakeError> {
    if events > max_events {
        Err(BakeError::EventBudget {
            events,
            budget: max_events,
        })
    } else {
        Ok(())
    }
}

/// [`Bsp`]'s events: the eye side of every node plane and the facing of every piece (culling,
/// and facing-away-first inside convex leaves). A coplanar piece's facing is its node's side,
/// so those events coincide and merge. Nothing else enters [`Bsp`]'s sort. Its
/// [`sorter`](EventSource::sorter) sorts the whole model: the live [`Bsp`] also skips subtrees
/// outside the image of a zoomed-in view, which no event describes.
#[derive(Clone, Debug)]
pub struct BspSource {
    tree: Arc<BspTree>,
}

impl BspSource {
    /// The source of a built tree.
    #[must_use]
    pub fn new(tree: Arc<BspTree>) -> Self {
        BspSource { tree }
    }

    /// The source of a geometry's tree with default options.
    #[must_use]
    pub fn of(geometry: &Geometry) -> Self {
        Self::new(Arc::clone(Bsp::new(geometry).tree()))
    }

    /// The tree.
    #[must_use]
    pub fn tree(&self) -> &Arc<BspTree> {
        &self.tree
    }
}

impl EventSource for BspSource {
    fn name(&self) -> &'static str {
        "bsp"
    }

    fn polygons(&self) -> &Arc<PolygonSet> {
        self.tree.fragments()
    }

    fn sorter(&self) -> Box<dyn FaceSorter> {
        Box::new(WholeModel(Bsp::from_tree(Arc::clone(&self.tree))))
    }

    fn events(
        &self,
        spin: &Spin,
        start: f64,
        end: f64,
        max_events: usize,
        out: &mut Vec<Event>,
    ) -> Result<(), BakeError> {
        for plane in self
            .tree
            .node_planes()
            .iter()
            .chain(self.tree.piece_planes())
        {
            push_roots(spin.facing_fn(plane), start, end, out);
            budget(out.len(), max_events)?;
        }
        Ok(())
    }

    fn rows(&self, max_events: usize, out: &mut Vec<Row>) -> Result<(), BakeError> {
        let planes = self
            .tree
            .node_planes()
            .iter()
            .chain(self.tree.piece_planes());
        out.extend(planes.map(|&plane| Row::Facing(plane)));
        budget(out.len(), max_events)
    }
}

/// [`Bsp`] without its frustum culling: a view zoomed in far enough makes the live sort skip
/// subtrees outside the image, a per-frame saving that no event function describes. A bake's
/// lists hold the whole model, so that a realisation may pan and zoom (and the pieces outside
/// the image paint nothing anyway).
struct WholeModel(Bsp);

impl FaceSorter for WholeModel {
    fn name(&self) -> &'static str {
        self.0.name()
    }

    fn sort(&mut self, view: &face_sort::View, out: &mut face_sort::DrawList) {
        self.0.sort_culled(&view.cull_test(), out);
    }

    fn stats(&self) -> face_sort::SorterStats {
        self.0.stats()
    }
}

/// [`Centroid`]'s events: each piece's facing, and the swaps of a kinetic sorted list of
/// centroid depths. Only pairs adjacent in the current order are watched (a priority queue
/// of their next crossing), never all `n²` pairs; each swap costs `O(log n)`.
#[derive(Clone, Debug)]
pub struct CentroidSource {
    geometry: Geometry,
    pieces: Arc<PolygonSet>,
    centroids: Vec<DVec3>,
}

impl CentroidSource {
    /// The source over a geometry's pieces (the centroids [`Centroid`] sorts by).
    #[must_use]
    pub fn of(geometry: &Geometry) -> Self {
        let pieces = Arc::clone(geometry.pieces());
        let centroids = (0..pieces.len())
            .map(|i| {
                let c = pieces.corners(i);
                c.iter().copied().sum::<DVec3>() / c.len() as f64
            })
            .collect();
        CentroidSource {
            geometry: geometry.clone(),
            pieces,
            centroids,
        }
    }

    /// Each piece's facing plane: [`Centroid`] culls with `n·(e − v₀)` (perspective) or
    /// `n·d`, its plane through its first corner `v₀`.
    fn facing_planes(&self) -> impl Iterator<Item = Plane> + '_ {
        (self.pieces.planes().iter().enumerate())
            .map(|(i, plane)| plane.through(self.pieces.corners(i)[0]))
    }
}

#[derive(Clone, Copy, PartialEq)]
struct Time(f64);

impl Eq for Time {}

impl PartialOrd for Time {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Time {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// The next down-crossing of `g` at or after `now − SAME_ROOT_RAD`: where the later key of an
/// adjacent pair falls below the earlier one.
fn next_down(g: &EventFn, now: f64) -> Option<f64> {
    match g.roots() {
        Roots::Two { down, .. } => Some(crate::event::reduce(down, now - SAME_ROOT_RAD)),
        _ => None,
    }
}

impl EventSource for CentroidSource {
    fn name(&self) -> &'static str {
        "centroid"
    }

    /// Every piece's facing and every pair's depth difference: `n²/2` rows (a kinetic list
    /// does not carry over to two parameters), so the budget matters.
    fn rows(&self, max_events: usize, out: &mut Vec<Row>) -> Result<(), BakeError> {
        let n = self.centroids.len();
        budget(n + n * n.saturating_sub(1) / 2, max_events)?;
        out.extend(self.facing_planes().map(Row::Facing));
        for (i, &gi) in self.centroids.iter().enumerate() {
            for &gj in &self.centroids[i + 1..] {
                out.push(Row::Depth(gi - gj));
            }
        }
        Ok(())
    }

    fn polygons(&self) -> &Arc<PolygonSet> {
        &self.pieces
    }

    fn sorter(&self) -> Box<dyn FaceSorter> {
        Box::new(Centroid::new(&self.geometry))
    }

    fn events(
        &self,
        spin: &Spin,
        start: f64,
        end: f64,
        max_events: usize,
        out: &mut Vec<Event>,
    ) -> Result<(), BakeError> {
        for plane in self.facing_planes() {
            push_roots(spin.facing_fn(&plane), start, end, out);
        }
        budget(out.len(), max_events)?;
        let keys: Vec<EventFn> = self.centroids.iter().map(|&c| spin.depth_fn(c)).collect();
        let slope = |f: &EventFn, t: f64| -f.a * t.sin() + f.b * t.cos();
        let mut order: Vec<u32> = (0..keys.len() as u32).collect();
        order.sort_by(|&i, &j| {
            let (fi, fj) = (&keys[i as usize], &keys[j as usize]);
            fi.value(start)
                .total_cmp(&fj.value(start))
                .then(slope(fi, start).total_cmp(&slope(fj, start)))
                .then(i.cmp(&j))
        });
        let n = order.len();
        if n < 2 {
            return Ok(());
        }
        let mut stamp = vec![0u64; n - 1];
        let mut heap = BinaryHeap::new();
        let pair =
            |order: &[u32], p: usize| keys[order[p + 1] as usize].minus(&keys[order[p] as usize]);
        for p in 0..n - 1 {
            // Tied at `start` (to within the root's rounding), the two swap there: they are
            // sorted as just after it, so the pair's rising root is at `start`. Over a full
            // period that is the breakpoint between the last cell and the first, which the
            // search below (falling roots, after `start`) never gives.
            let g = pair(&order, p);
            if let Roots::Two { up, .. } = g.roots() {
                let after = crate::event::reduce(up, start) - start;
                if after.min(TAU - after) <= SAME_ROOT_RAD.max(g.root_uncertainty()) {
                    out.push(Event {
                        theta: start,
                        function: g,
                    });
                }
            }
            if let Some(t) = next_down(&g, start) {
                heap.push(Reverse((Time(t), p, 0u64)));
            }
        }
        budget(out.len(), max_events)?;
        while let Some(Reverse((Time(t), p, s))) = heap.pop() {
            if t >= end {
                break;
            }
            if stamp[p] != s {
                continue;
            }
            let g = pair(&order, p);
            order.swap(p, p + 1);
            out.push(Event {
                theta: t.max(start),
                function: g,
            });
            budget(out.len(), max_events)?;
            let first = p.saturating_sub(1);
            for (q, st) in stamp
                .iter_mut()
                .enumerate()
                .take((p + 2).min(n - 1))
                .skip(first)
            {
                *st += 1;
                if let Some(next) = next_down(&pair(&order, q), t) {
                    heap.push(Reverse((Time(next), q, *st)));
                }
            }
        }
        Ok(())
    }
}
