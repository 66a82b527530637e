//! A [`Presorted`]'s certificate as data, for realisations that run no sorter: a page whose
//! script only looks up the region of the viewer and shows its order.

use std::sync::Arc;

use glam::DVec3;

use super::region::Region;
use super::{CORE, NodeKind, Presorted};
use crate::{DrawList, Plane, PolygonSet, View};

/// Most planes of a cycle's BSP tree whose side varies over a region's viewers, which
/// [`CertifiedOrders`] enumerates (a cycle's orders number `2^planes`).
pub const MAX_CORE_PLANES: usize = 12;

/// One step of a certified order: a piece, or a cycle whose order depends on the viewer's
/// side of a few planes ([`CoreOrders`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrderStep {
    /// A piece: an index into [`CertifiedOrders::pieces`].
    Piece(u32),
    /// A cycle: an index into [`CertifiedOrders::cores`].
    Core(u32),
}

/// A region of directions toward the viewer (a spherical triangle in centred model space)
/// and the order certified for it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CertifiedRegion {
    /// Inward normals of the triangle's edges: the unit direction `u` from the geometry's
    /// centre toward the viewer (the eye, or the orthographic direction) is in the region
    /// when `n · u ≥ 0` for all three. Regions share edges; a direction on one is in both,
    /// and either order is exact there.
    pub edge_normals: [DVec3; 3],
    /// The triangle's corners (unit vectors, counter-clockwise seen from outside).
    pub corners: [DVec3; 3],
    /// Index into [`CertifiedOrders::orders`].
    pub order: u32,
}

/// A cycle's orders: a BSP tree of its own pieces, flattened for every side of its planes.
#[derive(Clone, Debug, PartialEq)]
pub struct CoreOrders {
    /// Planes in centred model space. Bit `k` of a viewer's key is set when it is on or in
    /// front of plane `k`: `n · e − offset ≥ 0` for an eye `e`, `n · u ≥ 0` for an
    /// orthographic direction `u`.
    pub planes: Vec<Plane>,
    /// Per key (`2^planes.len()` of them), the cycle's pieces (indices into
    /// [`CertifiedOrders::pieces`]) in paint order, back faces included: exact for every
    /// viewer with that key once the sink culls back faces.
    pub orders: Vec<Vec<u32>>,
}

/// Every order a [`Presorted`] certified for one kind of viewer: orthographic, or an eye at
/// one distance from the geometry's centre ([`Presorted::certified_orders`]).
///
/// A sink that hides back faces draws exactly when it paints, for a viewer in direction `u`,
/// the pieces of the order of a region holding `u` in sequence, each [`OrderStep::Core`]
/// replaced by that cycle's order for the viewer's key. Nothing else depends on the viewer.
#[derive(Clone, Debug)]
pub struct CertifiedOrders {
    /// The pieces: the geometry's, cut where they pass through each other, then every
    /// cycle's fragments. Corners are centred model space.
    pub pieces: Arc<PolygonSet>,
    /// The regions; together they cover every direction.
    pub regions: Vec<CertifiedRegion>,
    /// The orders regions refer to.
    pub orders: Vec<Vec<OrderStep>>,
    /// The cycles orders refer to.
    pub cores: Vec<CoreOrders>,
}

/// Regions, orders and cycles collected so far.
type Collected<'a> = (
    &'a mut Vec<CertifiedRegion>,
    &'a mut Vec<Vec<OrderStep>>,
    &'a mut Vec<CoreOrders>,
);

/// Most times a region is quartered so that its cycles have at most [`MAX_CORE_PLANES`]
/// planes whose side varies.
const CYCLE_SPLITS: usize = 4;

/// Why [`Presorted::certified_orders`] cannot give the orders of a kind of viewer.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CertifiedOrdersError {
    /// The eye is nearer the centre than the certificate reaches
    /// ([`PresortOptions::min_eye_distance`](crate::PresortOptions::min_eye_distance)), or
    /// the distance is not a number.
    #[error("an eye {distance} from the centre is nearer than the certified {near}")]
    TooNear {
        /// The eye distance asked for.
        distance: f64,
        /// The nearest certified distance.
        near: f64,
    },
    /// Some regions of these viewers have no certified order (their views fall back to the
    /// BSP), or the build stopped on a budget.
    #[error("{regions} regions of directions have no certified order")]
    Uncertified {
        /// How many regions (all eight octants when there is no certificate).
        regions: usize,
    },
    /// A cycle's BSP tree has more planes than [`MAX_CORE_PLANES`] whose side varies over
    /// its region's viewers.
    #[error(
        "a cycle's BSP tree has {planes} planes whose side varies over its region, more than {MAX_CORE_PLANES}"
    )]
    CorePlanes {
        /// Its planes.
        planes: usize,
    },
}

impl CertifiedOrders {
    /// The list a sink that hides back faces paints for `view` when it follows these orders:
    /// the region deepest around the direction toward the viewer, its cycles by the viewer's
    /// side of their planes, and back faces left out. This is what a page's script does, for
    /// checking it; `view` must be of the kind the orders were made for (orthographic, or its
    /// eye at their distance), with back faces culled.
    pub fn play(&self, view: &View, out: &mut DrawList) {
        out.begin(&self.pieces);
        let (point, w) = view.cull_test().viewer_point();
        let Some(u) = point.try_normalize() else {
            return;
        };
        let depth = |r: &CertifiedRegion| {
            r.edge_normals
                .iter()
                .map(|n| n.dot(u))
                .fold(f64::INFINITY, f64::min)
        };
        let Some(region) = self
            .regions
            .iter()
            .max_by(|a, b| depth(a).total_cmp(&depth(b)))
        else {
            return;
        };
        let side = |plane: &Plane| {
            let n = plane.normal();
            n.x * point.x + n.y * point.y + n.z * point.z - w * plane.offset()
        };
        let mut draw = |p: u32| {
            if side(self.pieces.plane(p as usize)) > 0.0 {
                out.push(p, self.pieces.face(p as usize));
            }
        };
        for step in &self.orders[region.order as usize] {
            match *step {
                OrderStep::Piece(p) => draw(p),
                OrderStep::Core(c) => {
                    let core = &self.cores[c as usize];
                    let key = core.planes.iter().enumerate().fold(0, |key, (k, plane)| {
                        key | usize::from(side(plane) >= 0.0) << k
                    });
                    for &p in &core.orders[key] {
                        draw(p);
                    }
                }
            }
        }
    }
}

impl Presorted {
    /// The pieces orders refer to: the geometry's, cut where they pass through each other,
    /// then every cycle's fragments; corners in centred model space.
    #[must_use]
    pub fn pieces(&self) -> &Arc<PolygonSet> {
        &self.shared
    }

    /// How many of [`pieces`](Self::pieces) come first as the geometry's pieces cut where
    /// they pass through each other: those tile every face once (the rest are cycles'
    /// fragments, which tile their cycle's pieces again).
    #[must_use]
    pub fn cut_pieces(&self) -> usize {
        self.pieces
    }

    /// Every certified order as stored, one per leaf region, back faces included: a sink
    /// that culls back faces itself (a GPU) draws a leaf without cycles as it stands; an
    /// [`OrderStep::Core`] is a cycle that [`sort_culled`](Self::sort_culled) orders per
    /// frame (its index is the cycle's, not one of [`CertifiedOrders::cores`]).
    #[must_use]
    pub fn leaf_orders(&self) -> Vec<Vec<OrderStep>> {
        self.leaves
            .iter()
            .map(|leaf| {
                leaf.pieces
                    .iter()
                    .map(|&p| {
                        if p & CORE == 0 {
                            OrderStep::Piece(p)
                        } else {
                            OrderStep::Core(p & !CORE)
                        }
                    })
                    .collect()
            })
            .collect()
    }

    /// The index into [`leaf_orders`](Self::leaf_orders) of the order
    /// [`sort_culled`](Self::sort_culled) follows for this viewer, or why the certificate
    /// does not cover it (then `sort_culled` falls back to the whole BSP). A region lookup,
    /// no allocation; the fallback count is not touched.
    ///
    /// # Errors
    /// The [`FallbackReason`](crate::FallbackReason) of a view the certificate does not cover.
    pub fn leaf_for(&mut self, cull: &crate::CullTest) -> Result<usize, super::FallbackReason> {
        self.locate(cull).map(|leaf| leaf as usize)
    }

    /// The certified orders for orthographic viewers (`eye_distance: None`) or eyes at
    /// `eye_distance` from the geometry's centre (centred model units: a [`View`]
    /// with perspective distance `d` pixels and scale `s` has its eye at `d / s`).
    ///
    /// # Errors
    /// [`CertifiedOrdersError`]: an eye too near, regions left uncertified, or a cycle too
    /// large to enumerate.
    pub fn certified_orders(
        &self,
        eye_distance: Option<f64>,
    ) -> Result<CertifiedOrders, CertifiedOrdersError> {
        let t = eye_distance.unwrap_or(f64::INFINITY);
        if t.is_nan() || t < self.near {
            return Err(CertifiedOrdersError::TooNear {
                distance: t,
                near: self.near,
            });
        }
        if self.nodes.is_empty() {
            return Err(CertifiedOrdersError::Uncertified { regions: 8 });
        }
        let mut regions = Vec::new();
        let mut leaf_order: Vec<Option<u32>> = vec![None; self.leaves.len()];
        let mut orders = Vec::new();
        let mut cores = Vec::new();
        let mut uncertified = 0;
        let mut stack: Vec<usize> = (0..8).rev().collect();
        while let Some(k) = stack.pop() {
            let node = &self.nodes[k];
            match node.kind {
                NodeKind::Directions { first } => {
                    stack.extend((first as usize..first as usize + 4).rev());
                }
                NodeKind::Distance { mid, first } => {
                    stack.push(first as usize + usize::from(t >= mid));
                }
                NodeKind::Uncertified => uncertified += 1,
                NodeKind::Leaf(leaf) => {
                    let stored = &self.leaves[leaf as usize];
                    if stored.pieces.iter().any(|&step| step & CORE != 0) {
                        let mut out = (&mut regions, &mut orders, &mut cores);
                        self.with_cycles(leaf, node.region, t, 0, &mut out)?;
                        continue;
                    }
                    let order = *leaf_order[leaf as usize].get_or_insert_with(|| {
                        orders.push(stored.pieces.iter().map(|&p| OrderStep::Piece(p)).collect());
                        orders.len() as u32 - 1
                    });
                    regions.push(CertifiedRegion {
                        edge_normals: node.region.edge_normals(),
                        corners: node.region.corners,
                        order,
                    });
                }
            }
        }
        if uncertified > 0 {
            return Err(CertifiedOrdersError::Uncertified {
                regions: uncertified,
            });
        }
        Ok(CertifiedOrders {
            pieces: Arc::clone(&self.shared),
            regions,
            orders,
            cores,
        })
    }

    /// Leaf `leaf`'s order for the viewers of `region` (part of its own) at distance `t`,
    /// with its cycles flattened for them; where a cycle has too many planes whose side
    /// varies over the region, each quarter of the region instead (at most
    /// [`CYCLE_SPLITS`] times).
    fn with_cycles(
        &self,
        leaf: u32,
        region: Region,
        t: f64,
        depth: usize,
        out: &mut Collected<'_>,
    ) -> Result<(), CertifiedOrdersError> {
        let stored = &self.leaves[leaf as usize];
        let mut cores = Vec::new();
        let mut steps = Vec::with_capacity(stored.pieces.len());
        for &step in &stored.pieces {
            if step & CORE == 0 {
                steps.push(OrderStep::Piece(step));
                continue;
            }
            match self.core_orders((step & !CORE) as usize, &region, t) {
                Ok(core) => {
                    steps.push(OrderStep::Core((out.2.len() + cores.len()) as u32));
                    cores.push(core);
                }
                Err(CertifiedOrdersError::CorePlanes { .. }) if depth < CYCLE_SPLITS => {
                    for child in region.split_directions() {
                        self.with_cycles(leaf, child, t, depth + 1, out)?;
                    }
                    return Ok(());
                }
                Err(e) => return Err(e),
            }
        }
        out.2.extend(cores);
        out.1.push(steps);
        out.0.push(CertifiedRegion {
            edge_normals: region.edge_normals(),
            corners: region.corners,
            order: out.1.len() as u32 - 1,
        });
        Ok(())
    }

    /// Core `c`'s tree flattened for every side of its inner planes that the viewers of
    /// `region` at distance `t` (∞: orthographic) may take; a plane every such viewer is on
    /// the same side of is decided once.
    fn core_orders(
        &self,
        c: usize,
        region: &Region,
        t: f64,
    ) -> Result<CoreOrders, CertifiedOrdersError> {
        let core = &self.cores[c];
        let rows = core.tree.inner_planes();
        let fixed: Vec<Option<bool>> = (rows.iter())
            .map(|plane| side_over(plane, region, t))
            .collect();
        let free: Vec<usize> = (0..rows.len()).filter(|&k| fixed[k].is_none()).collect();
        if free.len() > MAX_CORE_PLANES {
            return Err(CertifiedOrdersError::CorePlanes { planes: free.len() });
        }
        let mut bit_of = vec![usize::MAX; rows.len()];
        for (bit, &k) in free.iter().enumerate() {
            bit_of[k] = bit;
        }
        let mut orders = Vec::with_capacity(1 << free.len());
        let mut order = Vec::new();
        for key in 0..1usize << free.len() {
            core.tree.order_for_sides(
                &|k| fixed[k].unwrap_or_else(|| key >> bit_of[k] & 1 == 1),
                &mut order,
            );
            orders.push(order.iter().map(|&f| core.offset + f).collect());
        }
        Ok(CoreOrders {
            planes: free.iter().map(|&k| rows[k]).collect(),
            orders,
        })
    }
}

/// The side (`true`: on or in front) of plane `row` that every viewer of `region` (grown by
/// [`PRESORT_GROWTH`](crate::tolerance::PRESORT_GROWTH)) at distance `t` is on, if they
/// share one. Orthographic: `n · u` is linear over the triangle's cone, so its corners
/// decide. An eye `t · u`: `n · u` lies within `|n|·cos(α ± ρ)` for the angle `α` between `n`
/// and the triangle's centre and the triangle's angular radius `ρ`.
fn side_over(plane: &Plane, region: &Region, t: f64) -> Option<bool> {
    let grown = region.grown();
    let n = plane.normal();
    let (lo, hi) = if t.is_infinite() {
        let values = grown.corners.map(|c| n.dot(c));
        (
            values.iter().copied().fold(f64::INFINITY, f64::min),
            values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    } else {
        let (length, m, rho) = (n.length(), grown.centre(), grown.angular_radius());
        let alpha = (n.dot(m) / length).clamp(-1.0, 1.0).acos();
        let near = length * (alpha - rho).max(0.0).cos();
        let far = length * (alpha + rho).min(std::f64::consts::PI).cos();
        (t * far - plane.offset(), t * near - plane.offset())
    };
    if lo > 0.0 {
        Some(true)
    } else if hi < 0.0 {
        Some(false)
    } else {
        None
    }
}
