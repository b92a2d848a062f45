"""Smoke tests of experiments/bounded_sweep.py: the same domes whatever the count, the same CSV whatever the jobs."""

import json

import pandas as pd
import pytest

from equimesh.errors import InvalidSurfaceError
from equimesh.io.provenance import provenance


@pytest.fixture(scope="module")
def sweep(load_experiment):
    return load_experiment("bounded_sweep")


def test_dome_k_does_not_depend_on_the_count(sweep):
    """The first domes of a long sweep are the domes of a short one; the explicit example comes first."""
    long = sweep.cases(120)
    assert sweep.cases(3) == long[:3] and long[0] == (0, *sweep.EXPLICIT)
    assert [k for k, *_ in long] == list(range(120))
    assert all(2.0 <= rise < 15.0 and 0 <= seed < 2**32 - 1 and 4.5 <= l < 5.0 for _, rise, seed, l in long[1:])
    assert [sweep.set_of(k) for k in (0, 60, 61, 100, 101)] == ["design", "design", "held out", "held out", "further"]


def test_two_domes_give_the_same_csv_in_process_and_on_two_workers(sweep, tmp_path):
    one, two = tmp_path / "one", tmp_path / "two"
    assert sweep.main(["--count", "2", "--jobs", "1", "--out-dir", str(one)]) == 0
    assert sweep.main(["--count", "2", "--jobs", "2", "--out-dir", str(two)]) == 0
    assert (one / "bounded_sweep.csv").read_bytes() == (two / "bounded_sweep.csv").read_bytes()
    frame = pd.read_csv(one / "bounded_sweep.csv", keep_default_na=False)
    assert list(frame["index"]) == [0, 1] and (frame["bounded_share_in_l_2l"] == 1.0).all()
    assert (frame["bounded_min_angle"] >= 30.0).all() and (frame["paper_min_angle"] > 0.0).all()
    assert (frame["margin"] == frame["bounded_share_within_0.5pct"] - frame["paper_share_within_0.5pct"]).all()
    assert (pd.read_csv(one / "bounded_sweep_times.csv")[["paper_seconds", "bounded_seconds"]] > 0).all().all()
    report = (one / "bounded_sweep.md").read_text()
    assert "| design | 2 | 0 | 0 |" in report and "| all | 2 |" in report and "Provenance" in report
    assert json.loads((one / "bounded_sweep.provenance.json").read_text())["parameters"]["count"] == 2


def test_a_refused_dome_is_recorded_with_its_message(sweep, monkeypatch):
    """An error of ours on one objective is a row with the message, counted as refused, never a crash."""
    real = sweep.mesh_surface

    def refuse_bounded(surface, l, optimize, **kwargs):
        if optimize == "bounded":
            raise InvalidSurfaceError("optimisation (bounded): no mesh with every member in [l, 2l] found")
        return real(surface, l, optimize=optimize, **kwargs)

    monkeypatch.setattr(sweep, "mesh_surface", refuse_bounded)
    row, seconds = sweep.measure(sweep.cases(1)[0])
    assert row["bounded_error"].startswith("optimisation (bounded)") and row["bounded_njev"] == -1
    assert row["paper_error"] == "" and row["paper_njev"] > 0
    report = sweep.report(pd.DataFrame([row]), pd.DataFrame([seconds]), provenance({}), 1)
    assert "| design | 1 | 1 | 0 | 0 |" in report and "no mesh with every member" in report


@pytest.mark.parametrize("count", ["0", "-3", "two"])
def test_a_bad_count_is_refused_before_anything_is_written(sweep, tmp_path, capsys, count):
    with pytest.raises(SystemExit) as exit_:
        sweep.main(["--count", count, "--out-dir", str(tmp_path)])
    assert exit_.value.code == 2 and "--count must be a whole number >= 1" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())
