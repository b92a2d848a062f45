"""Smoke tests of the Section 4 experiments (Table 1 and Figs 1-5) on a coarse set-up.

The reference surface with l = 10 on a 6 x 6 auxiliary grid runs in well
under a second; the checks are what the full run must also satisfy: every
output file, the paper's rows and columns, the paper's values beside ours,
and the optimisation not making the G1 lengths less uniform.
"""

import json

import numpy as np
import pandas as pd
import pytest

COARSE = ["--grid", "6", "6", "--length", "10"]

PAPER_ROWS = [
    "initial surf.",
    "plane (G1)",
    "plane (total)",
    "final surf. (G1)",
    "final surf. (total)",
    "final opt. (G1)",
    "final opt (total)",
]


PAPER_COLUMNS = ["no. of members", "mean", "min.", "max.", "std. dev."]


@pytest.fixture(scope="module")
def experiments(load_experiment):
    return load_experiment("table1"), load_experiment("figures")


@pytest.fixture(scope="module")
def table1_run(experiments, tmp_path_factory):
    table1, _ = experiments
    out = tmp_path_factory.mktemp("results")
    assert table1.main([*COARSE, "--out-dir", str(out)]) == 0
    return out


def _ours(df, row, column):
    return df[(df["row"] == row) & (df["source"] == "equimesh")][column].iloc[0]


def test_table1_writes_every_output(table1_run):
    for name in ("table1.csv", "table1_quality.csv", "table1.md", "table1.provenance.json", "table1_mesh.npz"):
        assert (table1_run / name).stat().st_size > 0, name
    record = json.loads((table1_run / "table1.provenance.json").read_text())
    assert record["parameters"]["grid"] == [6, 6] and record["parameters"]["length"] == 10.0
    assert "numpy" in record["versions"] and "commit" in record["git"]


def test_table1_has_the_papers_rows_and_columns_beside_the_papers_values(experiments, table1_run):
    table1, _ = experiments
    df = pd.read_csv(table1_run / "table1.csv")
    assert list(df.columns) == ["row", "source", *PAPER_COLUMNS]
    assert list(df["row"]) == [r for r in PAPER_ROWS for _ in range(2)]
    assert list(df["source"]) == ["equimesh", "paper"] * len(PAPER_ROWS)
    paper = df[df["source"] == "paper"].set_index("row")
    assert paper.loc["initial surf.", "no. of members"] == 645
    assert paper.loc["plane (total)", "min."] == pytest.approx(4.5893)
    assert paper.loc["final opt (total)", "max."] == pytest.approx(13.3777)
    assert paper.loc["final opt. (G1)", "std. dev."] == pytest.approx(0.1915)


def test_table1_numbers_are_consistent(table1_run):
    """Counts follow from the grid and the groups; G1 is exactly l on the plane; Theorem 3 holds."""
    df = pd.read_csv(table1_run / "table1.csv")
    l, n = 10.0, 6
    assert _ours(df, "initial surf.", "no. of members") == 3 * n * n + 2 * n
    g1 = _ours(df, "plane (G1)", "no. of members")
    total = _ours(df, "plane (total)", "no. of members")
    for stage in ("plane", "final surf.", "final opt."):
        assert _ours(df, f"{stage} (G1)", "no. of members") == g1
    assert _ours(df, "final opt (total)", "no. of members") == total
    assert 0 < g1 < total
    assert _ours(df, "plane (G1)", "min.") == pytest.approx(l, rel=1e-9)
    assert _ours(df, "plane (G1)", "max.") == pytest.approx(l, rel=1e-9)
    assert _ours(df, "plane (total)", "min.") >= l * (1 - 1e-9)
    assert _ours(df, "plane (total)", "max.") <= 2 * l * (1 + 1e-9)


def test_optimisation_does_not_spread_g1(table1_run):
    df = pd.read_csv(table1_run / "table1.csv")
    assert _ours(df, "final opt. (G1)", "std. dev.") <= _ours(df, "final surf. (G1)", "std. dev.")


def test_table1_markdown_has_both_tables_comparison_and_provenance(table1_run):
    md = (table1_run / "table1.md").read_text()
    for text in (
        "| no. of members | mean | min. | max. | std. dev. |",
        "## Comparison with the paper",
        "## Beyond Table 1",
        "## Run",
        "## Provenance",
        *PAPER_ROWS,
    ):
        assert text in md, text
    quality = pd.read_csv(table1_run / "table1_quality.csv")
    assert list(quality["row"]) == PAPER_ROWS
    assert quality.loc[quality["row"] == "plane (G1)", "within_1pct"].iloc[0] == 1.0


def test_table1_output_is_deterministic(experiments, table1_run, tmp_path):
    table1, _ = experiments
    assert table1.main([*COARSE, "--out-dir", str(tmp_path)]) == 0
    for name in ("table1.csv", "table1_quality.csv", "table1_mesh.npz"):
        assert (tmp_path / name).read_bytes() == (table1_run / name).read_bytes(), name


def test_mesh_data_holds_every_stage(table1_run):
    with np.load(table1_run / "table1_mesh.npz", allow_pickle=False) as d:
        assert d["aux_points"].shape == ((6 + 1) ** 2, 3)
        assert d["flat_points"].shape == ((6 + 1) ** 2, 2)
        n = len(d["plane_points"])
        assert d["remapped_points"].shape == d["optimised_points"].shape == (n, 3)
        assert len(d["edges"]) == len(d["edge_groups"])


def test_figures_draws_every_figure_from_the_data(experiments, table1_run, tmp_path):
    _, figures = experiments
    assert figures.main(["--data", str(table1_run / "table1_mesh.npz"), "--fig-dir", str(tmp_path)]) == 0
    for name in figures.FIGURES:
        for suffix in (".png", ".pdf", ".provenance.json"):
            assert (tmp_path / f"{name}{suffix}").stat().st_size > 0, name + suffix
    record = json.loads((tmp_path / "fig5_optimised_deviation.provenance.json").read_text())
    assert record["parameters"]["source"].endswith("table1_mesh.npz")


def test_figures_without_data_says_to_run_table1(experiments, tmp_path, capsys):
    _, figures = experiments
    assert figures.main(["--data", str(tmp_path / "missing.npz"), "--fig-dir", str(tmp_path / "figs")]) == 2
    assert "run experiments/table1.py first" in capsys.readouterr().err
    assert not (tmp_path / "figs").exists()
