"""Meshes out through meshio (``.obj``, ``.vtk``, ``.vtu``, ``.stl``, ``.ply``, ``.msh``), the same bytes on every run.

meshio stamps the time of writing into two formats (``# Created by meshio
v5.3.5, 2026-...`` as the first line of an OBJ file, a ``comment`` line of a PLY
header); the stamp is cut back to the version, so that the same mesh gives the
same bytes (docs/decisions.md, "Same input, same bytes").
"""

import re

import meshio
import numpy as np

#: Cell data a meshio format requires (one zero per triangle for each name).
_REQUIRED_CELL_DATA = {"gmsh22": ("gmsh:physical", "gmsh:geometrical")}

#: meshio's time stamp: the text after the version on its "Created by" line.
_STAMP = re.compile(rb"(Created by meshio v[^,\n]*), [^\n]*")

#: The stamp is looked for in the first lines only (line 1 of OBJ, line 3 of PLY), never in a binary body.
_STAMP_LINES = 3


def write_mesh(tmp, products, fmt):
    """The registry's writer for the meshio format ``fmt`` (bound per row of
    :data:`~equimesh.io._outputs.OUTPUT_FORMATS`): ``products.mesh`` to ``tmp`` by :func:`write_meshio`."""
    write_meshio(tmp, fmt, products.mesh.points, products.mesh.triangles)


def write_meshio(path, fmt, points, triangles):
    """Write a triangle mesh to ``path`` in the meshio format ``fmt``, without meshio's time stamp."""
    cells = np.asarray(triangles, dtype=np.int32)
    zeros = np.zeros(len(cells), dtype=np.int32)
    cell_data = {name: [zeros] for name in _REQUIRED_CELL_DATA.get(fmt, ())}
    meshio.Mesh(np.asarray(points, dtype=float), [("triangle", cells)], cell_data=cell_data).write(
        path, file_format=fmt
    )
    with open(path, "r+b") as f:
        lines = f.read().split(b"\n", _STAMP_LINES)
        head, stamps = _STAMP.subn(rb"\1", b"\n".join(lines[:_STAMP_LINES]))
        if stamps:
            f.seek(0)
            f.write(b"\n".join([head, *lines[_STAMP_LINES:]]))
            f.truncate()
