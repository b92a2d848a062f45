"""Smoke test of experiments/problem2.py: it runs end to end on its --quick configuration and writes every output."""

import json

import numpy as np
import pandas as pd
import pytest


@pytest.fixture
def problem2(load_experiment):
    return load_experiment("problem2")


def test_problem2_quick_writes_data_summary_figures_and_provenance(problem2, tmp_path):
    """CSV with the documented columns, Theorem 3 on every mesh, Markdown, figures, provenance; --plot-only redraws."""
    out, figs = tmp_path / "results", tmp_path / "figs"
    argv = ["--quick", "--jobs", "1", "--out-dir", str(out), "--fig-dir", str(figs)]
    assert problem2.main(argv) == 0

    df = pd.read_csv(out / "problem2.csv")
    assert list(df.columns) == problem2.COLUMNS
    size = df[df["study"] == "size"]
    assert len(size) == 2 * len(problem2.QUICK_SHAPES) * len(problem2.QUICK_AREAS)
    assert set(df["study"]) == {"size", "spacing"}
    assert (df["min_edge"] >= 1.0 - 1e-9).all() and (df["max_edge"] <= 2.0 * (1.0 + 1e-9)).all()
    best = size[size["placement"] == "best"]
    assert (best["lattice_edges"] >= best["default_lattice_edges"]).all()
    assert np.allclose(df["g1_share"], df["n_g1"] / df["n_edges"])

    summary = (out / "problem2.md").read_text()
    assert "G1 share" in summary and "Boundary spacing" in summary and "## Provenance" in summary
    record = json.loads((out / "problem2.provenance.json").read_text())
    assert record["parameters"]["quick"] is True and "numpy" in record["versions"]
    for name in ("problem2_mesh", "problem2_share"):
        for suffix in (".png", ".pdf", ".provenance.json"):
            assert (figs / f"{name}{suffix}").stat().st_size > 0

    (figs / "problem2_share.png").unlink()
    assert problem2.main(["--plot-only", "--quick", "--out-dir", str(out), "--fig-dir", str(figs)]) == 0
    assert (figs / "problem2_share.png").stat().st_size > 0
