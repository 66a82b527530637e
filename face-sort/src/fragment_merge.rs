//! Drawing a split piece whole, per view, where nothing drawn between its fragments overlaps
//! it on screen.
//!
//! A BSP cuts a piece wherever a splitting plane crosses it, whatever the view. In most views
//! nothing drawn between its first and last fragment overlaps it on screen, and then one
//! polygon, the whole piece drawn at its last fragment's place, paints the same pixels.
//!
//! # Why it is exact
//! A BSP order is valid pair by pair: of two polygons that overlap on screen, the later one is
//! in front wherever they overlap. Replace the fragments of a piece `Q` by `Q` whole at the
//! place of its last fragment. Items drawn before its first fragment or after its last keep
//! their relation to every part of `Q`; only items drawn between change sides, and the merge
//! requires that none of them overlaps `Q`. Every item of another piece `R`, merged or not,
//! lies inside `R`'s projection and within `R`'s first and last fragments' places, so the
//! test is made on whole pieces and those places: it then holds whatever else is merged, and
//! merges are valid one by one in any order.
//!
//! # Two tests
//! 1. **Nothing overlaps `Q` at all** (most pieces; cheap). Let `m(x)` count the drawn
//!    pieces whose projections cover screen point `x`. Two drawn pieces that share an edge
//!    (its two corners bit for bit, in opposite directions) and face the same way lie on
//!    opposite sides of it on screen, so `m` does not change across it; it changes only
//!    across the other edges of drawn pieces, the **boundary** edges (silhouettes, the mesh's
//!    own boundary, edges whose neighbour is culled). If no boundary edge enters `Q`'s
//!    projection, `m` is constant inside it, and `m = 1` at one inner point (a winding number
//!    over the boundary edges) means `Q` alone covers its projection.
//! 2. **Nothing between its fragments overlaps it** (the rest): candidates from a screen grid
//!    of every drawn piece, those drawn between `Q`'s first and last fragment tested with
//!    [`Newell`](crate::Newell)'s overlap test (the exact convex intersection has more than
//!    [`OVERLAP_AREA`]` · L²` of area).

use std::ops::ControlFlow;

use glam::DVec2;

use crate::polygon::{Box2, clip_convex_2d, edges, separated_2d, signed_area_2d};
use crate::polygon_set::PolygonSet;
use crate::screen_grid::ScreenGrid;
use crate::tolerance::OVERLAP_AREA;
use crate::{DrawItem, View};

const NONE: u32 = u32::MAX;

/// Most cells along either side of the boundary edges' grid.
const MAX_SIDE: usize = 256;

/// Most bands of the winding test.
const MAX_BANDS: usize = 4096;

/// Per piece corner `k`, the piece across the edge from corner `k` to corner `k + 1`.
#[derive(Debug, Default)]
pub(crate) struct EdgeNeighbours {
    /// Per piece, the index of its first edge in `across` (one more entry at the end).
    start: Vec<u32>,
    /// The consistently oriented neighbour across each edge (the same corners in the opposite
    /// direction, bit for bit, on no third piece), or `NONE`.
    across: Vec<u32>,
}

impl EdgeNeighbours {
    /// Finds every piece's neighbours.
    pub(crate) fn new(pieces: &PolygonSet) -> Self {
        let key = |a: glam::DVec3, b: glam::DVec3| [a.x, a.y, a.z, b.x, b.y, b.z].map(f64::to_bits);
        let edges_of = |p: usize| edges(pieces.corners(p));
        // Directed edge → (piece, how many pieces have it).
        let mut directed = std::collections::HashMap::new();
        for p in 0..pieces.len() {
            for (a, b) in edges_of(p) {
                directed
                    .entry(key(a, b))
                    .and_modify(|e: &mut (u32, u32)| e.1 += 1)
                    .or_insert((p as u32, 1));
            }
        }
        let mut start = Vec::with_capacity(pieces.len() + 1);
        let mut across = Vec::new();
        for p in 0..pieces.len() {
            start.push(across.len() as u32);
            for (a, b) in edges_of(p) {
                let once = |k| {
                    directed
                        .get(&k)
                        .filter(|e: &&(u32, u32)| e.1 == 1)
                        .map(|e| e.0)
                };
                across.push(match (once(key(b, a)), once(key(a, b))) {
                    (Some(q), Some(_)) if q as usize != p => q,
                    _ => NONE,
                });
            }
        }
        start.push(across.len() as u32);
        EdgeNeighbours { start, across }
    }

    /// Heap bytes.
    pub(crate) fn heap_bytes(&self) -> usize {
        (self.start.capacity() + self.across.capacity()) * 4
    }
}

/// What the tree gives the merge.
pub(crate) struct MergeInput<'a> {
    /// The pieces (centred model space).
    pub pieces: &'a PolygonSet,
    /// Per piece, the index of its whole polygon in the draw list's set (`NONE`: not split),
    /// and its number of fragments.
    pub whole: &'a [u32],
    pub fragment_count: &'a [u32],
    /// Per fragment, its piece.
    pub fragment_piece: &'a [u32],
    /// Per piece, whether the viewer is in front of it.
    pub facing: &'a [bool],
    /// The model's diagonal `L`.
    pub diagonal: f64,
}

/// One projected boundary edge and the change of `m` when crossing it from right to left
/// (`±1`) at a height between its ends'.
#[derive(Clone, Copy, Debug)]
struct BoundaryEdge {
    a: DVec2,
    b: DVec2,
    /// `dx / dy` (infinite or NaN for a level edge, which no height crosses half-open).
    inverse_slope: f64,
    sign: i32,
}

/// Per-view buffers of the merge, kept between frames (steady frames allocate nothing).
#[derive(Debug, Default)]
pub(crate) struct FragmentMerge {
    /// The pieces' edge neighbours.
    neighbours: EdgeNeighbours,
    /// Per piece: the frame it was last drawn in, its index among that frame's drawn
    /// pieces, its fragments drawn, its first and last places, and the frame it was last
    /// merged in.
    seen: Vec<u32>,
    dense: Vec<u32>,
    count: Vec<u32>,
    first: Vec<u32>,
    last: Vec<u32>,
    merged: Vec<u32>,
    frame: u32,
    /// This frame's drawn pieces, their projections (pixels) and screen boxes.
    drawn: Vec<u32>,
    projected: Vec<DVec2>,
    projected_start: Vec<u32>,
    boxes: Vec<Box2>,
    /// Split pieces with two fragments or more drawn this frame, and those test 1 left.
    split: Vec<u32>,
    pending: Vec<u32>,
    /// Test 1: the boundary edges, filed by the grid cells their boxes touch and by the bands
    /// their heights meet (`cell_edges[cell_start[c]..cell_start[c + 1]]`, likewise bands).
    /// A counting sort rather than a [`ScreenGrid`]: the edges are filed once per frame and
    /// never added to, and a `ScreenGrid` here made the merge 14 % slower on spot (805 against
    /// 705 µs per frame, `STEP=0.02 profile_frame bsp-merged`).
    edges: Vec<BoundaryEdge>,
    origin: DVec2,
    inverse_cell: DVec2,
    columns: usize,
    rows: usize,
    /// Rows of the winding test's buckets (finer than the cells: few edges per bucket).
    bands: usize,
    inverse_band: f64,
    cell_start: Vec<u32>,
    cell_edges: Vec<u32>,
    row_start: Vec<u32>,
    row_edges: Vec<u32>,
    /// Test 2: every drawn piece's box.
    grid: ScreenGrid,
    clip_out: Vec<DVec2>,
    clip_scratch: Vec<DVec2>,
}

impl FragmentMerge {
    /// The merge over `pieces`: their edge neighbours, and buffers.
    pub(crate) fn new(pieces: &PolygonSet) -> Self {
        let neighbours = EdgeNeighbours::new(pieces);
        let pieces = pieces.len();
        FragmentMerge {
            neighbours,
            seen: vec![0; pieces],
            dense: vec![0; pieces],
            count: vec![0; pieces],
            first: vec![0; pieces],
            last: vec![0; pieces],
            merged: vec![0; pieces],
            ..FragmentMerge::default()
        }
    }

    /// Writes `items` (a BSP order of fragments) to `out`, each split piece that nothing
    /// drawn between its fragments overlaps on screen replaced by its whole polygon at its
    /// last fragment's place.
    pub(crate) fn merge(
        &mut self,
        view: &View,
        input: &MergeInput<'_>,
        items: &[DrawItem],
        out: &mut Vec<DrawItem>,
    ) {
        self.frame = self.frame.wrapping_add(1);
        if self.frame == 0 {
            self.seen.fill(0);
            self.merged.fill(0);
            self.frame = 1;
        }
        let frame = self.frame;
        self.drawn.clear();
        self.split.clear();
        for (i, item) in items.iter().enumerate() {
            let p = input.fragment_piece[item.polygon as usize] as usize;
            if self.seen[p] != frame {
                self.seen[p] = frame;
                self.dense[p] = self.drawn.len() as u32;
                self.count[p] = 0;
                self.first[p] = i as u32;
                self.drawn.push(p as u32);
            }
            self.count[p] += 1;
            // Only pieces with every fragment drawn: one culled off the image leaves part of
            // the piece unordered against what it would overlap there.
            if self.count[p] == input.fragment_count[p] && input.whole[p] != NONE {
                self.split.push(p as u32);
            }
            self.last[p] = i as u32;
        }
        if !self.split.is_empty() && self.project(view, input.pieces) {
            self.alone(input);
            // Newell's overlap tolerance, `OVERLAP_AREA · L²` in view units, in pixels².
            let l = input.diagonal * view.scale();
            self.nothing_between(input, OVERLAP_AREA * l * l);
        }
        for (i, item) in items.iter().enumerate() {
            let p = input.fragment_piece[item.polygon as usize] as usize;
            if self.merged[p] != frame {
                out.push(*item);
            } else if self.last[p] == i as u32 {
                out.push(DrawItem {
                    polygon: input.whole[p],
                    face: item.face,
                });
            }
        }
    }

    /// Projects this frame's drawn pieces; `false` when a corner lies behind the near plane
    /// (no merge this frame).
    fn project(&mut self, view: &View, pieces: &PolygonSet) -> bool {
        self.projected.clear();
        self.projected_start.clear();
        self.boxes.clear();
        for &p in &self.drawn {
            self.projected_start.push(self.projected.len() as u32);
            let start = self.projected.len();
            for &c in pieces.corners(p as usize) {
                match view.project_view_point(view.to_view(c)) {
                    Some(q) => self.projected.push(q),
                    None => return false,
                }
            }
            self.boxes.push(Box2::from_points(&self.projected[start..]));
        }
        self.projected_start.push(self.projected.len() as u32);
        true
    }

    /// The projection of the drawn piece with dense index `j`.
    fn polygon(&self, j: usize) -> &[DVec2] {
        &self.projected[self.projected_start[j] as usize..self.projected_start[j + 1] as usize]
    }

    /// Test 1: merges the split pieces that no other drawn piece overlaps; leaves the others
    /// in `pending`.
    fn alone(&mut self, input: &MergeInput<'_>) {
        self.pending.clear();
        if !self.boundary(input) || !self.file_edges() {
            self.pending.extend_from_slice(&self.split);
            return;
        }
        for s in 0..self.split.len() {
            let q = self.split[s];
            if self.covers_alone(self.dense[q as usize] as usize) {
                self.merged[q as usize] = self.frame;
            } else {
                self.pending.push(q);
            }
        }
    }

    /// Collects the boundary edges of this frame's drawn pieces; `false` when there is none
    /// or no piece's screen orientation is certain.
    fn boundary(&mut self, input: &MergeInput<'_>) -> bool {
        self.edges.clear();
        let frame = self.frame;
        // The screen orientation of a piece facing the viewer (all share it), from the piece
        // with the largest projected area among those with a boundary edge.
        let (mut orientation, mut largest) = (0.0, 0.0);
        for (j, &p) in self.drawn.iter().enumerate() {
            let p = p as usize;
            let n = &self.neighbours;
            let across = &n.across[n.start[p] as usize..n.start[p + 1] as usize];
            let on_boundary = |q: u32| {
                q == NONE
                    || self.seen[q as usize] != frame
                    || input.facing[q as usize] != input.facing[p]
            };
            if !across.iter().any(|&q| on_boundary(q)) {
                continue;
            }
            let corners = &self.projected
                [self.projected_start[j] as usize..self.projected_start[j + 1] as usize];
            let facing = if input.facing[p] { 1 } else { -1 };
            let area = signed_area_2d(corners) * f64::from(facing);
            if area.abs() > largest {
                (largest, orientation) = (area.abs(), area.signum());
            }
            for ((a, b), &q) in edges(corners).zip(across) {
                if on_boundary(q) {
                    // The orientation factor is applied below, once it is known.
                    self.edges.push(BoundaryEdge {
                        a,
                        b,
                        inverse_slope: (b.x - a.x) / (b.y - a.y),
                        sign: facing,
                    });
                }
            }
        }
        for e in &mut self.edges {
            // Crossing an upward edge (y growing) of a piece with positive signed area from
            // right to left enters the piece.
            let upward = if e.b.y > e.a.y { 1 } else { -1 };
            e.sign *= upward * orientation as i32;
        }
        orientation != 0.0 && !self.edges.is_empty()
    }

    /// Lays a grid over the boundary edges and files them by cell and by row; `false` when
    /// their bounds are not finite.
    fn file_edges(&mut self) -> bool {
        let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
        for e in &self.edges {
            lo = lo.min(e.a).min(e.b);
            hi = hi.max(e.a).max(e.b);
        }
        let size = hi - lo;
        if !(size.x.is_finite() && size.y.is_finite() && size.x > 0.0 && size.y > 0.0) {
            return false;
        }
        // About one cell per boundary edge, square cells.
        let side = (size.x * size.y / self.edges.len() as f64).sqrt();
        let count = |extent: f64| ((extent / side).ceil() as usize).clamp(1, MAX_SIDE);
        (self.columns, self.rows) = (count(size.x), count(size.y));
        self.origin = lo;
        self.inverse_cell = DVec2::new(self.columns as f64 / size.x, self.rows as f64 / size.y);
        self.bands = self.edges.len().clamp(1, MAX_BANDS);
        self.inverse_band = self.bands as f64 / size.y;
        let columns = self.columns;
        // A counting sort into cells and rows: count, prefix sums, then fill counting down.
        for (start, len) in [
            (&mut self.cell_start, columns * self.rows),
            (&mut self.row_start, self.bands),
        ] {
            start.clear();
            start.resize(len + 1, 0);
        }
        for fill in [false, true] {
            for (i, e) in self.edges.iter().enumerate() {
                let (x0, x1, y0, y1) = cells_of(
                    self.origin,
                    self.inverse_cell,
                    (columns, self.rows),
                    e.a.min(e.b),
                    e.a.max(e.b),
                );
                let band = |y: f64| {
                    (((y - self.origin.y) * self.inverse_band).max(0.0) as usize)
                        .min(self.bands - 1)
                };
                for k in band(e.a.y.min(e.b.y))..=band(e.a.y.max(e.b.y)) {
                    file(&mut self.row_start, &mut self.row_edges, k, i, fill);
                }
                for y in y0..=y1 {
                    for c in y * columns + x0..=y * columns + x1 {
                        file(&mut self.cell_start, &mut self.cell_edges, c, i, fill);
                    }
                }
            }
            if !fill {
                for (start, list) in [
                    (&mut self.cell_start, &mut self.cell_edges),
                    (&mut self.row_start, &mut self.row_edges),
                ] {
                    for k in 1..start.len() {
                        start[k] += start[k - 1];
                    }
                    list.clear();
                    list.resize(start[start.len() - 1] as usize, 0);
                }
            }
        }
        true
    }

    /// Whether the drawn piece with dense index `j` alone covers its projection: no boundary
    /// edge enters it, and the winding number over the boundary edges at its centroid is 1.
    fn covers_alone(&self, j: usize) -> bool {
        let corners = self.polygon(j);
        if signed_area_2d(corners) == 0.0 {
            return false;
        }
        let b = self.boxes[j];
        let (x0, x1, y0, y1) = cells_of(
            self.origin,
            self.inverse_cell,
            (self.columns, self.rows),
            b.min,
            b.max,
        );
        for y in y0..=y1 {
            for c in y * self.columns + x0..=y * self.columns + x1 {
                let list = self.cell_start[c] as usize..self.cell_start[c + 1] as usize;
                for &e in &self.cell_edges[list] {
                    let e = self.edges[e as usize];
                    // An edge whose box misses the piece's cannot enter it.
                    let (lo, hi) = (e.a.min(e.b), e.a.max(e.b));
                    let apart =
                        hi.x < b.min.x || lo.x > b.max.x || hi.y < b.min.y || lo.y > b.max.y;
                    if !apart && !separated_2d(corners, &[e.a, e.b]) {
                        return false;
                    }
                }
            }
        }
        let inside = corners.iter().copied().sum::<DVec2>() / corners.len() as f64;
        let band = (((inside.y - self.origin.y) * self.inverse_band).max(0.0) as usize)
            .min(self.bands - 1);
        let list = self.row_start[band] as usize..self.row_start[band + 1] as usize;
        let m: i32 = self.row_edges[list]
            .iter()
            .map(|&e| {
                let e = &self.edges[e as usize];
                // Half-open in y, so that an end shared by two edges counts once; no branch.
                let crosses = (e.a.y <= inside.y) != (e.b.y <= inside.y);
                let x = e.a.x + (inside.y - e.a.y) * e.inverse_slope;
                i32::from(crosses & (x > inside.x)) * e.sign
            })
            .sum();
        m == 1
    }

    /// Test 2: merges each pending split piece that no piece drawn between its fragments
    /// overlaps.
    fn nothing_between(&mut self, input: &MergeInput<'_>, min_area: f64) {
        if self.pending.is_empty() {
            return;
        }
        let mut all = Box2::EMPTY;
        for b in &self.boxes {
            all.min = all.min.min(b.min);
            all.max = all.max.max(b.max);
        }
        self.grid.reset(all, self.drawn.len());
        for (j, b) in self.boxes.iter().enumerate() {
            self.grid.insert(j as u32, b);
        }
        for s in 0..self.pending.len() {
            let q = self.pending[s] as usize;
            let jq = self.dense[q] as usize;
            let (first, last) = (self.first[q], self.last[q]);
            let q_box = self.boxes[jq];
            let mut hidden = false;
            let (drawn, firsts, lasts, boxes) = (&self.drawn, &self.first, &self.last, &self.boxes);
            let (projected, starts) = (&self.projected, &self.projected_start);
            let polygon = |j: usize| &projected[starts[j] as usize..starts[j + 1] as usize];
            let (clip_out, clip_scratch) = (&mut self.clip_out, &mut self.clip_scratch);
            let n = &self.neighbours;
            let across = &n.across[n.start[q] as usize..n.start[q + 1] as usize];
            // A neighbour facing the same way lies on the other side of the shared edge.
            let beside =
                |r: usize| input.facing[r] == input.facing[q] && across.contains(&(r as u32));
            self.grid.for_each_candidate(&q_box, |j| {
                let r = drawn[j as usize] as usize;
                if r == q
                    || firsts[r] >= last
                    || lasts[r] <= first
                    || !boxes[j as usize].overlaps(&q_box)
                    || beside(r)
                    || separated_2d(polygon(jq), polygon(j as usize))
                {
                    return ControlFlow::Continue(());
                }
                clip_convex_2d(polygon(jq), polygon(j as usize), clip_out, clip_scratch);
                hidden = clip_out.len() >= 3 && signed_area_2d(clip_out).abs() > min_area;
                if hidden {
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(())
                }
            });
            if !hidden {
                self.merged[q] = self.frame;
            }
        }
    }

    /// Heap bytes.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.neighbours.heap_bytes()
            + (self.seen.capacity()
                + self.dense.capacity()
                + self.count.capacity()
                + self.first.capacity()
                + self.last.capacity()
                + self.merged.capacity()
                + self.drawn.capacity()
                + self.projected_start.capacity()
                + self.split.capacity()
                + self.pending.capacity()
                + self.cell_start.capacity()
                + self.cell_edges.capacity()
                + self.row_start.capacity()
                + self.row_edges.capacity())
                * 4
            + (self.projected.capacity() + self.clip_out.capacity() + self.clip_scratch.capacity())
                * size_of::<DVec2>()
            + self.boxes.capacity() * size_of::<Box2>()
            + self.edges.capacity() * size_of::<BoundaryEdge>()
    }
}

/// Files item `i` under key `k` of a counting sort: counts it (`fill` false), or, once the
/// counts are summed into the ends of the lists, writes it (`fill` true), `start[k]`
/// counting down from the end of its list to its start.
fn file(start: &mut [u32], list: &mut [u32], k: usize, i: usize, fill: bool) {
    if fill {
        start[k] -= 1;
        list[start[k] as usize] = i as u32;
    } else {
        start[k] += 1;
    }
}

/// The cells `[x0, x1] × [y0, y1]` of a grid (`origin`, `inverse_cell`, `(columns, rows)`)
/// that the box `[lo, hi]` touches, clamped to the grid.
fn cells_of(
    origin: DVec2,
    inverse_cell: DVec2,
    (columns, rows): (usize, usize),
    lo: DVec2,
    hi: DVec2,
) -> (usize, usize, usize, usize) {
    let a = (lo - origin) * inverse_cell;
    let b = (hi - origin) * inverse_cell;
    // Truncation is the floor for the non-negative values kept (casts saturate; NaN is 0).
    let index = |v: f64, n: usize| (v.max(0.0) as usize).min(n - 1);
    (
        index(a.x, columns),
        index(b.x, columns),
        index(a.y, rows),
        index(b.y, rows),
    )
}
