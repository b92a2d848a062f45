"""The outputs of a run (``io/_outputs.py``): one table of formats that the help, the errors and the README are made
from; every file checked before the work and written all or none; the same mesh, the same bytes."""

import os
import subprocess
import sys
import time
import tomllib

import numpy as np
import pandas as pd
import pytest
from refusals import assert_one_line
from repository import ROOT

from equimesh import MissingDependencyError, OutputPathError
from equimesh.io import (
    OUTPUT_FORMATS,
    OUTPUT_SLOTS,
    check_output_path,
    output_format,
    output_formats,
    output_table,
    surface_mesh_writer,
    write_members,
    write_surface_mesh,
)

EXTRAS = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]


def installed(fmt):
    try:
        __import__(fmt.module or "equimesh")
    except ImportError:
        return False
    return True


def test_every_format_is_complete():
    """Each row: a known slot, a lower-case extension, a writer, a description; an extra of pyproject.toml with the
    module it provides; no two rows answer the same extension of a slot."""
    keys = [(f.slot, f.extension) for f in OUTPUT_FORMATS]
    assert len(keys) == len(set(keys))
    for f in OUTPUT_FORMATS:
        assert f.slot in OUTPUT_SLOTS and f.extension.startswith(".") and f.extension == f.extension.lower()
        assert callable(f.write) and f.name and f.holds
        assert (f.extra is None) == (f.module is None)
        if f.extra is not None:
            assert f.extra in EXTRAS and any(req.startswith(f.module) for req in EXTRAS[f.extra])
    assert set(OUTPUT_SLOTS) == {f.slot for f in OUTPUT_FORMATS}


def test_readme_lists_every_format():
    """The README's output table is the one the registry makes."""
    assert output_table() in (ROOT / "README.md").read_text()


@pytest.mark.parametrize(
    "name, slot, extension",
    [
        ("roof.obj", "mesh", ".obj"),
        ("ROOF.OBJ", "mesh", ".obj"),
        ("roof.compas.json", "mesh", ".compas.json"),
        ("roof.v2.compas.JSON", "mesh", ".compas.json"),
        ("roof.3dm", "mesh", ".3dm"),
        ("m.csv", "members", ".csv"),
        ("n.csv", "nodes", ".csv"),
    ],
)
def test_the_longest_extension_selects_the_format(name, slot, extension):
    assert output_format(name, slot).extension == extension


@pytest.mark.parametrize(
    "name, slot", [("roof.json", "mesh"), ("roof.xyz", "mesh"), ("roof", "mesh"), ("m.txt", "members")]
)
def test_an_unknown_extension_lists_the_known_ones(name, slot):
    """A plain .json is a surface description, not a mesh: refused, with every extension of the slot listed."""
    with pytest.raises(OutputPathError) as err:
        output_format(name, slot)
    assert_one_line(str(err.value))
    assert all(ext in str(err.value) for ext in output_formats(slot))


@pytest.mark.parametrize("fmt", [f for f in OUTPUT_FORMATS if f.extra], ids=lambda f: f.extension)
def test_a_format_without_its_extra_says_how_to_install_it(fmt, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, fmt.module, None)  # import fails as if not installed
    with pytest.raises(MissingDependencyError) as err:
        check_output_path(tmp_path / f"m{fmt.extension}", fmt.slot)
    assert f"pip install 'equimesh[{fmt.extra}]'" in str(err.value)
    assert_one_line(str(err.value))
    assert list(tmp_path.iterdir()) == []


def test_outputs_are_written_together_or_not_at_all(tent_mesh, tmp_path, monkeypatch):
    write_surface_mesh(tent_mesh, tmp_path / "m.obj", tmp_path / "m.csv", nodes=tmp_path / "n.csv")
    written = ["m.classes.csv", "m.csv", "m.obj", "n.csv"]
    assert sorted(p.name for p in tmp_path.iterdir()) == written

    def disk_full(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(pd.DataFrame, "to_csv", disk_full)
    with pytest.raises(OSError, match="disk full"):
        write_surface_mesh(tent_mesh, tmp_path / "x.obj", tmp_path / "x.csv", nodes=tmp_path / "y.csv")
    assert sorted(p.name for p in tmp_path.iterdir()) == written


def test_every_file_is_checked_before_the_writer_is_returned(tmp_path):
    """Two outputs that are one file, an output that is an input: refused when the writer is made."""
    source = tmp_path / "roof.obj"
    source.write_text("v 0 0 0\n")
    with pytest.raises(OutputPathError, match="would destroy the input"):
        surface_mesh_writer({"mesh": tmp_path / "." / "roof.obj"}, inputs=[source])
    with pytest.raises(OutputPathError, match="length classes .* and the node schedule"):
        surface_mesh_writer(
            {"mesh": tmp_path / "m.obj", "members": tmp_path / "a.csv", "nodes": tmp_path / "a.classes.csv"}
        )
    with pytest.raises(TypeError, match="unknown outputs"):
        surface_mesh_writer({"mesh": tmp_path / "m.obj", "mesh2": tmp_path / "n.obj"})
    assert sorted(p.name for p in tmp_path.iterdir()) == ["roof.obj"]


def test_members_alone_are_written_with_their_classes(tent_mesh, tmp_path):
    m = tent_mesh
    write_members(tmp_path / "s.csv", m.points, m.edges, m.edge_groups, m.length)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.classes.csv", "s.csv"]
    assert len(pd.read_csv(tmp_path / "s.csv")) == len(m.edges)


WRITE_ALL = """
import sys, types
import numpy as np
from equimesh.io import write_surface_mesh
arrays = np.load(sys.argv[1])
mesh = types.SimpleNamespace(**{k: arrays[k] for k in arrays.files})
mesh.length = float(mesh.length)
out = sys.argv[2]
for k, ext in enumerate(sys.argv[3:]):
    extra = {"members": f"{out}/m{k}.csv", "nodes": f"{out}/n{k}.csv"} if k == 0 else {}
    write_surface_mesh(mesh, f"{out}/m{ext}", dxf_labels=True, **extra)
"""


def test_the_same_mesh_gives_the_same_bytes_in_every_format(saddle_mesh, tmp_path):
    """Two interpreters, with other hash seeds and at other times (more than a second apart), write every format
    whose library is installed; every file is the same, byte for byte."""
    arrays = tmp_path / "mesh.npz"
    m = saddle_mesh
    np.savez(arrays, points=m.points, triangles=m.triangles, edges=m.edges, edge_groups=m.edge_groups, length=m.length)
    extensions = [f.extension for f in OUTPUT_FORMATS if f.slot == "mesh" and installed(f)]
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    runs = []
    for seed in ("1", "2"):
        out = tmp_path / f"run{seed}"
        out.mkdir()
        subprocess.run(
            [sys.executable, "-c", WRITE_ALL, str(arrays), str(out), *extensions],
            env={**env, "PYTHONHASHSEED": seed},
            check=True,
            timeout=300,
        )
        runs.append({p.name: p.read_bytes() for p in out.iterdir()})
        time.sleep(1.1)  # clocks that stamp seconds (Rhino's revision history) move on
    assert sorted(runs[0]) == sorted(runs[1]) and len(runs[0]) == len(extensions) + 3
    assert [name for name in runs[0] if runs[0][name] != runs[1][name]] == []
