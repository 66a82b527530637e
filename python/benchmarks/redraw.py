"""Median redraw time of a 100 x 100 plot_surface crossed by a plane, projection="exact3d"
against stock "3d", in the same run (not a test: run it by hand or from docs/bench.md).

    python python/benchmarks/redraw.py [--frames 30] [--size 100] [--runs 3] [--report FILE]

Each frame turns the view by 3 degrees (as interactive rotation does) and draws the figure
with Agg at 100 dpi, 6.4 x 4.8 inches. The two projections alternate frame by frame so
that both see the same machine load. The first frame of each (exact3d builds its BSP there)
is reported on its own.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import facesort.mpl  # noqa: E402,F401


def figure(projection: str, size: int):
    fig = plt.figure(figsize=(6.4, 4.8), dpi=100)
    ax = fig.add_subplot(projection=projection)
    x = np.linspace(-2, 2, size)
    X, Y = np.meshgrid(x, x)
    Z = np.sin(X * 1.3) * np.cos(Y * 1.1)
    ax.plot_surface(X, Y, Z, cmap="viridis", rstride=1, cstride=1)
    ax.plot_surface(X, Y, 0.3 * X - 0.2 * Y, color="tab:orange", alpha=1.0, rstride=max(1, size // 10), cstride=max(1, size // 10))
    return fig, ax


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=30)
    parser.add_argument("--size", type=int, default=100)
    parser.add_argument("--runs", type=int, default=1)
    parser.add_argument("--report", help="also write the runs as a markdown report here")
    args = parser.parse_args()
    rows = [run(args) for _ in range(args.runs)]
    if args.report:
        write_report(args, rows)


def write_report(args, rows):
    """docs/bench-matplotlib.md: the runs' table, with the command and the machine's facts."""
    import datetime
    import platform

    import matplotlib as mpl

    lines = [
        "# matplotlib redraw: exact3d against stock 3d",
        "",
        f"Written by `python python/benchmarks/redraw.py --frames {args.frames} --size {args.size} "
        f"--runs {args.runs} --report docs/bench-matplotlib.md` on {datetime.date.today()} "
        f"(matplotlib {mpl.__version__}, Python {platform.python_version()}, {os.cpu_count()} cores).",
        "",
        f"A {args.size - 1} x {args.size - 1} `plot_surface` with a colour map crossed by a plane, Agg at "
        f"640 x 480; each frame turns the view by 3 degrees and the two projections alternate frame by frame.",
        "",
        "| run | 3d first frame | exact3d first frame | 3d median redraw | exact3d median redraw | exact3d / 3d |",
        "| --- | --- | --- | --- | --- | --- |",
    ]
    for n, (first, med) in enumerate(rows, 1):
        lines.append(
            f"| {n} | {first['3d'] * 1000:.1f} ms | {first['exact3d'] * 1000:.1f} ms | {med['3d'] * 1000:.1f} ms "
            f"| {med['exact3d'] * 1000:.1f} ms | {med['exact3d'] / med['3d']:.2f} |"
        )
    with open(args.report, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


def run(args):
    """One run: first-frame and median redraw times per projection."""
    figs = {p: figure(p, args.size) for p in ("3d", "exact3d")}
    times = {p: [] for p in figs}
    first = {}
    for frame in range(args.frames + 1):
        for p, (fig, ax) in figs.items():
            ax.view_init(elev=25, azim=-60 + 3 * frame)
            start = time.perf_counter()
            fig.canvas.draw()
            elapsed = time.perf_counter() - start
            if frame == 0:
                first[p] = elapsed
            else:
                times[p].append(elapsed)
    med = {p: statistics.median(t) for p, t in times.items()}
    polys = args.size - 1
    print(f"{polys}x{polys} surface + crossing plane, {args.frames} turning frames, Agg 640x480")
    for p in figs:
        print(f"  {p:8s} first frame {first[p] * 1000:7.1f} ms, median redraw {med[p] * 1000:7.1f} ms")
    print(f"  exact3d / 3d median redraw: {med['exact3d'] / med['3d']:.2f}")
    for fig, _ in figs.values():
        plt.close(fig)
    return first, med


if __name__ == "__main__":
    main()
