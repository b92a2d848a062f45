"""``equimesh mesh --report/--plot``: written together with every other output of the run, or none of them."""

import sys

import pytest
from hostile_paths import unwritable_folder
from matplotlib.figure import Figure
from repository import SURFACES
from test_cli import run

from equimesh.surface import pipeline

SADDLE = SURFACES / "saddle.json"
QUICK = ["--length", "6", "--grid", "6", "6", "--optimize", "none"]


def test_report_and_plot_are_written_with_the_mesh_and_the_schedule(tmp_path, capsys):
    pytest.importorskip("plotly", reason="the report needs plotly: pip install 'equimesh[report]'")
    out = {name: tmp_path / name for name in ("m.obj", "m.csv", "r.html", "p.png")}
    args = ["-o", out["m.obj"], "--members", out["m.csv"], "--report", out["r.html"], "--plot", out["p.png"]]
    code, captured = run(["mesh", SADDLE, *QUICK, "--tolerance", "1%", *args], capsys)
    assert code == 0, captured.err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.classes.csv", "m.csv", "m.obj", "p.png", "r.html"]
    assert f"{out['r.html']}, {out['p.png']}:" in captured.err
    report = out["r.html"].read_text(encoding="utf-8")
    for shown in (f"parameter: input</th><td>{SADDLE}", "parameter: tolerance</th><td>0.01", "parameter: grid"):
        assert shown in report
    assert out["p.png"].read_bytes().startswith(b"\x89PNG")


BAD = {
    "report folder missing": lambda d: ["--report", d / "missing" / "r.html"],
    "report folder unwritable": lambda d: ["--report", unwritable_folder(d) / "r.html"],
    "report extension": lambda d: ["--report", d / "r.pdf"],
    "report is a folder": lambda d: ["--report", (d / "r.html").mkdir() or d / "r.html"],
    "plot folder missing": lambda d: ["--plot", d / "missing" / "p.png"],
    "plot folder unwritable": lambda d: ["--plot", unwritable_folder(d) / "p.png"],
    "plot extension": lambda d: ["--plot", d / "p.jpg"],
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_a_report_or_plot_that_cannot_be_written_is_refused_before_meshing(case, tmp_path, capsys, monkeypatch):
    """One line, exit 2, nothing written, and the mesh never computed."""
    pytest.importorskip("plotly", reason="the report needs plotly: pip install 'equimesh[report]'")
    monkeypatch.setattr(pipeline, "mesh_surface", _never_called)
    extra = BAD[case](tmp_path)
    made = sorted(tmp_path.rglob("*"))
    code, captured = run(["mesh", SADDLE, "--length", 5, "-q", "-o", tmp_path / "m.obj", *extra], capsys)
    assert code == 2 and captured.err.count("\n") == 1, captured.err
    assert sorted(tmp_path.rglob("*")) == made


def test_without_plotly_the_report_is_refused_in_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(pipeline, "mesh_surface", _never_called)
    monkeypatch.setitem(sys.modules, "plotly", None)  # import plotly raises ImportError
    code, captured = run(
        ["mesh", SADDLE, "--length", 5, "-o", tmp_path / "m.obj", "--report", tmp_path / "r.html"], capsys
    )
    message = captured.err.strip()
    assert code == 2 and message.startswith("equimesh: error: ") and "\n" not in message
    assert message.endswith(
        "r.html: writing HTML files (.html) needs plotly, which is not installed: pip install 'equimesh[report]'"
    )
    assert list(tmp_path.iterdir()) == []


def test_a_failing_plot_leaves_no_output_of_the_run(tmp_path, capsys, monkeypatch):
    """The plot is renamed with the mesh and the schedule: when drawing it fails, none of them is written."""

    def disk_full(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(Figure, "savefig", disk_full)
    args = ["-o", tmp_path / "m.obj", "--members", tmp_path / "m.csv", "--plot", tmp_path / "p.png"]
    code, captured = run(["mesh", SADDLE, *QUICK, "-q", *args], capsys)
    assert code == 3 and "No space left on device" in captured.err and captured.err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []


def _never_called(*args, **kwargs):
    raise AssertionError("the mesh was computed although an output could not be written")
