//! Baked realisation: precomputed painter orders over an animation angle, as data.
//!
//! `aspect-bake` computes cells `[lo, hi)` of an angle with a constant painter order
//! ([`Bake`]); this module realises a bake as one container per cell, shown only while the
//! angle lies in the cell ([`BakedSpriteTree`]). A
//! backend turns each container's [`AngleRange`] into its own animation expression (e.g. a
//! composition expression or CSS), so that the animation needs no per-frame CPU.

use std::sync::{Arc, Mutex};

use face_sort::{Geometry, PolygonSet, View};
use glam::{DMat3, DVec2, DVec3};

use aspect_bake::{AngleRange, Bake};

use crate::{Brush, PieceMap, PieceMaps, SpriteSpace, SpriteTransform};

/// One sprite of a baked container.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BakedSprite {
    /// Polygon of the bake (its transform and clip: [`BakedSpriteTree::polygon_map`]).
    pub polygon: u32,
    /// Source face (its brush: [`BakedSpriteTree::brush`]).
    pub face: u32,
}

/// A container: its sprites in paint order, shown only while the angle is in `visible_while`.
#[derive(Clone, Debug, PartialEq)]
pub struct BakedContainer {
    /// The visibility predicate.
    pub visible_while: AngleRange,
    /// Sprites, back to front.
    pub sprites: Vec<BakedSprite>,
}

/// A bake realised as a sprite tree: under the root, one container per cell of the bake
/// holding that cell's sprites in paint order, each sprite with a fixed transform, and each
/// container shown only while the angle lies in its cell. Swapping materials only changes
/// [`brush`](Self::brush) results; the containers are reused.
#[derive(Clone, Debug)]
pub struct BakedSpriteTree {
    maps: Vec<Option<PieceMap>>,
    containers: Vec<BakedContainer>,
    brushes: Vec<Brush>,
}

impl BakedSpriteTree {
    /// Realises `bake` for `geometry` in the sprite space of `view` (scale and size). A
    /// polygon gets its source piece's transform (matched by face and plane) and a clip
    /// polygon unless it is a whole quad piece. Polygons without a piece map are left out.
    #[must_use]
    pub fn realise(bake: &Bake, geometry: &Geometry, view: &View) -> Self {
        let set = &bake.polygons();
        let polygon_maps = polygon_maps(set, geometry, view);
        let containers = bake
            .cells()
            .iter()
            .map(|cell| BakedContainer {
                visible_while: cell.range,
                sprites: cell
                    .order
                    .iter()
                    .filter(|&&p| polygon_maps.get(p as usize).is_some_and(Option::is_some))
                    .map(|&p| BakedSprite {
                        polygon: p,
                        face: set.face(p as usize),
                    })
                    .collect(),
            })
            .collect();
        BakedSpriteTree {
            maps: polygon_maps,
            containers,
            brushes: vec![Brush::Palette; geometry.face_count()],
        }
    }

    /// The containers.
    #[must_use]
    pub fn containers(&self) -> &[BakedContainer] {
        &self.containers
    }

    /// Index of the container shown at `angle` (the first whose range contains it).
    #[must_use]
    pub fn container_at(&self, angle: f64) -> Option<usize> {
        self.containers
            .iter()
            .position(|c| c.visible_while.contains(angle))
    }

    /// Transform and clip of a bake polygon.
    #[must_use]
    pub fn polygon_map(&self, polygon: u32) -> Option<(&SpriteTransform, Option<&[DVec2]>)> {
        self.maps
            .get(polygon as usize)?
            .as_ref()
            .map(|m| (&m.transform, m.clip.as_deref()))
    }

    /// Brush of a face.
    #[must_use]
    pub fn brush(&self, face: u32) -> Brush {
        self.brushes
            .get(face as usize)
            .copied()
            .unwrap_or(Brush::Palette)
    }

    /// Reassigns brushes; returns how many baked sprites (over all containers) must be told,
    /// i.e. the `set_brush` operations a retained backend receives. Nothing else changes.
    pub fn set_brushes(&mut self, mut brush: impl FnMut(u32) -> Brush) -> usize {
        let mut changed = vec![false; self.brushes.len()];
        for (face, b) in self.brushes.iter_mut().enumerate() {
            let new = brush(face as u32);
            changed[face] = new != *b;
            *b = new;
        }
        self.containers
            .iter()
            .flat_map(|c| &c.sprites)
            .filter(|s| changed.get(s.face as usize).copied().unwrap_or(false))
            .count()
    }

    /// Total sprites over all containers (memory grows with cells × visible polygons).
    #[must_use]
    pub fn sprite_count(&self) -> usize {
        self.containers.iter().map(|c| c.sprites.len()).sum()
    }
}

/// Per polygon of `set` (e.g. a bake's polygons), its source piece's transform in the sprite
/// space of `view` (the piece of the same face whose plane is nearest the polygon's) and a
/// clip polygon unless it is that whole piece; `None` when no piece has a map.
#[must_use]
pub fn polygon_maps(set: &PolygonSet, geometry: &Geometry, view: &View) -> Vec<Option<PieceMap>> {
    let maps = PieceMaps::new(geometry, view);
    let space = *maps.space();
    let pieces = geometry.pieces();
    let mut pieces_of: std::collections::HashMap<u32, Vec<usize>> =
        std::collections::HashMap::new();
    for p in 0..pieces.len() {
        pieces_of.entry(pieces.face(p)).or_default().push(p);
    }
    (0..set.len())
        .map(|i| {
            let (face, plane, corners) = (set.face(i), set.plane(i), set.corners(i));
            let piece = pieces_of.get(&face)?.iter().copied().max_by(|&a, &b| {
                let s = |p: usize| pieces.plane(p).normal().dot(plane.normal());
                s(a).total_cmp(&s(b))
            })?;
            let map = maps.get(piece)?;
            let clip = if map.clip.is_none() && pieces.corners(piece) == corners {
                None
            } else {
                Some(clip_of(&space, &map.transform, corners))
            };
            Some(PieceMap {
                transform: map.transform,
                clip,
            })
        })
        .collect()
}

fn clip_of(space: &SpriteSpace, t: &SpriteTransform, corners: &[DVec3]) -> Vec<DVec2> {
    corners
        .iter()
        .map(|&c| t.unit_coords(space.point(c)))
        .collect()
}

/// A shared, swappable holder of the [`BakedSpriteTree`] being shown: a new tree (baked on
/// any thread, e.g. after the model changed) replaces it in one step, and every clone of
/// the slot sees the replacement.
#[derive(Clone, Debug)]
pub struct BakedTreeSlot {
    current: Arc<Mutex<Arc<BakedSpriteTree>>>,
}

impl BakedTreeSlot {
    /// A slot showing `graph`.
    #[must_use]
    pub fn new(graph: BakedSpriteTree) -> Self {
        BakedTreeSlot {
            current: Arc::new(Mutex::new(Arc::new(graph))),
        }
    }

    /// The graph shown now.
    #[must_use]
    pub fn load(&self) -> Arc<BakedSpriteTree> {
        match self.current.lock() {
            Ok(g) => Arc::clone(&g),
            Err(poisoned) => Arc::clone(&poisoned.into_inner()),
        }
    }

    /// Shows `graph` from now on.
    pub fn store(&self, graph: BakedSpriteTree) {
        let graph = Arc::new(graph);
        match self.current.lock() {
            Ok(mut g) => *g = graph,
            Err(poisoned) => *poisoned.into_inner() = graph,
        }
    }
}

/// For convex meshes no order is needed, only culling: face `i` is drawn while
/// `a · cos θ + b · sin θ + c > 0` (the front-facing test of CONVENTIONS.md as a function of
/// a yaw angle `θ` applied on top of a base rotation). Replaces cells entirely.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FacingPredicate {
    /// Coefficient of `cos θ`.
    pub a: f64,
    /// Coefficient of `sin θ`.
    pub b: f64,
    /// Constant.
    pub c: f64,
}

impl FacingPredicate {
    /// Whether the face is drawn at yaw `degrees`.
    #[must_use]
    pub fn is_drawn(&self, degrees: f64) -> bool {
        let t = degrees.to_radians();
        self.a * t.cos() + self.b * t.sin() + self.c > 0.0
    }

    /// The predicate as an expression over a variable holding the angle in degrees.
    #[must_use]
    pub fn to_expression(&self, variable: &str) -> String {
        format!(
            "({:e} * cos({variable} * {r:e}) + {:e} * sin({variable} * {r:e}) + {:e} > 0)",
            self.a,
            self.b,
            self.c,
            r = std::f64::consts::PI / 180.0
        )
    }
}

/// The facing predicate of every piece of `geometry` for views `Ry(θ) · view.rotation()`
/// (a yaw spin on top of `view`'s rotation), for counter-clockwise fronts and back-face
/// culling, without margin. Orthographic: `(R n)·ẑ`; perspective: `(R n)·(e − R v₀)`.
#[must_use]
pub fn convex_facing_predicates(geometry: &Geometry, view: &View) -> Vec<FacingPredicate> {
    let pieces = geometry.pieces();
    let base: DMat3 = view.rotation();
    (0..pieces.len())
        .map(|i| {
            let n = base * pieces.plane(i).normal();
            // Ry(θ)·n has z = −sin θ · n.x + cos θ · n.z.
            match view.eye_in_view() {
                None => FacingPredicate {
                    a: n.z,
                    b: -n.x,
                    c: 0.0,
                },
                Some(eye) => {
                    let v0 = base * pieces.corners(i)[0];
                    FacingPredicate {
                        a: eye.z * n.z,
                        b: -eye.z * n.x,
                        c: -n.dot(v0),
                    }
                }
            }
        })
        .collect()
}
