"""An independent z-buffer truth for mplot3d pictures, from matplotlib's own projection.

It shares no code with facesort: every primitive is projected with ``ax.get_proj()`` and
``ax.transData`` and rasterised per pixel centre in numpy, nearest depth winning (ties to
the lower id), as docs/CONVENTIONS.md defines the truth and its unambiguous pixels:

- a polygon is the fan of triangles from its first corner; its depth at a pixel is its
  projected z (smaller is nearer in mplot3d), affine over the screen for a planar piece;
- a line of width ``w`` pixels covers the pixel centres within ``w / 2`` of its projected
  centreline (butt ends), at the depth of the centreline point beside them;
- a marker is a disc of its radius at its point's depth (a billboard).

A pixel is unambiguous when it is covered, at least ``MARGIN`` pixels from every edge of
every primitive (triangle sides, fan diagonals, line sides and ends, disc outlines), and its
nearest two depths differ by more than ``1e-6`` of the scene's depth range, and its centre
is at least ``MARGIN`` pixels from where those two surfaces cross. Agg without
anti-aliasing does not sample pixel centres: it fills every pixel a polygon's outline
touches (measured: up to 0.70 px beyond the outline), so the polygon painted last at a
crossing spills over it by up to that much, whatever the order. A crossing is an edge of
the picture as much as a polygon's side, and gets the same margin.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

MARGIN = 0.75


@dataclass
class Primitives:
    """What a test scene draws, in data coordinates, each with its id (1-based)."""

    polygons: list = field(default_factory=list)  # ((k, 3) array, id)
    lines: list = field(default_factory=list)  # ((2, 3) array, width_px, id)
    discs: list = field(default_factory=list)  # ((3,) array, radius_px, id)


def id_colour(i: int) -> str:
    """The ID colour of id ``i`` (CONVENTIONS.md: R high byte, B low byte)."""
    return "#{:02x}{:02x}{:02x}".format((i >> 16) & 255, (i >> 8) & 255, i & 255)


def decode(rgb: np.ndarray) -> np.ndarray:
    """Ids of an (h, w, 3+) uint8 image."""
    rgb = rgb[..., :3].astype(np.int64)
    return (rgb[..., 0] << 16) | (rgb[..., 1] << 8) | rgb[..., 2]


def _planar(pts, rel=1e-9):
    """Whether 3D points lie on one plane (to ``rel`` of their extent)."""
    p = np.asarray(pts, float) - np.mean(pts, axis=0)
    size = np.abs(p).max()
    return size == 0 or np.linalg.svd(p, compute_uv=False)[-1] <= rel * size * np.sqrt(len(p))


def _convex(x, y):
    """Whether a 2D polygon turns one way only."""
    dx, dy = np.roll(x, -1) - x, np.roll(y, -1) - y
    turn = dx * np.roll(dy, -1) - dy * np.roll(dx, -1)
    return bool(np.all(turn >= 0) or np.all(turn <= 0))


def _project(ax, pts):
    """Data points → (display x, y with y down in image rows, projected z)."""
    M = ax.get_proj()
    pts = np.asarray(pts, float).reshape(-1, 3)
    h = np.column_stack([pts, np.ones(len(pts))]) @ M.T
    ndc = h[:, :3] / h[:, 3:4]
    disp = ax.transData.transform(ndc[:, :2])
    height = ax.figure.bbox.height
    return disp[:, 0], height - disp[:, 1], ndc[:, 2]


class Truth:
    """Nearest id and depth per pixel, and the ambiguity mask."""

    def __init__(self, width: int, height: int):
        self.w, self.h = width, height
        self.depth = np.full((height, width), np.inf)
        self.second = np.full((height, width), np.inf)
        # Screen gradients (per pixel, x and y) of the nearest and second depths.
        self.grad = np.zeros((height, width, 2))
        self.grad2 = np.zeros((height, width, 2))
        self.ids = np.zeros((height, width), np.int64)
        self.near_edge = np.zeros((height, width), bool)
        self.zmin, self.zmax = np.inf, -np.inf

    def _box(self, xs, ys, pad):
        x0 = max(int(np.floor(min(xs) - pad)), 0)
        x1 = min(int(np.ceil(max(xs) + pad)) + 1, self.w)
        y0 = max(int(np.floor(min(ys) - pad)), 0)
        y1 = min(int(np.ceil(max(ys) + pad)) + 1, self.h)
        if x0 >= x1 or y0 >= y1:
            return None
        px, py = np.meshgrid(np.arange(x0, x1) + 0.5, np.arange(y0, y1) + 0.5)
        return (slice(y0, y1), slice(x0, x1)), px, py

    def _offer(self, where, mask, z, grad, ident):
        d, s, ids = self.depth[where], self.second[where], self.ids[where]
        g, g2 = self.grad[where], self.grad2[where]
        grad = np.broadcast_to(np.asarray(grad, float), g.shape)
        nearer = mask & ((z < d) | ((z == d) & (ident < ids)))
        farther = mask & ~nearer
        # The old nearest becomes the second where it is nearer than the old second.
        demote = nearer & (d < s)
        s = np.where(demote, d, s)
        g2 = np.where(demote[..., None], g, g2)
        promote = farther & (z < s)
        s = np.where(promote, z, s)
        g2 = np.where(promote[..., None], grad, g2)
        d_new = np.where(nearer, z, d)
        g = np.where(nearer[..., None], grad, g)
        ids[nearer] = ident
        self.depth[where], self.second[where], self.ids[where] = d_new, s, ids
        self.grad[where], self.grad2[where] = g, g2

    def _edge(self, a, b):
        """Marks pixels within MARGIN of segment a–b (display, y down)."""
        box = self._box([a[0], b[0]], [a[1], b[1]], MARGIN + 1)
        if box is None:
            return
        where, px, py = box
        e = b - a
        l2 = e @ e
        t = np.clip(((px - a[0]) * e[0] + (py - a[1]) * e[1]) / l2, 0, 1) if l2 > 0 else 0 * px
        dx, dy = px - (a[0] + t * e[0]), py - (a[1] + t * e[1])
        self.near_edge[where] |= dx * dx + dy * dy < MARGIN * MARGIN

    def triangle(self, x, y, z, ident):
        self.zmin, self.zmax = min(self.zmin, z.min()), max(self.zmax, z.max())
        p = np.column_stack([x, y])
        for k in range(3):
            self._edge(p[k], p[(k + 1) % 3])
        area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0])
        if area == 0:
            return
        box = self._box(x, y, 0)
        if box is None:
            return
        where, px, py = box
        w0 = ((x[1] - px) * (y[2] - py) - (x[2] - px) * (y[1] - py)) / area
        w1 = ((x[2] - px) * (y[0] - py) - (x[0] - px) * (y[2] - py)) / area
        w2 = 1 - w0 - w1
        inside = (w0 >= 0) & (w1 >= 0) & (w2 >= 0)
        # z = a·x + b·y + c over the triangle.
        gx = ((z[1] - z[0]) * (y[2] - y[0]) - (z[2] - z[0]) * (y[1] - y[0])) / area
        gy = ((x[1] - x[0]) * (z[2] - z[0]) - (x[2] - x[0]) * (z[1] - z[0])) / area
        self._offer(where, inside, w0 * z[0] + w1 * z[1] + w2 * z[2], (gx, gy), ident)

    def polygon(self, ax, pts, ident):
        x, y, z = _project(ax, pts)
        if len(x) > 3 and _planar(pts) and not _convex(x, y):
            self.planar_polygon(x, y, z, ident)
            return
        for k in range(1, len(x) - 1):
            idx = [0, k, k + 1]
            self.triangle(x[idx], y[idx], z[idx], ident)

    def planar_polygon(self, x, y, z, ident):
        """A planar, possibly non-convex polygon: pixel centres inside its projected outline
        (matplotlib.path's point-in-polygon test), depth from its plane (affine over the
        screen, fitted through its corners)."""
        from matplotlib.path import Path

        self.zmin, self.zmax = min(self.zmin, z.min()), max(self.zmax, z.max())
        n = len(x)
        for k in range(n):
            self._edge(np.array([x[k], y[k]]), np.array([x[(k + 1) % n], y[(k + 1) % n]]))
        box = self._box(x, y, 0)
        if box is None:
            return
        where, px, py = box
        inside = Path(np.column_stack([x, y])).contains_points(np.column_stack([px.ravel(), py.ravel()])).reshape(px.shape)
        A = np.column_stack([x, y, np.ones(n)])
        (gx, gy, c), *_ = np.linalg.lstsq(A, z, rcond=None)
        self._offer(where, inside, gx * px + gy * py + c, (gx, gy), ident)

    def line(self, ax, ends, width, ident):
        x, y, z = _project(ax, ends)
        a, b = np.array([x[0], y[0]]), np.array([x[1], y[1]])
        e = b - a
        length = np.hypot(*e)
        if length == 0:
            return
        n = np.array([-e[1], e[0]]) / length * width / 2
        corners = [a + n, b + n, b - n, a - n]
        for k in range(4):
            self._edge(corners[k], corners[(k + 1) % 4])
        box = self._box([c[0] for c in corners], [c[1] for c in corners], 0)
        if box is None:
            return
        where, px, py = box
        t = ((px - a[0]) * e[0] + (py - a[1]) * e[1]) / (length * length)
        dist = np.abs((px - a[0]) * e[1] - (py - a[1]) * e[0]) / length
        inside = (t >= 0) & (t <= 1) & (dist <= width / 2)
        slope = (z[1] - z[0]) / (length * length)
        self._offer(where, inside, z[0] + (z[1] - z[0]) * t, (slope * e[0], slope * e[1]), ident)

    def disc(self, ax, at, radius, ident):
        x, y, z = _project(ax, [at])
        box = self._box([x[0]], [y[0]], radius + MARGIN + 1)
        if box is None:
            return
        where, px, py = box
        r = np.hypot(px - x[0], py - y[0])
        self.near_edge[where] |= np.abs(r - radius) < MARGIN
        self._offer(where, r <= radius, np.full(px.shape, z[0]), (0.0, 0.0), ident)

    def unambiguous(self):
        floor = 1e-6 * max(self.zmax - self.zmin, 1e-300)
        covered = np.isfinite(self.depth)
        with np.errstate(invalid="ignore"):
            gap = self.second - self.depth
            swing = np.linalg.norm(self.grad2 - self.grad, axis=-1) * MARGIN
            clear = ~np.isfinite(self.second) | ((gap > floor) & (gap > swing))
        return covered & ~self.near_edge & clear


def truth_of(ax, prims: Primitives, width: int, height: int) -> Truth:
    t = Truth(width, height)
    for pts, ident in prims.polygons:
        t.polygon(ax, pts, ident)
    for ends, width_px, ident in prims.lines:
        t.line(ax, ends, width_px, ident)
    for at, radius, ident in prims.discs:
        t.disc(ax, at, radius, ident)
    return t


def wrong_pixels(image_ids: np.ndarray, truth: Truth) -> tuple[int, int]:
    """(wrong unambiguous pixels, unambiguous pixels)."""
    mask = truth.unambiguous()
    return int(np.count_nonzero(image_ids[mask] != truth.ids[mask])), int(np.count_nonzero(mask))
