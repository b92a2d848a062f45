"""Smoke test of experiments/inputs.py (the inputs table) in quick mode.

What the full run must also satisfy: one row per input, every output file,
every planar member in [l, 2l] (Theorem 3) and a G1 share above zero for each
meshed input, and a row that says so when an optional reader is missing.
"""

import json

import pandas as pd
import pytest

from equimesh.errors import MissingDependencyError
from equimesh.tolerance import REL_TOL


@pytest.fixture(scope="module")
def inputs(load_experiment):
    return load_experiment("inputs")


def test_inputs_table_meshes_every_input_in_l_2l(inputs, tmp_path):
    assert inputs.main(["--quick", "--jobs", "1", "--out-dir", str(tmp_path)]) == 0
    for name in ("inputs.csv", "inputs.md", "inputs.provenance.json"):
        assert (tmp_path / name).stat().st_size > 0, name
    df = pd.read_csv(tmp_path / "inputs.csv", keep_default_na=False)
    assert list(df["input"]) == [item.label for item in inputs.INPUTS]
    meshed = df[df["note"] == ""]
    assert len(meshed) >= len(df) - 1  # only the Rhino row may lack its extra
    assert (meshed["plane_min_over_l"] >= 1.0 - REL_TOL).all() and (meshed["plane_max_over_l"] <= 2.0 + REL_TOL).all()
    assert (meshed["g1_share"] > 0).all() and (meshed["members"] > 0).all()
    record = json.loads((tmp_path / "inputs.provenance.json").read_text())
    assert record["parameters"]["quick"] is True and len(record["parameters"]["inputs"]) == len(df)


def test_a_missing_extra_gives_a_row_that_says_so(inputs, monkeypatch):
    def missing(path, object=None):
        raise MissingDependencyError("reading .3dm needs rhino3dm: pip install 'equimesh[rhino]'")

    monkeypatch.setattr(inputs, "load_surface", missing)
    row = inputs._measure((inputs.Input("roof", "roof.3dm", 3.0, object="roof"), inputs.QUICK))
    assert row["note"].startswith("not run: reading .3dm needs rhino3dm") and "members" not in row
