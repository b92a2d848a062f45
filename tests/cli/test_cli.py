"""The command line: every output format, the member schedule, and every bad input (exit 2, no file).

Exit codes: 0 written, 2 bad input or unwritable output (one line, nothing
written), 3 internal error (one line asking for a report), 130 interrupted.
"""

import dataclasses
import json
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import types
import warnings
from pathlib import Path

import meshio
import numpy as np
import pandas as pd
import pytest
from hostile_paths import fifo, name_max, unwritable_folder
from repository import SURFACES
from surface_invariants import assert_valid_surface_mesh
from triangle_meshes import bad_meshes, roof

from equimesh import (
    InternalError,
    InvalidLengthError,
    load_surface,
    mesh_surface,
)
from equimesh._cli import main
from equimesh.io import _paths as io_paths
from equimesh.metrics import triangle_angles
from equimesh.surface import pipeline
from equimesh.surface.optimize import OBJECTIVES
from equimesh.testing.meshes import ellipse, roof_mesh

SADDLE = SURFACES / "saddle.json"
#: A quick run on the saddle: a coarse grid, no optimisation, no summary.
QUICK_SADDLE = ["mesh", SADDLE, "--length", 6, "--grid", 6, 6, "--optimize", "none", "-q"]


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


@pytest.mark.parametrize("objective", ["paper", "none"])
def test_a_mesh_with_joints_too_sharp_names_the_objective_that_keeps_them_sound(tmp_path, capsys, objective):
    """The saddle at L = 6: the paper's objective and none leave an angle below 30 degrees, which the summary counts
    and a note on standard error answers with the objectives that keep every joint sound (quiet with -q); the default
    one's summary counts none, and it adds no note."""
    args = ["mesh", SADDLE, "--length", 6, "--grid", 8, 8, "-o", tmp_path / "m.obj"]
    code, sharp = run([*args, "--optimize", objective], capsys)
    share = re.search(r"^an angle below 30 degrees +([\d.]+) % of triangles$", sharp.out, re.M)
    assert code == 0 and float(share.group(1)) > 0
    note = "equimesh: note: --optimize bounded or classes keeps every triangle angle at least 30 degrees, or a sharper"
    assert note in sharp.err
    code, quiet = run([*args, "--optimize", objective, "-q"], capsys)
    assert code == 0 and quiet.out == "" and "note:" not in quiet.err
    if objective == "paper":
        code, sound = run(args, capsys)
        assert code == 0 and "an angle below 30 degrees  0.0 % of triangles" in sound.out and "note:" not in sound.err


def test_a_run_ended_at_its_work_bound_says_so(tmp_path, capsys, monkeypatch):
    """The saddle at L = 6 takes 82 Jacobian evaluations under bounded: with a bound of 81 its optimisation ends at
    the best round end kept before it, and a note says so; within its bound, no such note."""
    args = ["mesh", SADDLE, "--length", 6, "--grid", 8, 8, "-o", tmp_path / "m.obj"]
    code, free = run(args, capsys)
    assert code == 0 and "work bound" not in free.err
    monkeypatch.setitem(OBJECTIVES, "bounded", dataclasses.replace(OBJECTIVES["bounded"], max_jacobians=81))
    code, bounded = run(args, capsys)
    note = (
        "equimesh: note: the optimisation ended at the best point found within 81 Jacobian evaluations (its work "
        "bound), not converged"
    )
    assert code == 0 and note in bounded.err and bounded.out == free.out


def test_members_schedule_classes_and_summary(tmp_path, capsys):
    """--members writes one row per member with its class and deviation from L, the classes CSV beside it,
    and the summary on standard output agrees with both files."""
    code, captured = run(
        [
            "mesh",
            SADDLE,
            "--length",
            6,
            "--grid",
            8,
            8,
            "-o",
            tmp_path / "m.obj",
            "--members",
            tmp_path / "m.csv",
            "--optimize",
            "none",
            "--tolerance",
            "1%",
        ],
        capsys,
    )
    assert code == 0
    table = pd.read_csv(tmp_path / "m.csv")
    assert list(table.columns) == [
        "member",
        "node_i",
        "node_j",
        "length",
        "group",
        "class",
        "deviation",
        "relative_deviation",
    ]
    np.testing.assert_allclose(table["deviation"], table["length"] - 6.0, rtol=0, atol=1e-8)
    assert set(table["group"]) <= {"G1", "other"} and (table["group"] == "G1").any()
    classes = pd.read_csv(tmp_path / "m.classes.csv")
    assert classes["count"].sum() == len(table) and classes["class"].tolist() == list(range(len(classes)))
    nominal = classes["nominal_length"].to_numpy()[table["class"]]
    assert np.all(np.abs(table["length"] - nominal) <= 0.01 * 6.0 * (1 + 1e-12))
    summary = dict(line.split("  ", 1) for line in captured.out.splitlines())
    assert int(summary["members"]) == len(table)
    assert summary["length classes"].strip().startswith(f"{len(classes)} ")
    share = 100 * classes["count"].max() / len(table)
    assert summary["in the largest class"].strip() == f"{share:.1f} %"
    within = 100 * np.mean(np.abs(table["length"] - 6.0) <= 0.06)
    assert summary["within +-1 % of L"].strip() == f"{within:.1f} %"
    top = 100 * np.sort(classes["count"].to_numpy())[::-1][:10].sum() / len(table)
    assert summary["in the 10 largest classes"].strip() == f"{top:.1f} %"
    written = meshio.read(tmp_path / "m.obj")
    angles = triangle_angles(written.points, written.cells_dict["triangle"])
    assert summary["triangle angles"].strip() == f"{angles.min():.1f} to {angles.max():.1f} degrees"
    assert summary["off the surface"].strip() == "max 0, mean 0"


def test_optimize_default_is_the_library_default():
    """--optimize omitted means mesh_surface's own default, whatever the library makes it."""
    import inspect

    from equimesh._cli import build_parser

    args = build_parser().parse_args(["mesh", str(SADDLE), "--length", "5", "-o", "m.obj"])
    assert args.optimize == inspect.signature(pipeline.mesh_surface).parameters["optimize"].default


def _write(path, text):
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    return path


BAD = {
    "missing file": lambda d: (["mesh", d / "nope.json", "--length", 5], "not found"),
    "malformed JSON": lambda d: (["mesh", _write(d / "s.json", "{"), "--length", 5], "malformed JSON"),
    "wrong type": lambda d: (
        ["mesh", _write(d / "s.json", json.dumps({"type": "mesh", "control_points": []})), "--length", 5],
        "bezier",
    ),
    "wrong net shape": lambda d: (
        [
            "mesh",
            _write(
                d / "s.json", json.dumps({"type": "bezier", "control_points": [[[0, 0, 0], [1, 0, 0]], [[0, 1, 0]]]})
            ),
            "--length",
            5,
        ],
        "points",
    ),
    "point of 2 numbers": lambda d: (
        [
            "mesh",
            _write(
                d / "s.json", json.dumps({"type": "bezier", "control_points": [[[0, 0], [1, 0]], [[0, 1], [1, 1]]]})
            ),
            "--length",
            5,
        ],
        "3 numbers",
    ),
    "non-finite": lambda d: (
        [
            "mesh",
            _write(
                d / "s.json", '{"type": "bezier", "control_points": [[[0, 0, NaN], [1, 0, 0]], [[0, 1, 0], [1, 1, 0]]]}'
            ),
            "--length",
            5,
        ],
        "finite",
    ),
    "L = 0": lambda d: (["mesh", SADDLE, "--length", 0], "positive"),
    "L < 0": lambda d: (["mesh", SADDLE, "--length", -5], "positive"),
    "L nan": lambda d: (["mesh", SADDLE, "--length", "nan"], "finite"),
    "L too small": lambda d: (["mesh", SADDLE, "--length", 0.05], "max-nodes"),
    "L too large": lambda d: (["mesh", SADDLE, "--length", 500], "shorter than l"),
    "L huge": lambda d: (["mesh", SADDLE, "--length", 1e300], "outside the supported range"),
    "L longer than a side": lambda d: (["mesh", SADDLE, "--length", 1e6], "shorter than l"),
    "L inf": lambda d: (["mesh", SADDLE, "--length", "inf"], "finite"),
    "L not a number": lambda d: (["mesh", SADDLE, "--length", "five"], "--length"),
    "5000-digit integer": lambda d: (["mesh", _write(d / "s.json", "[" + "9" * 5000 + "]"), "--length", 5], "digits"),
    "nested 100000 deep": lambda d: (["mesh", _write(d / "s.json", "[" * 100_000), "--length", 5], "nested too deeply"),
    "not UTF-8": lambda d: (["mesh", _write(d / "s.json", b'{"type": "b\xe9zier"}'), "--length", 5], "UTF-8"),
    "input is a folder": lambda d: (["mesh", d, "--length", 5], "extension"),
    "input folder named .json": lambda d: (
        ["mesh", (d / "x.json").mkdir() or d / "x.json", "--length", 5],
        "not a regular file",
    ),
    "input path too long": lambda d: (["mesh", d / ("a" * 5000 + ".json"), "--length", 5], "path too long"),
    "max-nodes not a number": lambda d: (["mesh", SADDLE, "--length", 5, "--max-nodes", "2.5"], "whole number"),
    "bad grid": lambda d: (["mesh", SADDLE, "--length", 5, "--grid", 0, 4], "n_u"),
    "bad max-nodes": lambda d: (["mesh", SADDLE, "--length", 5, "--max-nodes", 0], "max-nodes"),
    "missing length": lambda d: (["mesh", SADDLE], "--length"),
    "bad optimize": lambda d: (["mesh", SADDLE, "--length", 5, "--optimize", "magic"], "optimize"),
    "tolerance 0": lambda d: (["mesh", SADDLE, "--length", 5, "--tolerance", "0"], "above 0"),
    "tolerance negative": lambda d: (["mesh", SADDLE, "--length", 5, "--tolerance=-0.5%"], "above 0"),
    "tolerance 50 %": lambda d: (["mesh", SADDLE, "--length", 5, "--tolerance", "50%"], "below 50%"),
    "tolerance 0.7": lambda d: (["mesh", SADDLE, "--length", 5, "--tolerance", "0.7"], "below 50%"),
    "tolerance nan": lambda d: (["mesh", SADDLE, "--length", 5, "--tolerance", "nan"], "above 0"),
    "tolerance not a number": lambda d: (["mesh", SADDLE, "--length", 5, "--tolerance", "tight"], "--tolerance"),
    "surface tolerance negative": lambda d: (["mesh", SADDLE, "--length", 5, "--surface-tolerance=-1"], "at least 0"),
    "surface tolerance nan": lambda d: (["mesh", SADDLE, "--length", 5, "--surface-tolerance", "nan"], "at least 0"),
    "surface tolerance not a number": lambda d: (
        ["mesh", SADDLE, "--length", 5, "--surface-tolerance", "wide"],
        "--surface-tolerance",
    ),
    "surface tolerance at least L": lambda d: (["mesh", SADDLE, "--length", 5, "--surface-tolerance", 5], "below l"),
    "surface tolerance with paper": lambda d: (
        ["mesh", SADDLE, "--length", 5, "--surface-tolerance", 0.1, "--optimize", "paper"],
        "surface_tolerance",
    ),
    "lengths empty": lambda d: (["mesh", SADDLE, "--length", 5, "--optimize", "classes", "--lengths", ","], "at least"),
    "lengths not numbers": lambda d: (
        ["mesh", SADDLE, "--length", 5, "--optimize", "classes", "--lengths", "5,six"],
        "--lengths",
    ),
    "length outside [L, 2L]": lambda d: (
        ["mesh", SADDLE, "--length", 5, "--optimize", "classes", "--lengths", "5,10.5"],
        "outside [l, 2l]",
    ),
    "lengths without classes": lambda d: (["mesh", SADDLE, "--length", 5, "--lengths", "5"], "optimize='classes'"),
    "catalogue cannot hold the outline": lambda d: (
        ["mesh", SADDLE, "--length", 6, "--optimize", "classes", "--lengths", "7.7"],
        "adds up to side",
    ),
    "feature angle not a number": lambda d: (["mesh", SADDLE, "--length", 5, "--feature-angle", "sharp"], "degrees"),
    "feature angle negative": lambda d: (["mesh", SADDLE, "--length", 5, "--feature-angle=-1"], "at least 0"),
    "feature angle 180": lambda d: (["mesh", SADDLE, "--length", 5, "--feature-angle", "180"], "below 180"),
    "feature angle 1e3": lambda d: (["mesh", SADDLE, "--length", 5, "--feature-angle", "1e3"], "below 180"),
    "feature angle nan": lambda d: (["mesh", SADDLE, "--length", 5, "--feature-angle", "nan"], "degrees"),
    "feature angle 4_5": lambda d: (["mesh", SADDLE, "--length", 5, "--feature-angle", "4_5"], "got '4_5'"),
    "feature angle for a chart": lambda d: (
        ["mesh", SADDLE, "--length", 5, "--feature-angle", "30"],
        "feature angle finds the corners of a triangle mesh",
    ),
    "tolerance -1% as its own word": lambda d: (["mesh", SADDLE, "--length", 5, "--tolerance", "-1%"], "above 0"),
    "tolerance 1_0%": lambda d: (["mesh", SADDLE, "--length", 5, "--tolerance", "1_0%"], "got '1_0%'"),
    "L -1e3": lambda d: (["mesh", SADDLE, "--length", "-1e3"], "positive"),
    "L 1_0": lambda d: (["mesh", SADDLE, "--length", "1_0"], "--length/-l: the value must be a number, got '1_0'"),
    "grid 1_5": lambda d: (["mesh", SADDLE, "--length", 5, "--grid", "1_5", 4], "must be a whole number, got '1_5'"),
    "max-nodes 1_000": lambda d: (["mesh", SADDLE, "--length", 5, "--max-nodes", "1_000"], "whole number"),
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


@pytest.mark.parametrize(
    "target, match",
    [
        ("missing/mesh.obj", "does not exist"),
        ("mesh.xyz", "unknown extension '.xyz' for the mesh"),
        ("mesh.json", "use one of .obj, .vtk, .vtu, .stl, .ply, .msh, .3dm, .compas.json, .dxf"),
    ],
)
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


@pytest.mark.parametrize(
    "streams",
    ["1>&-", "2>&-", "1>&- 2>&-", "1>/dev/full", "2>/dev/full", "a pipe nobody reads"],
)
def test_a_closed_or_full_stream_neither_fails_nor_stops_a_run(streams, tmp_path):
    """Progress lines, the summary and notes only report a run: with standard output or error closed, on a full
    device or a pipe whose reader quit, the mesh is written and the exit code is 0."""
    exe = shutil.which("equimesh") or str(Path(sys.executable).with_name("equimesh"))
    mesh = tmp_path / "m.obj"
    command = [exe, "mesh", str(SADDLE), "--length", "5", "-o", str(mesh)]
    if streams == "a pipe nobody reads":
        read, write = os.pipe()
        os.close(read)
        done = subprocess.run(command, stdout=write, stderr=subprocess.DEVNULL, check=False)
        os.close(write)
    else:
        if "/dev/full" in streams and not Path("/dev/full").exists():
            pytest.skip("no /dev/full on this system")
        done = subprocess.run(" ".join([*map(shlex.quote, command), streams]), shell=True, check=False)
    assert done.returncode == 0 and len(meshio.read(mesh).cells_dict["triangle"]) > 0


def test_tiny_length_is_refused_in_one_line(tmp_path, capsys):
    code, captured = run(["mesh", SADDLE, "--length", 1e-300, "-o", tmp_path / "m.obj", "-q"], capsys)
    assert code == 2 and captured.err.count("\n") == 1, captured.err
    assert list(tmp_path.iterdir()) == []


BAD_OUTPUTS = {
    "output is a folder": lambda d: ["-o", (d / "m.obj").mkdir() or d / "m.obj"],
    "output under a regular file": lambda d: ["-o", _write(d / "plain", "x") / "m.obj"],
    "output a named pipe": lambda d: ["-o", fifo(d / "m.obj")],
    "output name too long": lambda d: ["-o", d / ("a" * (name_max(d) - 3) + ".obj")],
    "output folder unwritable": lambda d: ["-o", unwritable_folder(d) / "m.obj"],
    "members folder unwritable": lambda d: ["-o", d / "m.obj", "--members", unwritable_folder(d) / "m.csv"],
    "members extension": lambda d: ["-o", d / "m.obj", "--members", d / "m.txt"],
    "classes CSV is a folder": lambda d: ["-o", d / "m.obj", "--members", (d / "m.classes.csv").mkdir() or d / "m.csv"],
    "nodes folder unwritable": lambda d: ["-o", d / "m.obj", "--nodes", unwritable_folder(d) / "n.csv"],
    "nodes folder missing": lambda d: ["-o", d / "m.obj", "--nodes", d / "missing" / "n.csv"],
    "nodes extension": lambda d: ["-o", d / "m.obj", "--nodes", d / "n.obj"],
    "members and nodes one file": lambda d: ["-o", d / "m.obj", "--members", d / "a.csv", "--nodes", d / "a.csv"],
    "nodes are the classes CSV": lambda d: [
        "-o",
        d / "m.obj",
        "--members",
        d / "a.csv",
        "--nodes",
        d / "a.classes.csv",
    ],
    "plain JSON mesh": lambda d: ["-o", d / "m.json"],
}


@pytest.mark.parametrize("case", sorted(BAD_OUTPUTS))
def test_bad_outputs_are_refused_before_meshing(case, tmp_path, capsys, monkeypatch):
    """Every output is checked before the mesh is computed: one line, exit 2, nothing written."""
    monkeypatch.setattr(pipeline, "mesh_surface", _never_called)
    extra = BAD_OUTPUTS[case](tmp_path)
    made = sorted(tmp_path.rglob("*"))
    code, captured = run(["mesh", SADDLE, "--length", 5, "-q", *extra], capsys)
    assert code == 2 and captured.err.count("\n") == 1, captured.err
    assert sorted(tmp_path.rglob("*")) == made


def test_longest_name_is_written(tmp_path, capsys):
    """A file name of exactly NAME_MAX bytes works: the temporary name does not add to it."""
    out = tmp_path / ("a" * (name_max(tmp_path) - 4) + ".stl")
    code, captured = run(["mesh", SADDLE, "--length", 6, "--grid", 6, 6, "--optimize", "none", "-q", "-o", out], capsys)
    assert code == 0, captured.err
    assert [p.name for p in tmp_path.iterdir()] == [out.name]


def test_members_write_failure_leaves_no_mesh(tmp_path, capsys, monkeypatch):
    """The mesh and the member schedule are renamed together: a failing second write leaves neither."""

    def disk_full(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(pd.DataFrame, "to_csv", disk_full)
    code, captured = run(
        [*QUICK_SADDLE, "-o", tmp_path / "m.obj", "--members", tmp_path / "m.csv"],
        capsys,
    )
    assert code == 3 and "No space left on device" in captured.err and captured.err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []


def test_each_output_is_probed_once(tmp_path, capsys, monkeypatch):
    """The outputs are checked before meshing and not again: one probe per file (mesh, schedule, classes)."""
    probed = []
    monkeypatch.setattr(io_paths, "probe_folder", lambda folder, suffix="": probed.append(suffix))
    code, captured = run(
        [*QUICK_SADDLE, "-o", tmp_path / "m.obj", "--members", tmp_path / "m.csv"],
        capsys,
    )
    assert code == 0, captured.err
    assert probed == [".obj", ".csv", ".csv"]


def _never_called(*args, **kwargs):
    raise AssertionError("mesh_surface must not run")


def _raising(exc):
    def mesh_surface(*args, **kwargs):
        raise exc

    return mesh_surface


@pytest.mark.parametrize(
    "exc, code, message",
    [
        (
            InvalidLengthError("target length l must be positive"),
            2,
            "equimesh: error: target length l must be positive",
        ),
        (
            InternalError("edge 3 is 2.5 long, more than 2l = 2.0"),
            3,
            "equimesh: internal error: InternalError: edge 3 is 2.5 long, more than 2l = 2.0 (please report this",
        ),
        (
            ZeroDivisionError("float division by zero"),
            3,
            "equimesh: internal error: ZeroDivisionError: float division by zero",
        ),
        (
            RuntimeError("Triangle failed\nInternal error in finddirection()"),
            3,
            "equimesh: internal error: RuntimeError: Triangle failed Internal error in finddirection()",
        ),
        (MemoryError(), 2, "equimesh: error: out of memory"),
        (KeyboardInterrupt(), 130, "equimesh: interrupted"),
    ],
)
def test_every_failure_is_one_line_with_its_exit_code(exc, code, message, tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(sys, "unraisablehook", sys.unraisablehook)  # an interrupt changes it
    monkeypatch.setattr(pipeline, "mesh_surface", _raising(exc))
    got, captured = run(["mesh", SADDLE, "--length", 5, "-o", tmp_path / "m.obj", "-q"], capsys)
    assert got == code
    assert captured.err.count("\n") == 1 and captured.err.startswith(message), captured.err
    assert list(tmp_path.iterdir()) == []


def test_an_interrupt_silences_the_finalisers_it_broke(tmp_path, capsys, monkeypatch):
    """After Ctrl-C, an exception a half-built object's finaliser raises (llvmlite's, when numba was compiling) is
    not printed: the one line stays the only one."""
    before = sys.__unraisablehook__
    monkeypatch.setattr(sys, "unraisablehook", before)  # restored after the test
    monkeypatch.setattr(pipeline, "mesh_surface", _raising(KeyboardInterrupt()))
    code, captured = run(["mesh", SADDLE, "--length", 5, "-o", tmp_path / "m.obj", "-q"], capsys)
    assert code == 130 and captured.err == "equimesh: interrupted\n"
    assert sys.unraisablehook is not before
    error = AttributeError("'ValueRef' object has no attribute '_as_parameter_'")
    sys.unraisablehook(
        types.SimpleNamespace(
            exc_type=AttributeError, exc_value=error, exc_traceback=None, err_msg="Exception ignored in", object=None
        )
    )
    assert capsys.readouterr().err == ""


def test_an_interrupt_a_finaliser_swallowed_stops_the_run(tmp_path, capsys, monkeypatch):
    """A SIGINT whose KeyboardInterrupt is raised inside a finaliser (and so dropped by Python) still ends the run
    at the next stage: exit 130, one line, nothing written."""
    monkeypatch.setattr(sys, "unraisablehook", sys.unraisablehook)

    class Finalised:
        def __del__(self):
            signal.raise_signal(signal.SIGINT)  # its KeyboardInterrupt is raised here, and dropped

    def mesh_surface(*args, progress, **kwargs):
        Finalised()
        progress("auxiliary triangulation", 0.0)
        raise AssertionError("the run went on past the interrupt")

    monkeypatch.setattr(pipeline, "mesh_surface", mesh_surface)
    code, captured = run(["mesh", SADDLE, "--length", 5, "-o", tmp_path / "m.obj"], capsys)
    assert code == 130 and captured.err == "equimesh: interrupted\n", captured.err
    assert list(tmp_path.iterdir()) == []


def test_an_internal_error_asks_for_a_report_once(tmp_path, capsys, monkeypatch):
    """The library's InternalError asks for a report itself; the command line does not ask again."""
    error = InternalError("Triangle failed on a validated input: a bug in equimesh, please report it")
    monkeypatch.setattr(pipeline, "mesh_surface", _raising(error))
    code, captured = run(["mesh", SADDLE, "--length", 5, "-o", tmp_path / "m.obj", "-q"], capsys)
    assert code == 3 and captured.err.count("report") == 1 and "--traceback shows the details" in captured.err


def test_library_noise_does_not_reach_the_terminal(tmp_path, capfd, monkeypatch):
    """Triangle's C-level stdout and numpy's RuntimeWarnings are not printed: the one error line is."""

    def noisy(*args, **kwargs):
        os.write(1, b"Internal error in finddirection():\n")
        np.array([1e300]) * 1e300  # overflow warning
        raise RuntimeError("Triangulation failed")

    monkeypatch.setattr(pipeline, "mesh_surface", noisy)
    with warnings.catch_warnings(record=True) as shown:
        warnings.simplefilter("always")
        code = main(["mesh", str(SADDLE), "--length", "5", "-o", str(tmp_path / "m.obj"), "-q"])
    captured = capfd.readouterr()
    assert code == 3 and captured.out == "" and captured.err.count("\n") == 1, captured
    assert shown == []


def test_traceback_option_reraises_internal_errors(tmp_path, monkeypatch):
    monkeypatch.setattr(pipeline, "mesh_surface", _raising(InternalError("broken")))
    with pytest.raises(InternalError, match="broken"):
        main(["--traceback", "mesh", str(SADDLE), "--length", "5", "-o", str(tmp_path / "m.obj")])


@pytest.mark.parametrize(
    "given, passed",
    [
        ([], {}),
        (["--max-nodes", "none"], {"max_nodes": None}),
        (["--max-nodes", "1000"], {"max_nodes": 1000}),
        (["--feature-angle", "45"], {"feature_angle": 45.0}),
        (["--feature-angle", "0"], {"feature_angle": 0.0}),
    ],
)
def test_limits_reach_the_library(given, passed, tmp_path, capsys, monkeypatch):
    """Not given: the library's default applies; --max-nodes 'none': no limit (None); a number: that limit or
    feature angle."""
    seen = {}

    def mesh_surface(surface, l, **kwargs):
        seen.update(kwargs)
        raise InvalidLengthError("stop here")

    monkeypatch.setattr(pipeline, "mesh_surface", mesh_surface)
    run(["mesh", SADDLE, "--length", 5, "-o", tmp_path / "m.obj", "-q", *given], capsys)
    assert {k: v for k, v in seen.items() if k in ("max_nodes", "feature_angle")} == passed


def test_sigint_prints_one_line_exits_130_and_writes_nothing(tmp_path):
    """Ctrl-C in a long run: 'equimesh: interrupted', exit code 130, no output nor temporary file."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "equimesh._cli",
            "mesh",
            str(SADDLE),
            "--length",
            "1",
            "--optimize",
            "none",
            "--max-nodes",
            "100000",
            "-o",
            str(tmp_path / "m.obj"),
            "--members",
            str(tmp_path / "m.csv"),
        ],
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    try:
        first = proc.stderr.readline()  # the first progress line: the run is under way
        assert "auxiliary triangulation" in first, first
        proc.send_signal(signal.SIGINT)
        rest = proc.stderr.read()
        code = proc.wait(timeout=60)
    finally:
        proc.kill()
        proc.wait()
        proc.stderr.close()
    assert code == 130 and rest.strip().splitlines()[-1] == "equimesh: interrupted", rest
    assert "Traceback" not in rest
    assert list(tmp_path.iterdir()) == []


ROOF_3DM = SURFACES / "roof.3dm"


def test_a_rhino_file_meshes_through_the_command_line(tmp_path, capsys):
    """The roof of experiments/surfaces/roof.3dm through `equimesh mesh` (the INPUT_FORMATS row): the mesh the
    library makes of that surface, written."""
    pytest.importorskip("rhino3dm", reason="rhino3dm (the optional extra [rhino]) is not installed")
    out = tmp_path / "roof.obj"
    args = ["mesh", ROOF_3DM, "--object", "roof", "--length", 6, "--grid", 8, 8, "--optimize", "none", "-o", out]
    code, _ = run([*args, "-q"], capsys)
    assert code == 0
    roof = load_surface(ROOF_3DM, object="roof")
    mesh = mesh_surface(roof, 6.0, grid=(8, 8), optimize="none")
    assert_valid_surface_mesh(mesh, roof)
    np.testing.assert_array_equal(meshio.read(out).points, mesh.points)


@pytest.mark.parametrize("choice, expect", [(None, "holds 2 surfaces"), ("nosuch", "has no surface 'nosuch'")])
def test_rhino_object_must_be_named_when_ambiguous_or_unknown(tmp_path, capsys, choice, expect):
    pytest.importorskip("rhino3dm", reason="rhino3dm (the optional extra [rhino]) is not installed")
    args = ["mesh", ROOF_3DM, "--length", 2, "-o", tmp_path / "m.obj", "-q"] + (["--object", choice] if choice else [])
    code, captured = run(args, capsys)
    assert code == 2 and expect in captured.err and len(captured.err.strip().splitlines()) == 1
    assert not list(tmp_path.iterdir())


def test_rhino_trimmed_face_warns_in_one_line_and_meshes(tmp_path, capsys):
    pytest.importorskip("rhino3dm", reason="rhino3dm (the optional extra [rhino]) is not installed")
    code, captured = run(
        [
            "mesh",
            ROOF_3DM,
            "--object",
            "skylight plate",
            "--length",
            1,
            "--optimize",
            "none",
            "--grid",
            6,
            6,
            "-o",
            tmp_path / "m.obj",
            "-q",
        ],
        capsys,
    )
    assert code == 0 and (tmp_path / "m.obj").is_file()
    assert captured.err.strip() == (
        f"equimesh: warning: object 1 'skylight plate' of {ROOF_3DM} is a trimmed face: "
        "it is meshed on its untrimmed surface, not on the trimmed outline"
    )


def test_the_command_line_imports_the_library_inside_main():
    """``import equimesh._cli`` loads no numpy, scipy or shapely: a Ctrl-C during their import (seconds on
    a busy machine) happens inside main and is one line and exit code 130, not a traceback."""
    code = (
        "import sys, equimesh._cli; "
        "print(sorted({m.split('.')[0] for m in sys.modules} & {'numpy', 'scipy', 'shapely', 'meshio'}))"
    )
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True).stdout
    assert out.strip() == "[]"


L = 1.5


# --------------------------------------------------------------------------- triangle meshes in


def test_command_line_meshes_an_obj(tmp_path, capsys):
    v, t = roof()
    source = tmp_path / "roof.obj"
    meshio.write(source, meshio.Mesh(v, [("triangle", t)]))
    out = tmp_path / "out.vtu"
    assert main(["mesh", str(source), "--length", str(L), "--optimize", "none", "-q", "-o", str(out)]) == 0
    written = meshio.read(out)
    assert len(written.cells_dict["triangle"]) > 0


def test_command_line_meshes_a_round_opening_cut_out_of_a_fine_mesh(tmp_path, capsys):
    """A dome on 60 x 60 cells with a round opening 10 across cut out, its rim a staircase of mesh edges 1/2 long:
    meshed at l = 3 at the default feature angle, at 45 and at 0 degrees (the turns that fit are kept), and refused
    in one line at l = 11, where no ring of parts of at least l fits in the opening."""
    v, t = roof_mesh(30.0, 30.0, (60, 60), 3.0, cut=[ellipse((15.0, 15.0), 5.0, 5.0)])
    source = tmp_path / "dome.obj"
    meshio.write(source, meshio.Mesh(v, [("triangle", t)]))
    for given in ([], ["--feature-angle", "45"], ["--feature-angle", "0"]):
        out = tmp_path / "out.vtu"
        assert main(["mesh", str(source), "--length", "3", "--optimize", "none", "-q", "-o", str(out), *given]) == 0
        assert len(meshio.read(out).cells_dict["triangle"]) > 0
        out.unlink()
    code, captured = run(["mesh", source, "--length", 11, "-q", "-o", tmp_path / "m.vtu"], capsys)
    assert code == 2 and captured.err.count("\n") == 1, captured.err
    assert "hole 0" in captured.err and "too small for l = 11" in captured.err, captured.err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["dome.obj"]


@pytest.mark.parametrize("case", sorted(bad_meshes()))
def test_command_line_refuses_bad_meshes(tmp_path, capsys, case):
    """Every malformed mesh, written as a .vtu file: one line, exit 2, nothing written; an index out of range is
    named as the file writes it."""
    (v, t), match = bad_meshes()[case]
    if case == "index out of range":
        match = r"bad\.vtu: cell 0 \(a triangle\) refers to point 4, but the file has 4 points \(0 \.\. 3\)"
    source = tmp_path / "bad.vtu"
    # meshio cannot read back an empty triangle block: a mesh of lines only has no triangles either.
    cells = [("line", np.array([[0, 1]]))] if case == "no triangles" else [("triangle", np.asarray(t, dtype=np.int64))]
    meshio.write(source, meshio.Mesh(np.asarray(v, dtype=float), cells))
    out = tmp_path / "out.vtu"
    assert main(["mesh", str(source), "--length", "1", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("equimesh: error: ") and re.search(match, err), err
    assert not out.exists()
