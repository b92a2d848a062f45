"""Meshes out through meshio (``io/_meshes.py``): every format reads back with meshio as the same mesh, and no
file carries the time it was written."""

import meshio
import numpy as np
import pytest

from equimesh.io import output_formats, write_surface_mesh
from equimesh.io._meshes import write_meshio

MESHIO = [ext for ext, fmt in output_formats("mesh").items() if fmt.module is None]


@pytest.mark.parametrize("ext", MESHIO)
def test_every_meshio_format_reads_back_as_the_same_mesh(ext, saddle_mesh, tmp_path):
    write_surface_mesh(saddle_mesh, tmp_path / f"m{ext}")
    got = meshio.read(tmp_path / f"m{ext}")
    triangles = got.cells_dict["triangle"]
    if ext == ".stl":  # STL stores each triangle's corners: compare the corners
        np.testing.assert_allclose(got.points[triangles], saddle_mesh.points[saddle_mesh.triangles], rtol=1e-6)
    else:
        np.testing.assert_array_equal(triangles, saddle_mesh.triangles)
        np.testing.assert_allclose(got.points, saddle_mesh.points, rtol=0, atol=0)


@pytest.mark.parametrize("fmt, line", [("obj", 0), ("ply", 2)])
def test_meshio_time_stamp_is_cut_back_to_the_version(fmt, line, saddle_mesh, tmp_path):
    """meshio writes 'Created by meshio vX, <now>'; the file keeps 'Created by meshio vX' and still reads back."""
    path = tmp_path / f"m.{fmt}"
    write_meshio(path, fmt, saddle_mesh.points, saddle_mesh.triangles)
    header = path.read_bytes().split(b"\n")[line].decode()
    assert header.endswith(f"Created by meshio v{meshio.__version__}"), header
    assert len(meshio.read(path).points) == len(saddle_mesh.points)
