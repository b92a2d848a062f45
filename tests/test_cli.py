"""The command line: every output format, the member schedule, and every bad input (exit 2, no file)."""

import json
import shutil
import subprocess
import sys
from pathlib import Path

import meshio
import numpy as np
import pandas as pd
import pytest

from equimesh._cli import main

SURFACES = Path(__file__).resolve().parents[1] / "experiments" / "surfaces"
SADDLE = SURFACES / "saddle.json"


def run(args, capsys):
    try:
        code = main([str(a) for a in args])
    except SystemExit as exc:  # argparse usage errors
        code = exc.code
    return code, capsys.readouterr()


@pytest.fixture(scope="module")
def meshed(tmp_path_factory):
    """One mesh written in every format (coarse grid to stay quick)."""
    out = tmp_path_factory.mktemp("formats")
    for ext in (".obj", ".vtk", ".vtu", ".stl", ".ply", ".msh"):
        assert main(["mesh", str(SADDLE), "--length", "6", "--grid", "8", "8", "-q", "-o", str(out / f"m{ext}")]) == 0
    return out


@pytest.mark.parametrize("ext", [".obj", ".vtk", ".vtu", ".stl", ".ply", ".msh"])
def test_every_format_reads_back(meshed, ext):
    """Each format is readable by meshio with the same triangles and points."""
    ref = meshio.read(meshed / "m.vtu")
    got = meshio.read(meshed / f"m{ext}")
    tri = got.cells_dict["triangle"]
    assert tri.shape == ref.cells_dict["triangle"].shape
    if ext != ".stl":  # STL stores triangles as coordinate triples
        np.testing.assert_allclose(got.points, ref.points, rtol=1e-6, atol=1e-6)


def test_members_schedule(tmp_path, capsys):
    """--members writes one row per member with its deviation from L."""
    code, _ = run(["mesh", SADDLE, "--length", 6, "--grid", 8, 8, "-o", tmp_path / "m.obj",
                   "--members", tmp_path / "m.csv", "--optimize", "none"], capsys)
    assert code == 0
    table = pd.read_csv(tmp_path / "m.csv")
    assert list(table.columns) == ["member", "node_i", "node_j", "length", "group", "deviation", "relative_deviation"]
    np.testing.assert_allclose(table["deviation"], table["length"] - 6.0, rtol=0, atol=1e-8)
    assert set(table["group"]) <= {"G1", "other"} and (table["group"] == "G1").any()


def _write(path, text):
    path.write_text(text)
    return path


BAD = {
    "missing file": lambda d: (["mesh", d / "nope.json", "--length", 5], "not found"),
    "malformed JSON": lambda d: (["mesh", _write(d / "s.json", "{"), "--length", 5], "malformed JSON"),
    "wrong type": lambda d: (["mesh", _write(d / "s.json", json.dumps({"type": "nurbs", "control_points": []})),
                              "--length", 5], "bezier"),
    "wrong net shape": lambda d: (["mesh", _write(d / "s.json", json.dumps(
        {"type": "bezier", "control_points": [[[0, 0, 0], [1, 0, 0]], [[0, 1, 0]]]})), "--length", 5], "points"),
    "point of 2 numbers": lambda d: (["mesh", _write(d / "s.json", json.dumps(
        {"type": "bezier", "control_points": [[[0, 0], [1, 0]], [[0, 1], [1, 1]]]})), "--length", 5], "3 numbers"),
    "non-finite": lambda d: (["mesh", _write(d / "s.json", '{"type": "bezier", "control_points": '
                              '[[[0, 0, NaN], [1, 0, 0]], [[0, 1, 0], [1, 1, 0]]]}'), "--length", 5], "finite"),
    "L = 0": lambda d: (["mesh", SADDLE, "--length", 0], "positive"),
    "L < 0": lambda d: (["mesh", SADDLE, "--length", -5], "positive"),
    "L nan": lambda d: (["mesh", SADDLE, "--length", "nan"], "finite"),
    "L too small": lambda d: (["mesh", SADDLE, "--length", 0.05], "max-nodes"),
    "L too large": lambda d: (["mesh", SADDLE, "--length", 500], "shorter than l"),
    "bad grid": lambda d: (["mesh", SADDLE, "--length", 5, "--grid", 0, 4], "n_u"),
    "bad max-nodes": lambda d: (["mesh", SADDLE, "--length", 5, "--max-nodes", 0], "max-nodes"),
    "missing length": lambda d: (["mesh", SADDLE], "--length"),
    "bad optimize": lambda d: (["mesh", SADDLE, "--length", 5, "--optimize", "magic"], "optimize"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_input_exits_2_without_output(case, tmp_path, capsys):
    """Bad input: exit code 2, one line on stderr naming the problem, no output file (nor temp file) left."""
    args, match = BAD[case](tmp_path)
    out = tmp_path / "out" / "mesh.obj"
    out.parent.mkdir()
    code, captured = run([*args, "-o", out, "--members", tmp_path / "out" / "m.csv", "-q"], capsys)
    assert code == 2
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and match in lines[0], captured.err
    assert list(out.parent.iterdir()) == []


@pytest.mark.parametrize("target, match", [("missing/mesh.obj", "does not exist"), ("mesh.xyz", "extension")])
def test_bad_output_path(target, match, tmp_path, capsys):
    code, captured = run(["mesh", SADDLE, "--length", 5, "-o", tmp_path / target], capsys)
    assert code == 2 and match in captured.err
    assert list(tmp_path.iterdir()) == []


def test_console_script_and_help():
    """The installed entry point runs; --help of every subcommand works and exits 0."""
    exe = shutil.which("equimesh") or str(Path(sys.executable).with_name("equimesh"))
    for args in (["--help"], ["mesh", "--help"], ["table1", "--help"], ["figures", "--help"]):
        done = subprocess.run([exe, *args], capture_output=True, text=True, check=False)
        assert done.returncode == 0 and "usage" in done.stdout
    done = subprocess.run([exe, "mesh", str(SADDLE), "--length", "0", "-o", "x.obj"], capture_output=True, text=True)
    assert done.returncode == 2 and done.stderr.count("\n") == 1
