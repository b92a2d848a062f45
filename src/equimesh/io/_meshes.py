"""Surfaces in (JSON), meshes and member schedules out.

Surface JSON::

    {"type": "bezier", "control_points": [[[x, y, z], ...], ...]}

rows over u, columns over v; an (m+1) x (n+1) net gives a Bézier surface of
degree (m, n).  Meshes are written through meshio in the format given by the
file extension; every output is written to a temporary file beside the
target and renamed, so a failure never leaves a partial file.
"""

import json
from pathlib import Path

import meshio
import numpy as np
import pandas as pd

from ._atomic import atomic_path
from ..errors import EquimeshError, InvalidSurfaceError, OutputPathError
from ..mesh import edge_lengths
from ..surface.bezier import BezierSurface

#: Output formats by extension (meshio format names).
MESH_FORMATS = {".obj": "obj", ".vtk": "vtk", ".vtu": "vtu", ".stl": "stl", ".ply": "ply", ".msh": "gmsh"}


def load_surface(path):
    """Read a surface JSON file; raise :class:`InvalidSurfaceError` naming the problem."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InvalidSurfaceError(f"surface file not found: {path}") from None
    except (IsADirectoryError, PermissionError, UnicodeDecodeError) as exc:
        raise InvalidSurfaceError(f"cannot read surface file {path}: {exc.__class__.__name__}") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InvalidSurfaceError(f"{path}: malformed JSON at line {exc.lineno} column {exc.colno}: {exc.msg}") from None
    return BezierSurface.from_json_dict(data)


def check_output_path(path, formats):
    """Validate an output path: known extension and an existing folder.  Returns the format."""
    path = Path(path)
    fmt = formats.get(path.suffix.lower())
    if fmt is None:
        raise OutputPathError(f"unknown output extension {path.suffix!r} for {path}; use one of {sorted(formats)}")
    if not path.parent.is_dir():
        raise OutputPathError(f"output folder does not exist: {path.parent}")
    return fmt


def write_mesh(path, points, triangles):
    """Write a triangle mesh to ``path`` (format by extension, see :data:`MESH_FORMATS`), atomically."""
    fmt = check_output_path(path, MESH_FORMATS)
    cells = np.asarray(triangles, dtype=np.int32)
    cell_data = {}
    if fmt == "gmsh":
        fmt = "gmsh22"
        zeros = [np.zeros(len(cells), dtype=np.int32)]
        cell_data = {"gmsh:physical": zeros, "gmsh:geometrical": zeros}
    mesh = meshio.Mesh(np.asarray(points, dtype=float), [("triangle", cells)], cell_data=cell_data)
    with atomic_path(path) as tmp:
        mesh.write(tmp, file_format=fmt)


def member_schedule(points, edges, groups, l):
    """The member schedule: one row per edge with its nodes, length, group and deviation from l."""
    e = np.asarray(edges)
    length = edge_lengths(points, e)
    return pd.DataFrame(
        {
            "member": np.arange(len(e)),
            "node_i": e[:, 0],
            "node_j": e[:, 1],
            "length": length,
            "group": np.where(np.asarray(groups) == 1, "G1", "other"),
            "deviation": length - l,
            "relative_deviation": (length - l) / l,
        }
    )


def write_members(path, points, edges, groups, l):
    """Write :func:`member_schedule` as CSV to ``path``, atomically."""
    check_output_path(path, {".csv": "csv"})
    table = member_schedule(points, edges, groups, l)
    with atomic_path(path) as tmp:
        table.to_csv(tmp, index=False, float_format="%.10g")
