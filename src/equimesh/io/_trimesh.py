"""Triangle meshes in (``.obj``, ``.stl``, ``.ply``, ``.vtk``, ``.vtu``): OBJ by our own reader, the others by meshio.

The mesh becomes a :class:`~equimesh.surface.charts.triangulated.TriangulatedSurface`,
the auxiliary triangulation of Section 4 given by the user (its checks:
connected, manifold, orientable, with a boundary).  Cells: triangles are
taken as they are; a quadrilateral is cut into two triangles along its
shorter diagonal (the first one, corners 0 and 2, on a tie); points and lines
(a modeller's edges and seams) are ignored; any other cell (polygons of more
corners, curved or volume cells) is refused, naming its type.  Points given in
the plane (two coordinates) get z = 0.  A cell referring to a point the file does
not have is refused naming the cell and the index as the file writes them (from 0
in VTK, PLY; from 1 in OBJ).

OBJ files are read by :mod:`._obj`, as meshio's OBJ reader refuses what modellers
write (texture coordinates or normals in other numbers than the vertices,
relative indices, vertex colours; docs/decisions.md, "OBJ files by a reader of
our own").
"""

import contextlib
import functools
import importlib
import io
import warnings

import numpy as np

from ..errors import InvalidSurfaceError
from ..surface.charts.triangulated import TriangulatedSurface
from ._obj import FACE_KINDS, read_obj
from ._schema import shown_path

#: meshio cell types that carry no surface and are skipped.
IGNORED_CELLS = ("vertex", "line", "line3", "polyline")

#: Corners of the surface cells read, by meshio's name (the OBJ reader's too).
SURFACE_CELLS = {kind: corners for corners, kind in FACE_KINDS.items()}


def _read_with_meshio(module, path, where):
    """Points and ``(kind, cells)`` blocks of ``path`` by meshio's reader ``meshio.<module>``, every surface cell's
    indices in range."""
    # The format's own reader, not meshio.read, which prints and calls sys.exit on a file it cannot read.
    reader = importlib.import_module(f"meshio.{module}")
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
    blocks, first = [], 0
    for block in mesh.cells:
        cells = block.data
        if block.type in SURFACE_CELLS:
            cells = _in_range(block.type, np.asarray(cells), first, len(mesh.points), where)
        blocks.append((block.type, cells))
        first += len(block.data)
    return mesh.points, blocks


#: Triangle-mesh formats by extension: a name for messages and the reader of ``(points, [(kind, cells), ...])``.
TRIANGLE_MESH_FORMATS = {
    ".obj": ("Wavefront OBJ", read_obj),
    ".stl": ("STL", functools.partial(_read_with_meshio, "stl")),
    ".ply": ("PLY", functools.partial(_read_with_meshio, "ply")),
    ".vtk": ("VTK", functools.partial(_read_with_meshio, "vtk")),
    ".vtu": ("VTK XML", functools.partial(_read_with_meshio, "vtu")),
}


def read_triangle_mesh(path):
    """The :class:`~equimesh.surface.charts.triangulated.TriangulatedSurface` in the mesh file ``path`` (format by
    extension).

    Raises
    ------
    InvalidSurfaceError
        One line: the file cannot be read as that format, it holds no
        triangles or cells that are not surface triangles or quadrilaterals,
        a cell refers to a point the file does not have, or the mesh fails a
        check of :class:`TriangulatedSurface`.
    """
    where = shown_path(path)
    points, blocks = TRIANGLE_MESH_FORMATS[path.suffix.lower()][1](path, where)
    points = np.asarray(points, dtype=float)
    if not points.size:
        raise InvalidSurfaceError(f"{where} has no points and no triangles")
    if points.ndim != 2 or points.shape[1] not in (2, 3):
        raise InvalidSurfaceError(f"{where}: mesh points must have 2 or 3 coordinates, got shape {points.shape}")
    if points.shape[1] == 2:
        points = np.column_stack([points, np.zeros(len(points))])
    triangles = [_triangles(kind, cells, points, where) for kind, cells in blocks]
    triangles = [t for t in triangles if t is not None]
    if not triangles or not sum(len(t) for t in triangles):
        kinds = sorted({kind for kind, _ in blocks}) or ["no cells"]
        raise InvalidSurfaceError(
            f"{where} has no triangles (it holds {', '.join(kinds)}); export the surface as triangles"
        )
    try:
        return TriangulatedSurface(points, np.concatenate(triangles))
    except InvalidSurfaceError as exc:
        raise InvalidSurfaceError(f"{where}: {exc}") from None


def _in_range(kind, cells, first, n_points, where):
    """``cells`` (a block of ``kind``, its first one cell ``first`` of the file) as int64, or a refusal naming the
    first cell that refers to a point outside ``0 .. n_points - 1``, shown as read (unsigned, or a float where meshio
    reads VTU indices as floats), never wrapped around."""
    if cells.dtype.kind not in "iuf" or cells.ndim != 2 or cells.shape[1] != SURFACE_CELLS[kind]:
        raise InvalidSurfaceError(f"{where}: the {kind} cells are not rows of {SURFACE_CELLS[kind]} point indices")
    inside = (cells >= 0) & (cells < n_points)
    if cells.dtype.kind == "f":
        inside &= cells == np.floor(cells)
    bad = np.argwhere(~inside)
    if len(bad):
        i, j = bad[0]
        index = cells[i, j].item()
        raise InvalidSurfaceError(
            f"{where}: cell {first + int(i)} (a {kind}) refers to point {index!r}, but the file has {n_points} points "
            f"(0 .. {n_points - 1})"
        )
    return cells.astype(np.int64)


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
