//! Visible edges for pen plotters: hidden-line removal, exact in f64, written as strokes.
//!
//! A plotter cannot paint one colour over another, so the painter's order alone does not
//! make a plot: it needs the visible parts of the lines themselves. [`plot_edges`] finds the
//! edges a drawing shows (boundaries, silhouettes, creases, non-manifold edges, on welded
//! vertices) and clips each one exactly where a drawn piece covers it.
//!
//! **Why the clipping is exact.** Take an edge `A + t·(B − A)` and a drawn convex piece `P`.
//! A point of the edge is covered by `P` when its projection lies inside `P`'s projection and
//! it lies behind `P`'s plane, seen from the viewer. In homogeneous screen coordinates the
//! projection of the edge is linear in `t` (the perspective divide is by `w(t) > 0`, linear
//! too), so "inside the line through one edge of `P`'s projection" is the sign of a linear
//! function of `t`, and so is "behind `P`'s plane". The covered set is an intersection of
//! half-lines: one interval per piece, in closed form. The edge's visible part is `[0, 1]`
//! minus the union of those intervals. This is the same test as the painter's order (a
//! piece drawn later covers what lies behind it), asked of every point of the line at once.
//!
//! The pieces an edge lies on never cover it (it lies on their boundary, where no f64 inside
//! test is reliable): they are left out of its candidates. Those are the pieces of the faces
//! whose edge it is that have corners at both its ends; another fan triangle of a non-planar
//! face can cover its own face's edge, and does. Pieces that only touch an
//! edge at an end cover at most a sliver that the margins ([`PLOT_INSIDE_PX`](crate::tolerance::PLOT_INSIDE_PX),
//! [`PLOT_BEHIND`]) remove.
//!
//! Where two drawn faces pass through each other, their intersection segment (on the line
//! where their planes meet, the overlap of the chords each cuts from the other's plane) is
//! one more edge, clipped the same way ([`EdgeKind::Intersection`]).

use std::collections::HashMap;

use face_sort::{Geometry, PolygonMesh, View, Viewer, newell_normal};

use crate::occlusion::{Occluder, Occluders, Segment, weld};
use glam::{DVec2, DVec3};

use crate::tolerance::{PLOT_BEHIND, PLOT_JOIN_PX, PLOT_SAME_CORNER};

/// Options of [`plot_edges`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct PlotOptions {
    /// Edges between two drawn faces whose normals differ by at least this angle (degrees)
    /// are creases and drawn. Default: 30.
    pub crease_deg: f64,
}

impl PlotOptions {
    /// The defaults.
    pub const DEFAULT: PlotOptions = PlotOptions { crease_deg: 30.0 };

    /// The crease angle in degrees.
    #[must_use]
    pub fn with_crease_deg(mut self, degrees: f64) -> Self {
        self.crease_deg = degrees;
        self
    }
}

impl Default for PlotOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Why an edge is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum EdgeKind {
    /// The edge of one face only, which is drawn.
    Boundary,
    /// Between a face turned toward the viewer and one turned away (with back-face culling:
    /// one drawn, one culled).
    Silhouette,
    /// Between two drawn faces whose normals differ by at least the crease angle.
    Crease,
    /// Shared by three or more faces, at least one of them drawn.
    NonManifold,
    /// Where two drawn faces pass through each other.
    Intersection,
}

/// One drawn edge and its visible parts.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotEdge {
    /// Why it is drawn.
    pub kind: EdgeKind,
    /// Its ends in centred model space (model position minus the geometry's bounds centre).
    pub ends: [DVec3; 2],
    /// Its visible parts as parameter intervals `[t0, t1]` of `ends[0] + t·(ends[1] −
    /// ends[0])`, sorted and disjoint; empty when it is hidden.
    pub visible: Vec<[f64; 2]>,
}

/// The plot of one view: the drawn edges with their visible parts, joined into polylines
/// for the pen.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Plot {
    /// Every drawn edge, visible or not.
    pub edges: Vec<PlotEdge>,
    /// The visible parts, joined end to end into polylines (pixels), in pen order.
    pub polylines: Vec<Vec<DVec2>>,
    /// Length drawn with the pen down (pixels).
    pub pen_down_px: f64,
    /// Travel with the pen up between polylines, in pen order (pixels).
    pub pen_up_px: f64,
    /// Image size (pixels).
    pub size: (u32, u32),
}

/// The visible edges of `mesh` seen in `view`, and the intersection lines of its drawn faces,
/// clipped exactly (module docs).
///
/// `geometry` is `Geometry::new(mesh)` (its pieces are the occluders; pieces culled by the
/// view hide nothing). Vertices at exactly the same position are one vertex, so OBJ seams
/// do not cut lines and a flat face cut into two has no line across it.
#[must_use]
pub fn plot_edges(
    mesh: &PolygonMesh,
    geometry: &Geometry,
    view: &View,
    options: &PlotOptions,
) -> Plot {
    plot_edges_where(mesh, geometry, view, options, |_| true)
}

/// [`plot_edges`] over the faces `include` keeps: the others neither draw edges nor hide
/// anything (e.g. a ground grid, lines over a transparent face).
#[must_use]
pub fn plot_edges_where(
    mesh: &PolygonMesh,
    geometry: &Geometry,
    view: &View,
    options: &PlotOptions,
    include: impl Fn(u32) -> bool,
) -> Plot {
    let centre = geometry.bounds().centre();
    let occluders = Occluders::new(geometry, view, &include);
    let length = geometry.bounds().diagonal().max(f64::MIN_POSITIVE);
    let mut edges = classify_edges(mesh, centre, &occluders, view, options);
    edges.extend(intersection_edges(&occluders, length));
    let same_corner = PLOT_SAME_CORNER * length;
    let mut stamp = vec![u32::MAX; occluders.pieces.len()];
    let mut candidates = Vec::new();
    let mut covered = Vec::new();
    let mut out = Vec::with_capacity(edges.len());
    for (k, edge) in edges.into_iter().enumerate() {
        let visible = match Segment::new(view, edge.ends) {
            Some(segment) => {
                occluders.candidates(&segment, k as u32, &mut stamp, &mut candidates);
                covered.clear();
                for &piece in &candidates {
                    let p = &occluders.pieces[piece as usize];
                    if !edge.lies_on(piece, p, same_corner)
                        && let Some(interval) = segment.covered_by(p, length)
                    {
                        covered.push(interval);
                    }
                }
                segment.visible_parts(&mut covered)
            }
            None => Vec::new(),
        };
        out.push(PlotEdge {
            kind: edge.kind,
            ends: edge.ends,
            visible,
        });
    }
    let segments: Vec<[DVec2; 2]> = out
        .iter()
        .flat_map(|e| {
            e.visible.iter().filter_map(move |&[t0, t1]| {
                let at =
                    |t: f64| view.project_view_point(view.to_view(e.ends[0].lerp(e.ends[1], t)));
                Some([at(t0)?, at(t1)?])
            })
        })
        .collect();
    let polylines = order_for_pen(join_segments(&segments));
    let pen_down_px = polylines
        .iter()
        .map(|l| l.windows(2).map(|w| w[0].distance(w[1])).sum::<f64>())
        .sum();
    let pen_up_px = polylines
        .windows(2)
        .map(|w| w[0][w[0].len() - 1].distance(w[1][0]))
        .sum();
    Plot {
        edges: out,
        polylines,
        pen_down_px,
        pen_up_px,
        size: (view.width(), view.height()),
    }
}

/// An edge to draw, before clipping.
struct Classified {
    kind: EdgeKind,
    ends: [DVec3; 2],
    /// The faces whose boundary it is.
    faces: Vec<u32>,
    /// The two pieces it lies inside (intersection lines).
    pieces: Option<[u32; 2]>,
}

impl Classified {
    /// Whether the edge lies on occluder `index` (`piece`), which therefore never covers it:
    /// a piece of a face whose boundary it is with corners at both its ends (within
    /// `same_corner`: planar faces are snapped onto their plane), or one of the two pieces of
    /// an intersection line. Another fan triangle of a non-planar face may cover its own
    /// face's edge, and does.
    fn lies_on(&self, index: u32, piece: &Occluder, same_corner: f64) -> bool {
        if let Some(pieces) = self.pieces {
            return pieces.contains(&index);
        }
        self.faces.contains(&piece.face)
            && self.ends.iter().all(|&end| {
                piece
                    .corners_3d
                    .iter()
                    .any(|&c| c.distance_squared(end) <= same_corner * same_corner)
            })
    }
}

/// The edges a drawing shows, on welded vertices (same position, bit for bit, is one
/// vertex; `-0.0` is `0.0`).
fn classify_edges(
    mesh: &PolygonMesh,
    centre: DVec3,
    occluders: &Occluders,
    view: &View,
    options: &PlotOptions,
) -> Vec<Classified> {
    let ids = weld(mesh);
    // (low id, high id) → (face, the face runs it low → high), in face order.
    let mut edges: HashMap<(u32, u32), Vec<(u32, bool)>> = HashMap::new();
    let mut order = Vec::new();
    for (face, corners) in mesh.faces().enumerate() {
        if !occluders.has_pieces[face] {
            continue; // no area: it neither draws nor joins edges
        }
        for k in 0..corners.len() {
            let (a, b) = (
                ids[corners[k] as usize],
                ids[corners[(k + 1) % corners.len()] as usize],
            );
            if a == b {
                continue;
            }
            let key = (a.min(b), a.max(b));
            let list = edges.entry(key).or_default();
            if list.is_empty() {
                order.push((key, corners[k], corners[(k + 1) % corners.len()]));
            }
            if !list.iter().any(|&(f, _)| f == face as u32) {
                list.push((face as u32, a < b));
            }
        }
    }
    let normal = |face: u32| {
        let corners: Vec<DVec3> = mesh
            .face(face as usize)
            .iter()
            .map(|&i| mesh.positions()[i as usize] - centre)
            .collect();
        newell_normal(&corners).normalize_or_zero()
    };
    let viewer = view.viewer();
    let toward = |face: u32, n: DVec3| -> bool {
        let first = mesh.positions()[mesh.face(face as usize)[0] as usize] - centre;
        match viewer {
            Viewer::Direction(d) => n.dot(d) > 0.0,
            Viewer::Eye(e) => n.dot(e - first) > 0.0,
        }
    };
    let cos_crease = options.crease_deg.to_radians().cos();
    let mut out = Vec::new();
    for (key, a, b) in order {
        let faces = &edges[&key];
        let drawn = |f: u32| occluders.drawn_faces[f as usize];
        let kind = match faces.as_slice() {
            [(f, _)] => drawn(*f).then_some(EdgeKind::Boundary),
            [(f, f_up), (g, g_up)] => {
                let (nf, mut ng) = (normal(*f), normal(*g));
                // Consistent winding runs a shared edge in opposite directions; otherwise
                // one normal is flipped for the dihedral.
                if f_up == g_up {
                    ng = -ng;
                }
                let turned = toward(*f, nf) != toward(*g, ng);
                match (drawn(*f), drawn(*g)) {
                    (false, false) => None,
                    (true, true) if turned => Some(EdgeKind::Silhouette),
                    (true, true) => (nf.dot(ng) <= cos_crease).then_some(EdgeKind::Crease),
                    _ => Some(EdgeKind::Silhouette),
                }
            }
            many => many
                .iter()
                .any(|&(f, _)| drawn(f))
                .then_some(EdgeKind::NonManifold),
        };
        if let Some(kind) = kind {
            out.push(Classified {
                kind,
                ends: [
                    mesh.positions()[a as usize] - centre,
                    mesh.positions()[b as usize] - centre,
                ],
                faces: faces.iter().map(|&(f, _)| f).collect(),
                pieces: None,
            });
        }
    }
    out
}

/// The intersection segments of drawn pieces that pass through each other (each has corners
/// on both sides of the other's plane by more than [`PLOT_BEHIND`] times `length`): on the
/// line where their planes meet, the overlap of the chords each cuts from the other's plane.
/// Pieces that only touch (neighbours along an edge or a corner) have none.
fn intersection_edges(occluders: &Occluders, length: f64) -> Vec<Classified> {
    let tol = PLOT_BEHIND * length;
    let mut out = Vec::new();
    let mut stamp = vec![u32::MAX; occluders.pieces.len()];
    let mut d = Vec::new();
    for (i, p) in occluders.pieces.iter().enumerate() {
        let (c0, r0, c1, r1) = occluders.cell_range(p.min, p.max);
        for r in r0..=r1 {
            for c in c0..=c1 {
                for &j in &occluders.cells[r * occluders.cols + c] {
                    let q = &occluders.pieces[j as usize];
                    if j as usize <= i
                        || stamp[j as usize] == i as u32
                        || q.face == p.face
                        || q.min.x > p.max.x
                        || q.max.x < p.min.x
                        || q.min.y > p.max.y
                        || q.max.y < p.min.y
                    {
                        continue;
                    }
                    stamp[j as usize] = i as u32;
                    let direction = p.plane.normal().cross(q.plane.normal());
                    let (Some(a), Some(b)) = (
                        chord(p, q, direction, tol, &mut d),
                        chord(q, p, direction, tol, &mut d),
                    ) else {
                        continue;
                    };
                    // Overlap of the two chords along the line.
                    let lo = if a.0[0] >= b.0[0] { a.1[0] } else { b.1[0] };
                    let hi = if a.0[1] <= b.0[1] { a.1[1] } else { b.1[1] };
                    if direction.dot(hi - lo) > 0.0 {
                        out.push(Classified {
                            kind: EdgeKind::Intersection,
                            ends: [lo, hi],
                            faces: Vec::new(),
                            pieces: Some([i as u32, j]),
                        });
                    }
                }
            }
        }
    }
    out
}

/// The chord piece `p` cuts from `q`'s plane: its ends' positions along `direction` and the
/// ends (sorted along it). `None` unless `p` has corners on both sides by more than `tol`.
fn chord(
    p: &Occluder,
    q: &Occluder,
    direction: DVec3,
    tol: f64,
    d: &mut Vec<f64>,
) -> Option<([f64; 2], [DVec3; 2])> {
    d.clear();
    d.extend(p.corners_3d.iter().map(|&c| q.plane.signed_distance(c)));
    let (lo, hi) = d
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    if lo >= -tol || hi <= tol {
        return None;
    }
    let n = d.len();
    let mut ends: Option<([f64; 2], [DVec3; 2])> = None;
    for k in 0..n {
        let (da, db) = (d[k], d[(k + 1) % n]);
        if (da > 0.0) == (db > 0.0) {
            continue;
        }
        let (a, b) = (p.corners_3d[k], p.corners_3d[(k + 1) % n]);
        let x = a + (b - a) * (da / (da - db));
        let s = direction.dot(x);
        ends = Some(match ends {
            None => ([s, s], [x, x]),
            Some((mut range, mut points)) => {
                if s < range[0] {
                    range[0] = s;
                    points[0] = x;
                }
                if s > range[1] {
                    range[1] = s;
                    points[1] = x;
                }
                (range, points)
            }
        });
    }
    ends.filter(|(range, _)| range[1] > range[0])
}

/// Segments (pixels) joined into polylines where their ends meet (within [`PLOT_JOIN_PX`]):
/// each walk starts at an end where an odd number of segments meet, when there is one.
fn join_segments(segments: &[[DVec2; 2]]) -> Vec<Vec<DVec2>> {
    let key = |p: DVec2| {
        (
            (p.x / PLOT_JOIN_PX).round() as i64,
            (p.y / PLOT_JOIN_PX).round() as i64,
        )
    };
    let mut nodes: HashMap<(i64, i64), usize> = HashMap::new();
    let mut ends: Vec<[usize; 2]> = Vec::with_capacity(segments.len());
    let mut incident: Vec<Vec<usize>> = Vec::new();
    for (s, seg) in segments.iter().enumerate() {
        let mut node = |p: DVec2| {
            let next = nodes.len();
            let n = *nodes.entry(key(p)).or_insert(next);
            if n == incident.len() {
                incident.push(Vec::new());
            }
            incident[n].push(s);
            n
        };
        ends.push([node(seg[0]), node(seg[1])]);
    }
    let mut used = vec![false; segments.len()];
    let mut cursor = vec![0usize; incident.len()];
    let mut walk = |start: usize, used: &mut Vec<bool>| -> Option<Vec<DVec2>> {
        let mut line = Vec::new();
        let mut node = start;
        loop {
            let next = loop {
                let c = cursor[node];
                if c >= incident[node].len() {
                    break None;
                }
                cursor[node] += 1;
                if !used[incident[node][c]] {
                    break Some(incident[node][c]);
                }
            };
            let Some(s) = next else { break };
            used[s] = true;
            let forward = ends[s][0] == node;
            let (from, to) = if forward {
                (segments[s][0], segments[s][1])
            } else {
                (segments[s][1], segments[s][0])
            };
            if line.is_empty() {
                line.push(from);
            }
            line.push(to);
            node = if forward { ends[s][1] } else { ends[s][0] };
        }
        (line.len() >= 2).then_some(line)
    };
    let mut lines = Vec::new();
    let odd: Vec<usize> = (0..incident.len())
        .filter(|&n| incident[n].len() % 2 == 1)
        .collect();
    for n in odd.into_iter().chain(0..incident.len()) {
        while let Some(line) = walk(n, &mut used) {
            lines.push(line);
        }
    }
    lines
}

/// Polylines in pen order: from the end of each, the nearest start or end (reversing the
/// polyline) of one not yet drawn, found in a grid of polyline ends.
fn order_for_pen(mut lines: Vec<Vec<DVec2>>) -> Vec<Vec<DVec2>> {
    if lines.len() < 2 {
        return lines;
    }
    let (lo, hi) = lines
        .iter()
        .flatten()
        .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    let side = ((lines.len() as f64).sqrt().ceil() as usize).clamp(1, 512);
    let cell = ((hi - lo).max_element() / side as f64).max(f64::MIN_POSITIVE);
    let index = |p: DVec2| {
        let c = ((p - lo) / cell).floor();
        (
            (c.x.max(0.0) as usize).min(side - 1),
            (c.y.max(0.0) as usize).min(side - 1),
        )
    };
    // Each cell lists (polyline, which end: 0 start, 1 end).
    let mut grid: Vec<Vec<(usize, u8)>> = vec![Vec::new(); side * side];
    for (k, line) in lines.iter().enumerate() {
        for (end, p) in [(0u8, line[0]), (1u8, line[line.len() - 1])] {
            let (c, r) = index(p);
            grid[r * side + c].push((k, end));
        }
    }
    let mut done = vec![false; lines.len()];
    let mut order: Vec<(usize, bool)> = Vec::with_capacity(lines.len());
    let mut pen = lines[0][0];
    for _ in 0..lines.len() {
        let (c, r) = index(pen);
        let mut best: Option<(f64, usize, u8)> = None;
        for ring in 0..side {
            let (r0, r1) = (r.saturating_sub(ring), (r + ring).min(side - 1));
            let (c0, c1) = (c.saturating_sub(ring), (c + ring).min(side - 1));
            for rr in r0..=r1 {
                for cc in c0..=c1 {
                    if rr != r0 && rr != r1 && cc != c0 && cc != c1 {
                        continue; // inside the ring: already searched
                    }
                    for &(k, end) in &grid[rr * side + cc] {
                        if done[k] {
                            continue;
                        }
                        let p = if end == 0 {
                            lines[k][0]
                        } else {
                            lines[k][lines[k].len() - 1]
                        };
                        let d = p.distance(pen);
                        if best.is_none_or(|b| d < b.0) {
                            best = Some((d, k, end));
                        }
                    }
                }
            }
            // Anything beyond this ring is at least `ring · cell` away.
            if best.is_some_and(|b| b.0 <= ring as f64 * cell) {
                break;
            }
        }
        let Some((_, k, end)) = best else { break };
        done[k] = true;
        let reversed = end == 1;
        pen = if reversed {
            lines[k][0]
        } else {
            lines[k][lines[k].len() - 1]
        };
        order.push((k, reversed));
    }
    let mut taken: Vec<Option<Vec<DVec2>>> = lines.drain(..).map(Some).collect();
    order
        .into_iter()
        .filter_map(|(k, reversed)| {
            let mut line = taken[k].take()?;
            if reversed {
                line.reverse();
            }
            Some(line)
        })
        .collect()
}
