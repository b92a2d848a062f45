"""experiments/optimisation_timing.py: one JSON record per objective, and with ``--trace`` one line per solve."""

import json


def test_optimisation_timing_prints_one_record_per_objective(load_experiment, capsys):
    """experiments/optimisation_timing.py: one JSON line per objective, bounded at least the paper's share (l = 10)."""
    timing = load_experiment("optimisation_timing")
    assert timing.main(["--length", "10", "--objective", "paper", "bounded"]) == 0
    records = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert [r["objective"] for r in records] == ["paper", "bounded"]
    for r in records:
        assert r["members"] > 0 and 0.0 <= r["within_band"] <= 1.0
        assert "optimisation of inner nodes" in r["seconds"]
    assert records[1]["within_band"] >= records[0]["within_band"]


def test_optimisation_timing_traces_every_solve(load_experiment, capsys):
    """``--trace``: a line per solve before the record; the solves report where they ended, and the mesh
    returned is where one of them ended in [l, 2l] (the best point kept)."""
    timing = load_experiment("optimisation_timing")
    assert timing.main(["--length", "10", "--objective", "bounded", "--trace"]) == 0
    lines = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    solves, record = lines[:-1], lines[-1]
    assert [s["solve"] for s in solves] == list(range(1, len(solves) + 1)) and record["objective"] == "bounded"
    assert record["jacobians"] == sum(s["iterations"] + 1 for s in solves)
    assert record["within_band"] in {s["within_band"] for s in solves if s["inside"]}
    assert optimize_is_restored(timing)


def optimize_is_restored(timing):
    """After a traced run the optimisation's functions are the library's again."""
    from equimesh.surface.optimize import driver, members, solver

    return (
        driver.least_squares is solver.least_squares and timing.members.edge_length_terms.__module__ == members.__name__
    )
