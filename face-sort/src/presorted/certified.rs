//! A [`Presorted`]'s certificate as data, for realisations that run no sorter: a page whose
//! script only looks up the region of the viewer and shows its order.

use std::sync::Arc;

use glam::DVec3;

use super::{CORE, NodeKind, Presorted};
use crate::PolygonSet;

/// Most inner planes of a cycle's BSP tree that [`CertifiedOrders`] enumerates the sides of
/// (its orders number `2^planes`).
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
    /// Plane rows `[nx, ny, nz, offset]` in centred model space. Bit `k` of a viewer's key is
    /// set when it is on or in front of plane `k`: `n · e − offset ≥ 0` for an eye `e`,
    /// `n · u ≥ 0` for an orthographic direction `u`.
    pub planes: Vec<[f64; 4]>,
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
    /// A cycle's BSP tree has more planes than [`MAX_CORE_PLANES`].
    #[error("a cycle's BSP tree has {planes} planes, more than {MAX_CORE_PLANES}")]
    CorePlanes {
        /// Its planes.
        planes: usize,
    },
}

impl Presorted {
    /// The certified orders for orthographic viewers (`eye_distance: None`) or eyes at
    /// `eye_distance` from the geometry's centre (centred model units: a [`View`](crate::View)
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
        let mut core_index: Vec<Option<u32>> = vec![None; self.cores.len()];
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
                    let order = match leaf_order[leaf as usize] {
                        Some(order) => order,
                        None => {
                            let steps = self.leaves[leaf as usize]
                                .pieces
                                .iter()
                                .map(|&step| {
                                    if step & CORE == 0 {
                                        return Ok(OrderStep::Piece(step));
                                    }
                                    let c = (step & !CORE) as usize;
                                    if core_index[c].is_none() {
                                        cores.push(self.core_orders(c)?);
                                        core_index[c] = Some(cores.len() as u32 - 1);
                                    }
                                    Ok(OrderStep::Core(core_index[c].unwrap_or_default()))
                                })
                                .collect::<Result<Vec<_>, _>>()?;
                            orders.push(steps);
                            let order = orders.len() as u32 - 1;
                            leaf_order[leaf as usize] = Some(order);
                            order
                        }
                    };
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

    /// Core `c`'s tree flattened for every side of its inner planes.
    fn core_orders(&self, c: usize) -> Result<CoreOrders, CertifiedOrdersError> {
        let core = &self.cores[c];
        let planes = core.tree.inner_rows();
        if planes.len() > MAX_CORE_PLANES {
            return Err(CertifiedOrdersError::CorePlanes {
                planes: planes.len(),
            });
        }
        let mut orders = Vec::with_capacity(1 << planes.len());
        let mut order = Vec::new();
        for key in 0..1usize << planes.len() {
            core.tree
                .order_for_sides(&|k| key >> k & 1 == 1, &mut order);
            orders.push(order.iter().map(|&f| core.offset + f).collect());
        }
        Ok(CoreOrders { planes, orders })
    }
}
