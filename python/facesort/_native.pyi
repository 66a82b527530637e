"""Type stubs of the native module (Rust, PyO3). See each item's docstring at run time."""

from os import PathLike
from typing import Literal, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Cull = Literal["back", "front", "none"]
_Sorter = Literal["bsp", "bsp-merged", "newell", "presorted", "centroid", "topological"]
_Faces = Union[npt.NDArray[np.integer], Sequence[Sequence[int]]]
_Path = Union[str, PathLike[str]]

class Mesh:
    """A polygon mesh: vertices (n, 3) float64 and faces (convex polygons of 3+ corners)."""

    def __init__(
        self,
        vertices: npt.NDArray[np.floating],
        faces: _Faces,
        colours: Optional[npt.NDArray[np.generic]] = None,
        uvs: Optional[npt.NDArray[np.floating]] = None,
        texture: Optional[_Path] = None,
    ) -> None: ...
    @staticmethod
    def load(path: _Path) -> Mesh:
        """Loads an OBJ (with its MTL and textures) or glTF file; raises OSError."""
    @property
    def vertices(self) -> npt.NDArray[np.float64]: ...
    @property
    def face_count(self) -> int: ...
    def sort(self, camera: Camera, sorter: _Sorter = "bsp") -> Order:
        """Orders the faces seen by `camera`, back to front (the GIL released)."""

class Camera:
    """A camera and an image size."""

    @staticmethod
    def orbit(
        yaw: float = 0.0,
        pitch: float = 0.0,
        roll: float = 0.0,
        width: int = 512,
        height: int = 512,
        perspective: Union[None, bool, float] = None,
        cull: _Cull = "back",
    ) -> Camera: ...
    @staticmethod
    def look_at(
        eye: tuple[float, float, float],
        target: tuple[float, float, float],
        up: tuple[float, float, float] = (0.0, 1.0, 0.0),
        fov_y: Optional[float] = None,
        ortho_height: Optional[float] = None,
        near: float = 0.01,
        width: int = 512,
        height: int = 512,
        cull: _Cull = "back",
    ) -> Camera: ...
    @staticmethod
    def from_matrices(
        view: npt.NDArray[np.floating],
        projection: npt.NDArray[np.floating],
        width: int = 512,
        height: int = 512,
        clip: Literal["opengl", "directx", "vulkan"] = "opengl",
        cull: _Cull = "back",
    ) -> Camera: ...
    def with_cull(self, cull: _Cull) -> Camera: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...

class Order:
    """Faces in paint order for one view (fragments keep their face's id)."""

    @property
    def faces(self) -> npt.NDArray[np.uint32]: ...
    def polygons(self) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
        """(points (k, 2) in pixels, offsets (len + 1,))."""
    def violations(self) -> int:
        """The oracle's count of order violations (0 when exact)."""
    def __len__(self) -> int: ...

class Presorted:
    """Certified orders for every view of a rigid mesh, built once."""

    def __init__(self, mesh: Mesh) -> None: ...
    def sort(self, camera: Camera) -> Order: ...
    @property
    def regions(self) -> int: ...
    @property
    def orders(self) -> int: ...
    @property
    def fallback_frames(self) -> int: ...
    @property
    def refused(self) -> Optional[str]: ...

class Plot:
    """The visible edges of a mesh in one view."""

    @property
    def polylines(self) -> list[npt.NDArray[np.float64]]: ...
    @property
    def pen_down(self) -> float: ...
    @property
    def pen_up(self) -> float: ...
    def svg(self, stroke: float = 1.0) -> str: ...
    def hpgl(self, units_per_px: float = 10.0) -> str: ...

class YawBake:
    """A yaw turn's exact picture orders, as cells of yaw angles."""

    @property
    def cells(self) -> list[tuple[float, float]]: ...
    def spin_html(self, period: float = 8.0, paused: Optional[float] = None, ids: bool = False) -> str: ...

class ExactScene:
    """Polygons ordered exactly for any viewer (the engine of facesort.mpl)."""

    def __init__(
        self,
        points: npt.NDArray[np.float64],
        offsets: npt.NDArray[np.integer],
        sorter: Literal["newell", "bsp", "bsp-merged"] = "newell",
    ) -> None: ...
    @property
    def polygon_count(self) -> int: ...
    def order(
        self,
        viewer: tuple[float, float, float, float],
        width: int,
        height: int,
        opaque: npt.NDArray[np.bool_],
        lines: Optional[npt.NDArray[np.float64]] = None,
        merge: bool = False,
    ) -> dict[str, object]: ...

def svg(mesh: Mesh, camera: Camera, hidden: Literal["remove", "keep"] = "remove", ids: bool = False) -> str: ...
def pdf(mesh: Mesh, camera: Camera, hidden: Literal["remove", "keep"] = "remove", ids: bool = False) -> bytes: ...
def html(mesh: Mesh, camera: Camera, ids: bool = False) -> str: ...
def plot_edges(mesh: Mesh, camera: Camera, crease: float = 30.0) -> Plot: ...
def bake_yaw(
    mesh: Mesh, pitch: float = 20.0, width: int = 512, height: int = 512, perspective: Optional[float] = None
) -> YawBake: ...
