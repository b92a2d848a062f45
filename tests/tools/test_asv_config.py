"""``benchmarks/asv.conf.json`` builds commits in environments asv makes itself (``make bench-history``).

The first test reads the configuration with asv's own loader.  The second
builds the committed HEAD as a wheel, installs it into the asv-built
virtualenv and runs one quick benchmark on it, recording the result in a
temporary folder.  Creating that virtualenv downloads the dependencies from
the package index (about 10 minutes on the reference machine), so the test
runs when ``.asv/env`` exists already (after one ``make bench-history``), or
when ``EQUIMESH_ASV_BUILD=1`` asks for it; otherwise it is skipped with that
reason.  With the environment in place it takes about a minute.
"""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from repository import ROOT

asv_config = pytest.importorskip("asv.config", reason="asv (the [bench] extra) is not installed")


asv_util = pytest.importorskip("asv.util")


CONFIG = ROOT / "benchmarks" / "asv.conf.json"


ASV = Path(sys.executable).with_name("asv")


BENCHMARK = "bench_problem1.Increment.track_node_count"


def test_configuration_builds_from_the_repository_into_dot_asv():
    """virtualenv environments built from the repository; everything asv writes under the gitignored .asv/."""
    conf = asv_config.Config.load(str(CONFIG))
    assert conf.environment_type == "virtualenv" and conf.dvcs == "git"
    here = CONFIG.parent  # asv resolves the paths from the configuration's folder
    assert (here / conf.repo).resolve() == ROOT
    for folder in (conf.env_dir, conf.results_dir, conf.html_dir):
        assert (here / folder).resolve().parent == ROOT / ".asv"
    assert ".asv/" in (ROOT / ".gitignore").read_text().split()


def _head():
    done = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True)
    return done.stdout.strip() if done.returncode == 0 else None


@pytest.mark.skipif(
    not ((ROOT / ".asv" / "env").is_dir() or os.environ.get("EQUIMESH_ASV_BUILD") == "1"),
    reason="no asv-built environment in .asv/env yet: run `make bench-history` once, or set EQUIMESH_ASV_BUILD=1",
)
def test_asv_builds_and_benchmarks_the_head_commit(tmp_path):
    """One quick benchmark of HEAD, built and installed by asv; its result is recorded against HEAD."""
    head = _head()
    if head is None or not ASV.exists():
        pytest.skip("needs a git checkout and the asv command beside this Python")
    conf = asv_util.load_json(str(CONFIG), js_comments=True)
    conf.update(
        repo=str(ROOT),
        benchmark_dir=str(ROOT / "benchmarks" / "benchmarks"),
        env_dir=str(ROOT / ".asv" / "env"),
        results_dir=str(tmp_path / "results"),
        html_dir=str(tmp_path / "html"),
    )
    path = tmp_path / "asv.conf.json"
    path.write_text(json.dumps(conf))
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}  # the benchmark must import the built wheel
    subprocess.run([str(ASV), "machine", "--yes"], cwd=tmp_path, env=env, check=True, capture_output=True)
    done = subprocess.run(
        [str(ASV), "run", "--config", str(path), "--quick", "--show-stderr", "--bench", f"^{BENCHMARK}", f"{head}^!"],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    (result,) = [p for p in (tmp_path / "results").glob("*/*.json") if p.name != "machine.json"]
    record = json.loads(result.read_text())
    assert record["commit_hash"] == head
    values = record["results"][BENCHMARK][0]
    assert all(v is not None and v > 0 for v in values), values


def test_bench_compare_refuses_an_unknown_base_in_one_line():
    """``make bench-compare BASE=<unknown>``: one line naming the base, exit status 2, before any venv or asv work."""
    if shutil.which("make") is None or _head() is None:
        pytest.skip("needs make and a git checkout")
    done = subprocess.run(
        ["make", "--no-print-directory", "bench-compare", "BASE=no-such-commit"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert done.returncode == 2
    assert done.stderr.splitlines()[0] == "make bench-compare: unknown base commit 'no-such-commit'"
    assert done.stdout == ""
