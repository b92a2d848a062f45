"""experiments/classes_sweep.py: the classes objective with its narrowing scale and with a constant one, on random
patches, with provenance."""

import json

import pandas as pd

from equimesh.surface.optimize import class_rounds


def test_classes_sweep_runs_both_scales_on_each_patch(load_experiment, tmp_path):
    """Two patches (a developable one and a doubly curved one at three l): a row per scale; on the doubly curved patch
    the two scales give different meshes (the constant one is patched in, and only while it runs)."""
    experiment = load_experiment("classes_sweep")
    before = class_rounds.CLASSES_SCALE_START
    out = tmp_path / "results"
    assert experiment.main(["--count", "2", "--jobs", "1", "--out-dir", str(out)]) == 0
    assert class_rounds.CLASSES_SCALE_START == before
    df = pd.read_csv(out / "classes_sweep.csv")
    assert list(df.columns) == experiment.COLUMNS and (df["status"] == "ok").all()
    assert df["kind"].tolist() == ["developable"] * 2 + ["doubly curved"] * 6
    assert df["scale"].tolist() == list(experiment.SCALES) * 4
    curved = df[df["kind"] == "doubly curved"].set_index(["divisor", "scale"])
    assert (curved.loc[(16, "narrowing")] != curved.loc[(16, "constant")])[["classes_05", "within_05"]].any()
    assert (df["angle_min"] >= 30.0 - 1e-9).all()
    report = (out / "classes_sweep.md").read_text()
    assert "## Means" in report and "| doubly curved | span / 24 | 1 |" in report
    assert json.loads((out / "classes_sweep.provenance.json").read_text())["parameters"]["count"] == 2


def test_patches_are_the_seeds_own_and_developable_every_third(load_experiment):
    """The same seed gives the same control net; seed % 3 == 2 is a vault whose rows are one profile."""
    experiment = load_experiment("classes_sweep")
    (kind_a, a), (_, b) = experiment.patch(201), experiment.patch(201)
    assert kind_a == "doubly curved" and (a.control_points == b.control_points).all()
    kind, vault = experiment.patch(203)
    heights = vault.control_points[..., 2]
    assert kind == "developable" and (heights == heights[:, :1]).all()
