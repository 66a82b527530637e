"""Exact painter's-algorithm ordering of 3D polygon meshes, for surfaces without a depth buffer.

The native core (Rust: ``face-sort``, ``aspect-bake``, ``sprite-compose``) orders faces exactly,
splitting them where they pass through each other, and writes SVG, PDF, HTML pages, plotter
edges and spinning pages. Arrays go in and out as numpy arrays.

>>> import numpy as np, facesort
>>> v = np.array([[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0],
...               [1, 1, 1], [3, 1, 1], [3, 3, 1], [1, 3, 1]], dtype=float)
>>> mesh = facesort.Mesh(v, [[4, 5, 6, 7], [0, 1, 2, 3]])
>>> order = mesh.sort(facesort.Camera.orbit(width=256, height=256))
>>> order.faces.tolist()   # the far square first
[1, 0]
>>> order.violations()
0

``facesort.mpl`` registers matplotlib's ``"exact3d"`` projection; ``facesort.vpype_plugin``
is the ``vpype facesort-mesh`` command.
"""

from ._native import (
    Camera,
    ExactScene,
    Mesh,
    Order,
    Plot,
    Presorted,
    YawBake,
    __version__,
    bake_yaw,
    html,
    pdf,
    plot_edges,
    svg,
)

__all__ = [
    "Camera",
    "ExactScene",
    "Mesh",
    "Order",
    "Plot",
    "Presorted",
    "YawBake",
    "__version__",
    "bake_yaw",
    "html",
    "pdf",
    "plot_edges",
    "svg",
]
