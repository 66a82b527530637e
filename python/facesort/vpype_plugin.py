"""The vpype plugin: ``vpype facesort-mesh MODEL [--yaw --pitch --persp --crease]``.

Adds the visible edges of a mesh (boundaries, silhouettes, creases and intersection lines,
clipped exactly where faces hide them) as one layer, in pixels of a ``--size`` square view
(vpype's px: 1/96 inch)::

    vpype facesort-mesh spot.obj --yaw 145 --pitch -25 write spot.svg

Install with ``pip install "./python[vpype]"``.
"""

from __future__ import annotations

import click
import vpype as vp
import vpype_cli

import facesort


@click.command("facesort-mesh")
@click.argument("model", type=click.Path(exists=True, dir_okay=False))
@click.option("--yaw", type=float, default=0.0, show_default=True, help="Yaw in degrees.")
@click.option("--pitch", type=float, default=0.0, show_default=True, help="Pitch in degrees.")
@click.option("--roll", type=float, default=0.0, show_default=True, help="Roll in degrees.")
@click.option("--persp", type=float, default=None, help="Perspective eye distance in pixels (default: orthographic).")
@click.option("--crease", type=float, default=30.0, show_default=True, help="Crease angle in degrees.")
@click.option("--size", type=int, default=512, show_default=True, help="View size in pixels (square).")
@vpype_cli.generator
def facesort_mesh(model, yaw, pitch, roll, persp, crease, size) -> vp.LineCollection:
    """Visible edges of a 3D mesh (OBJ or glTF), hidden lines removed exactly."""
    try:
        mesh = facesort.Mesh.load(model)
        camera = facesort.Camera.orbit(yaw, pitch, roll, width=size, height=size, perspective=persp)
        plot = facesort.plot_edges(mesh, camera, crease=crease)
    except (OSError, ValueError) as error:
        raise click.BadParameter(str(error)) from error
    lines = vp.LineCollection()
    for polyline in plot.polylines:
        lines.append(polyline[:, 0] + 1j * polyline[:, 1])
    return lines
