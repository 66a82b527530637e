"""projection="exact3d" against an independent z-buffer truth (truth.py), on the scenes of
mplot3d's best-known ordering reports, orthographic and perspective, in ID colours through
Agg with anti-aliasing off. Stock "3d"'s wrong pixels on the same scenes are printed beside.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import facesort.mpl  # noqa: E402,F401  (registers "exact3d")
from truth import Primitives, decode, id_colour, truth_of, wrong_pixels  # noqa: E402

DPI = 80
SIZE_IN = 5.0


def _faces3d(collection):
    """The 3D polygons a Poly3DCollection holds (matplotlib's own arrays, read directly)."""
    if hasattr(collection, "_faces"):
        faces = np.asarray(collection._faces, float)
        bad = np.broadcast_to(np.asarray(collection._invalid_vertices), faces.shape[:2])
        return [f[~b] for f, b in zip(faces, bad)]
    vec = np.asarray(collection._vec)
    xyz = (vec[:3] / vec[3]).T
    return [xyz[s] for s in collection._segslices]


class Scene:
    """A figure in ID colours and the primitives the truth rasterises."""

    def __init__(self, projection, proj_type, elev, azim):
        self.fig = plt.figure(figsize=(SIZE_IN, SIZE_IN), dpi=DPI, facecolor="black")
        self.ax = self.fig.add_subplot(projection=projection, facecolor="black")
        self.ax.set_axis_off()
        if proj_type == "persp":
            self.ax.set_proj_type("persp", focal_length=0.6)
        else:
            self.ax.set_proj_type("ortho")
        self.ax.view_init(elev=elev, azim=azim)
        self.prims = Primitives()
        self.next_id = 1

    def _ids(self, n):
        ids = list(range(self.next_id, self.next_id + n))
        self.next_id += n
        return ids

    def polygons(self, collection):
        faces = _faces3d(collection)
        ids = self._ids(len(faces))
        collection.set_facecolor([id_colour(i) for i in ids])
        collection.set_edgecolor("none")
        collection.set_linewidth(0)
        collection.set_antialiased(False)
        for f, i in zip(faces, ids):
            self.prims.polygons.append((f, i))

    def line(self, xs, ys, zs, width_pt=2.0):
        (i,) = self._ids(1)
        self.ax.plot(xs, ys, zs, color=id_colour(i), lw=width_pt, antialiased=False, solid_capstyle="butt")
        pts = np.column_stack([xs, ys, zs])
        for a, b in zip(pts[:-1], pts[1:]):
            self.prims.lines.append((np.array([a, b]), width_pt * DPI / 72, i))

    def scatter(self, pts, size_pt=8.0):
        ids = self._ids(len(pts))
        self.ax.scatter(
            pts[:, 0], pts[:, 1], pts[:, 2], c=[id_colour(i) for i in ids], s=size_pt**2,
            depthshade=False, linewidths=0, antialiased=False,
        )
        for p, i in zip(pts, ids):
            self.prims.discs.append((p, size_pt / 2 * DPI / 72, i))

    def score(self):
        self.fig.canvas.draw()
        image = np.asarray(self.fig.canvas.buffer_rgba())
        h, w = image.shape[:2]
        truth = truth_of(self.ax, self.prims, w, h)
        wrong, total = wrong_pixels(decode(image), truth)
        plt.close(self.fig)
        return wrong, total


def crossing_planes(s: Scene):
    """#29060: two planar surfaces crossing along a line."""
    x = np.linspace(-1, 1, 12)
    X, Y = np.meshgrid(x, x)
    s.polygons(s.ax.plot_surface(X, Y, 0.6 * X + 0.1 * Y, shade=False))
    s.polygons(s.ax.plot_surface(X, Y, -0.5 * X + 0.3 * Y + 0.1, shade=False))


def _sphere(c, r, n=14):
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, n, endpoint=False), np.linspace(0.15, np.pi - 0.15, n // 2))
    pts = np.column_stack([np.cos(u).ravel() * np.sin(v).ravel(), np.sin(u).ravel() * np.sin(v).ravel(), np.cos(v).ravel()])
    pts = np.vstack([pts, [[0, 0, 1], [0, 0, -1]]]) * r + c
    return pts


def two_spheres(s: Scene):
    """Two intersecting triangulated spheres (plot_trisurf, Delaunay in each's own
    projection: its triangles are the sphere's upper and lower caps)."""
    import matplotlib.tri as mtri

    for c in ([-0.35, 0, 0], [0.35, 0.1, 0.1]):
        pts = _sphere(np.array(c), 0.6)
        for sign in (1, -1):
            half = pts[(pts[:, 2] - c[2]) * sign >= -1e-9]
            tri = mtri.Triangulation(half[:, 0], half[:, 1])
            s.polygons(s.ax.plot_trisurf(tri, half[:, 2], shade=False))
    s.ax.set_box_aspect((1, 1, 1))
    s.ax.set_xlim(-1.1, 1.1), s.ax.set_ylim(-1.1, 1.1), s.ax.set_zlim(-1.1, 1.1)


def _torus(R, r, n, m, transform):
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, n), np.linspace(0, 2 * np.pi, m))
    x = (R + r * np.cos(v)) * np.cos(u)
    y = (R + r * np.cos(v)) * np.sin(u)
    z = r * np.sin(v)
    p = transform(np.stack([x, y, z], axis=-1))
    return p[..., 0], p[..., 1], p[..., 2]


def interlocking_rings(s: Scene):
    """Two tori through each other's holes."""
    s.polygons(s.ax.plot_surface(*_torus(1.0, 0.25, 24, 10, lambda p: p), shade=False))
    s.polygons(
        s.ax.plot_surface(*_torus(1.0, 0.25, 24, 10, lambda p: p[..., [0, 2, 1]] + [1.0, 0, 0]), shade=False)
    )
    s.ax.set_box_aspect((2.5, 1, 1))
    s.ax.set_xlim(-1.3, 2.3), s.ax.set_ylim(-1.3, 1.3), s.ax.set_zlim(-1.3, 1.3)


def line_through_plane(s: Scene):
    """#7684: a line through a plane, with scatter points on both sides of it."""
    x = np.linspace(-1, 1, 6)
    X, Y = np.meshgrid(x, x)
    s.polygons(s.ax.plot_surface(X, Y, 0 * X, shade=False))
    t = np.linspace(-1, 1, 9)
    s.line(0.3 * t, 0.2 * t, t)
    rng = np.random.default_rng(7684)
    pts = np.column_stack([rng.uniform(-0.8, 0.8, 16), rng.uniform(-0.8, 0.8, 16), rng.choice([-0.6, 0.6], 16)])
    s.scatter(pts)


def bars_and_voxels(s: Scene):
    """bar3d boxes standing in a voxel block, one passing through it."""
    filled = np.zeros((3, 3, 2), bool)
    filled[0, :, 0] = filled[:, 0, 0] = filled[1, 1, 1] = True
    for collection in s.ax.voxels(filled).values():
        s.polygons(collection)
    s.polygons(s.ax.bar3d([0.5, 1.5, 2.2], [0.5, 1.2, 0.4], [0.0, 0.5, 0.0], 0.6, 0.6, [2.5, 1.0, 1.5], shade=False))


def non_convex_fill(s: Scene):
    """A planar non-convex polygon (a star, as fill_between(mode="polygon") or contourf
    make) through a tilted surface (add_collection3d: every matplotlib from 3.8)."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    t = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    r = 0.8 + 0.15 * np.sin(5 * t)
    star = np.column_stack([r * np.cos(t), r * np.sin(t), 0.2 + 0 * t])
    s.polygons(s.ax.add_collection3d(Poly3DCollection([star])) or s.ax.collections[-1])
    x = np.linspace(-1, 1, 8)
    X, Y = np.meshgrid(x, x)
    s.polygons(s.ax.plot_surface(X, Y, 0.5 * X - 0.2 * Y + 0.2, shade=False))


SCENES = {
    "crossing_planes": (crossing_planes, 25, -60),
    "two_spheres": (two_spheres, 20, -50),
    "interlocking_rings": (interlocking_rings, 30, -70),
    "line_through_plane": (line_through_plane, 20, -35),
    "bars_and_voxels": (bars_and_voxels, 30, -55),
    "non_convex_fill": (non_convex_fill, 35, -65),
}


@pytest.mark.parametrize("proj_type", ["ortho", "persp"])
@pytest.mark.parametrize("name", list(SCENES))
def test_exact3d_draws_issue_scenes_exactly(name, proj_type):
    build, elev, azim = SCENES[name]
    results = {}
    for projection in ("3d", "exact3d"):
        scene = Scene(projection, proj_type, elev, azim)
        build(scene)
        results[projection] = scene.score()
    (stock, total), (exact, total_exact) = results["3d"], results["exact3d"]
    print(f"{name} {proj_type}: exact3d {exact} wrong of {total_exact} unambiguous px; stock 3d {stock} of {total}")
    assert total_exact > 1000, "the scene must cover the picture"
    assert exact == 0


def _translucent_planes(projection, proj_type):
    """#29060's planes, translucent: each paints alpha 0.5 of its own colour."""
    s = Scene(projection, proj_type, 25, -60)
    x = np.linspace(-1, 1, 4)
    X, Y = np.meshgrid(x, x)
    surfaces = []
    for colour, Z in (("#ff2000", 0.6 * X + 0.1 * Y), ("#0040ff", -0.5 * X + 0.3 * Y + 0.1)):
        c = s.ax.plot_surface(X, Y, Z, shade=False, color=colour, alpha=0.5, antialiased=False, linewidth=0)
        surfaces.append((c, colour))
    return s, surfaces


@pytest.mark.parametrize("proj_type", ["ortho", "persp"])
def test_exact3d_composites_translucent_surfaces_in_depth_order(proj_type):
    """Alpha compositing in exact order: every unambiguous pixel is the background with the
    far surface, then the near one, composited over it (per truth.py's depths), to within
    Agg's 8-bit rounding."""
    from matplotlib import colors as mcolors

    from truth import Truth, _project  # noqa: F401

    errors = {}
    for projection in ("3d", "exact3d"):
        s, surfaces = _translucent_planes(projection, proj_type)
        s.fig.canvas.draw()
        image = np.asarray(s.fig.canvas.buffer_rgba())[..., :3].astype(float)
        h, w = image.shape[:2]
        per_surface, both = [], Primitives()
        for n, (c, colour) in enumerate(surfaces):
            prims = Primitives(polygons=[(f, n + 1) for f in _faces3d(c)])
            both.polygons += prims.polygons
            per_surface.append((truth_of(s.ax, prims, w, h), np.array(mcolors.to_rgb(colour)) * 255))
        combined = truth_of(s.ax, both, w, h)
        mask = combined.unambiguous() & np.isfinite(per_surface[0][0].depth) & np.isfinite(per_surface[1][0].depth)
        (ta, ca), (tb, cb) = per_surface
        a_near = ta.depth < tb.depth
        far = np.where(a_near[..., None], cb, ca)
        near = np.where(a_near[..., None], ca, cb)
        expected = (0.5 * far) * 0.5 + 0.5 * near  # over a black background
        diff = np.abs(image - expected).max(axis=-1)
        errors[projection] = (int(np.count_nonzero(diff[mask] > 2.0)), int(np.count_nonzero(mask)))
        plt.close(s.fig)
    print(f"translucent planes {proj_type}: exact3d {errors['exact3d'][0]} off of {errors['exact3d'][1]} px; stock 3d {errors['3d'][0]}")
    assert errors["exact3d"][1] > 1000
    assert errors["exact3d"][0] == 0
    assert errors["3d"][0] > 0, "the scene must be one stock mplot3d gets wrong"


def test_computed_zorder_false_draws_each_zorder_as_a_layer():
    """With computed_zorder=False the user's zorder wins, as in mplot3d: a line of a higher
    zorder is drawn over a surface even where the surface hides it; each layer is exact."""
    s = Scene("exact3d", "ortho", 20, -35)
    s.ax.computed_zorder = False
    x = np.linspace(-1, 1, 6)
    X, Y = np.meshgrid(x, x)
    s.polygons(s.ax.plot_surface(X, Y, 0 * X, shade=False, zorder=1))
    t = np.linspace(-1, 1, 9)
    (i,) = s._ids(1)
    s.ax.plot(0.3 * t, 0.2 * t, t, color=id_colour(i), lw=2, antialiased=False, zorder=5)
    s.fig.canvas.draw()
    image = decode(np.asarray(s.fig.canvas.buffer_rgba()))
    h, w = image.shape
    # The truth of a layered picture: the line's pixels over the surface's truth.
    line_only = Primitives(lines=[(np.array([a, b]), 2 * DPI / 72, i) for a, b in zip(
        np.column_stack([0.3 * t, 0.2 * t, t])[:-1], np.column_stack([0.3 * t, 0.2 * t, t])[1:])])
    surface = Primitives(polygons=s.prims.polygons)
    lt, st_ = truth_of(s.ax, line_only, w, h), truth_of(s.ax, surface, w, h)
    expected = np.where(np.isfinite(lt.depth), lt.ids, st_.ids)
    mask = (lt.unambiguous() | (~np.isfinite(lt.depth) & st_.unambiguous())) & ~lt.near_edge
    wrong = int(np.count_nonzero(image[mask] != expected[mask]))
    hidden_but_drawn = int(np.count_nonzero(mask & np.isfinite(lt.depth) & np.isfinite(st_.depth) & (st_.depth < lt.depth)))
    plt.close(s.fig)
    print(f"computed_zorder=False: {wrong} wrong of {np.count_nonzero(mask)} px; {hidden_but_drawn} line px drawn over the surface that hides them")
    assert hidden_but_drawn > 20, "the line must pass behind the surface"
    assert wrong == 0


def test_interactive_rotation_redraws_exactly():
    """A mouse drag turns the view (mplot3d's own handlers) and the next draw is exact for
    the new view."""
    from matplotlib.backend_bases import MouseButton, MouseEvent

    s = Scene("exact3d", "ortho", 25, -60)
    crossing_planes(s)
    s.fig.canvas.draw()
    before = (s.ax.elev, s.ax.azim)
    canvas = s.fig.canvas
    x0, y0 = s.ax.bbox.x0 + 200, s.ax.bbox.y0 + 200
    for name, dx, dy in (("button_press_event", 0, 0), ("motion_notify_event", 40, 25), ("button_release_event", 40, 25)):
        event = MouseEvent(name, canvas, x0 + dx, y0 + dy, button=MouseButton.LEFT)
        event.inaxes = s.ax
        canvas.callbacks.process(name, event)
    assert (s.ax.elev, s.ax.azim) != before, "the drag must turn the view"
    wrong, total = s.score()
    print(f"after a drag to elev {s.ax.elev:.1f}, azim {s.ax.azim:.1f}: exact3d {wrong} wrong of {total}")
    assert total > 1000 and wrong == 0
