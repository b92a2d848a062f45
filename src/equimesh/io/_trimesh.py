"""Triangle meshes in (``.obj``, ``.stl``, ``.ply``, ``.vtk``, ``.vtu``), read with meshio.

The mesh becomes a :class:`~equimesh.surface.charts.triangulated.TriangulatedSurface`,
the auxiliary triangulation of Section 4 given by the user (its checks:
connected, manifold, orientable, with a boundary).  Cells: triangles are
taken as they are; a quadrilateral is cut into two triangles along its
shorter diagonal (the first one, corners 0 and 2, on a tie); points and lines
(a modeller's edges and seams) are ignored; any other cell (polygons of more
corners, curved or volume cells) is refused, naming its type.  Points given in
the plane (two coordinates) get z = 0.
"""

import contextlib
import importlib
import io
import warnings

import numpy as np

from ..errors import InvalidSurfaceError
from ..surface.charts.triangulated import TriangulatedSurface
from ._schema import shown_path

#: Triangle-mesh formats by extension: a name for messages and the meshio module that reads it.
TRIANGLE_MESH_FORMATS = {
    ".obj": ("Wavefront OBJ", "obj"),
    ".stl": ("STL", "stl"),
    ".ply": ("PLY", "ply"),
    ".vtk": ("VTK", "vtk"),
    ".vtu": ("VTK XML", "vtu"),
}

#: meshio cell types that carry no surface and are skipped.
IGNORED_CELLS = ("vertex", "line", "line3", "polyline")


def read_triangle_mesh(path):
    """The :class:`~equimesh.surface.charts.triangulated.TriangulatedSurface` in the mesh file ``path`` (format by
    extension).

    Raises
    ------
    InvalidSurfaceError
        One line: the file cannot be read as that format, it holds no
        triangles or cells that are not surface triangles or quadrilaterals,
        or the mesh fails a check of :class:`TriangulatedSurface`.
    """
    where = shown_path(path)
    # The format's own reader, not meshio.read, which prints and calls sys.exit on a file it cannot read.
    reader = importlib.import_module(f"meshio.{TRIANGLE_MESH_FORMATS[path.suffix.lower()][1]}")
    try:
        with (
            warnings.catch_warnings(),
            contextlib.redirect_stdout(io.StringIO()),
            contextlib.redirect_stderr(io.StringIO()),
        ):
            warnings.simplefilter("ignore")  # meshio's own overflow and format warnings on malformed files
            mesh = reader.read(str(path))
    except MemoryError:
        raise
    except Exception as exc:  # meshio raises anything from ReadError to IndexError on a malformed file
        reason = " ".join(str(exc).split())[:200] or type(exc).__name__
        raise InvalidSurfaceError(f"cannot read {where} as a {path.suffix.lower()} mesh: {reason}") from None
    points = np.asarray(mesh.points, dtype=float)
    if not points.size:
        raise InvalidSurfaceError(f"{where} has no points and no triangles")
    if points.ndim != 2 or points.shape[1] not in (2, 3):
        raise InvalidSurfaceError(f"{where}: mesh points must have 2 or 3 coordinates, got shape {points.shape}")
    if points.shape[1] == 2:
        points = np.column_stack([points, np.zeros(len(points))])
    triangles = [_triangles(block.type, np.asarray(block.data, dtype=np.int64), points, where) for block in mesh.cells]
    triangles = [t for t in triangles if t is not None]
    if not triangles or not sum(len(t) for t in triangles):
        kinds = sorted({block.type for block in mesh.cells}) or ["no cells"]
        raise InvalidSurfaceError(
            f"{where} has no triangles (it holds {', '.join(kinds)}); export the surface as triangles"
        )
    try:
        return TriangulatedSurface(points, np.concatenate(triangles))
    except InvalidSurfaceError as exc:
        raise InvalidSurfaceError(f"{where}: {exc}") from None


def _triangles(kind, cells, points, where):
    """The triangles of one meshio cell block, or None for a block without surface."""
    if kind in IGNORED_CELLS:
        return None
    if kind == "triangle":
        return cells
    if kind == "quad":
        p = points[cells]
        first = np.linalg.norm(p[:, 2] - p[:, 0], axis=1) <= np.linalg.norm(p[:, 3] - p[:, 1], axis=1)
        a = np.where(first[:, None], cells[:, [0, 1, 2]], cells[:, [0, 1, 3]])
        b = np.where(first[:, None], cells[:, [0, 2, 3]], cells[:, [1, 2, 3]])
        return np.concatenate([a, b])
    raise InvalidSurfaceError(
        f"{where} holds cells of type {kind!r}; only triangles and quadrilaterals (split into triangles) are read"
    )
