"""Smoke test of experiments/compare_peers.py: one surface, the meshers this machine has, every output."""

import json
import sys

import pandas as pd
import pytest


@pytest.fixture
def compare_peers(load_experiment):
    return load_experiment("compare_peers")


def test_compare_peers_writes_table_histograms_figures_and_provenance(compare_peers, tmp_path):
    out, figs = tmp_path / "results", tmp_path / "figs"
    methods = ["equimesh paper", "gmsh Frontal-Delaunay", "pymeshlab isotropic"]
    args = ["--surfaces", "barrel", "--methods", *methods, "--jobs", "1", "--out-dir", str(out), "--fig-dir", str(figs)]
    assert compare_peers.main(args) == 0

    df = pd.read_csv(out / "compare_peers.csv")
    ran = [m for m in methods if m in compare_peers.methods()[0]]
    assert df["method"].tolist() == ran and set(df["surface"]) == {"barrel"} and (df["status"] == "ok").all()
    assert ((0 <= df["within_05"]) & (df["within_05"] <= df["within_1"]) & (df["within_1"] <= df["within_5"])).all()
    assert (df["classes_1"] <= df["classes_05"]).all()

    hist = pd.read_csv(out / "compare_peers_histograms.csv")
    for row in df.itertuples():
        part = hist[hist["method"] == row.method]
        assert part["count"].sum() == row.members  # every member in one bin
        near = part[(part["ratio"] - 1.0).abs() < 1e-9]["count"].sum()  # the bin at 1 is +-0.5 % of l
        assert abs(near / row.members - row.within_05) < 0.02  # bins and the metric agree but for edge rounding
    report = (out / "compare_peers.md").read_text()
    assert "| barrel | equimesh paper |" in report and "## Provenance" in report
    record = json.loads((out / "compare_peers.provenance.json").read_text())
    assert record["parameters"]["methods"] == ran
    assert (figs / "compare_peers_equimesh_paper.png").stat().st_size > 0

    (figs / "compare_peers_equimesh_paper.png").unlink()
    assert compare_peers.main(["--plot-only", "--out-dir", str(out), "--fig-dir", str(figs)]) == 0
    assert (figs / "compare_peers_equimesh_paper.png").stat().st_size > 0


def test_a_missing_peer_is_skipped_with_the_reason(compare_peers, monkeypatch):
    monkeypatch.setitem(sys.modules, "gmsh", None)  # import gmsh raises ImportError
    available, skipped = compare_peers.methods()
    assert not any(m.startswith("gmsh") for m in available) and "equimesh paper" in available
    assert all("pip install 'equimesh[peers]'" in skipped[f"gmsh {a}"] for a in compare_peers.GMSH_ALGORITHMS)
