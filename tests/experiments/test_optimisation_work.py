"""experiments/optimisation_work.py: the work of each objective and the start's distance from [l, 2l], with
provenance."""

import json

import pandas as pd

from equimesh.surface.optimize import OBJECTIVES
from equimesh.tolerance import REACH_SHARE


def test_optimisation_work_counts_the_jacobians_and_refuses_the_stretched_tube(load_experiment, tmp_path):
    """--quick: the dome meshed by every objective within its work bound; the closed tube's start beyond
    REACH_SHARE, refused by the objectives that bound the members without a Jacobian, meshed by "paper"."""
    experiment = load_experiment("optimisation_work")
    out = tmp_path / "results"
    assert experiment.main(["--quick", "--jobs", "1", "--out-dir", str(out)]) == 0
    df = pd.read_csv(out / "optimisation_work.csv", keep_default_na=False)
    assert list(df.columns) == experiment.COLUMNS
    assert list(df["objective"]) == 2 * list(OBJECTIVES)
    dome, tube = df[df["surface"] == "reference dome"], df[df["surface"] != "reference dome"]
    meshed = dome[dome["outcome"] == "meshed"]
    assert {"paper", "bounded"} <= set(meshed["objective"])
    assert (meshed["jacobians"] > 0).all() and (meshed["jacobians"] <= meshed["max_jacobians"]).all()
    assert (tube["start_short_share"] > REACH_SHARE).all()
    refused = tube[tube["objective"] != "paper"]
    assert refused["outcome"].str.contains("within reach of the remapped mesh").all()
    assert (tube[tube["objective"] == "paper"]["outcome"] == "meshed").all()
    assert "| bounded |" in (out / "optimisation_work.md").read_text()
    assert json.loads((out / "optimisation_work.provenance.json").read_text())["parameters"]["quick"] is True
