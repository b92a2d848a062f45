"""Meshes out through meshio (``io/_meshes.py``): every format reads back with meshio as the same mesh, and no
file carries the time it was written: the bytes are meshio's but for its time stamp."""

import re
from types import SimpleNamespace

import meshio
import numpy as np
import pytest

from equimesh.io import output_formats
from equimesh.io._meshes import write_mesh, write_meshio

#: The meshio formats of the mesh outputs: meshio's name -> the extension.
FORMATS = {"obj": ".obj", "vtk": ".vtk", "vtu": ".vtu", "stl": ".stl", "ply": ".ply", "gmsh22": ".msh"}

#: A pyramid's four faces over a square, corners of no short decimal form.
POINTS = np.array([[0.0, 0, 0], [np.pi, 0, 0], [np.pi, np.e, 0], [0, np.e, 0], [np.pi / 2, np.e / 2, 1 / 3]])
TRIANGLES = np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]])


def test_the_formats_are_those_of_the_mesh_outputs():
    assert sorted(FORMATS.values()) == sorted(ext for ext, fmt in output_formats("mesh").items() if fmt.module is None)


@pytest.mark.parametrize("fmt", FORMATS)
def test_every_meshio_format_reads_back_as_the_same_mesh(fmt, tmp_path, capsys):
    """Written without a word from meshio (it warns on stderr of tags it must make up for Gmsh)."""
    path = tmp_path / f"m{FORMATS[fmt]}"
    write_meshio(path, fmt, POINTS, TRIANGLES)
    assert capsys.readouterr() == ("", "")
    got = meshio.read(path)
    triangles = got.cells_dict["triangle"]
    if fmt == "stl":  # STL stores each triangle's corners: compare the corners
        np.testing.assert_allclose(got.points[triangles], POINTS[TRIANGLES], rtol=1e-6)
    else:
        np.testing.assert_array_equal(triangles, TRIANGLES)
        np.testing.assert_array_equal(got.points, POINTS)


@pytest.mark.parametrize("fmt", FORMATS)
def test_the_writer_of_a_format_writes_the_mesh_of_a_run_in_that_format(fmt, tmp_path):
    """Whatever the extension of the (temporary) file, and with the coordinates of any numeric type."""
    products = SimpleNamespace(mesh=SimpleNamespace(points=POINTS, triangles=TRIANGLES))
    write_mesh(tmp_path / f"m{FORMATS[fmt]}", products, fmt)
    write_meshio(tmp_path / "m.out", fmt, POINTS, TRIANGLES)
    assert (tmp_path / f"m{FORMATS[fmt]}").read_bytes() == (tmp_path / "m.out").read_bytes()
    write_meshio(tmp_path / "whole.out", fmt, np.round(POINTS).astype(np.int64), TRIANGLES)
    write_meshio(tmp_path / "float.out", fmt, np.round(POINTS), TRIANGLES)
    assert (tmp_path / "whole.out").read_bytes() == (tmp_path / "float.out").read_bytes()


@pytest.mark.parametrize("fmt", FORMATS)
def test_the_bytes_are_meshios_without_its_time_stamp(fmt, tmp_path):
    """meshio writes 'Created by meshio vX, <now>' (OBJ's line 1, PLY's line 3); the file keeps 'Created by meshio
    vX', and every other byte is meshio's."""
    path = tmp_path / "m.out"
    write_meshio(path, fmt, POINTS, TRIANGLES)
    cell_data = {name: [np.zeros(4, dtype=np.int32)] for name in ("gmsh:physical", "gmsh:geometrical")}
    meshio.Mesh(
        POINTS, [("triangle", TRIANGLES.astype(np.int32))], cell_data=cell_data if fmt == "gmsh22" else {}
    ).write(tmp_path / "meshio.out", file_format=fmt)
    own = (tmp_path / "meshio.out").read_bytes()
    stamped = {"obj": 0, "ply": 2}.get(fmt)
    if stamped is not None:
        lines = own.split(b"\n")
        assert re.fullmatch(rb".*Created by meshio v[\d.]+, \d{4}-.*", lines[stamped]), lines[stamped]
        lines[stamped] = lines[stamped].split(b", ")[0]
        own = b"\n".join(lines)
        line = path.read_bytes().split(b"\n")[stamped].decode()
        assert line.endswith(f"Created by meshio v{meshio.__version__}"), line
    assert path.read_bytes() == own
