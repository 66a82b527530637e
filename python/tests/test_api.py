"""The facesort API: exact orders on random meshes and cameras (hypothesis, judged by the
oracle), files, plots, bakes and Presorted, and hostile inputs that raise only the
documented exceptions."""

from __future__ import annotations

import doctest
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import facesort

ROOT = Path(__file__).resolve().parents[2]
SPOT = ROOT / "assets/models/keenan-crane/spot/spot_quadrangulated.obj"
CUBE_V = np.array(
    [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1]], float
)
CUBE_F = np.array([[0, 2, 3, 1], [4, 5, 7, 6], [0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3]])


def test_package_docstring_examples_run():
    failed, attempted = doctest.testmod(facesort)
    assert attempted > 0 and failed == 0


@st.composite
def triangle_soups(draw):
    """2–12 random triangles in a unit box (crossing each other freely)."""
    n = draw(st.integers(2, 12))
    v = draw(hnp.arrays(np.float64, (3 * n, 3), elements=st.floats(-1, 1, allow_nan=False, width=32)))
    return v, np.arange(3 * n).reshape(n, 3)


@st.composite
def cameras(draw):
    yaw, pitch, roll = (draw(st.floats(-180, 180, allow_nan=False)) for _ in range(3))
    persp = draw(st.one_of(st.none(), st.floats(300, 3000)))
    cull = draw(st.sampled_from(["back", "none"]))
    return facesort.Camera.orbit(yaw, pitch, roll, width=256, height=256, perspective=persp, cull=cull)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(triangle_soups(), cameras(), st.sampled_from(["bsp", "newell"]))
def test_exact_sorters_have_no_oracle_violations(soup, camera, sorter):
    vertices, faces = soup
    try:
        mesh = facesort.Mesh(vertices, faces)
    except ValueError:
        return  # degenerate draws (zero-area triangles everywhere) are refused, by name
    order = mesh.sort(camera, sorter=sorter)
    assert order.violations() == 0
    points, offsets = order.polygons()
    assert len(offsets) == len(order) + 1 and points.shape[1] == 2
    assert set(order.faces.tolist()) <= set(range(len(faces)))


def test_centroid_is_measured_wrong_where_bsp_is_exact():
    # Two long crossing quads: the centroid sort cannot order them for every pixel.
    v = np.array([[-2, 0, -1], [2, 0, 1], [2, 1, 1], [-2, 1, -1], [-2, 0, 1], [2, 0, -1], [2, 1, -1], [-2, 1, 1]], float)
    mesh = facesort.Mesh(v, [[0, 1, 2, 3], [4, 5, 6, 7]])
    camera = facesort.Camera.orbit(10, 20, width=256, height=256, cull="none")
    assert mesh.sort(camera, "bsp").violations() == 0
    assert mesh.sort(camera, "centroid").violations() > 0


def test_cameras_from_look_at_and_matrices_agree():
    mesh = facesort.Mesh(CUBE_V, CUBE_F)
    eye, target = (3.0, 2.0, 4.0), (0.5, 0.5, 0.5)
    a = mesh.sort(facesort.Camera.look_at(eye, target, fov_y=40, width=200, height=100))
    f = np.array(eye) - target
    f = -f / np.linalg.norm(f)
    r = np.cross(f, [0, 1, 0])
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    view = np.eye(4)
    view[:3, :3] = [r, u, -f]
    view[:3, 3] = -view[:3, :3] @ eye
    t = 1 / np.tan(np.radians(20))
    near, far = 0.01, 100.0
    proj = np.array(
        [[t / 2, 0, 0, 0], [0, t, 0, 0], [0, 0, (far + near) / (near - far), 2 * far * near / (near - far)], [0, 0, -1, 0]]
    )
    b = mesh.sort(facesort.Camera.from_matrices(view, proj, width=200, height=100, clip="opengl"))
    assert a.faces.tolist() == b.faces.tolist()
    pa, pb = a.polygons()[0], b.polygons()[0]
    assert np.allclose(pa, pb, atol=1e-6)


def test_files_plots_bakes_and_presorted_on_spot():
    mesh = facesort.Mesh.load(SPOT)
    camera = facesort.Camera.orbit(145, -25, width=256, height=256)
    assert facesort.svg(mesh, camera).startswith("<svg")
    assert facesort.pdf(mesh, camera).startswith(b"%PDF")
    assert "<html" in facesort.html(mesh, camera).lower()
    fills = re.findall(r'fill="#([0-9a-f]{6})"', facesort.svg(mesh, camera, ids=True))
    assert fills and all(1 <= int(f, 16) <= mesh.face_count for f in fills)
    plot = facesort.plot_edges(mesh, camera, crease=30)
    assert plot.polylines and plot.pen_down > 0
    hpgl = plot.hpgl(40)
    assert hpgl.startswith("IN") and "PD" in hpgl
    presorted = facesort.Presorted(mesh)
    assert presorted.refused is None and presorted.regions > 0
    for yaw in (0, 90, 200):
        order = presorted.sort(facesort.Camera.orbit(yaw, 20, width=256, height=256))
        assert order.violations() == 0
    assert presorted.fallback_frames == 0


def test_yaw_bake_of_a_cube_and_its_page():
    bake = facesort.bake_yaw(facesort.Mesh(CUBE_V, CUBE_F), pitch=20, width=128, height=128)
    cells = bake.cells
    assert 1 <= len(cells) <= 8 and cells[0][0] == pytest.approx(0.0)
    page = bake.spin_html(period=4, paused=1.0)
    assert "<html" in page.lower() and "@keyframes" in page


def test_textured_mesh_from_arrays():
    texture = ROOT / "assets/models/keenan-crane/spot/spot_texture.png"
    uvs = np.column_stack([CUBE_V[:, 0], CUBE_V[:, 1]])
    mesh = facesort.Mesh(CUBE_V, CUBE_F, uvs=uvs, texture=texture)
    svg = facesort.svg(mesh, facesort.Camera.orbit(30, 20, width=128, height=128))
    assert "data:image/png;base64," in svg


def test_colours_are_used():
    colours = np.zeros((6, 3), np.uint8)
    colours[:, 0] = 255
    svg = facesort.svg(facesort.Mesh(CUBE_V, CUBE_F, colours=colours), facesort.Camera.orbit(30, 20))
    assert "#ff0000" in svg.lower()


# -- hostile input: only the documented exceptions, each naming what is wrong -------------


@pytest.mark.parametrize(
    "vertices, faces, kind, words",
    [
        (np.full((3, 3), np.nan), [[0, 1, 2]], ValueError, "vertices[0, 0]"),
        (np.array([[0, 0, 0], [1, 0, 0], [0, np.inf, 0]]), [[0, 1, 2]], ValueError, "vertices[2, 1]"),
        (np.zeros((3, 3), np.int32), [[0, 1, 2]], TypeError, "float64"),
        (np.zeros((3, 2)), [[0, 1, 2]], ValueError, "shape"),
        (np.zeros((3, 6))[:, ::2], [[0, 1, 2]], ValueError, "C-contiguous"),
        ([[0, 0, 0]] * 3, [[0, 1, 2]], TypeError, "numpy array"),
        (CUBE_V, [[0, 1, 9]], ValueError, "face 0 names vertex 9"),
        (CUBE_V, [[0, 1, 2], [0, -1, 2]], ValueError, "face 1 names vertex -1"),
        (CUBE_V, [[0, 1]], ValueError, "face 0 has 2 corners"),
        (CUBE_V, np.zeros((2, 3)), TypeError, "integers"),
        (CUBE_V, "faces", TypeError, "faces"),
        (CUBE_V, [[0, 1, "x"]], TypeError, "faces[0]"),
    ],
)
def test_bad_meshes_raise_named_errors(vertices, faces, kind, words):
    with pytest.raises(kind, match=None) as error:
        facesort.Mesh(vertices, faces)
    assert words in str(error.value)


def test_bad_cameras_and_options_raise_named_errors():
    mesh = facesort.Mesh(CUBE_V, CUBE_F)
    with pytest.raises(ValueError, match="width and height"):
        facesort.Camera.orbit(width=0)
    with pytest.raises(ValueError, match="cull"):
        facesort.Camera.orbit(cull="sideways")
    with pytest.raises(ValueError, match="eye"):
        facesort.Camera.look_at((0, 0, 0), (0, 0, 0), fov_y=40)
    with pytest.raises(ValueError, match="fov_y"):
        facesort.Camera.look_at((0, 0, 5), (0, 0, 0))
    with pytest.raises(ValueError, match="rigid"):
        facesort.Camera.from_matrices(np.diag([2.0, 1, 1, 1]), np.eye(4))
    with pytest.raises(ValueError, match="sorter"):
        mesh.sort(facesort.Camera.orbit(), sorter="magic")
    with pytest.raises(ValueError, match="colours"):
        facesort.Mesh(CUBE_V, CUBE_F, colours=np.zeros((5, 3)))
    with pytest.raises(ValueError, match="outside 0..1"):
        facesort.Mesh(CUBE_V, CUBE_F, colours=np.full((6, 3), 2.0))
    with pytest.raises(OSError, match="no_such.obj"):
        facesort.Mesh.load("no_such.obj")


@settings(max_examples=200, deadline=None)
@given(
    st.one_of(
        hnp.arrays(
            st.sampled_from([np.float64, np.float32]),
            hnp.array_shapes(min_dims=1, max_dims=3, max_side=5),
            elements=st.floats(allow_nan=True, allow_infinity=True, width=32),
        ),
        hnp.arrays(
            st.sampled_from([np.int64, np.uint8]),
            hnp.array_shapes(min_dims=1, max_dims=3, max_side=5),
            elements=st.integers(0, 200),
        ),
    ),
    st.lists(st.lists(st.integers(-3, 8), max_size=6), max_size=5),
)
def test_hostile_arrays_raise_only_documented_errors(vertices, faces):
    try:
        mesh = facesort.Mesh(vertices, faces)
    except (TypeError, ValueError):
        return
    # Whatever was accepted orders without a crash.
    mesh.sort(facesort.Camera.orbit(30, 20, width=64, height=64, cull="none"), sorter="bsp")
