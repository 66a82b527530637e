"""The vpype plugin writes the same visible edges as `cargo xtask render --plot`."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

vpype_cli = pytest.importorskip("vpype_cli")

ROOT = Path(__file__).resolve().parents[2]
SPOT = ROOT / "assets/models/keenan-crane/spot/spot_quadrangulated.obj"


def _polylines(svg: str):
    """Every polyline of an SVG as an (n, 2) array: <polyline>, <polygon> (closed),
    <path d="M.. L.."> and <line>, as the two writers emit them."""
    out = []
    for kind, pts in re.findall(r'<(polyline|polygon)[^>]*points="([^"]+)"', svg):
        p = np.array(re.split(r"[ ,]+", pts.strip()), float).reshape(-1, 2)
        out.append(np.vstack([p, p[:1]]) if kind == "polygon" else p)
    for d in re.findall(r'<path[^>]*\sd="([^"]+)"', svg):
        for part in re.split(r"(?=M)", d.strip()):
            nums = re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", part)
            if len(nums) >= 4:
                out.append(np.array(nums, float).reshape(-1, 2))
    for element in re.findall(r"<line\s[^>]*>", svg):
        a = dict(re.findall(r'(x1|y1|x2|y2)="([^"]+)"', element))
        out.append(np.array([[a["x1"], a["y1"]], [a["x2"], a["y2"]]], float))
    return out


def _length(polylines):
    return sum(float(np.sum(np.hypot(*np.diff(p, axis=0).T))) for p in polylines)


def _sample(polylines, step=0.5):
    pts = []
    for p in polylines:
        for a, b in zip(p[:-1], p[1:]):
            n = max(int(np.hypot(*(b - a)) / step), 1)
            t = np.linspace(0, 1, n + 1)[:, None]
            pts.append(a + (b - a) * t)
    return np.concatenate(pts) if pts else np.zeros((0, 2))


def _xtask_plot(tmp_path):
    cargo = shutil.which("cargo")
    if cargo is None:
        if os.environ.get("FACESORT_REQUIRE_XTASK"):
            pytest.fail("cargo is needed for the xtask comparison")
        pytest.skip("cargo is not installed")
    out = tmp_path / "xtask.svg"
    subprocess.run(
        [cargo, "run", "--quiet", "-p", "xtask", "--", "render", str(SPOT), "--yaw", "145", "--pitch", "-25",
         "--plot", str(out)],
        cwd=ROOT, check=True, capture_output=True,
    )
    return out.read_text()


def test_vpype_facesort_mesh_matches_xtask_plot(tmp_path):
    out = tmp_path / "vpype.svg"
    vpype = Path(sys.executable).with_name("vpype")
    # vpype chains commands: a command's options come before its arguments.
    subprocess.run(
        [str(vpype), "facesort-mesh", "--yaw", "145", "--pitch", "-25", str(SPOT), "write", str(out)],
        check=True, capture_output=True,
    )
    ours = _polylines(out.read_text())
    reference = _polylines(_xtask_plot(tmp_path))
    assert ours and reference
    # `write` moves the drawing to its page's corner: compare from each drawing's corner.
    lo = lambda ps: np.min(np.concatenate(ps), axis=0)  # noqa: E731
    ours = [p - lo(ours) for p in ours]
    reference = [p - lo(reference) for p in reference]
    # The same pen-down length, and every point of either near a point of the other.
    assert _length(ours) == pytest.approx(_length(reference), rel=1e-4)
    from scipy.spatial import cKDTree

    a, b = _sample(ours), _sample(reference)
    assert cKDTree(b).query(a)[0].max() < 0.6
    assert cKDTree(a).query(b)[0].max() < 0.6
