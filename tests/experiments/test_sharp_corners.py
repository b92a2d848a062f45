"""experiments/sharp_corners.py: its counts and quality table, with provenance, on a tiny input."""

import json

import pandas as pd


def test_sharp_corners_writes_counts_and_quality_with_provenance(load_experiment, tmp_path):
    """experiments/sharp_corners.py --quick: one row per family and size, every outcome a known kind, the
    meshed rows with their angles and G1 shares, the Markdown table and the provenance."""
    sharp = load_experiment("sharp_corners")
    out = tmp_path / "results"
    assert sharp.main(["--quick", "--jobs", "1", "--out-dir", str(out)]) == 0
    df = pd.read_csv(out / "sharp_corners.csv")
    assert list(df.columns) == sharp.COLUMNS and len(df) == len(sharp.KINDS) * len(sharp.QUICK_SIZES)
    assert set(df["outcome"]) <= {"meshed", *sharp.REFUSALS} and (df["outcome"] == df["reference"]).all()
    meshed = df[df["outcome"] == "meshed"]
    assert len(meshed) and (meshed["min_angle"] <= meshed["min_angle_near"]).all()
    assert (meshed["g1_share_near"].between(0, 1)).all()
    assert "| spike | 20 |" in (out / "sharp_corners.md").read_text()
    assert json.loads((out / "sharp_corners.provenance.json").read_text())["parameters"]["quick"] is True
