"""experiments/ratio_sweep.py end to end on a tiny input: every output, and a figure that reads only the CSV."""

import json

import pandas as pd
import pytest


@pytest.fixture
def ratio_sweep(load_experiment):
    return load_experiment("ratio_sweep")


def test_ratio_sweep_writes_data_summary_figure_and_provenance(ratio_sweep, tmp_path):
    """experiments/ratio_sweep.py: CSV with the documented columns, Markdown, PNG/PDF, provenance."""
    out, figs = tmp_path / "results", tmp_path / "figs"
    small = [
        "--n-polygons",
        "12",
        "--max-area",
        "40",
        "--tail-fraction",
        "0",
        "--out-dir",
        str(out),
        "--fig-dir",
        str(figs),
    ]
    assert ratio_sweep.main(small + ["--jobs", "1"]) == 0

    df = pd.read_csv(out / "ratio_sweep.csv")
    assert list(df.columns) == ratio_sweep.COLUMNS
    assert len(df) == 12 and list(df["index"]) == list(range(12))
    assert (3 * df["n_nodes"] <= 16 * df["lower_bound"]).all()
    summary = (out / "ratio_sweep.md").read_text()
    assert "median n'/LB" in summary and "## Provenance" in summary
    record = json.loads((out / "ratio_sweep.provenance.json").read_text())
    assert record["parameters"]["n_polygons"] == 12 and "numpy" in record["versions"]
    for name in ("ratio_sweep.png", "ratio_sweep.pdf", "ratio_sweep.provenance.json"):
        assert (figs / name).stat().st_size > 0

    # Rows do not depend on the number of worker processes.
    first = (out / "ratio_sweep.csv").read_bytes()
    assert ratio_sweep.main(small + ["--jobs", "2"]) == 0
    assert (out / "ratio_sweep.csv").read_bytes() == first


def test_ratio_sweep_plot_reads_only_the_csv(ratio_sweep, tmp_path):
    """The figure is redrawn from an existing CSV without recomputing anything."""
    out, figs = tmp_path / "results", tmp_path / "figs"
    ratio_sweep.main(
        [
            "--n-polygons",
            "5",
            "--max-area",
            "20",
            "--tail-fraction",
            "0",
            "--jobs",
            "1",
            "--out-dir",
            str(out),
            "--fig-dir",
            str(figs),
        ]
    )
    (figs / "ratio_sweep.png").unlink()
    assert ratio_sweep.main(["--plot-only", "--out-dir", str(out), "--fig-dir", str(figs)]) == 0
    assert (figs / "ratio_sweep.png").stat().st_size > 0
