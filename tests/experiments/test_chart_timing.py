"""experiments/chart_timing.py: a record per degree and per net size, beyond the limits too, and a counted run."""

import json


def test_chart_timing_measures_beyond_the_limits_and_restores_them(load_experiment, capsys):
    """Degrees above both charts' MAX_DEGREE are measured, the bounds are in force again afterwards, a net above
    MAX_NET_POINTS is refused, and the counted run evaluates the chart at least once per node."""
    from equimesh.surface.charts import bezier, nurbs

    timing = load_experiment("chart_timing")
    bounds = bezier.MAX_DEGREE, nurbs.MAX_DEGREE
    argv = [
        "--nurbs",
        "2,2",
        f"{nurbs.MAX_DEGREE + 1},1",
        "--bezier",
        f"{bezier.MAX_DEGREE + 1},1",
        "--nets",
        "4",
        "317",
    ]
    assert timing.main([*argv, "--points", "20", "--length", "6"]) == 0
    assert (bezier.MAX_DEGREE, nurbs.MAX_DEGREE) == bounds
    records = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    run, costs, nets = records[0], records[1:4], records[4:]
    assert run["points_evaluated"] >= run["nodes"] > 0
    assert [r["chart"] for r in costs] == ["nurbs", "nurbs", "bezier"] and costs[0]["ratio_to_first"] == 1.0
    assert all(r["us_per_point"] > 0 and r["run_seconds_projected"] >= 0 for r in costs)
    assert "refused" not in nets[0] and "more than the 100000" in nets[1]["refused"]
