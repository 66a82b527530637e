"""The peer of issue 28: matplotlib's `plot_trisurf` SVG and PDF of a mesh, for size.

    python3 xtask/peers/matplotlib_trisurf.py MODEL.obj OUT_PREFIX [--yaw 145 --pitch -25]

Writes OUT_PREFIX.svg and OUT_PREFIX.pdf at 512 x 512 px (orthographic, one colour per
face as our palette output has) and prints their sizes. matplotlib orders the triangles by
the mean depth of their corners (Poly3DCollection, zsort='average'), the rule of our
centroid baseline; its pixel error is that of `cargo xtask render MODEL --sorter centroid`.
Needs `pip install matplotlib`.
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load_obj(path):
    vs, faces = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                vs.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "f":
                idx = [int(p.split("/")[0]) - 1 for p in parts[1:]]
                for k in range(1, len(idx) - 1):
                    faces.append((idx[0], idx[k], idx[k + 1]))
    return vs, faces


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("model")
    ap.add_argument("out")
    ap.add_argument("--yaw", type=float, default=145.0)
    ap.add_argument("--pitch", type=float, default=-25.0)
    a = ap.parse_args()
    vs, faces = load_obj(a.model)
    xs, ys, zs = zip(*vs)
    fig = plt.figure(figsize=(5.12, 5.12), dpi=100)
    ax = fig.add_subplot(projection="3d")
    ax.set_proj_type("ortho")
    # Model +Y is up in our conventions; matplotlib's vertical axis is z.
    ax.plot_trisurf(xs, [-z for z in zs], ys, triangles=faces, cmap="hsv", linewidth=0)
    ax.view_init(elev=-a.pitch, azim=a.yaw - 90.0)
    ax.set_axis_off()
    for ext in ("svg", "pdf"):
        path = f"{a.out}.{ext}"
        fig.savefig(path)
        print(f"{path}: {os.path.getsize(path)} bytes, {len(faces)} triangles")


if __name__ == "__main__":
    main()
