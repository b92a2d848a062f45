"""``--scheduler`` of the sweeps: the same results, bit for bit, on a local pool and on Dask; bad values refused.

The Dask tests start a ``dask.distributed`` LocalCluster of two workers; they
are skipped when the optional extra ``[dask]`` is not installed.
"""

import pytest


@pytest.fixture
def common(load_experiment):
    return load_experiment("_common")


@pytest.fixture
def ratio_sweep(load_experiment):
    return load_experiment("ratio_sweep")


def small_sweep(out):
    return [
        "--n-polygons",
        "6",
        "--max-area",
        "30",
        "--tail-fraction",
        "0",
        "--out-dir",
        str(out),
        "--fig-dir",
        str(out),
    ]


@pytest.mark.parametrize("value", ["local", "dask", "tcp://127.0.0.1:8786", "tcp://scheduler.example:1"])
def test_scheduler_values_accepted(common, value):
    assert common.scheduler(value) == value


@pytest.mark.parametrize("value", ["spark", "", "tcp://host", "http://127.0.0.1:8786", "tcp://a b:1"])
def test_unknown_scheduler_is_refused_before_anything_runs(ratio_sweep, tmp_path, capsys, value):
    """An unknown name: argparse's one-line error, exit status 2, no results file."""
    with pytest.raises(SystemExit) as exit_:
        ratio_sweep.main(small_sweep(tmp_path) + ["--scheduler", value])
    assert exit_.value.code == 2
    assert "unknown scheduler" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


def test_unreachable_scheduler_ends_with_one_line(ratio_sweep, common, tmp_path, monkeypatch):
    """No Dask scheduler at the address: one line naming it, a non-zero exit, no results file."""
    pytest.importorskip("distributed", reason="the optional extra [dask] is not installed")
    monkeypatch.setattr(common, "CONNECT_TIMEOUT", "1s")
    with pytest.raises(SystemExit) as exit_:
        ratio_sweep.main(small_sweep(tmp_path) + ["--scheduler", "tcp://127.0.0.1:9"])
    message = str(exit_.value.code)
    assert message == "--scheduler tcp://127.0.0.1:9: no Dask scheduler answered within 1s"
    assert not list(tmp_path.iterdir())


def test_ratio_sweep_on_a_local_cluster_is_bit_identical(ratio_sweep, tmp_path):
    """The ratio sweep's CSV is the same bytes in-process and on a LocalCluster of two workers.

    Six polygons in batches of four: two Dask tasks whose rows must come back in index order.
    """
    pytest.importorskip("distributed", reason="the optional extra [dask] is not installed")
    local, dask = tmp_path / "local", tmp_path / "dask"
    assert ratio_sweep.main(small_sweep(local) + ["--jobs", "1"]) == 0
    assert ratio_sweep.main(small_sweep(dask) + ["--jobs", "2", "--scheduler", "dask"]) == 0
    assert (dask / "ratio_sweep.csv").read_bytes() == (local / "ratio_sweep.csv").read_bytes()
