"""Real consumers of vector files: headless Chromium for SVG, poppler's pdftoppm for PDF.
Missing ones skip the test, unless CI is set (then the test fails: CI installs both)."""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest


def _need(tool: str) -> str:
    found = shutil.which(tool)
    if found is None:
        if os.environ.get("CI"):
            pytest.fail(f"{tool} is missing and CI is set: .ci/run installs it")
        pytest.skip(f"{tool} is not installed")
    return found


def _png(path: Path) -> np.ndarray:
    from matplotlib import image

    return (image.imread(str(path))[..., :3] * 255).round().astype(np.uint8)


def chromium_svg(svg: Path, width: int, height: int) -> np.ndarray:
    """Chromium's screenshot of an SVG file, RGB uint8, `width` × `height` CSS pixels."""
    browser = _need("chromium")
    with tempfile.TemporaryDirectory() as tmp:
        shot = Path(tmp) / "shot.png"
        subprocess.run(
            [
                browser, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                "--disable-background-networking", "--disable-component-update", "--disable-sync",
                f"--user-data-dir={tmp}/profile", "--hide-scrollbars", "--force-device-scale-factor=1",
                "--force-color-profile=srgb", "--run-all-compositor-stages-before-draw",
                f"--screenshot={shot}", f"--window-size={width},{height}", f"file://{svg}",
            ],
            check=True, capture_output=True, timeout=180,
        )
        return _png(shot)


def poppler_pdf(pdf: Path, dpi: int) -> np.ndarray:
    """pdftoppm's rendering of a PDF's first page at `dpi`, RGB uint8."""
    tool = _need("pdftoppm")
    with tempfile.TemporaryDirectory() as tmp:
        stem = Path(tmp) / "page"
        subprocess.run([tool, "-png", "-r", str(dpi), "-singlefile", str(pdf), str(stem)], check=True, capture_output=True)
        return _png(stem.with_suffix(".png"))
