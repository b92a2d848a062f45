"""Smoke test of experiments/scaling.py: every method measured, exponents fitted, every output written."""

import json

import pandas as pd


def test_scaling_writes_data_report_figure_and_provenance(load_experiment, tmp_path, monkeypatch):
    """The sweep's logic in this process (the script runs each measurement in a fresh one): rows, fits, files."""
    scaling = load_experiment("scaling")
    monkeypatch.setattr(scaling, "_run", scaling.measure)
    out, figs = tmp_path / "results", tmp_path / "figs"
    assert scaling.main(["--sizes", "30", "60", "--out-dir", str(out), "--fig-dir", str(figs), "--fit-floor", "0"]) == 0
    frame = pd.read_csv(out / "scaling.csv")
    assert list(frame.columns) == scaling.COLUMNS
    assert sorted(set(frame["method"])) == sorted(scaling.METHODS)
    assert (frame["n_points"] > 0).all() and (frame["seconds"] > 0).all()
    report = (out / "scaling.md").read_text()
    assert "Fitted exponents" in report and "| fast |" in report and "Provenance" in report
    assert json.loads((out / "scaling.provenance.json").read_text())["parameters"]["sizes"] == [30, 60]
    for name in ("scaling.png", "scaling.pdf", "scaling.provenance.json"):
        assert (figs / name).exists()
    (figs / "scaling.png").unlink()
    assert scaling.main(["--plot-only", "--out-dir", str(out), "--fig-dir", str(figs)]) == 0
    assert (figs / "scaling.png").exists()


def test_reference_skipped_when_predicted_over_the_limit(load_experiment, monkeypatch):
    """The reference engine stops once its predicted time passes the limit; the other methods go on."""
    scaling = load_experiment("scaling")

    def fake(method, n, like=None):
        return {
            "method": method,
            "n_target": n,
            "n_points": n,
            "seconds": 1e-3 * n,
            "us_per_point": 1e3,
            "peak_mb": 0.0,
            "first_call_s": 0.0,
        }

    monkeypatch.setattr(scaling, "_run", fake)
    frame = scaling.sweep([10, 100, 1000], reference_limit=5.0, progress=lambda _: None)
    assert list(frame[frame["method"] == "reference"]["n_target"]) == [10, 100]
    assert list(frame[frame["method"] == "fast"]["n_target"]) == [10, 100, 1000]
    # Before any reference run, the prediction starts from REFERENCE_START (0.44 s at 308 nodes).
    frame = scaling.sweep([100000], reference_limit=60.0, progress=lambda _: None)
    assert "reference" not in set(frame["method"])


def test_pipeline_sweep_writes_data_report_figure_and_provenance(load_experiment, tmp_path, monkeypatch):
    """``--pipeline`` at about 300 members, in this process, with the default factorisation (and gmsh if installed):
    rows with every stage, exponents, ratios to gmsh, every output."""
    from equimesh.surface.optimize.solver import DEFAULT_FACTORISATION

    scaling = load_experiment("scaling")
    methods = [m for m in scaling.pipeline_methods() if m in (f"equimesh {DEFAULT_FACTORISATION}", scaling.GMSH)]
    monkeypatch.setattr(scaling, "pipeline_methods", lambda: methods)
    monkeypatch.setattr(scaling, "_run_pipeline", scaling.measure_pipeline)
    out, figs = tmp_path / "results", tmp_path / "figs"
    assert scaling.main(["--pipeline", "--sizes", "300", "600", "--out-dir", str(out), "--fig-dir", str(figs)]) == 0
    frame = pd.read_csv(out / "pipeline_scaling.csv")
    assert list(frame.columns) == scaling.PIPELINE_COLUMNS and list(frame["method"].unique()) == methods
    equimesh_rows = frame[frame["method"] != scaling.GMSH]
    assert (equimesh_rows["members"] > 200).all() and (frame["seconds"] > 0).all() and (frame["peak_mb"] > 0).all()
    assert all("optimisation of inner nodes" in json.loads(stages) for stages in equimesh_rows["stages"])
    report = (out / "pipeline_scaling.md").read_text()
    assert "Fitted exponents" in report and "ratio to gmsh" in report and "Provenance" in report
    for name in ("pipeline_scaling.png", "pipeline_scaling.pdf", "pipeline_scaling.provenance.json"):
        assert (figs / name).exists()


def test_a_pipeline_run_predicted_over_the_limit_is_skipped(load_experiment, monkeypatch):
    """A method whose time, scaled from its last size as members^PIPELINE_EXPONENT, passes the limit is not run."""
    scaling = load_experiment("scaling")
    seconds = {"equimesh slow": 10.0, "equimesh quick": 0.1}
    calls = []

    def fake(method, members):
        calls.append((method, members))
        return {"method": method, "n_target": members, "seconds": seconds[method] * members / 1000}

    monkeypatch.setattr(scaling, "pipeline_methods", lambda: list(seconds))
    monkeypatch.setattr(scaling, "_run_pipeline", fake)
    frame = scaling.pipeline_sweep([1000, 10000, 100000], limit=400.0, progress=lambda _: None)
    assert calls[0] == ("equimesh slow", scaling.PIPELINE_WARM_UP) and len(frame) == len(calls) - 1  # untimed
    assert list(frame[frame["method"] == "equimesh slow"]["n_target"]) == [1000, 10000]
    assert list(frame[frame["method"] == "equimesh quick"]["n_target"]) == [1000, 10000, 100000]
