"""experiments/optimisation_levers.py: bounded solved again from other starts and with other round constants, beside
the pipeline's solve, with provenance."""

import dataclasses
import json

import numpy as np
import pandas as pd
import pytest

import equimesh
from equimesh.surface.optimize import objectives


def test_optimisation_levers_solves_each_lever_beside_the_pipelines(load_experiment, tmp_path):
    """--quick: a row per lever, the pipeline's first (its Jacobians those of mesh_surface, which the script checks);
    from bounded's own result fewer Jacobians than from the remapped mesh; the constants patched only while solved."""
    experiment = load_experiment("optimisation_levers")
    before = {name: getattr(objectives, name) for name, _ in experiment.CONSTANTS}
    out = tmp_path / "results"
    assert experiment.main(["--quick", "--out-dir", str(out)]) == 0
    assert {name: getattr(objectives, name) for name, _ in experiment.CONSTANTS} == before
    df = pd.read_csv(out / "optimisation_levers.csv")
    assert list(df.columns) == experiment.COLUMNS
    assert len(df) == 3 + len(experiment.SMOOTHINGS) + len(experiment.LOCAL_GLOBAL) + len(experiment.CONSTANTS)
    pipeline, own = df.iloc[0], df.iloc[1]
    assert pipeline["lever"].startswith("the pipeline's") and own["jacobians"] < pipeline["jacobians"]
    meshed = df[df["outcome"] == "meshed"]
    assert meshed["in_band"].all() and (meshed["jacobians"] > 0).all()
    assert "| the pipeline's (from the remapped mesh) |" in (out / "optimisation_levers.md").read_text()
    assert json.loads((out / "optimisation_levers.provenance.json").read_text())["parameters"]["quick"] is True


def test_the_script_stops_when_its_solve_from_the_remap_is_not_the_pipelines(load_experiment, monkeypatch):
    """The first row must be the pipeline's solve: a count of Jacobians off by one stops the script."""
    experiment = load_experiment("optimisation_levers")
    solve = experiment.solve

    def off_by_one(*args, **kwargs):
        result = solve(*args, **kwargs)
        return dataclasses.replace(result, njev=result.njev + 1)

    monkeypatch.setattr(experiment, "solve", off_by_one)
    with pytest.raises(RuntimeError, match="Jacobians here"):
        experiment.measure(experiment.QUICK_LENGTHS[0])


def test_smoothing_holds_the_boundary_and_averages_the_inside(load_experiment):
    """On a path 0 - 1 - 2 with node 0 on the boundary, one step takes node 1 halfway to its neighbours' mean."""
    experiment = load_experiment("optimisation_levers")
    d = np.array([[5.0, 5.0], [2.0, 0.0], [0.0, 4.0]])
    out = experiment.smoothed(d, np.array([[0, 1], [1, 2]]), 1, 1)
    np.testing.assert_allclose(out, [[0.0, 0.0], [1.0, 1.0], [1.0, 2.0]])


def test_local_global_holds_the_sides_and_pulls_members_to_the_target(load_experiment):
    """From the remapped reference dome at l = 5: the corners stay bit for bit, each side node keeps its side's
    coordinate, and more members come within 0.5 % of l than in the remapped mesh."""
    experiment = load_experiment("optimisation_levers")
    surface = equimesh.surface_from_dict(json.loads(experiment.DOME.read_text()))
    mesh = equimesh.mesh_surface(surface, 5.0, optimize="none", placement="default")
    start, edges = mesh.stages.remapped_uv, mesh.stages.plane.edges
    end = experiment.local_global(surface, start, edges, 5.0, 50)
    on_side = (start == 0.0) | (start == 1.0)
    assert np.array_equal(end[on_side], start[on_side]) and on_side.all(axis=1).sum() == 4
    assert not np.array_equal(end, start) and ((end >= 0.0) & (end <= 1.0)).all()
    before, after = (experiment.ratios(surface, uv, edges, 5.0) for uv in (start, end))
    assert np.mean(np.abs(after - 1.0) <= 0.005) > np.mean(np.abs(before - 1.0) <= 0.005)
