"""matplotlib's mplot3d, drawn exactly: the ``"exact3d"`` projection.

Importing this module registers the projection::

    import matplotlib.pyplot as plt
    import facesort.mpl  # noqa: F401  (registers "exact3d")

    ax = plt.figure().add_subplot(projection="exact3d")
    ax.plot_surface(X, Y, Z)          # any code written for projection="3d"

Stock mplot3d sorts every artist by one depth, and every polygon of a collection by one
depth, and draws lines whole; surfaces that cross or interleave come out wrong. An
``ExactAxes3D`` gathers, at draw time, every polygon of its ``Poly3DCollection`` artists
(``plot_surface``, ``plot_trisurf``, ``bar3d``, ``voxels``, ``add_collection3d``,
``fill_between``), every segment of its ``Line3D`` and ``Line3DCollection`` artists (``plot``,
``plot_wireframe``) and every point of its ``Path3DCollection`` artists (``scatter``), and
draws them as one picture:

- polygons are split where they pass through each other and painted in an exact order
  (Newell's, in the axes' box coordinates, prepared once per set of polygons; it splits
  only what overlaps cyclically, so the picture has few more items than polygons, and
  neighbouring pieces of one polygon are drawn as one path);
- lines are clipped where polygons hide them, and their visible parts are painted among
  translucent polygons at their place in the order, so alpha composites exactly;
- a marker is a disc facing the viewer at its point's depth: it is painted just before the
  first polygon in front of it, so polygons cut it exactly where they cover it;
- colours, edge colours, line widths, alpha, mplot3d's shading (baked into the face colours
  when the artist is made) and scatter's depth shading are kept.

The projection is mplot3d's own (``get_proj()``: orthographic or perspective,
``focal_length``, ``roll``, ``box_aspect``): the order depends only on where the viewer is,
which this module reads off ``get_proj()``'s matrix. With ``computed_zorder=False`` each
``zorder`` is drawn as its own exact layer, lower first, as the user asked.

Differences from ``"3d"``:

- a line's visible parts are found along its centre line: where it passes behind the
  outline of a nearer polygon, its stroke reaches half its width over that outline;
- dashed lines restart their dash pattern at every visible part;
- a polygon's edge (``edgecolor``) is stroked where the polygon is; where a polygon was
  split, the cut is not stroked.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field

import numpy as np
from matplotlib import collections as mcoll
from matplotlib import colors as mcolors
from matplotlib import markers as mmarkers
from matplotlib import path as mpath
from matplotlib.artist import Artist
from matplotlib.projections import register_projection
from matplotlib.transforms import IdentityTransform
from mpl_toolkits.mplot3d import Axes3D, art3d, proj3d

from ._native import ExactScene

__all__ = ["ExactAxes3D"]

_MOVETO, _LINETO, _CLOSE = mpath.Path.MOVETO, mpath.Path.LINETO, mpath.Path.CLOSEPOLY


@dataclass
class _Gathered:
    """Everything one exact layer draws, in data coordinates (scaled where axes are)."""

    # Polygons, one chunk per artist: corners (p, 3), corner counts (n,), and per polygon
    # face and edge colours (n, 4), line width, anti-aliasing, edges in the face colour.
    corners: list = field(default_factory=list)
    counts: list = field(default_factory=list)
    face_rgba: list = field(default_factory=list)
    edge_rgba: list = field(default_factory=list)
    poly_lw: list = field(default_factory=list)
    poly_aa: list = field(default_factory=list)
    edge_face: list = field(default_factory=list)

    def polygon_arrays(self):
        """The polygon chunks joined: (corners, counts, face, edge, lw, aa, edge_face)."""
        if not self.counts:
            return None
        join = np.concatenate
        return (
            join(self.corners), join(self.counts), join(self.face_rgba), join(self.edge_rgba),
            join(self.poly_lw), join(self.poly_aa), join(self.edge_face),
        )
    lines: list = field(default_factory=list)  # (2, 3) segments
    line_rgba: list = field(default_factory=list)
    line_lw: list = field(default_factory=list)
    line_aa: list = field(default_factory=list)
    line_style: list = field(default_factory=list)
    points: list = field(default_factory=list)  # (3,) positions
    point_path: list = field(default_factory=list)  # unit marker paths
    point_size: list = field(default_factory=list)  # marker size in points (diameter)
    point_face: list = field(default_factory=list)
    point_edge: list = field(default_factory=list)
    point_lw: list = field(default_factory=list)


def _scaled(axes, xs, ys, zs):
    """Data coordinates after the axes' scales (matplotlib >= 3.11 projects these)."""
    apply = getattr(proj3d, "_apply_scale_transforms", None)
    if apply is None:
        return np.asarray(xs, float), np.asarray(ys, float), np.asarray(zs, float)
    xs, ys, zs = apply(xs, ys, zs, axes)
    return np.asarray(xs, float), np.asarray(ys, float), np.asarray(zs, float)


def _per_item(values, n):
    """``values`` (one per item, or one for all) as n rows."""
    values = np.asarray(values)
    if len(values) == 0:
        return None
    if len(values) != n:
        values = np.broadcast_to(values[:1] if values.ndim > 1 else values[0], (n,) + values.shape[1:])
    return values


def _poly3d_faces(col):
    """The 3D polygons of a Poly3DCollection as (corners (p, 3), counts (n,)), invalid
    (masked) vertices left out (matplotlib 3.8's layout and later ones')."""
    if hasattr(col, "_faces"):
        faces = np.asarray(col._faces, float)
        if faces.size == 0:
            return np.zeros((0, 3)), np.zeros(0, np.int64)
        valid = ~np.broadcast_to(np.asarray(col._invalid_vertices), faces.shape[:2])
        return faces[valid], valid.sum(axis=1)
    vec = np.asarray(col._vec)
    xyz = (vec[:3] / vec[3]).T
    counts = np.array([sl.stop - sl.start for sl in col._segslices], np.int64)
    return xyz, counts


def _gather_poly(col, axes, out: _Gathered):
    col.do_3d_projection()  # mplot3d's own colour mapping, into _facecolor3d
    corners, counts = _poly3d_faces(col)
    n = len(counts)
    if n == 0:
        return
    fc = _per_item(mcolors.to_rgba_array(col._facecolor3d), n)
    edge_face = isinstance(col._edgecolors, str) and col._edgecolors == "face"
    ec = _per_item(mcolors.to_rgba_array(col._edgecolor3d), n) if len(col._edgecolor3d) else None
    if fc is None:
        fc = np.zeros((n, 4))
    if ec is None:  # no edge colour: no edges, as mplot3d draws them
        ec, edge_face = np.zeros((n, 4)), False
    lw = _per_item(col.get_linewidths(), n)
    aa = _per_item(col.get_antialiased(), n)
    xs, ys, zs = _scaled(axes, corners[:, 0], corners[:, 1], corners[:, 2])
    corners = np.column_stack([xs, ys, zs])
    # Corners that are not finite (masked surfaces, log of ≤ 0) are left out; polygons
    # left with fewer than 3 corners are dropped.
    finite = np.all(np.isfinite(corners), axis=1)
    owner = np.repeat(np.arange(n), counts)
    counts = np.bincount(owner[finite], minlength=n)
    corners = corners[finite]
    keep = counts >= 3
    corners = corners[np.repeat(keep, counts)]
    out.corners.append(corners)
    out.counts.append(counts[keep])
    out.face_rgba.append(np.asarray(fc, float)[keep])
    out.edge_rgba.append(np.asarray(ec, float)[keep])
    out.poly_lw.append((np.asarray(lw, float) if lw is not None else np.zeros(n))[keep])
    out.poly_aa.append((np.asarray(aa, bool) if aa is not None else np.ones(n, bool))[keep])
    same = np.all(np.asarray(ec) == np.asarray(fc), axis=1) | edge_face
    out.edge_face.append(same[keep])
    # An invisible edge strokes nothing.
    out.poly_lw[-1] = np.where(np.asarray(ec, float)[keep][:, 3] > 0, out.poly_lw[-1], 0.0)


def _add_polyline(out: _Gathered, pts, rgba, lw, aa, style):
    pts = np.asarray(pts, float)
    for a, b in zip(pts[:-1], pts[1:]):
        if np.all(np.isfinite(a)) and np.all(np.isfinite(b)) and not np.array_equal(a, b):
            out.lines.append(np.array([a, b]))
            out.line_rgba.append(rgba)
            out.line_lw.append(lw)
            out.line_aa.append(aa)
            out.line_style.append(style)


def _marker_path(marker):
    style = marker if isinstance(marker, mmarkers.MarkerStyle) else mmarkers.MarkerStyle(marker)
    return style.get_path().transformed(style.get_transform()), style.is_filled()


def _gather_line(line, axes, out: _Gathered):
    xs, ys, zs = (np.asarray(v, float) for v in line.get_data_3d())
    xs, ys, zs = _scaled(axes, xs, ys, zs)
    pts = np.column_stack([xs, ys, zs])
    rgba = mcolors.to_rgba(line.get_color(), line.get_alpha())
    if line.get_linestyle() not in ("None", "none", "", " ") and line.get_linewidth() > 0:
        _add_polyline(out, pts, rgba, line.get_linewidth(), line.get_antialiased(), line.get_linestyle())
    marker = line.get_marker()
    if marker not in (None, "None", "none", "", " "):
        path, filled = _marker_path(line._marker)
        face = mcolors.to_rgba(line.get_markerfacecolor(), line.get_alpha()) if filled else (0, 0, 0, 0)
        edge = mcolors.to_rgba(line.get_markeredgecolor(), line.get_alpha())
        for p in pts[np.all(np.isfinite(pts), axis=1)]:
            out.points.append(p)
            out.point_path.append(path)
            out.point_size.append(line.get_markersize())
            out.point_face.append(face)
            out.point_edge.append(edge)
            out.point_lw.append(line.get_markeredgewidth())


def _gather_line_collection(col, axes, out: _Gathered):
    segments = col._segments3d
    n = len(segments)
    if n == 0:
        return
    rgba = _per_item(col.get_edgecolor(), n)
    lw = _per_item(col.get_linewidths(), n)
    aa = _per_item(col.get_antialiased(), n)
    styles = col.get_linestyle()
    for i, seg in enumerate(segments):
        seg = np.ma.filled(np.ma.asarray(seg, float), np.nan)
        xs, ys, zs = _scaled(axes, seg[:, 0], seg[:, 1], seg[:, 2])
        style = styles[i % len(styles)] if styles else "solid"
        if lw is not None and lw[i] > 0 and rgba is not None:
            _add_polyline(out, np.column_stack([xs, ys, zs]), rgba[i], float(lw[i]), bool(aa[i]), style)


def _gather_scatter(col, axes, out: _Gathered):
    xs, ys, zs = (np.ma.filled(np.ma.asarray(v, float), np.nan).ravel() for v in col._offsets3d)
    n = len(xs)
    if n == 0:
        return
    col.do_3d_projection()  # mplot3d's depth shading, in its sorted order
    order = np.asarray(getattr(col, "_z_markers_idx", np.arange(n)))
    face = mcolors.to_rgba_array(col.get_facecolor())
    edge = mcolors.to_rgba_array(col.get_edgecolor())

    def unsort(c):
        if len(c) == n and len(order) == n:
            back = np.empty_like(c)
            back[order] = c
            return back
        return _per_item(c, n) if len(c) else np.zeros((n, 4))

    face, edge = unsort(face), unsort(edge)
    sizes = _per_item(getattr(col, "_sizes3d", col.get_sizes()), n)
    lws = _per_item(getattr(col, "_linewidths3d", col.get_linewidths()), n)
    path = col.get_paths()[0] if col.get_paths() else _marker_path("o")[0]
    xs, ys, zs = _scaled(axes, xs, ys, zs)
    for i in range(n):
        p = np.array([xs[i], ys[i], zs[i]])
        if not np.all(np.isfinite(p)):
            continue
        out.points.append(p)
        out.point_path.append(path)
        out.point_size.append(float(np.sqrt(sizes[i])) if sizes is not None else 6.0)
        out.point_face.append(face[i])
        out.point_edge.append(edge[i])
        out.point_lw.append(float(lws[i]) if lws is not None else 0.0)


_GATHER = (
    (art3d.Poly3DCollection, _gather_poly),
    (art3d.Line3DCollection, _gather_line_collection),
    (art3d.Path3DCollection, _gather_scatter),
    (art3d.Line3D, _gather_line),
)


def _handled(artist) -> bool:
    return any(isinstance(artist, kind) for kind, _ in _GATHER)


def _viewer(M, to_box):
    """The viewer of projection matrix ``M`` in box coordinates, as a homogeneous point:
    the point (eye) or direction (parallel projection, w = 0) that ``M`` sends to the
    screen's centre of projection (x, y and w rows all zero)."""
    A = (M @ np.linalg.inv(to_box))[[0, 1, 3]]
    null = np.linalg.svd(A)[2][-1]
    if abs(null[3]) > 1e-12 * np.abs(null[:3]).max():
        return tuple(null / null[3])
    # A direction: point it toward the viewer, where mplot3d's projected z decreases.
    direction = null[:3] / np.linalg.norm(null[:3])
    Mb = M @ np.linalg.inv(to_box)
    centre = np.array([0.5, 0.5, 0.5, 1.0])
    z = lambda p: (Mb @ p)[2] / (Mb @ p)[3]  # noqa: E731
    if z(centre + np.append(direction, 0.0)) > z(centre):
        direction = -direction
    return (*direction, 0.0)


def _disc_meets_polygon(c, radius, poly):
    """Whether a disc and a convex polygon (display coordinates) overlap."""
    n = len(poly)
    edges = np.roll(poly, -1, axis=0) - poly
    rel = c - poly
    cross = edges[:, 0] * rel[:, 1] - edges[:, 1] * rel[:, 0]
    if np.all(cross >= 0) or np.all(cross <= 0):
        return True
    length2 = np.einsum("ij,ij->i", edges, edges)
    t = np.clip(np.einsum("ij,ij->i", rel, edges) / np.where(length2 > 0, length2, 1), 0, 1)
    closest = poly + edges * t[:, None]
    return bool(np.min(np.hypot(*(c - closest).T)) < radius) and n >= 3


def _depth_at(poly, pz, c):
    """The depth of a planar polygon's plane at display point ``c`` (affine over the
    screen), from the corner triple that spans the most area."""
    best, area = None, 0.0
    n = len(poly)
    for j in range(1, n - 1):
        a = (poly[j] - poly[0])
        b = (poly[j + 1] - poly[0])
        s = a[0] * b[1] - a[1] * b[0]
        if abs(s) > abs(area):
            best, area = j, s
    if best is None or area == 0:
        return float(np.mean(pz))
    j = best
    a, b, d = poly[j] - poly[0], poly[j + 1] - poly[0], c - poly[0]
    u = (d[0] * b[1] - d[1] * b[0]) / area
    v = (a[0] * d[1] - a[1] * d[0]) / area
    return float(pz[0] + u * (pz[j] - pz[0]) + v * (pz[j + 1] - pz[0]))


class _ExactLayer(Artist):
    """One exact picture of some of the axes' artists, drawn in their place."""

    def __init__(self, axes, artists, zorder):
        super().__init__()
        self.axes = axes
        self._sources = artists
        self.set_zorder(zorder)
        self.set_figure(axes.figure)

    def draw(self, renderer):
        axes = self.axes
        gathered = _Gathered()
        for artist in self._sources:
            for kind, gather in _GATHER:
                if isinstance(artist, kind):
                    gather(artist, axes, gathered)
                    break
        if not gathered.counts and not gathered.lines and not gathered.points:
            return
        collection = axes._exact_collection(gathered, renderer)
        # Clipped as the artists it draws are (mplot3d's: to the axes' patch).
        clipped = [a for a in self._sources if a.get_clip_on()]
        if clipped:
            collection.set_clip_on(True)
            collection.set_clip_box(clipped[0].get_clip_box())
            collection.set_clip_path(clipped[0].get_clip_path())
        collection.draw(renderer)


class ExactAxes3D(Axes3D):
    """An ``Axes3D`` whose polygons, lines and markers are drawn as one exact picture
    (module docs). Use it as ``projection="exact3d"``; everything else is ``Axes3D``."""

    name = "exact3d"

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._exact_cache = {}
        # matplotlib's tick locators and axis margins test `axes.name == "3d"`: an exact
        # axes ticks as mplot3d's (the projection stays registered as "exact3d").
        self.name = "3d"

    def draw(self, renderer):
        if not self.get_visible():
            return
        sources = [a for a in self._children if _handled(a) and a.get_visible()]
        if not sources:
            return super().draw(renderer)
        if self.computed_zorder:
            zorder = max(axis.get_zorder() for axis in self._axis_map.values()) + 1
            groups = [(zorder, sources)]
        else:
            by_z = {}
            for a in sources:
                by_z.setdefault(a.get_zorder(), []).append(a)
            groups = sorted(by_z.items(), key=lambda g: g[0])
        layers = [_ExactLayer(self, artists, z) for z, artists in groups]
        # Hide the sources from the stock draw without marking anything stale (no redraw
        # loop): their picture is the layers'.
        for a in sources:
            a._visible = False
        self._children.extend(layers)
        try:
            super().draw(renderer)
        finally:
            for layer in layers:
                self._children.remove(layer)
            for a in sources:
                a._visible = True

    # -- the engine ---------------------------------------------------------------------

    def _box(self):
        """Data (scaled) → unit box: an affine map per axis, from the axes' limits."""
        lims = []
        for get in (self.get_xlim3d, self.get_ylim3d, self.get_zlim3d):
            lo, hi = get()
            lims.append((lo, hi))
        lo = np.array([l for l, _ in lims], float)
        hi = np.array([h for _, h in lims], float)
        apply = getattr(proj3d, "_apply_scale_transforms", None)
        if apply is not None:
            lo = np.array(apply(*lo, self), float).ravel()
            hi = np.array(apply(*hi, self), float).ravel()
        span = np.where(hi - lo == 0, 1.0, hi - lo)
        to_box = np.eye(4)
        to_box[:3, :3] = np.diag(1.0 / span)
        to_box[:3, 3] = -lo / span
        return to_box

    def _scene(self, points_box, offsets):
        """The ExactScene of these polygons, built once while they stay the same."""
        key = hashlib.blake2b(points_box.tobytes() + offsets.tobytes(), digest_size=16).digest()
        scene = self._exact_cache.get(key)
        if scene is None:
            scene = ExactScene(points_box, offsets)
            self._exact_cache = {key: scene}  # one set of polygons kept per axes
        return scene

    @staticmethod
    def _marker_places(r, centres, depths, radii, display):
        """Where each marker goes in the paint order: just before the first item in front
        of it among those its disc overlaps (a marker is a disc facing the viewer at its
        point's depth). Every item behind it that its disc overlaps overlaps that item too,
        so an exact order paints them earlier; items in front paint over the marker, opaque
        or not, so a marker half behind a polygon's outline is cut there."""
        k = r["items"]
        places = np.full(len(centres), k, dtype=np.int64)
        if k == 0:
            return places
        xy, z = display(r["points"], with_depth=True)
        offs = r["offsets"]
        starts, stops = offs[:-1], offs[1:]
        lo = np.minimum.reduceat(xy, starts, axis=0)
        hi = np.maximum.reduceat(xy, starts, axis=0)
        for m, (c, depth, radius) in enumerate(zip(centres, depths, radii)):
            near = np.nonzero(np.all(lo <= c + radius, axis=1) & np.all(hi >= c - radius, axis=1))[0]
            for i in near:
                a, b = starts[i], stops[i]
                poly, pz = xy[a:b], z[a:b]
                if not _disc_meets_polygon(c, radius, poly):
                    continue
                # The item's depth under the marker's centre: its plane, affine over the
                # screen (three corners that span it).
                front = _depth_at(poly, pz, c) < depth
                if front:
                    places[m] = min(places[m], i)
                    break  # items come in paint order: the first in front decides
        return places

    def _exact_collection(self, g: _Gathered, renderer):
        M = self.M
        to_box = self._box()

        def box(p):
            p = np.asarray(p, float).reshape(-1, 3)
            return p @ to_box[:3, :3].T + to_box[:3, 3]

        def display(p_box, with_depth=False):
            """Box coordinates → display pixels (and mplot3d's projected z, smaller
            nearer), through mplot3d's projection."""
            data = (p_box - to_box[:3, 3]) / np.diag(to_box)[:3]
            h = np.column_stack([data, np.ones(len(data))]) @ M.T
            xy = self.transData.transform(h[:, :2] / h[:, 3:4])
            return (xy, h[:, 2] / h[:, 3]) if with_depth else xy

        polygons = g.polygon_arrays()
        n_poly = 0 if polygons is None else len(polygons[1])
        if n_poly:
            corners, counts, face_rgba, edge_rgba, poly_lw, poly_aa, edge_face = polygons
            offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
            points = np.ascontiguousarray(box(corners))
        else:
            # No polygon: a scene of one tiny invisible triangle (lines and points are then
            # all visible, in their given order).
            offsets = np.array([0, 3], np.int64)
            points = np.array([[0.0, 0.0, 0.0], [1e-3, 0.0, 0.0], [0.0, 1e-3, 0.0]])
            face_rgba = np.zeros((1, 4))
        scene = self._scene(points, offsets)
        viewer = _viewer(M, to_box)
        bbox = self.bbox
        width = int(max(1, min(32768, round(bbox.width))))
        height = int(max(1, min(32768, round(bbox.height))))
        opaque = (face_rgba[:, 3] >= 1.0) if n_poly else np.zeros(1, bool)
        lines = np.ascontiguousarray(box(np.array(g.lines).reshape(-1, 3)).reshape(-1, 2, 3)) if g.lines else None
        # Same-polygon neighbours drawn as one item (fewer paths for Agg), except where
        # markers are placed among the items by their planes.
        r = scene.order(viewer, width, height, np.ascontiguousarray(opaque), lines, merge=not g.points)

        # Elements of one collection, each with a sort key: item i at 2i + 1, a line part
        # or marker painted before item j at 2j.
        paths, keys = [], []
        fcs, ecs, lws, aas, styles = [], [], [], [], []
        none = np.zeros(4)
        k = r["items"]
        if n_poly and k:
            xy = display(r["points"])
            offs = r["offsets"]
            faces = r["faces"].astype(np.int64)
            sizes = np.diff(offs)
            # Each item closed (its first corner repeated), all in one array; each path a
            # view of it, made without matplotlib's per-path checks (the same paths, made
            # the way matplotlib makes its own).
            closed = np.empty((len(xy) + k, 2))
            at = offs[:-1] + np.arange(k)
            gather = np.arange(len(xy) + k) - np.repeat(np.arange(k), sizes + 1)
            ends = at + sizes
            gather[ends] = offs[:-1]
            closed[:] = xy[gather]
            codes_of = {}
            template = mpath.Path(np.zeros((2, 2)))
            template.should_simplify = False
            fast = mpath.Path._fast_from_codes_and_verts
            for i in range(k):
                n = sizes[i]
                codes = codes_of.get(n)
                if codes is None:
                    codes = np.full(n + 1, _LINETO, dtype=mpath.Path.code_type)
                    codes[0], codes[-1] = _MOVETO, _CLOSE
                    codes_of[n] = codes
                paths.append(fast(closed[at[i] : at[i] + n + 1], codes, internals_from=template))
            same = edge_face[faces]
            lw = poly_lw[faces]
            fcs.append(face_rgba[faces])
            ecs.append(np.where((same & (lw > 0))[:, None], face_rgba[faces], none))
            lws.append(np.where(same, lw, 0.0))
            aas.append(poly_aa[faces])
            styles += ["solid"] * k
            keys.append(2 * np.arange(k) + 1)
            # Edges in their own colour: the parts of each item's outline on its polygon's
            # outline (not where it was cut), stroked right after the item.
            edges = r["edges"]
            stroked = (~same) & (lw > 0) & (edge_rgba[faces][:, 3] > 0)
            for i in np.nonzero(stroked)[0]:
                a, b = offs[i], offs[i + 1]
                on = np.nonzero(edges[a:b])[0]
                if len(on) == 0:
                    continue
                verts = np.empty((2 * len(on), 2))
                verts[0::2] = xy[a + on]
                verts[1::2] = xy[a + (on + 1) % sizes[i]]
                codes = np.tile(np.array([_MOVETO, _LINETO], dtype=mpath.Path.code_type), len(on))
                paths.append(mpath.Path(verts, codes))
                fcs.append(none[None])
                ecs.append(edge_rgba[faces[i]][None])
                lws.append(lw[i : i + 1])
                aas.append(poly_aa[faces[i]][None])
                styles.append("solid")
                keys.append(np.array([2 * i + 1]))
        if g.lines:
            ends = np.array(g.lines)
            for line, (t0, t1), before in zip(r["line"], r["line_t"], r["line_before"]):
                a, b = ends[line]
                part = box(np.array([a + (b - a) * t0, a + (b - a) * t1]))
                paths.append(mpath.Path(display(part)))
                fcs.append(none[None])
                ecs.append(np.asarray(g.line_rgba[line], float)[None])
                lws.append(np.array([g.line_lw[line]], float))
                aas.append(np.array([g.line_aa[line]], bool))
                styles.append(g.line_style[line])
                keys.append(np.array([2 * before]))
        if g.points:
            scale = renderer.points_to_pixels(1.0)
            centres, depths = display(box(np.array(g.points)), with_depth=True)
            radii = np.array(g.point_size) * scale / 2
            places = self._marker_places(r, centres, depths, radii, display)
            for point, before in enumerate(places):
                unit = g.point_path[point]
                size = g.point_size[point] * scale
                paths.append(mpath.Path(unit.vertices * size + centres[point], unit.codes))
                fcs.append(np.asarray(g.point_face[point], float)[None])
                ecs.append(np.asarray(g.point_edge[point], float)[None])
                lws.append(np.array([g.point_lw[point]], float))
                aas.append(np.array([True]))
                styles.append("solid")
                keys.append(np.array([2 * before]))
        order = np.argsort(np.concatenate(keys).astype(np.int64), kind="stable")
        pick = lambda xs: [xs[i] for i in order]  # noqa: E731
        widths = np.concatenate(lws)[order]
        if len(widths) and np.all(widths == widths[0]):
            widths = widths[:1]  # one width for all: matplotlib scales one dash pattern
        collection = mcoll.PathCollection(
            pick(paths),
            facecolors=np.concatenate(fcs).reshape(-1, 4)[order],
            edgecolors=np.concatenate(ecs).reshape(-1, 4)[order],
            linewidths=widths,
            antialiaseds=np.concatenate(aas)[order],
            linestyles=pick(styles) if any(s != "solid" for s in styles) else "solid",
            transform=IdentityTransform(),
        )
        collection.set_figure(self.figure)
        collection.set_clip_on(False)
        return collection


register_projection(ExactAxes3D)
