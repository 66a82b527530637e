//! The planner: look at a geometry once and pick the cheapest exact way to order it.
//!
//! [`Plan::analyse`] proves what it can about a geometry and records the strategy with its
//! reason; [`Auto`] is the [`FaceSorter`] that follows the plan.
//!
//! - **Convex position → [`CullOnly`].** When every piece's plane has all of the geometry's
//!   vertices on one side (all on the back side: outward normals; all on the front side:
//!   inward normals), the pieces lie on the boundary of one convex body. A ray meets that
//!   boundary at most twice: once where it enters (the entry piece faces the viewer when
//!   normals point outward) and once where it leaves. So no two entry pieces overlap on
//!   screen, no two exit pieces do, and every exit piece lies behind every entry piece it
//!   overlaps: drawing the drawn exit pieces first, then the drawn entry pieces, is exact for
//!   every view, projection and cull mode. Under back-face culling with no margin only entry
//!   pieces are drawn, so this is culling alone: no sort, no fragments. The proof is exact up
//!   to [`PLANE_SIDE`] and costs one support query per piece against a bounding-volume
//!   hierarchy of the vertices.
//! - **Separate convex parts → [`ConvexParts`].** A mesh made of several connected parts
//!   (pieces sharing no vertex), each in convex position, whose bounding boxes an
//!   axis-aligned tree of planes separates (every box entirely on one side of each plane):
//!   across such a plane nothing on the side away from the viewer can cover anything on the
//!   viewer's side (along a ray from the viewer the plane's coordinate changes monotonically),
//!   so the tree, walked far side first, orders the parts as wholes, and inside each part the
//!   convex-position argument above needs no sort. Per frame: a walk over the part tree and
//!   one culling pass; no fragments. Boxes that overlap (interlocking or nested parts) leave
//!   the choice to the next rule.
//! - **Otherwise the cheaper exact sorter for the frames the caller will draw.** [`Newell`]
//!   needs no tree (for a few frames, no build at all: `NEWELL_COVERAGE_FRAMES`) and draws
//!   almost no extra items; [`Bsp`] pays a build once and then traverses cheaply;
//!   [`Presorted`](crate::Presorted) pays a build near `n log n` (with a constant about 70
//!   times the BSP's) and then only looks up and culls
//!   (about a third of the BSP's frame, no extra items), so it wins only for callers that
//!   announce very many frames (about `4,500 · log2 n`: on spot, about 57,000). The model counts the sorter's
//!   time only, not the sink's per item.
//!   [`PlanHint::frames`] says how many frames the build is spread over: one picture (an
//!   export) is [`PlanHint::ONE_FRAME`]. The cost model and its measured
//!   constants are [`CostModel`].

use std::sync::Arc;

use glam::DVec3;

use crate::tolerance::PLANE_SIDE;
use crate::{
    Bsp, BspFallback, BspOptions, DrawList, FaceSorter, Geometry, Newell, PolygonSet, SorterStats,
    View,
};

/// What the caller will do with the sorter, for the planner's cost model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlanHint {
    /// Frames the caller expects to draw with one sorter (at least 1).
    pub frames: u64,
}

impl PlanHint {
    /// One picture: an export, a one-shot render.
    pub const ONE_FRAME: PlanHint = PlanHint { frames: 1 };
    /// An animation or an interactive view: many frames share one build.
    pub const ANIMATION: PlanHint = PlanHint { frames: 10_000 };
}

impl Default for PlanHint {
    fn default() -> Self {
        PlanHint::ANIMATION
    }
}

/// Which way the planner orders.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strategy {
    /// [`CullOnly`]: the geometry is in convex position; culling (exit pieces, then entry
    /// pieces) is the whole order.
    CullOnly,
    /// [`ConvexParts`]: separate parts, each in convex position, separated by axis-aligned
    /// planes; ordered as wholes by those planes, culling alone inside each.
    ConvexParts,
    /// [`Newell`]: no build; cheapest for few frames.
    Newell,
    /// [`Bsp`]: a build amortised over many frames.
    Bsp,
    /// [`Presorted`](crate::Presorted): a costly build, then a lookup and a cull per frame;
    /// for callers that announce very many frames.
    Presorted,
}

impl Strategy {
    /// Lower-case name, as the sorters name themselves.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Strategy::CullOnly => "cull-only",
            Strategy::ConvexParts => "convex-parts",
            Strategy::Newell => "newell",
            Strategy::Bsp => "bsp",
            Strategy::Presorted => "presorted",
        }
    }
}

/// Per-piece costs of the exact sorters, in nanoseconds on the reference machine, from
/// which the planner predicts the cheaper one. Only their ratios matter.
///
/// Measured with `cargo run --release -p face-sort --example plan_costs` (spot, blub and
/// generated tori, orthographic; the example prints these medians) on the reference
/// machine's two cores: the BSP build uses every core ([`BspOptions::threads`]), so on one
/// core it costs more. The build per piece and level stays nearly constant as the piece
/// count grows: the `n log n` model fits since large sets may split at a median plane.
/// `Newell`'s own set-up (its pieces' edge neighbours) is left out: counted, it would move
/// the break-even frame count between the two only a little. The measurements are in
/// docs/bench.md.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CostModel {
    /// BSP build, per piece and per level (`n · log2 n` pieces·levels).
    pub bsp_build_per_piece_level: f64,
    /// BSP traversal per frame, per piece.
    pub bsp_frame_per_piece: f64,
    /// Newell per frame, per piece.
    pub newell_frame_per_piece: f64,
    /// Presorted build, per piece and per level (`n · log2 n`). `cargo run --release -p
    /// face-sort --example presort_models` prints it for spot, blub and the scan-like blob on
    /// one thread; the build on every core costs about half of that. The constant lies
    /// between the models'.
    pub presorted_build_per_piece_level: f64,
    /// Presorted per frame (region lookup and cull), per piece (the same example).
    pub presorted_frame_per_piece: f64,
}

impl CostModel {
    /// The constants measured on this repository's models (see the type's docs).
    pub const MEASURED: CostModel = CostModel {
        bsp_build_per_piece_level: 262.0,
        bsp_frame_per_piece: 5.8,
        newell_frame_per_piece: 88.0,
        presorted_build_per_piece_level: 18_000.0,
        presorted_frame_per_piece: 1.9,
    };

    /// Predicted nanoseconds of a `Presorted` build of `n` pieces.
    fn presorted_build(&self, n: f64) -> f64 {
        self.presorted_build_per_piece_level * n * n.log2().max(1.0)
    }

    /// Predicted nanoseconds for `pieces` pieces over `frames` frames.
    #[must_use]
    pub fn predict(&self, strategy: Strategy, pieces: usize, frames: u64) -> f64 {
        let n = pieces.max(1) as f64;
        let frames = frames.max(1) as f64;
        match strategy {
            Strategy::CullOnly | Strategy::ConvexParts => 0.0,
            Strategy::Newell => frames * self.newell_frame_per_piece * n,
            Strategy::Bsp => {
                self.bsp_build_per_piece_level * n * n.log2().max(1.0)
                    + frames * self.bsp_frame_per_piece * n
            }
            Strategy::Presorted => {
                self.presorted_build(n) + frames * self.presorted_frame_per_piece * n
            }
        }
    }
}

/// The planner's decision and why.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// What to run.
    pub strategy: Strategy,
    /// One line a person can read, e.g. `convex position → cull only`.
    pub reason: String,
    /// What the strategy's sorter needs from the analysis.
    found: Found,
    /// The frames the caller said it will draw ([`PlanHint::frames`]).
    frames: u64,
}

/// From this many frames on, the planner's [`Newell`] finds its pieces' edge neighbours for
/// the coverage test: about as many frames as that one-time set-up takes to pay for itself
/// on spot, blub and the bumpy 10k torus. On the bumpy 1k torus, fandisk and suzanne it
/// barely pays or not at all (the test stops on meshes that fold over themselves, and small
/// cascades are cheap), and on 64 separate spheres never (the planner orders those as convex
/// parts). Since Newell's cascade queries its screen grid in depth order, a frame without the
/// test costs far less than before the test existed, so the test pays back later than it did
/// then. The measurements are in docs/bench.md.
const NEWELL_COVERAGE_FRAMES: u64 = 10;

/// What a [`Plan`]'s analysis found for its sorter.
#[derive(Clone, Debug, PartialEq)]
enum Found {
    /// Convex position: whether exit pieces are the back-facing ones (outward normals)
    /// rather than the front-facing ones (inward normals).
    Convex { exits_face_away: bool },
    /// Separate convex parts and the planes between them.
    Parts(Arc<PartTree>),
    /// Nothing (Newell and BSP need no analysis).
    Nothing,
}

impl Plan {
    /// Analyses `geometry` once, with the measured [`CostModel`].
    #[must_use]
    pub fn analyse(geometry: &Geometry, hint: PlanHint) -> Plan {
        Plan::analyse_with(geometry, hint, &CostModel::MEASURED)
    }

    /// Analyses `geometry` once, with a caller's cost model.
    #[must_use]
    pub fn analyse_with(geometry: &Geometry, hint: PlanHint, costs: &CostModel) -> Plan {
        let pieces = geometry.pieces();
        if let Some(exits_face_away) = convex_position(pieces, geometry.bounds().diagonal()) {
            let normals = if exits_face_away { "outward" } else { "inward" };
            return Plan {
                strategy: Strategy::CullOnly,
                reason: format!(
                    "convex position ({} pieces, normals {normals}) → cull only: no sort, no fragments",
                    pieces.len()
                ),
                found: Found::Convex { exits_face_away },
                frames: hint.frames,
            };
        }
        if let Some(tree) = PartTree::analyse(geometry) {
            return Plan {
                strategy: Strategy::ConvexParts,
                reason: format!(
                    "{} separate parts in convex position, split by {} axis-aligned planes ({} pieces) → parts ordered as wholes, cull only inside: no sort, no fragments",
                    tree.parts.len(),
                    tree.parts.len() - 1,
                    pieces.len()
                ),
                found: Found::Parts(Arc::new(tree)),
                frames: hint.frames,
            };
        }
        let n = pieces.len();
        let frames = hint.frames.max(1);
        let frame_words = if frames == 1 {
            "one frame".to_owned()
        } else {
            format!("{frames} frames")
        };
        // Presorted only when its build is predicted to finish within its own time budget
        // (a refused build would leave every frame to the BSP after paying for it).
        let budget_ns = crate::PresortOptions::default()
            .max_build_time
            .as_secs_f64()
            * 1e9;
        let presort_build_ns = costs.presorted_build(n.max(1) as f64);
        let over_budget = presort_build_ns > budget_ns;
        let mut predicted: Vec<(Strategy, f64)> =
            [Strategy::Newell, Strategy::Bsp, Strategy::Presorted]
                .into_iter()
                .filter(|&s| !(over_budget && s == Strategy::Presorted))
                .map(|s| (s, costs.predict(s, n, frames)))
                .collect();
        predicted.sort_by(|a, b| a.1.total_cmp(&b.1));
        let ((strategy, cheaper), (_, dearer)) = (predicted[0], predicted[1]);
        let excluded = if over_budget {
            format!(
                "; presorted left out: its build is predicted at {:.0} s, over its {:.0} s budget",
                presort_build_ns * 1e-9,
                budget_ns * 1e-9
            )
        } else {
            String::new()
        };
        Plan {
            strategy,
            reason: format!(
                "not convex; {frame_words}, {n} pieces → {} (predicted {:.1} ms against {:.1} ms){excluded}",
                strategy.name(),
                cheaper * 1e-6,
                dearer * 1e-6
            ),
            found: Found::Nothing,
            frames: hint.frames,
        }
    }

    /// Builds the sorter this plan names; a cull-only or convex-parts strategy that the
    /// analysis did not prove (a `strategy` changed by hand) builds the BSP, which is exact.
    #[must_use]
    pub fn build(&self, geometry: &Geometry) -> Box<dyn FaceSorter> {
        match (self.strategy, &self.found) {
            (Strategy::CullOnly, &Found::Convex { exits_face_away }) => Box::new(CullOnly {
                pieces: Arc::clone(geometry.pieces()),
                exits_face_away,
                grouped: None,
            }),
            (Strategy::ConvexParts, Found::Parts(tree)) => Box::new(ConvexParts {
                pieces: Arc::clone(geometry.pieces()),
                tree: Arc::clone(tree),
                stack: Vec::new(),
            }),
            (Strategy::Newell, _) if self.frames >= NEWELL_COVERAGE_FRAMES => {
                Box::new(Newell::new(geometry))
            }
            (Strategy::Newell, _) => Box::new(Newell::without_coverage(geometry)),
            (Strategy::Presorted, _) => Box::new(crate::Presorted::new(geometry)),
            // A tree over its fragment budget (BspOptions) would cost more than it saves:
            // Newell is exact too and needs no tree.
            _ => Bsp::new_or_fallback(geometry, &BspOptions::DEFAULT, BspFallback::Newell)
                .expect("the Newell fallback is never refused"),
        }
    }
}

/// The order of a geometry in convex position (every piece's plane has all of its vertices
/// on one side, so a ray meets its surface at most twice, entering and leaving): drawn exit
/// pieces, then drawn entry pieces, each group in piece order, or grouped by brush
/// ([`FaceSorter::group_by_brush`]). Built only by a [`Plan`] that
/// proved convex position; exact for every view.
#[derive(Debug)]
pub struct CullOnly {
    pieces: Arc<PolygonSet>,
    exits_face_away: bool,
    /// The pieces in drawing order within each pass when grouped by brush; `None` is piece
    /// order.
    grouped: Option<Vec<u32>>,
}

impl FaceSorter for CullOnly {
    fn name(&self) -> &'static str {
        "cull-only"
    }

    fn sort(&mut self, view: &View, out: &mut DrawList) {
        out.begin(&self.pieces);
        let cull = view.cull_test();
        let order = self.grouped.as_deref();
        draw_convex(&self.pieces, &cull, self.exits_face_away, order, out);
    }

    fn group_by_brush(&mut self, brush: &dyn Fn(u32) -> u32) -> bool {
        let pieces = &self.pieces;
        let mut order: Vec<u32> = (0..pieces.len() as u32).collect();
        order.sort_by_key(|&i| brush(pieces.face(i as usize)));
        self.grouped = Some(order);
        true
    }

    fn stats(&self) -> SorterStats {
        SorterStats {
            polygons: self.pieces.len(),
            ..SorterStats::default()
        }
    }
}

/// The planner's sorter: analyses the geometry once ([`Plan::analyse`]) and runs what the
/// plan names. The default of the command line.
///
/// **Same view, no work:** when `sort` is called with the view of its previous call and a list
/// that still holds what that call wrote (the list is sealed after each sort and any change
/// breaks the seal: no comparison, no copy), it returns at once;
/// [`skipped_frames`](Self::skipped_frames) counts those calls.
pub struct Auto {
    plan: Plan,
    inner: Box<dyn FaceSorter>,
    last_view: Option<View>,
    last_seal: Option<u64>,
    skipped: u64,
}

impl std::fmt::Debug for Auto {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Auto").field("plan", &self.plan).finish()
    }
}

impl Auto {
    /// Plans and builds for `geometry`.
    #[must_use]
    pub fn new(geometry: &Geometry, hint: PlanHint) -> Self {
        let plan = Plan::analyse(geometry, hint);
        let inner = plan.build(geometry);
        Auto {
            plan,
            inner,
            last_view: None,
            last_seal: None,
            skipped: 0,
        }
    }

    /// Calls of `sort` that found the view and the list unchanged and did nothing.
    #[must_use]
    pub fn skipped_frames(&self) -> u64 {
        self.skipped
    }

    /// The plan followed.
    #[must_use]
    pub fn plan(&self) -> &Plan {
        &self.plan
    }
}

impl FaceSorter for Auto {
    fn name(&self) -> &'static str {
        self.inner.name()
    }

    fn group_by_brush(&mut self, brush: &dyn Fn(u32) -> u32) -> bool {
        let grouped = self.inner.group_by_brush(brush);
        // The next frame is drawn in the new order.
        self.last_view = None;
        grouped
    }

    fn sort(&mut self, view: &View, out: &mut DrawList) {
        // A view seen last frame, and the list still sealed as this sorter left it.
        if self.last_view.as_ref() == Some(view) && out.sealed() == self.last_seal {
            self.skipped += 1;
            return;
        }
        self.inner.sort(view, out);
        self.last_view = Some(*view);
        self.last_seal = Some(out.seal());
    }

    fn stats(&self) -> SorterStats {
        self.inner.stats()
    }
}

/// One part of a [`PartTree`]: its pieces and which way its normals point.
#[derive(Clone, Debug, PartialEq)]
struct Part {
    pieces: Vec<u32>,
    exits_face_away: bool,
}

/// A node of the part tree: a leaf part, or an axis-aligned plane `x[axis] = at` with every
/// part of `low` at or below it and every part of `high` at or above it.
#[derive(Clone, Copy, Debug, PartialEq)]
enum PartNode {
    Leaf(u32),
    Split {
        axis: usize,
        at: f64,
        low: u32,
        high: u32,
    },
}

/// Separate convex parts and the axis-aligned planes between them (see the module docs).
#[derive(Clone, Debug, PartialEq)]
struct PartTree {
    parts: Vec<Part>,
    nodes: Vec<PartNode>,
}

impl PartTree {
    /// The parts of `geometry` (connected by shared vertices), if there are at least two,
    /// each is in convex position and axis-aligned planes separate all their boxes.
    fn analyse(geometry: &Geometry) -> Option<PartTree> {
        if geometry.part_count() < 2 {
            return None;
        }
        let (pieces, diagonal) = (geometry.pieces(), geometry.bounds().diagonal());
        let mut groups: Vec<Vec<u32>> = vec![Vec::new(); geometry.part_count()];
        for (i, &part) in geometry.piece_parts().iter().enumerate() {
            groups[part as usize].push(i as u32);
        }
        let mut parts = Vec::with_capacity(groups.len());
        let mut boxes = Vec::with_capacity(groups.len());
        for group in groups {
            let mut set = PolygonSet::new();
            for &i in &group {
                let i = i as usize;
                set.push(pieces.corners(i), pieces.face(i), *pieces.plane(i));
            }
            let all_corners = group.iter().flat_map(|&i| pieces.corners(i as usize));
            let b = crate::Bounds::from_points(all_corners.copied())
                .expect("a part has pieces, a piece has corners");
            let (lo, hi) = (b.min, b.max);
            let exits_face_away = convex_position(&set, diagonal)?;
            parts.push(Part {
                pieces: group,
                exits_face_away,
            });
            boxes.push((lo, hi));
        }
        let mut nodes = Vec::with_capacity(2 * parts.len());
        let all: Vec<u32> = (0..parts.len() as u32).collect();
        split_parts(&boxes, all, &mut nodes)?;
        Some(PartTree { parts, nodes })
    }
}

/// Builds the subtree over `members` into `nodes` and returns its index; `None` when some
/// set of two or more boxes has no axis-aligned plane between them.
fn split_parts(
    boxes: &[(DVec3, DVec3)],
    mut members: Vec<u32>,
    nodes: &mut Vec<PartNode>,
) -> Option<u32> {
    let index = nodes.len() as u32;
    if members.len() == 1 {
        nodes.push(PartNode::Leaf(members[0]));
        return Some(index);
    }
    // The most balanced plane over the three axes: members sorted by their boxes' low
    // ends, a cut after position k where every box before ends at or below every box after.
    // (axis, cut position, plane, balance)
    let mut best: Option<(usize, usize, f64, usize)> = None;
    let by_low_end = |members: &mut Vec<u32>, axis: usize| {
        members.sort_by(|&a, &b| boxes[a as usize].0[axis].total_cmp(&boxes[b as usize].0[axis]));
    };
    for axis in 0..3 {
        by_low_end(&mut members, axis);
        let mut reach = f64::NEG_INFINITY;
        for k in 1..members.len() {
            reach = reach.max(boxes[members[k - 1] as usize].1[axis]);
            let next = boxes[members[k] as usize].0[axis];
            if reach <= next {
                let balance = k.min(members.len() - k);
                if best.is_none_or(|(.., b)| balance > b) {
                    best = Some((axis, k, 0.5 * (reach + next), balance));
                }
            }
        }
    }
    let (axis, k, at, _) = best?;
    nodes.push(PartNode::Leaf(0));
    // The first `k` by low end lie at or below `at`, the others at or above.
    by_low_end(&mut members, axis);
    let high = members.split_off(k);
    let low = members;
    let low = split_parts(boxes, low, nodes)?;
    let high = split_parts(boxes, high, nodes)?;
    nodes[index as usize] = PartNode::Split {
        axis,
        at,
        low,
        high,
    };
    Some(index)
}

/// The order of separate convex parts ([`Strategy::ConvexParts`]): the part tree walked far
/// side first, each part drawn like [`CullOnly`]. Exact for every view; no fragments.
#[derive(Debug)]
pub struct ConvexParts {
    pieces: Arc<PolygonSet>,
    tree: Arc<PartTree>,
    /// Nodes still to visit (kept between frames: no allocation once grown).
    stack: Vec<u32>,
}

impl FaceSorter for ConvexParts {
    fn name(&self) -> &'static str {
        "convex-parts"
    }

    fn sort(&mut self, view: &View, out: &mut DrawList) {
        let cull = view.cull_test();
        let (point, w) = cull.viewer_point();
        out.begin(&self.pieces);
        self.stack.clear();
        self.stack.push(0);
        while let Some(k) = self.stack.pop() {
            match self.tree.nodes[k as usize] {
                PartNode::Split {
                    axis,
                    at,
                    low,
                    high,
                } => {
                    // The far side first: pushed last, popped first.
                    if point[axis] - w * at >= 0.0 {
                        self.stack.extend([high, low]);
                    } else {
                        self.stack.extend([low, high]);
                    }
                }
                PartNode::Leaf(p) => {
                    let part = &self.tree.parts[p as usize];
                    let order = Some(part.pieces.as_slice());
                    draw_convex(&self.pieces, &cull, part.exits_face_away, order, out);
                }
            }
        }
    }

    fn stats(&self) -> SorterStats {
        SorterStats {
            polygons: self.pieces.len(),
            ..SorterStats::default()
        }
    }
}

/// Draws the pieces of `set` named by `order` (all, in set order, for `None`) of a body in
/// convex position (see the module docs): exit pieces first, then entry pieces. When the cull
/// rule never keeps exit pieces (back-face culling of outward normals, no margin) that is one
/// culling pass. A piece exactly edge-on projects to nothing and is never drawn
/// (CONVENTIONS.md), so it may go in either pass.
fn draw_convex(
    set: &PolygonSet,
    cull: &crate::CullTest,
    exits_face_away: bool,
    order: Option<&[u32]>,
    out: &mut DrawList,
) {
    let planes = set.planes();
    match order {
        None => draw_pieces(set, cull, exits_face_away, planes.iter().enumerate(), out),
        Some(order) => {
            let pieces = order.iter().map(|&i| (i as usize, &planes[i as usize]));
            draw_pieces(set, cull, exits_face_away, pieces, out);
        }
    }
}

/// [`draw_convex`] over `(index, plane)` pairs.
fn draw_pieces<'a>(
    set: &PolygonSet,
    cull: &crate::CullTest,
    exits_face_away: bool,
    pieces: impl Iterator<Item = (usize, &'a crate::Plane)> + Clone,
    out: &mut DrawList,
) {
    let exits_drawn = cull.facing_rule().is_none_or(|(keep_facing, keep_away)| {
        if exits_face_away {
            keep_away
        } else {
            keep_facing
        }
    });
    if !exits_drawn {
        for (i, plane) in pieces {
            if cull.is_drawn(plane, set.corners(i)[0]) {
                out.push(i as u32, set.face(i));
            }
        }
        return;
    }
    for entry_pass in [false, true] {
        for (i, plane) in pieces.clone() {
            let is_entry = (cull.viewer.facing(plane) > 0.0) == exits_face_away;
            if is_entry == entry_pass && cull.is_drawn(plane, set.corners(i)[0]) {
                out.push(i as u32, set.face(i));
            }
        }
    }
}

/// Whether every piece's plane has all vertices of `pieces` on one side, the same side for
/// every piece, within `PLANE_SIDE · diagonal`. `Some(true)`: all behind (outward normals);
/// `Some(false)`: all in front (inward normals); `None`: not in convex position.
fn convex_position(pieces: &PolygonSet, diagonal: f64) -> Option<bool> {
    let tolerance = PLANE_SIDE * diagonal;
    // `signed_distance = n · p − offset` with a unit normal: in front means above the plane.
    let oriented = |plane: &crate::Plane, outward: bool| {
        if outward {
            (plane.normal(), plane.offset() + tolerance)
        } else {
            (-plane.normal(), -plane.offset() + tolerance)
        }
    };
    // Most meshes fail at once: test every plane against a few vertices spread over the
    // mesh (one corner of every `step`-th piece) before building the tree for the proof.
    let step = (pieces.len() / SAMPLE_PIECES).max(1);
    let sample: Vec<DVec3> = (0..pieces.len())
        .step_by(step)
        .map(|i| pieces.corners(i)[0])
        .collect();
    let candidates: Vec<bool> = [true, false]
        .into_iter()
        .filter(|&outward| {
            pieces.planes().iter().all(|plane| {
                let (n, limit) = oriented(plane, outward);
                sample.iter().all(|p| n.dot(*p) <= limit)
            })
        })
        .collect();
    if candidates.is_empty() {
        return None;
    }
    let points: Vec<DVec3> = (0..pieces.len())
        .flat_map(|i| pieces.corners(i).iter().copied())
        .collect();
    let tree = PointTree::new(points);
    let mut stack = Vec::new();
    candidates.into_iter().find(|&outward| {
        pieces.planes().iter().all(|plane| {
            let (n, limit) = oriented(plane, outward);
            !tree.any_above(n, limit, &mut stack)
        })
    })
}

/// Pieces whose first corner the quick rejection of [`convex_position`] tests every plane
/// against.
const SAMPLE_PIECES: usize = 64;

/// A bounding-volume hierarchy over points, for "does any point lie above this plane"
/// queries: a subtree whose box lies below the plane is skipped whole.
struct PointTree {
    points: Vec<DVec3>,
    nodes: Vec<PointNode>,
}

struct PointNode {
    min: DVec3,
    max: DVec3,
    /// Leaf: `points[start..end]`; inner: children at `start` and `end` (node indices).
    start: u32,
    end: u32,
    leaf: bool,
}

const LEAF_POINTS: usize = 8;

impl PointTree {
    fn new(mut points: Vec<DVec3>) -> Self {
        let mut nodes = Vec::with_capacity(2 * points.len() / LEAF_POINTS + 1);
        if !points.is_empty() {
            let len = points.len();
            build_points(&mut points, 0, len, &mut nodes);
        }
        PointTree { points, nodes }
    }

    /// Whether some point `p` has `n · p > limit`.
    fn any_above(&self, n: DVec3, limit: f64, stack: &mut Vec<u32>) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        stack.clear();
        stack.push(0);
        while let Some(i) = stack.pop() {
            let node = &self.nodes[i as usize];
            let top = n.x * if n.x > 0.0 { node.max.x } else { node.min.x }
                + n.y * if n.y > 0.0 { node.max.y } else { node.min.y }
                + n.z * if n.z > 0.0 { node.max.z } else { node.min.z };
            if top <= limit {
                continue;
            }
            if node.leaf {
                if self.points[node.start as usize..node.end as usize]
                    .iter()
                    .any(|p| n.dot(*p) > limit)
                {
                    return true;
                }
            } else {
                stack.push(node.start);
                stack.push(node.end);
            }
        }
        false
    }
}

/// Builds the subtree over `points[start..end]` and returns its node index.
fn build_points(points: &mut [DVec3], start: usize, end: usize, nodes: &mut Vec<PointNode>) -> u32 {
    let slice = &points[start..end];
    let (min, max) = slice.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let index = nodes.len() as u32;
    nodes.push(PointNode {
        min,
        max,
        start: start as u32,
        end: end as u32,
        leaf: true,
    });
    if end - start > LEAF_POINTS {
        let extent = max - min;
        let axis = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        let mid = (end - start) / 2;
        points[start..end].select_nth_unstable_by(mid, |a, b| a[axis].total_cmp(&b[axis]));
        let left = build_points(points, start, start + mid, nodes);
        let right = build_points(points, start + mid, end, nodes);
        let node = &mut nodes[index as usize];
        node.start = left;
        node.end = right;
        node.leaf = false;
    }
    index
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PolygonMesh;

    fn cube(inward: bool) -> Geometry {
        let p: Vec<DVec3> = (0..8)
            .map(|i| DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2)))
            .collect();
        let mut faces = vec![
            [0u32, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        if inward {
            for f in &mut faces {
                f.reverse();
            }
        }
        Geometry::new(&PolygonMesh::new(p, faces).unwrap()).unwrap()
    }

    #[test]
    fn a_cube_is_in_convex_position_either_way_round() {
        let outward = Plan::analyse(&cube(false), PlanHint::ONE_FRAME);
        assert_eq!(outward.strategy, Strategy::CullOnly, "{}", outward.reason);
        assert_eq!(
            outward.found,
            Found::Convex {
                exits_face_away: true
            }
        );
        let inward = Plan::analyse(&cube(true), PlanHint::ONE_FRAME);
        assert_eq!(inward.strategy, Strategy::CullOnly, "{}", inward.reason);
        assert_eq!(
            inward.found,
            Found::Convex {
                exits_face_away: false
            }
        );
    }

    #[test]
    fn point_tree_answers_like_a_scan() {
        let points: Vec<DVec3> = (0..500)
            .map(|i| {
                let t = f64::from(i) * 0.37;
                DVec3::new(t.sin(), (t * 1.7).cos(), (t * 0.3).sin() * 2.0)
            })
            .collect();
        let tree = PointTree::new(points.clone());
        for k in 0..50 {
            let a = f64::from(k) * 0.9;
            let n = DVec3::new(a.cos(), a.sin(), (a * 0.5).cos()).normalize();
            for limit in [-1.0, 0.0, 0.5, 1.2, 3.0] {
                let scan = points.iter().any(|p| n.dot(*p) > limit);
                assert_eq!(tree.any_above(n, limit, &mut Vec::new()), scan);
            }
        }
    }
}
