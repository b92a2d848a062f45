"""Triangle mesh files in (``io/_trimesh.py``, via meshio): every format reads back the same surface, quadrilaterals
are split, and unreadable files or unknown extensions are refused in one line.
"""

import meshio
import numpy as np
import pytest
from refusals import assert_one_line
from triangle_meshes import roof

from equimesh import InvalidSurfaceError, TriangulatedSurface
from equimesh.io import load_surface


@pytest.mark.parametrize("ext", [".obj", ".stl", ".ply", ".vtk", ".vtu"])
def test_round_trip_through_each_format(tmp_path, ext):
    """Written by meshio, read back by load_surface: the same surface (STL and PLY store float32 coordinates)."""
    v, t = roof()
    path = tmp_path / f"roof{ext}"
    meshio.write(path, meshio.Mesh(v, [("triangle", t)]))
    got = load_surface(path)
    assert isinstance(got, TriangulatedSurface)
    reference = TriangulatedSurface(v, t)
    assert len(got.vertices) == len(reference.vertices) and len(got.triangles) == len(reference.triangles)
    np.testing.assert_allclose(np.sort(got.vertices, axis=0), np.sort(reference.vertices, axis=0), rtol=0, atol=1e-5)


def test_quadrilaterals_are_split(tmp_path):
    """A quad mesh is read as triangles, each quad cut along its shorter diagonal."""
    v = np.array([[0.0, 0, 0], [4, 0, 0], [4, 1, 0], [0, 1, 0], [8, 0, 1], [8, 1, 1]])
    path = tmp_path / "quads.vtu"
    meshio.write(path, meshio.Mesh(v, [("quad", np.array([[0, 1, 2, 3], [1, 4, 5, 2]])), ("line", np.array([[0, 1]]))]))
    got = load_surface(path)
    assert len(got.triangles) == 4 and len(got.loops) == 1


def unreadable(tmp_path):
    lines = tmp_path / "lines.vtu"
    meshio.write(lines, meshio.Mesh(np.eye(3), [("line", np.array([[0, 1], [1, 2]]))]))
    tetra = tmp_path / "tetra.vtu"
    meshio.write(tetra, meshio.Mesh(np.vstack([np.eye(3), [[0, 0, 0]]]), [("tetra", np.array([[0, 1, 2, 3]]))]))
    garbage = tmp_path / "garbage.stl"
    garbage.write_bytes(b"\x00" * 10)
    ply = tmp_path / "text.ply"
    ply.write_text("this is not a ply file\n")
    empty = tmp_path / "empty.obj"
    empty.write_text("")
    return {
        "empty": (empty, "has no points and no triangles"),
        "only lines": (lines, "has no triangles"),
        "volume cells": (tetra, "cells of type 'tetra'"),
        "garbage STL": (garbage, "cannot read"),
        "not PLY": (ply, "cannot read"),
    }


@pytest.mark.parametrize("case", ["empty", "only lines", "volume cells", "garbage STL", "not PLY"])
def test_unreadable_files_are_refused_in_one_line(tmp_path, case):
    path, match = unreadable(tmp_path)[case]
    with pytest.raises(InvalidSurfaceError, match=match) as info:
        load_surface(path)
    assert_one_line(str(info.value))
    assert path.name in str(info.value)


def test_unknown_extension_lists_the_mesh_formats(tmp_path):
    path = tmp_path / "roof.off"
    path.write_text("OFF\n")
    with pytest.raises(InvalidSurfaceError, match=r"\.obj.*\.ply.*\.stl.*\.vtk.*\.vtu"):
        load_surface(path)


def _square_cells(tmp_path, ext, kind, cells, dtype=np.int64):
    v = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
    path = tmp_path / f"bad{ext}"
    blocks = [("line", np.array([[0, 1]], dtype=dtype)), (kind, np.asarray(cells, dtype=dtype))]
    meshio.write(path, meshio.Mesh(v, blocks))
    return path


@pytest.mark.parametrize(
    "ext, kind, cells, dtype, fragment",
    [
        (".vtu", "quad", [[0, 1, 2, 9]], np.int64, "cell 1 (a quad) refers to point 9, but the file has 4 points"),
        (".vtk", "quad", [[0, 1, 2, 3], [0, 1, 2, -2]], np.int64, "cell 2 (a quad) refers to point -2"),
        (".vtu", "triangle", [[0, 1, 2], [0, 2, 7]], np.int64, "cell 2 (a triangle) refers to point 7"),
        (".ply", "triangle", [[0, 1, 2], [0, 2, 2**64 - 1]], np.uint64, "refers to point 18446744073709551615"),
    ],
)
def test_a_cell_out_of_range_is_named_by_its_number_in_the_file(tmp_path, ext, kind, cells, dtype, fragment):
    """Quadrilaterals are range-checked like triangles (no IndexError), and an unsigned index is shown as the file
    holds it, not wrapped to a negative number; cells count from 0 in the file's order, as in VTK and PLY."""
    with pytest.raises(InvalidSurfaceError) as err:
        load_surface(_square_cells(tmp_path, ext, kind, cells, dtype))
    assert fragment in str(err.value)
    assert_one_line(str(err.value))
