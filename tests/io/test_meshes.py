"""Writing meshes and member schedules (``io/_meshes.py``): output paths checked before any work, mesh and members
written together or not at all, member groups read from the G1 constant.
"""

import numpy as np
import pandas as pd
import pytest
from hostile_paths import fifo, name_max, plain_file, unwritable_folder
from refusals import assert_one_line

from equimesh import OutputPathError
from equimesh.io import (
    MEMBER_FORMATS,
    MESH_FORMATS,
    check_output_path,
    member_schedule,
    write_surface_mesh,
)
from equimesh.io._atomic import atomic_paths
from equimesh.mesh import G1, OTHER


@pytest.mark.parametrize(
    "make, fragment",
    [
        (lambda d: d / "m.xyz", "unknown output extension '.xyz'"),
        (lambda d: d / "missing" / "m.obj", "output folder does not exist"),
        (lambda d: plain_file(d) / "m.obj", "output folder is not a folder"),
        (lambda d: (d / "m.obj").mkdir() or d / "m.obj", "is a folder"),
        (lambda d: fifo(d / "m.obj"), "exists and is not a regular file"),
        (lambda d: d / ("a" * (name_max(d) - 3) + ".obj"), "bytes long, more than the"),
        (lambda d: d.joinpath(*["a" * 200] * 30, "m.obj"), "output path is"),
        (lambda d: unwritable_folder(d) / "m.obj", "cannot write"),
    ],
)
def test_output_checks(make, fragment, tmp_path):
    """A refused output path is one line; nothing, not even a temporary file, is left behind."""
    path = make(tmp_path)
    made = sorted(tmp_path.rglob("*"))
    with pytest.raises(OutputPathError) as err:
        check_output_path(path, MESH_FORMATS)
    assert fragment in str(err.value)
    assert_one_line(str(err.value))
    assert sorted(tmp_path.rglob("*")) == made


def test_longest_allowed_name_is_written(tmp_path):
    """A name of exactly NAME_MAX bytes is accepted and written: the temporary name does not grow with it."""
    path = tmp_path / ("a" * (name_max(tmp_path) - 4) + ".csv")
    assert check_output_path(path, MEMBER_FORMATS) == "csv"
    with atomic_paths(path) as (tmp,):
        assert len(tmp.name) < 30
        tmp.write_text("x")
    assert path.read_text() == "x"


class _Mesh:
    """The fields of a SurfaceMesh that write_surface_mesh reads."""

    points = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    triangles = np.array([[0, 1, 2]])
    edges = np.array([[0, 1], [0, 2], [1, 2]])
    edge_groups = np.array([G1, G1, OTHER])
    length = 1.0


def test_mesh_and_members_are_written_together_or_not_at_all(tmp_path, monkeypatch):
    write_surface_mesh(_Mesh, tmp_path / "m.obj", tmp_path / "m.csv")
    written = ["m.classes.csv", "m.csv", "m.obj"]
    assert sorted(p.name for p in tmp_path.iterdir()) == written
    table = pd.read_csv(tmp_path / "m.csv")
    assert list(table["group"]) == ["G1", "G1", "other"]

    def disk_full(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(pd.DataFrame, "to_csv", disk_full)
    with pytest.raises(OSError, match="disk full"):
        write_surface_mesh(_Mesh, tmp_path / "n.obj", tmp_path / "n.csv")
    assert sorted(p.name for p in tmp_path.iterdir()) == written


def test_member_groups_follow_the_g1_constant():
    table = member_schedule(_Mesh.points, _Mesh.edges, _Mesh.edge_groups, 1.0)
    assert list(table["group"]) == ["G1", "G1", "other"]
    np.testing.assert_allclose(table["deviation"], [0.0, 0.0, np.sqrt(2.0) - 1.0])


def test_no_temporary_file_is_left_in_the_folder(tmp_path):
    write_surface_mesh(_Mesh, tmp_path / "m.vtu")
    assert [p.name for p in tmp_path.iterdir()] == ["m.vtu"]
