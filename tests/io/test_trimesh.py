"""Triangle mesh files in (``io/_trimesh.py``, via meshio): every format reads back the same surface, quadrilaterals
are split, and unreadable files or unknown extensions are refused in one line.
"""

import importlib
import sys
import warnings
from pathlib import Path
from types import SimpleNamespace

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


# --------------------------------------------------------------------------- what meshio's readers give


def read_as(monkeypatch, tmp_path, points, blocks, name="m.vtu"):
    """``load_surface`` of a file whose reader (meshio's, for its extension) returns ``points`` and ``blocks``."""
    mesh = SimpleNamespace(points=np.asarray(points), cells=[SimpleNamespace(type=k, data=c) for k, c in blocks])
    path = tmp_path / name
    path.write_text("read by the stand-in reader")
    module = importlib.import_module(f"meshio.{Path(name).suffix.lower().lstrip('.')}")
    monkeypatch.setattr(module, "read", lambda filename: mesh)
    return load_surface(path)


def refusal_of(monkeypatch, tmp_path, points, blocks, name="m.vtu"):
    with pytest.raises(InvalidSurfaceError) as err:
        read_as(monkeypatch, tmp_path, points, blocks, name)
    assert_one_line(str(err.value))
    return str(err.value).removeprefix(f"{tmp_path / name}")


SQUARE = [[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]


def triangle_sets(surface):
    return sorted(sorted(surface.vertices[t, :2].tolist()) for t in surface.triangles)


def test_a_square_is_cut_along_its_first_diagonal(monkeypatch, tmp_path):
    """Both diagonals are as long: the first one, corners 0 and 2."""
    points = [[0.0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0]]
    got = read_as(monkeypatch, tmp_path, points, [("quad", np.array([[0, 1, 2, 3]]))])
    assert triangle_sets(got) == [[[0, 0], [0, 2], [2, 2]], [[0, 0], [2, 0], [2, 2]]]


@pytest.mark.parametrize("dtype", [np.float64, np.uint8])
def test_each_quadrilateral_is_cut_along_its_shorter_diagonal(monkeypatch, tmp_path, dtype):
    """Two quadrilaterals side by side, away from the origin: the first one's shorter diagonal joins its corners 1
    and 3, the second one's its corners 0 and 2; unsigned coordinates are taken as the numbers they are."""
    xy = np.array([[10, 20], [40, 20], [40, 30], [11, 30], [70, 20], [69, 30]])
    points = np.column_stack([xy, np.zeros(6)]).astype(dtype)
    got = read_as(monkeypatch, tmp_path, points, [("quad", np.array([[0, 1, 2, 3], [1, 4, 5, 2]]))])
    expected = [[0, 1, 3], [1, 2, 3], [1, 4, 5], [1, 5, 2]]
    assert triangle_sets(got) == sorted(sorted(xy[t].tolist()) for t in expected)


def test_triangles_and_quadrilaterals_of_several_blocks_make_one_surface(monkeypatch, tmp_path):
    points = [[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0], [2, 1, 0]]
    blocks = [
        ("vertex", np.array([[0]])),
        ("triangle", np.array([[0, 1, 2], [0, 2, 3]])),
        ("quad", np.array([[1, 4, 5, 2]])),
    ]
    got = read_as(monkeypatch, tmp_path, points, blocks)
    assert len(got.triangles) == 4 and [len(loop) for loop in got.loops] == [6]


def test_points_in_the_plane_get_z_0(monkeypatch, tmp_path):
    got = read_as(
        monkeypatch, tmp_path, [[0.0, 0], [1, 0], [1, 1], [0, 1]], [("triangle", np.array([[0, 1, 2], [0, 2, 3]]))]
    )
    np.testing.assert_array_equal(np.sort(got.vertices, axis=0), np.sort(np.array(SQUARE), axis=0))


@pytest.mark.parametrize(
    "points, blocks, message",
    [
        (
            np.zeros((4, 4)),
            [("triangle", np.array([[0, 1, 2]]))],
            ": mesh points must have 2 or 3 coordinates, got shape (4, 4)",
        ),
        (
            np.zeros(3),
            [("triangle", np.array([[0, 1, 2]]))],
            ": mesh points must have 2 or 3 coordinates, got shape (3,)",
        ),
        (SQUARE, [], " has no triangles (it holds no cells); export the surface as triangles"),
        (
            SQUARE,
            [("line", np.array([[0, 1]])), ("vertex", np.array([[0]]))],
            " has no triangles (it holds line, vertex)",
        ),
        (SQUARE, [("triangle", np.zeros((0, 3), dtype=int))], " has no triangles (it holds triangle)"),
        (SQUARE, [("polygon", np.array([[0, 1, 2, 3]]))], " holds cells of type 'polygon'; only triangles and"),
        (SQUARE, [("triangle", np.array([[0, 1, 2, 3]]))], ": the triangle cells are not rows of 3 point indices"),
        (SQUARE, [("quad", np.array([0, 1, 2, 3]))], ": the quad cells are not rows of 4 point indices"),
        (SQUARE, [("triangle", np.array([[True, False, True]]))], ": the triangle cells are not rows of 3 point"),
        (
            SQUARE,
            [("line", np.array([[0, 1]])), ("triangle", np.array([[0, 1, 2], [0, 2, 4]], dtype=np.uint32))],
            ": cell 2 (a triangle) refers to point 4, but the file has 4 points (0 .. 3)",
        ),
        (
            SQUARE,
            [("line", np.array([[0, 1]])), ("line", np.array([[1, 2], [2, 3]])), ("quad", np.array([[0, 1, 2, 5]]))],
            ": cell 3 (a quad) refers to point 5, but the file has 4 points (0 .. 3)",
        ),
        (SQUARE, [("triangle", np.array([[0, 1, 2], [0, 2, 1.5]]))], ": cell 1 (a triangle) refers to point 1.5, but"),
        (SQUARE, [("triangle", np.array([[0, 1, -1.0]]))], ": cell 0 (a triangle) refers to point -1.0, but the file"),
        (SQUARE, [("triangle", np.array([[0, 1, 4.0]]))], ": cell 0 (a triangle) refers to point 4.0, but the file"),
        (SQUARE, [("triangle", np.array([[0, 1, 2], [1, 0, 2]]))], ": "),
    ],
)
def test_what_a_reader_gives_that_is_no_surface_is_refused_naming_the_file(
    monkeypatch, tmp_path, points, blocks, message
):
    assert refusal_of(monkeypatch, tmp_path, points, blocks).startswith(message)


def test_float_and_unsigned_indices_in_range_are_read(monkeypatch, tmp_path):
    cells = np.array([[0, 1, 2], [0, 2, 3]])
    for dtype in (np.float64, np.uint16):
        got = read_as(monkeypatch, tmp_path, SQUARE, [("triangle", cells.astype(dtype))])
        assert got.triangles.dtype.kind == "i" and triangle_sets(got) == [
            [[0, 0], [0, 1], [1, 1]],
            [[0, 0], [1, 0], [1, 1]],
        ]


def test_a_reader_failure_is_one_line_of_its_words_cut_short(monkeypatch, tmp_path, capsys):
    """Whatever meshio raises on a malformed file, and whatever it prints or warns on the way, is one line."""

    def failing(words):
        def read(filename):
            sys.stdout.write("meshio says something\n")
            sys.stderr.write("and on stderr\n")
            warnings.warn("overflow", RuntimeWarning)
            raise ValueError(words) if words else IndexError()

        return read

    path = tmp_path / "ROOF.STL"
    path.write_text("solid\n")
    for words, reason in [(" bad\n  header " + "x" * 300, "bad header " + "x" * 189), ("", "IndexError")]:
        monkeypatch.setattr(meshio.stl, "read", failing(words))
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            with pytest.raises(InvalidSurfaceError) as err:
                load_surface(path)
        assert str(err.value) == f"cannot read {path} as a .stl mesh: {reason}"
    assert capsys.readouterr() == ("", "")


def test_running_out_of_memory_is_not_a_malformed_file(monkeypatch, tmp_path):
    def read(filename):
        raise MemoryError

    monkeypatch.setattr(meshio.ply, "read", read)
    (tmp_path / "m.ply").write_text("ply\n")
    with pytest.raises(MemoryError):
        load_surface(tmp_path / "m.ply")
