"""The pictures of docs/matplotlib.md: stock mplot3d ("3d") beside "exact3d" on the scenes of
matplotlib issues #29060 (crossing planes) and #7684 (a line through a surface).

    python python/examples/before_after.py [OUT_DIR]   # default: docs/
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import facesort.mpl  # noqa: E402,F401  (registers "exact3d")


def crossing_planes(ax):
    x = np.linspace(-1, 1, 20)
    X, Y = np.meshgrid(x, x)
    ax.plot_surface(X, Y, 0.6 * X, color="tab:blue")
    ax.plot_surface(X, Y, -0.6 * X + 0.3 * Y, color="tab:orange")


def line_through_surface(ax):
    x = np.linspace(-1, 1, 20)
    X, Y = np.meshgrid(x, x)
    ax.plot_surface(X, Y, 0.3 * np.sin(2 * X) * np.cos(2 * Y), cmap="viridis")
    t = np.linspace(-1, 1, 50)
    ax.plot(0.2 * t, 0.3 * t, 1.2 * t, color="crimson", lw=3)
    rng = np.random.default_rng(7684)
    ax.scatter(rng.uniform(-1, 1, 30), rng.uniform(-1, 1, 30), rng.choice([-0.8, 0.8], 30), c="k", s=25, depthshade=False)


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parents[2] / "docs")
    for name, build, view in (
        ("mpl-crossing-planes", crossing_planes, (25, -50)),
        ("mpl-line-through-surface", line_through_surface, (20, -35)),
    ):
        fig = plt.figure(figsize=(8, 4), dpi=80)
        for k, projection in enumerate(("3d", "exact3d")):
            ax = fig.add_subplot(1, 2, k + 1, projection=projection)
            build(ax)
            ax.view_init(*view)
            ax.set_title(f'projection="{projection}"')
        fig.tight_layout()
        fig.savefig(out / f"{name}.png")
        plt.close(fig)
        print(out / f"{name}.png")


if __name__ == "__main__":
    main()
