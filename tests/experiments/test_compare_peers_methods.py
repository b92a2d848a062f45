"""experiments/compare_peers.py with a researcher's mesher: by ``--method`` or an ``equimesh.methods`` entry point."""

import sys

import pandas as pd
import pytest

from equimesh.metrics import comparison_figures
from equimesh.testing.benchmark import BENCHMARK, parameter_grid

MESHER = """
from equimesh.testing.benchmark import parameter_grid as grid


def nothing(surface, l):
    return None


def fails(surface, l):
    raise RuntimeError("cannot mesh this one")
"""


@pytest.fixture
def compare_peers(load_experiment, tmp_path, monkeypatch):
    (tmp_path / "my_mesher.py").write_text(MESHER)
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.chdir(tmp_path)
    yield load_experiment("compare_peers")
    sys.modules.pop("my_mesher", None)


def args(tmp_path, *extra):
    return ["--surfaces", "barrel", "--methods", "none", "--jobs", "1", "--out-dir", str(tmp_path / "results"),
            "--fig-dir", str(tmp_path / "figs"), *extra]  # fmt: skip


def test_a_method_joins_the_table_measured_by_the_same_function(compare_peers, tmp_path):
    assert compare_peers.main(args(tmp_path, "--method", "my_mesher:grid", "--method", "my_mesher:fails")) == 0
    df = pd.read_csv(tmp_path / "results" / "compare_peers.csv")
    assert df["method"].tolist() == ["my_mesher:grid", "my_mesher:fails"]
    grid, fails = df.iloc[0], df.iloc[1]
    barrel = BENCHMARK["barrel"]
    expected = comparison_figures(*parameter_grid(barrel.surface, barrel.length), barrel.length)
    assert grid["status"] == "ok" and grid["members"] == expected["members"]
    assert (
        grid["within_05"] == pytest.approx(expected["within_0.5pct"]) and grid["classes_1"] == expected["classes_1pct"]
    )
    assert fails["status"] == "failed: RuntimeError: cannot mesh this one"  # failing on a surface is a result
    assert (tmp_path / "figs" / "compare_peers_my_mesher_grid.png").stat().st_size > 0
    assert "| barrel | my_mesher:grid |" in (tmp_path / "results" / "compare_peers.md").read_text()


@pytest.mark.parametrize(
    "spec, message",
    [
        ("no_such_package.mesher:run", "cannot import no_such_package.mesher"),
        ("my_mesher:missing", "my_mesher has no missing"),
        ("my_mesher", "expected package.module:function"),
        ("my_mesher:nothing", "method my_mesher:nothing returned NoneType, not a triangle mesh"),
    ],
)
def test_a_bad_method_is_one_line_and_exit_2_with_nothing_written(compare_peers, tmp_path, capsys, spec, message):
    assert compare_peers.main(args(tmp_path, "--method", spec)) == 2
    err = capsys.readouterr().err
    assert err.startswith("compare_peers: error: ") and message in err and err.count("\n") == 1
    assert not (tmp_path / "results").exists() and not (tmp_path / "figs").exists()


def test_an_entry_point_adds_its_method_by_name(compare_peers, tmp_path, monkeypatch):
    info = tmp_path / "my_mesher-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: my-mesher\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text("[equimesh.methods]\nmy grid = my_mesher:grid\n")
    available, _ = compare_peers.methods()
    assert "my grid" in available
    assert compare_peers.main(args(tmp_path, "--methods", "my grid")) == 0
    df = pd.read_csv(tmp_path / "results" / "compare_peers.csv")
    assert df["method"].tolist() == ["my grid"] and (df["status"] == "ok").all()
