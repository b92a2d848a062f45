"""experiments/pardiso_threads.py: PARDISO's modes on a normal matrix of "bounded", with provenance."""

import json

import pandas as pd
import pytest

from equimesh.surface.optimize import solver


@pytest.mark.skipif("pardiso" not in solver.INSTALLED, reason="extra mkl: pypardiso not installed")
def test_pardiso_threads_times_each_mode_and_compares_its_bits(load_experiment, tmp_path):
    """One l (2,698 variables): a row per mode; the reproducible mode's bits are the same on one thread and on two,
    alone or beside another solve; the sequential mode's on two threads are not (what the reproducible mode is
    for)."""
    experiment = load_experiment("pardiso_threads")
    out = tmp_path / "results"
    assert experiment.main(["--lengths", "2.5", "--out-dir", str(out)]) == 0
    df = pd.read_csv(out / "pardiso_threads.csv", dtype={"bits": str})
    assert list(df.columns) == experiment.COLUMNS and len(df) == len(experiment.MODES)
    assert (df["variables"] > experiment.MIN_VARIABLES).all() and (df["factorisation_ms"] > 0).all()
    reproducible = df[df["mode"] == "reproducible"]
    assert reproducible["same_bits"].all() and reproducible["bits"].nunique() == 1
    sequential = df[df["mode"] == "sequential"]
    assert list(sequential["same_bits"]) == [True, False]
    assert "| reproducible | 2 | 2 |" in (out / "pardiso_threads.md").read_text()
    assert json.loads((out / "pardiso_threads.provenance.json").read_text())["parameters"]["lengths"] == [2.5]
