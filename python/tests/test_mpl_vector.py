"""exact3d's savefig to SVG and PDF stays vector and shows the PNG's picture: rasterised by
Chromium (SVG) and poppler (PDF), each within the writers' bar against Agg's PNG of the same
figure: at most 1 % of covered pixels off by more than 48 in a channel (anti-aliasing on in
all three)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import facesort.mpl  # noqa: E402,F401
from consumers import chromium_svg, poppler_pdf  # noqa: E402
from test_mpl_exact import SCENES, Scene  # noqa: E402

DPI = 96  # Chromium's CSS pixel and pdftoppm -r 96 match the PNG pixel for pixel


def _off_share(image, reference):
    covered = np.any(reference != 0, axis=-1) | np.any(image != 0, axis=-1)
    off = np.any(np.abs(image.astype(int) - reference.astype(int)) > 48, axis=-1)
    return np.count_nonzero(off & covered) / max(np.count_nonzero(covered), 1), np.count_nonzero(covered)


@pytest.mark.parametrize("name", list(SCENES))
def test_exact3d_svg_and_pdf_match_its_png(name, tmp_path):
    build, elev, azim = SCENES[name]
    scene = Scene("exact3d", "persp", elev, azim)
    build(scene)
    fig = scene.fig
    for artist in scene.ax.collections:
        artist.set_antialiased(True)
    for line in scene.ax.lines:
        line.set_antialiased(True)
    fig.savefig(tmp_path / "f.png", dpi=DPI, facecolor="black")
    fig.savefig(tmp_path / "f.svg", facecolor="black")
    fig.savefig(tmp_path / "f.pdf", facecolor="black")
    plt.close(fig)
    svg = (tmp_path / "f.svg").read_text()
    assert "<image" not in svg, "vector output must stay vector"
    from matplotlib import image

    png = (image.imread(str(tmp_path / "f.png"))[..., :3] * 255).round().astype(np.uint8)
    h, w = png.shape[:2]
    shots = {"svg (chromium)": chromium_svg(tmp_path / "f.svg", w, h), "pdf (poppler)": poppler_pdf(tmp_path / "f.pdf", DPI)}
    for what, shot in shots.items():
        assert shot.shape == png.shape, (what, shot.shape, png.shape)
        share, covered = _off_share(shot, png)
        print(f"{name} {what}: {share * 100:.3f} % of {covered} covered px off by > 48")
        assert covered > 2000
        assert share <= 0.01, f"{what}: {share:.4f}"
