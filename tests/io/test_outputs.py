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
from equimesh.classes import DEFAULT_TOLERANCE
from equimesh.io import (
    OUTPUT_FORMATS,
    OUTPUT_SLOTS,
    OutputFormat,
    Products,
    _outputs,
    check_output_path,
    output_format,
    output_formats,
    output_table,
    surface_mesh_writer,
    write_members,
    write_plot,
    write_report,
    write_surface_mesh,
)
from equimesh.io.provenance import provenance

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


def test_the_output_table_has_a_row_per_format():
    """A header, then per format its option (``-o`` for the mesh, ``--<slot>`` else), extension, name, contents
    and extra (quoted, or empty)."""
    lines = output_table().split("\n")
    assert lines[:2] == ["| option | extension | format | holds | extra |", "|---|---|---|---|---|"]
    assert len(lines) == 2 + len(OUTPUT_FORMATS)
    for line, f in zip(lines[2:], OUTPUT_FORMATS):
        option = "-o" if f.slot == "mesh" else f"--{f.slot}"
        extra = f"`{f.extra}`" if f.extra else ""
        assert line == f"| `{option}` | `{f.extension}` | {f.name} | {f.holds} | {extra} |"
    assert "| `-o` | `.obj` |" in lines[2] and lines[-1].startswith("| `--plot` | `.pdf` |")


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


def test_the_mesh_is_the_default_slot(tmp_path):
    assert output_format("roof.obj") is output_formats("mesh")[".obj"]
    assert check_output_path(tmp_path / "roof.csv", "nodes") is output_formats("nodes")[".csv"]
    assert check_output_path(tmp_path / "roof.obj") is output_formats("mesh")[".obj"]
    with pytest.raises(OutputPathError):
        check_output_path(tmp_path / "roof.csv")


def test_the_longest_extension_wins_where_two_nest(monkeypatch):
    """A row for ``.json`` beside ``.compas.json`` would leave ``.compas.json`` files to COMPAS."""
    plain = OutputFormat("mesh", ".json", "JSON", "a test row", lambda tmp, products: None)
    monkeypatch.setattr(_outputs, "OUTPUT_FORMATS", (*OUTPUT_FORMATS, plain))
    assert output_format("roof.compas.json").extension == ".compas.json"
    assert output_format("roof.json") is plain


def test_the_message_names_the_extension_the_file_and_every_extension_of_the_slot():
    known = ", ".join(output_formats("mesh"))
    with pytest.raises(OutputPathError) as err:
        output_format("roof.xyz")
    assert str(err.value) == f"unknown extension '.xyz' for the mesh roof.xyz; use one of {known}"
    with pytest.raises(OutputPathError) as err:
        output_format("dir/roof")
    assert str(err.value) == f"no extension for the mesh dir/roof; use one of {known}"
    with pytest.raises(OutputPathError) as err:
        output_format("m.txt", "members")
    assert str(err.value) == "unknown extension '.txt' for the member schedule m.txt; use one of .csv"


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
    assert str(err.value).startswith(f"{tmp_path / f'm{fmt.extension}'}: writing {fmt.name} files ")
    assert f"({fmt.extension}) needs {fmt.module}, which is not installed" in str(err.value)
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
    with pytest.raises(OutputPathError) as err:
        surface_mesh_writer({"mesh": tmp_path / "." / "roof.obj"}, inputs=[source])
    assert str(err.value) == (
        f"the mesh {source} is the input {source}: writing it would destroy the input; choose another output file"
    )
    with pytest.raises(OutputPathError, match="length classes .* and the node schedule"):
        surface_mesh_writer(
            {"mesh": tmp_path / "m.obj", "members": tmp_path / "a.csv", "nodes": tmp_path / "a.classes.csv"}
        )
    with pytest.raises(TypeError, match="unknown outputs"):
        surface_mesh_writer({"mesh": tmp_path / "m.obj", "mesh2": tmp_path / "n.obj"})
    assert sorted(p.name for p in tmp_path.iterdir()) == ["roof.obj"]


def test_an_output_not_given_is_skipped_and_the_others_written(tent_mesh, tmp_path):
    write_surface_mesh(tent_mesh, tmp_path / "m.obj", nodes=tmp_path / "n.csv", report=None, plot=tmp_path / "p.png")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.obj", "n.csv", "p.png"]


def written(write, products, tmp_path):
    """The bytes ``write`` (a format's writer) gives for ``products``."""
    tmp = tmp_path / "direct"
    write(tmp, products)
    return tmp.read_bytes()


def test_the_tolerance_and_the_labels_reach_every_writer(tent_mesh, tmp_path):
    """Each file is what its format's writer makes of Products(mesh, tolerance, dxf_labels); by default the
    fabrication tolerance and no DXF labels."""
    pytest.importorskip("ezdxf")
    mesh, formats = tent_mesh, output_formats("mesh")
    write_surface_mesh(mesh, tmp_path / "m.dxf", tmp_path / "m.csv", 0.05, dxf_labels=True)
    write_surface_mesh(mesh, tmp_path / "d.dxf", tmp_path / "d.csv")
    given, default = Products(mesh, 0.05, True), Products(mesh, DEFAULT_TOLERANCE, False)
    assert len(given.classes) < len(default.classes)  # the tolerance shows in the classes
    for name, products in (("m", given), ("d", default)):
        assert (tmp_path / f"{name}.dxf").read_bytes() == written(formats[".dxf"].write, products, tmp_path)
        members = (tmp_path / f"{name}.csv").read_bytes()
        assert members == written(output_formats("members")[".csv"].write, products, tmp_path)
        classes = (tmp_path / f"{name}.classes.csv").read_bytes()
        assert classes == written(output_formats("members")[".csv"].beside[0].write, products, tmp_path)
    assert b"labels" in (tmp_path / "m.dxf").read_bytes() and b"labels" not in (tmp_path / "d.dxf").read_bytes()


def test_a_writer_made_alone_writes_no_labels(tent_mesh, tmp_path):
    pytest.importorskip("ezdxf")
    surface_mesh_writer({"mesh": tmp_path / "m.dxf"})(tent_mesh)
    plain = written(output_formats("mesh")[".dxf"].write, Products(tent_mesh), tmp_path)
    assert (tmp_path / "m.dxf").read_bytes() == plain


def test_the_plot_and_the_report_are_those_of_their_writers(tent_mesh, tmp_path):
    """write_plot and write_report pass the tolerance, the parameters and the record to their writers."""
    pytest.importorskip("plotly")
    record = {**provenance({"input": "tent.json"}), "date": "2026-01-01T00:00:00+00:00"}
    write_plot(tent_mesh, tmp_path / "p.png", tolerance=0.05)
    plot = output_formats("plot")[".png"].write
    assert (tmp_path / "p.png").read_bytes() == written(plot, Products(tent_mesh, 0.05), tmp_path)
    assert (tmp_path / "p.png").read_bytes() != written(plot, Products(tent_mesh), tmp_path)
    write_report(tent_mesh, tmp_path / "r.html", tolerance=0.05, record=record)
    report = output_formats("report")[".html"].write
    assert (tmp_path / "r.html").read_bytes() == written(report, Products(tent_mesh, 0.05, record=record), tmp_path)
    write_report(tent_mesh, tmp_path / "s.html", parameters={"input": "tent.json", "length": 1.0})
    assert "<title>equimesh report: tent.json</title>" in (tmp_path / "s.html").read_text(encoding="utf-8")


def test_members_alone_are_written_with_their_classes(tent_mesh, tmp_path):
    m = tent_mesh
    write_members(tmp_path / "s.csv", m.points, m.edges, m.edge_groups, m.length, 0.05)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.classes.csv", "s.csv"]
    products = Products(m, 0.05)
    assert (tmp_path / "s.csv").read_bytes() == written(output_formats("members")[".csv"].write, products, tmp_path)
    classes = output_formats("members")[".csv"].beside[0].write
    assert (tmp_path / "s.classes.csv").read_bytes() == written(classes, products, tmp_path)


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


def test_the_same_mesh_gives_the_same_bytes_in_every_format(tent_mesh, tmp_path):
    """Two interpreters, with other hash seeds and at other times (more than a second apart), write every format
    whose library is installed; every file is the same, byte for byte."""
    arrays = tmp_path / "mesh.npz"
    m = tent_mesh
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
