"""experiments/sharp_sweep.py: the counts of each family of sharp corners, with provenance, on a tiny input."""

import json

import pandas as pd


def test_sharp_sweep_counts_each_family_with_provenance(load_experiment, tmp_path):
    """experiments/sharp_sweep.py --count 2: two draws per family, every outcome a known kind, the same draws of a
    family whichever families run, the Markdown table and the provenance."""
    sweep = load_experiment("sharp_sweep")
    out = tmp_path / "results"
    assert sweep.main(["--count", "2", "--jobs", "1", "--out-dir", str(out)]) == 0
    df = pd.read_csv(out / "sharp_sweep.csv")
    assert list(df.columns) == sweep.COLUMNS and len(df) == 2 * len(sweep.KINDS)
    assert set(df["outcome"]) <= {"meshed", *sweep.REFUSALS}
    assert sweep.cases(2, 0, [sweep.PAIR]) == [case for case in sweep.cases(2, 0) if case[0] == sweep.PAIR]
    assert "| two-corner triangle | 2 |" in (out / "sharp_sweep.md").read_text()
    assert json.loads((out / "sharp_sweep.provenance.json").read_text())["parameters"]["count"] == 2
