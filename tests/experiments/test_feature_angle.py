"""experiments/feature_angle.py: the turns of a mesh's loops and what each feature angle keeps, with provenance."""

import json

import pandas as pd


def test_feature_angle_writes_turns_and_corners_kept_with_provenance(load_experiment, tmp_path):
    """experiments/feature_angle.py --quick: one row per opening and feature angle, the square's four corners turning
    by about 90 degrees at the scale of l and kept at every feature angle tried, the tables and the provenance."""
    experiment = load_experiment("feature_angle")
    out = tmp_path / "results"
    assert experiment.main(["--quick", "--jobs", "1", "--out-dir", str(out)]) == 0
    df = pd.read_csv(out / "feature_angle.csv")
    assert list(df.columns) == experiment.COLUMNS and len(df) == 2 * len(experiment.FEATURE_ANGLES)
    assert set(df["outcome"]) <= {"ring", *experiment.REFUSALS}
    square = df[df["opening"] == "square"]
    assert (square["corners"] == 4).all() and square["corner_turn_min"].between(80, 100).all()
    assert (square["corners_kept"] == 4).all() and (square["outer_kept"] == 4).all()
    assert "| square | 1.5 |" in (out / "feature_angle.md").read_text()
    assert json.loads((out / "feature_angle.provenance.json").read_text())["parameters"]["quick"] is True
