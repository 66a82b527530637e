//! Which drawn pieces no other drawn piece overlaps on screen, per view.
//!
//! On a closed mesh seen from outside, the pieces facing the viewer tile the picture: two
//! overlap only where the surface folds over itself (an ear over a head, a leg behind a leg).
//! A piece that nothing overlaps can be drawn anywhere in the order; only the others need
//! sorting. [`Newell`](crate::Newell) draws such pieces first and sorts the rest, and the
//! fragment merge draws such split pieces whole.
//!
//! # Why it is exact
//! Let `m(x)` count the drawn pieces whose projections contain screen point `x`. Give each
//! piece's outline the direction that turns counter-clockwise around it on screen; then the
//! winding number of all outlines around `x` is `m(x)`. Two drawn pieces that share an edge
//! (its two corners bit for bit, in opposite directions) and turn the same way on screen lie
//! on opposite sides of it, and their two copies of the edge cancel in the sum. What is left
//! are the **boundary** edges: silhouettes, the mesh's own boundary, edges whose neighbour is
//! culled or turns the other way. So `m` changes only across boundary edges: if none enters a
//! piece's projection, `m` is constant inside it, and `m = 1` at one inner point (a winding
//! number over the boundary edges) means the piece alone covers its projection.
//!
//! Each piece's turning direction is its own projected signed area's sign, not its facing:
//! a piece seen almost edge-on may project turned the other way, and the cancellation then
//! does not apply to it.

use glam::DVec2;

use crate::ids::PieceId;
use crate::polygon::{Box2, edges, signed_area_2d};
use crate::polygon_set::PolygonSet;
use crate::screen_grid::GridFrame;

/// A cell's winding number where it is not constant or not known (above every `m ≤ 1`).
const UNKNOWN_WINDING: i32 = i32::MAX;

/// Most boundary-edge entries per grid cell and edge, on average, that a frame files (a
/// silhouette's short edges touch one to four cells each); beyond, the test gives up.
const MAX_FILED_PER_CELL: usize = 8;

/// Per piece corner `k`, the piece across the edge from corner `k` to corner `k + 1`.
#[derive(Debug, Default)]
pub(crate) struct EdgeNeighbours {
    /// Per piece, the index of its first edge in `across` (one more entry at the end).
    start: Vec<u32>,
    /// The consistently oriented neighbour across each edge (the same corners in the opposite
    /// direction, bit for bit, on no third piece), or `PieceId::NONE`.
    across: Vec<PieceId>,
}

impl EdgeNeighbours {
    /// Finds every piece's neighbours, by sorting: corners at the same position bit for bit
    /// become one vertex, then directed edges are sorted by their two vertices (O(n log n)
    /// whatever the mesh; a hash map of corner positions was too slow on the million-face
    /// torus, docs/bench.md). Unlike the plotter's weld, `-0.0` and `0.0` stay apart: an edge
    /// missed that way only leaves a boundary edge, and fewer pieces proved alone, never a
    /// wrong one.
    pub(crate) fn new(pieces: &PolygonSet) -> Self {
        // Every corner, numbered in piece order, with its position's bits.
        let mut start = Vec::with_capacity(pieces.len() + 1);
        let mut piece_of = Vec::with_capacity(pieces.vertex_count());
        let mut keyed: Vec<([u64; 3], u32)> = Vec::with_capacity(pieces.vertex_count());
        for p in 0..pieces.len() {
            start.push(keyed.len() as u32);
            for c in pieces.corners(p) {
                let corner = keyed.len() as u32;
                keyed.push(([c.x, c.y, c.z].map(f64::to_bits), corner));
                piece_of.push(p as u32);
            }
        }
        start.push(keyed.len() as u32);
        keyed.sort_unstable();
        let mut vertex = vec![0u32; keyed.len()];
        let mut v = 0;
        for (i, &(key, corner)) in keyed.iter().enumerate() {
            if i > 0 && key != keyed[i - 1].0 {
                v += 1;
            }
            vertex[corner as usize] = v;
        }
        drop(keyed);
        // Directed edge `c`, from corner `c` to the next corner of its piece, keyed by its
        // two vertices.
        let next = |c: usize| {
            let p = piece_of[c] as usize;
            if c + 1 == start[p + 1] as usize {
                start[p] as usize
            } else {
                c + 1
            }
        };
        let key = |from: u32, to: u32| (u64::from(from) << 32) | u64::from(to);
        let mut directed: Vec<(u64, u32)> = (0..vertex.len())
            .map(|c| (key(vertex[c], vertex[next(c)]), c as u32))
            .collect();
        directed.sort_unstable();
        let with = |k: u64| {
            let lo = directed.partition_point(|e| e.0 < k);
            let hi = directed.partition_point(|e| e.0 <= k);
            &directed[lo..hi]
        };
        let across = (0..vertex.len())
            .map(|c| {
                let (a, b) = (vertex[c], vertex[next(c)]);
                match (with(key(a, b)), with(key(b, a))) {
                    ([_], [(_, reverse)]) if piece_of[*reverse as usize] != piece_of[c] => {
                        PieceId::new(piece_of[*reverse as usize])
                    }
                    _ => PieceId::NONE,
                }
            })
            .collect();
        EdgeNeighbours { start, across }
    }

    /// The neighbours of piece `p`, one per edge (`PieceId::NONE` where there is none).
    pub(crate) fn of(&self, p: usize) -> &[PieceId] {
        &self.across[self.start[p] as usize..self.start[p + 1] as usize]
    }

    /// Heap bytes.
    pub(crate) fn heap_bytes(&self) -> usize {
        (self.start.capacity() + self.across.capacity()) * 4
    }
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
    /// The piece it belongs to (whose own edges never enter it).
    piece: u32,
}

impl BoundaryEdge {
    /// The edge's box.
    fn bounds(&self) -> Box2 {
        Box2 {
            min: self.a.min(self.b),
            max: self.a.max(self.b),
        }
    }
}

/// Per-frame buffers of the coverage test, kept between frames (steady frames allocate
/// nothing). Filed once per frame by [`file`](Self::file), then asked per piece by
/// [`alone`](Self::alone).
#[derive(Debug, Default)]
pub(crate) struct Coverage {
    neighbours: EdgeNeighbours,
    /// Per piece: the frame it was last filed in, and its screen turning direction then
    /// (`1` counter-clockwise, `-1` clockwise, `0` no area).
    seen: Vec<u32>,
    turn: Vec<i8>,
    frame: u32,
    /// The boundary edges, filed by the grid cells their boxes touch and by the rows their
    /// heights meet (`cell_edges[cell_start[c]..cell_start[c + 1]]`, likewise rows).
    /// A counting sort rather than a [`ScreenGrid`](crate::screen_grid::ScreenGrid): the
    /// edges are filed once per frame and never added to, and a `ScreenGrid` here made the
    /// fragment merge slower (docs/bench.md).
    edges: Vec<BoundaryEdge>,
    /// Per boundary edge, the cells its box touches `(x0, x1, y0, y1)`.
    edge_cells: Vec<(usize, usize, usize, usize)>,
    /// The grid laid over this frame's boundary edges.
    grid: GridFrame,
    cell_start: Vec<u32>,
    cell_edges: Vec<u32>,
    row_start: Vec<u32>,
    row_edges: Vec<u32>,
    /// Per cell: `m`, constant in a cell that no boundary edge's box touches, or
    /// [`UNKNOWN_WINDING`] (an edge's box touches it, or `m` is unknown on its row). A piece
    /// inside cells where `m ≤ 1` alone covers its projection; one with an inner point in a
    /// cell where `m` is known and not 1 does not.
    cell_winding: Vec<i32>,
    /// One row's crossings `(x, ±1)` of the boundary edges with the row's middle line.
    crossings: Vec<(f64, i32)>,
}

impl Coverage {
    /// The coverage test over `pieces`: their edge neighbours, and buffers.
    pub(crate) fn new(pieces: &PolygonSet) -> Self {
        Coverage {
            neighbours: EdgeNeighbours::new(pieces),
            seen: vec![0; pieces.len()],
            turn: vec![0; pieces.len()],
            ..Coverage::default()
        }
    }

    /// Whether drawn pieces `p` and `q` are edge neighbours turning the same way on screen
    /// this frame (after [`file`](Self::file)): then they lie on opposite sides of their
    /// shared edge and do not overlap.
    pub(crate) fn beside(&self, p: usize, q: usize) -> bool {
        self.turn[p] != 0
            && self.turn[p] == self.turn[q]
            && self.neighbours.of(p).contains(&PieceId::new(q as u32))
    }

    /// Files the boundary edges of this frame's drawn pieces, `drawn[j]` projecting to
    /// `polygon(j)` (any consistent screen units; every corner projected, none clipped);
    /// `false` when there is none, or more than `max_edges_per_piece` per drawn piece (then no
    /// piece is proved alone).
    pub(crate) fn file<'a>(
        &mut self,
        drawn: &[u32],
        polygon: impl Fn(usize) -> &'a [DVec2],
        max_edges_per_piece: f64,
    ) -> bool {
        self.frame = self.frame.wrapping_add(1);
        if self.frame == 0 {
            self.seen.fill(0);
            self.frame = 1;
        }
        let frame = self.frame;
        let max_edges = (max_edges_per_piece * drawn.len() as f64) as usize;
        for (j, &p) in drawn.iter().enumerate() {
            self.seen[p as usize] = frame;
            let area = signed_area_2d(polygon(j));
            self.turn[p as usize] = if area > 0.0 {
                1
            } else if area < 0.0 {
                -1
            } else {
                0
            };
        }
        self.edges.clear();
        for (j, &p) in drawn.iter().enumerate() {
            let p = p as usize;
            let turn = self.turn[p];
            if turn == 0 {
                // No area: its outline winds around no point, and no neighbour cancels it.
                continue;
            }
            let on_boundary = |q: PieceId| {
                q.get()
                    .is_none_or(|q| self.seen[q as usize] != frame || self.turn[q as usize] != turn)
            };
            let across = self.neighbours.of(p);
            if !across.iter().any(|&q| on_boundary(q)) {
                continue;
            }
            for ((a, b), &q) in edges(polygon(j)).zip(across) {
                if on_boundary(q) {
                    // Crossing an upward edge (y growing) of a counter-clockwise outline from
                    // right to left enters it.
                    let upward = if b.y > a.y { 1 } else { -1 };
                    self.edges.push(BoundaryEdge {
                        a,
                        b,
                        inverse_slope: (b.x - a.x) / (b.y - a.y),
                        sign: upward * i32::from(turn),
                        piece: p as u32,
                    });
                }
            }
            if self.edges.len() > max_edges {
                return false;
            }
        }
        !self.edges.is_empty() && self.file_edges(drawn.len())
    }

    /// Lays a grid of about `cells` square cells over the boundary edges (every point that
    /// a drawn piece covers lies within their bounds: elsewhere their winding number is 0),
    /// files them by cell and by row, and finds the cells where pieces are alone; `false`
    /// when their bounds are not finite.
    fn file_edges(&mut self, cells: usize) -> bool {
        let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
        for e in &self.edges {
            lo = lo.min(e.a).min(e.b);
            hi = hi.max(e.a).max(e.b);
        }
        let size = hi - lo;
        if !(size.x.is_finite() && size.y.is_finite() && size.x > 0.0 && size.y > 0.0) {
            return false;
        }
        self.grid = GridFrame::fit(lo, size, cells.max(self.edges.len()));
        let grid = self.grid;
        let (columns, rows) = (grid.columns, grid.rows);
        // Long edges (a triangle soup's, where every edge is a boundary edge) could touch
        // most cells each: past a bound on the work, no piece is proved alone this frame.
        // Each edge's cells are found once here and read by both filing passes.
        self.edge_cells.clear();
        self.edge_cells.extend(self.edges.iter().map(|e| {
            let b = e.bounds();
            grid.cells(b.min, b.max)
        }));
        let filed: usize = (self.edge_cells.iter())
            .map(|&(x0, x1, y0, y1)| (x1 - x0 + 1) * (y1 - y0 + 1))
            .sum();
        if filed > MAX_FILED_PER_CELL * (columns * rows + self.edges.len()) {
            return false;
        }
        // A counting sort into cells and rows: count, prefix sums, then fill counting down.
        for (start, len) in [
            (&mut self.cell_start, columns * rows),
            (&mut self.row_start, rows),
        ] {
            start.clear();
            start.resize(len + 1, 0);
        }
        for fill in [false, true] {
            for (i, &(x0, x1, y0, y1)) in self.edge_cells.iter().enumerate() {
                for y in y0..=y1 {
                    file(&mut self.row_start, &mut self.row_edges, y, i, fill);
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
        self.find_alone_cells();
        true
    }

    /// Per row, `m` at each cell's centre from the boundary edges crossing the row's middle
    /// line to its right, kept for the cells that no edge touches (`m` is constant there).
    fn find_alone_cells(&mut self) {
        let GridFrame {
            origin,
            inverse_cell,
            columns,
            rows,
        } = self.grid;
        self.cell_winding.clear();
        self.cell_winding.resize(columns * rows, UNKNOWN_WINDING);
        let cell = DVec2::ONE / inverse_cell;
        for row in 0..rows {
            let y = origin.y + (row as f64 + 0.5) * cell.y;
            self.crossings.clear();
            let mut poisoned = false;
            let list = self.row_start[row] as usize..self.row_start[row + 1] as usize;
            for &e in &self.row_edges[list] {
                let e = &self.edges[e as usize];
                if (e.a.y <= y) != (e.b.y <= y) {
                    // Not finite only when `dx / dy` overflows: then `m` is unknown here.
                    let x = e.a.x + (y - e.a.y) * e.inverse_slope;
                    poisoned |= !x.is_finite();
                    self.crossings.push((x, e.sign));
                }
            }
            self.crossings.sort_unstable_by(|a, b| b.0.total_cmp(&a.0));
            // From the right: `m` sums the crossings right of the cell's centre.
            let (mut m, mut next) = (0, 0);
            for column in (0..columns).rev() {
                let x = origin.x + (column as f64 + 0.5) * cell.x;
                while next < self.crossings.len() && self.crossings[next].0 > x {
                    m += self.crossings[next].1;
                    next += 1;
                }
                let c = row * columns + column;
                let constant = !poisoned && self.cell_start[c] == self.cell_start[c + 1];
                self.cell_winding[c] = if constant { m } else { UNKNOWN_WINDING };
            }
        }
    }

    /// Whether drawn piece `piece`, projecting to `corners` with screen box `bounds`, alone
    /// covers its projection: it lies in alone cells, or it has area, no boundary edge enters
    /// it (its own edges lie on its outline and are not tested), and the winding number over
    /// the boundary edges at its centroid is 1 (its cell's `m` where that is known, else
    /// summed along its row; a known `m` other than 1 decides before any edge is tested).
    /// Only after [`file`](Self::file) returned `true` for the frame.
    pub(crate) fn alone(&self, piece: u32, corners: &[DVec2], bounds: &Box2) -> bool {
        let b = bounds;
        let (x0, x1, y0, y1) = self.grid.cells(b.min, b.max);
        let columns = self.grid.columns;
        if (y0..=y1).all(|y| {
            self.cell_winding[y * columns + x0..=y * columns + x1]
                .iter()
                .all(|&m| m <= 1)
        }) {
            return true;
        }
        // Its turn, filed from the same projection.
        let turn = f64::from(self.turn[piece as usize]);
        if turn == 0.0 {
            return false;
        }
        // An inner point; where its cell's `m` is known, that is `m` there.
        let inside = corners.iter().copied().sum::<DVec2>() / corners.len() as f64;
        let (column, _, row, _) = self.grid.cells(inside, inside);
        let known = self.cell_winding[row * columns + column];
        if known != UNKNOWN_WINDING && known != 1 {
            return false;
        }
        for y in y0..=y1 {
            for c in y * columns + x0..=y * columns + x1 {
                let list = self.cell_start[c] as usize..self.cell_start[c + 1] as usize;
                for &e in &self.cell_edges[list] {
                    let e = self.edges[e as usize];
                    if e.piece == piece {
                        continue;
                    }
                    // An edge whose box misses the piece's cannot enter it.
                    if e.bounds().touches(b) && enters(corners, turn, e.a, e.b) {
                        return false;
                    }
                }
            }
        }
        if known == 1 {
            return true;
        }
        let list = self.row_start[row] as usize..self.row_start[row + 1] as usize;
        let (mut m, mut finite) = (0, true);
        for &e in &self.row_edges[list] {
            let e = &self.edges[e as usize];
            // Half-open in y, so that an end shared by two edges counts once; no branch.
            let crosses = (e.a.y <= inside.y) != (e.b.y <= inside.y);
            let x = e.a.x + (inside.y - e.a.y) * e.inverse_slope;
            m += i32::from(crosses & (x > inside.x)) * e.sign;
            // Not finite only when `dx / dy` overflows: then `m` is unknown.
            finite &= !crosses | x.is_finite();
        }
        finite && m == 1
    }

    /// Heap bytes.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.neighbours.heap_bytes()
            + self.seen.capacity() * 4
            + self.turn.capacity()
            + self.cell_winding.capacity() * 4
            + (self.cell_start.capacity()
                + self.cell_edges.capacity()
                + self.row_start.capacity()
                + self.row_edges.capacity())
                * 4
            + self.edges.capacity() * size_of::<BoundaryEdge>()
            + self.edge_cells.capacity() * size_of::<(usize, usize, usize, usize)>()
            + self.crossings.capacity() * size_of::<(f64, i32)>()
    }
}

/// Whether segment `a`–`b` meets the interior of the convex polygon `corners`, which turns
/// `turn` (`±1`) on screen. Not when a separating line exists (touching allowed): an edge's
/// line with the segment on its outer side and every corner on its inner side, one
/// strictly (so that a zero-length edge never separates), or the segment's line with every
/// corner on one side, one strictly. A stricter subset of
/// [`separated_2d`](crate::polygon::separated_2d)'s lines, for a segment against a polygon
/// of known turn: whenever it separates, `separated_2d` does too.
fn enters(corners: &[DVec2], turn: f64, a: DVec2, b: DVec2) -> bool {
    let separates = |from: DVec2, direction: DVec2, outer: &dyn Fn(f64) -> bool| {
        let (mut inner, mut strictly) = (true, false);
        for &c in corners {
            let side = direction.perp_dot(c - from);
            inner &= !outer(side) || side == 0.0;
            strictly |= side != 0.0;
        }
        inner && strictly
    };
    for (from, to) in edges(corners) {
        let edge = (to - from) * turn;
        let out = |x: DVec2| edge.perp_dot(x - from) <= 0.0;
        if out(a) && out(b) && separates(from, edge, &|side| side < 0.0) {
            return false;
        }
    }
    // The segment's own line, with the polygon on either side.
    let line = b - a;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &c in corners {
        let side = line.perp_dot(c - a);
        lo = lo.min(side);
        hi = hi.max(side);
    }
    !((hi <= 0.0 || lo >= 0.0) && (lo < 0.0 || hi > 0.0))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polygon::clip_convex_2d;
    use crate::tolerance::OVERLAP_AREA;
    use crate::{CullMode, Geometry, ProjectionScratch, View, generate};

    /// Neighbours share an edge's corners bit for bit in opposite directions, with no third
    /// piece on it: two triangles of a square are neighbours across their diagonal; a
    /// third triangle on the same diagonal, a copy of an edge in the same direction, an edge
    /// whose corners differ in one bit, or a repeated corner leave no neighbour.
    #[test]
    fn neighbours_share_an_edge_bit_for_bit() {
        let v = |x: f64, y: f64| glam::DVec3::new(x, y, 0.0);
        let set = |polygons: &[&[glam::DVec3]]| {
            let mut set = PolygonSet::new();
            for corners in polygons {
                let plane = crate::Plane::try_from_polygon(corners).unwrap();
                set.push(corners, 0, plane);
            }
            set
        };
        let none = PieceId::NONE;
        let (a, b, c, d) = (v(0.0, 0.0), v(1.0, 0.0), v(1.0, 1.0), v(0.0, 1.0));
        let square = EdgeNeighbours::new(&set(&[&[a, b, c], &[a, c, d]]));
        assert_eq!(square.of(0), &[none, none, PieceId::new(1)]);
        assert_eq!(square.of(1), &[PieceId::new(0), none, none]);
        // A third piece with the diagonal in the neighbour's direction: two candidates.
        let three = EdgeNeighbours::new(&set(&[&[a, b, c], &[a, c, d], &[a, c, v(2.0, 3.0)]]));
        assert_eq!(three.of(0)[2], none);
        // A copy of the diagonal in the piece's own direction.
        let same_way = EdgeNeighbours::new(&set(&[&[a, b, c], &[a, c, d], &[c, a, v(0.5, 2.0)]]));
        assert_eq!(same_way.of(0)[2], none);
        assert_eq!(same_way.of(1)[0], none);
        let nudged = v(0.0, f64::from_bits(1.0_f64.to_bits() + 1));
        let apart = EdgeNeighbours::new(&set(&[&[a, b, c], &[a, v(1.0, 1.0 + f64::EPSILON), d]]));
        assert_eq!(apart.of(0), &[none, none, none]);
        let repeated = EdgeNeighbours::new(&set(&[&[a, b, b, c], &[a, c, nudged]]));
        assert_eq!(repeated.of(0), &[none, none, none, PieceId::new(1)]);
        assert_eq!(repeated.of(1), &[PieceId::new(0), none, none]);
    }

    /// A repeated corner (a zero-length edge) separates nothing, in either winding; a
    /// segment through the interior enters, one outside or along an edge does not.
    #[test]
    fn segments_enter_only_through_the_interior() {
        let square = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
        ];
        let reversed: Vec<DVec2> = square.iter().rev().copied().collect();
        for (corners, turn) in [(&square[..], 1.0), (&reversed[..], -1.0)] {
            let enters = |a: (f64, f64), b: (f64, f64)| {
                enters(corners, turn, DVec2::new(a.0, a.1), DVec2::new(b.0, b.1))
            };
            assert!(enters((-1.0, 0.5), (2.0, 0.5)));
            assert!(enters((0.5, 0.5), (0.6, 0.6)));
            assert!(enters((1.0, -1.0), (0.5, 0.5)));
            assert!(!enters((1.0, -1.0), (1.0, 2.0)));
            assert!(!enters((0.0, 0.0), (1.0, 0.0)));
            assert!(!enters((2.0, -1.0), (2.0, 3.0)));
            assert!(!enters((-1.0, 2.0), (2.0, 1.5)));
        }
    }

    /// Every piece the test proves alone overlaps no other drawn piece (brute force over all
    /// pairs, with Newell's and the oracle's overlap tolerance), on a torus (folds in most
    /// views), a UV sphere, back faces culled and drawn, orthographic and perspective; and
    /// both answers occur.
    #[test]
    fn pieces_proved_alone_overlap_nothing() {
        let (mut proved, mut refused) = (0, 0);
        for mesh in [generate::torus(600), generate::uv_sphere(24, 12)] {
            let geometry = Geometry::new(&mesh).unwrap();
            let pieces = geometry.pieces();
            let mut coverage = Coverage::new(pieces);
            let base = View::fit(&geometry.bounds(), 256, 256);
            let l = geometry.bounds().diagonal() * base.scale();
            for (k, cull) in [CullMode::Back, CullMode::None].into_iter().enumerate() {
                for (yaw, pitch) in [(0.0, 0.0), (30.0, 20.0), (75.0, 60.0), (200.0, -35.0)] {
                    let mut view = base.with_yaw_pitch_roll(yaw, pitch, 0.0).with_cull(cull);
                    if k == 1 {
                        view = view.with_perspective(3.0 * l);
                    }
                    let cull = view.cull_test();
                    let (mut drawn, mut projected) = (Vec::new(), Vec::new());
                    let mut scratch = ProjectionScratch::default();
                    for p in 0..pieces.len() {
                        if cull.is_drawn(pieces.plane(p), pieces.corners(p)[0]) {
                            let mut out = Vec::new();
                            view.project_polygon(pieces.corners(p), &mut out, &mut scratch);
                            // No corner behind the near plane: the projection is the
                            // piece's own corners.
                            assert!(
                                pieces.corners(p).iter().all(|&c| {
                                    view.project_view_point(view.to_view(c)).is_some()
                                })
                            );
                            drawn.push(p as u32);
                            projected.push(out);
                        }
                    }
                    assert!(coverage.file(&drawn, |j| &projected[j], f64::INFINITY));
                    let (mut clip, mut scratch) = (Vec::new(), Vec::new());
                    for (j, a) in projected.iter().enumerate() {
                        if !coverage.alone(drawn[j], a, &Box2::from_points(a)) {
                            refused += 1;
                            continue;
                        }
                        proved += 1;
                        for (i, b) in projected.iter().enumerate() {
                            if i != j {
                                clip_convex_2d(a, b, &mut clip, &mut scratch);
                                let area = signed_area_2d(&clip).abs();
                                assert!(
                                    clip.len() < 3 || area <= OVERLAP_AREA * l * l,
                                    "view {yaw}, {pitch}: piece {} alone, but piece {} \
                                     overlaps it by {area} px²",
                                    drawn[j],
                                    drawn[i]
                                );
                            }
                        }
                    }
                }
            }
        }
        assert!(
            proved > 1000 && refused > 100,
            "{proved} proved, {refused} refused"
        );
    }
}
