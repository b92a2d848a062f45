"""Provenance records and atomic writes (every result file is complete or absent)."""

import datetime
import json
import platform
import re
import subprocess
import sys
from pathlib import Path

from equimesh.io.provenance import (
    git_state,
    library_versions,
    provenance,
    provenance_markdown,
    provenance_path,
    write_provenance,
)

GIT = ["git", "-c", "user.name=t", "-c", "user.email=t@t"]


def repository(folder):
    """A git repository in ``folder`` with one commit of src/f.txt, results/f.txt and paper_figs/f.txt; its sha."""
    git = [*GIT, "-C", str(folder)]
    for name in ("results", "paper_figs", "src"):
        (folder / name).mkdir()
        (folder / name / "f.txt").write_text("a")
    subprocess.run([*git, "init", "-q"], check=True)
    subprocess.run([*git, "add", "-A"], check=True)
    subprocess.run([*git, "commit", "-qm", "init"], check=True)
    return subprocess.run([*git, "rev-parse", "HEAD"], check=True, capture_output=True, text=True).stdout.strip()


def test_provenance_records_code_platform_versions_and_parameters():
    record = provenance([("seed", 1), ("n", 2)])
    assert set(record) == {"git", "date", "python", "implementation", "platform", "versions", "parameters"}
    assert record["parameters"] == {"seed": 1, "n": 2}
    assert record["git"] == git_state(Path(__file__).parent)  # the code's checkout, wherever it runs from
    assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\+00:00", record["date"])  # UTC, to the second
    now = datetime.datetime.now(datetime.timezone.utc)
    assert abs((now - datetime.datetime.fromisoformat(record["date"])).total_seconds()) < 60
    assert record["python"] == platform.python_version() and record["platform"] == platform.platform()
    assert record["implementation"] == sys.implementation.name
    for name in ("equimesh", "numpy", "scipy", "shapely", "triangle", "pandas", "matplotlib"):
        assert name in record["versions"]
    json.dumps(record)


def test_git_state_outside_a_repository_is_none(tmp_path):
    assert git_state(tmp_path) == {"commit": None, "dirty": None}


def test_git_state_without_a_commit_or_a_work_tree(tmp_path):
    """A repository without a commit has none; inside .git the commit is known but not whether the code is dirty."""
    (tmp_path / "new").mkdir()
    subprocess.run([*GIT, "-C", str(tmp_path / "new"), "init", "-q"], check=True)
    assert git_state(tmp_path / "new") == {"commit": None, "dirty": None}
    sha = repository(tmp_path / "new")
    assert git_state(tmp_path / "new" / ".git") == {"commit": sha, "dirty": None}


def test_git_state_dirty_means_code_not_outputs(tmp_path):
    """Rewritten results/ and paper_figs/ do not mark the code dirty; any other change does."""
    sha = repository(tmp_path)
    assert git_state(tmp_path / "src") == {"commit": sha, "dirty": False}
    (tmp_path / "results" / "f.txt").write_text("b")
    (tmp_path / "paper_figs" / "new.png").write_text("b")
    assert git_state(tmp_path / "src")["dirty"] is False
    (tmp_path / "src" / "f.txt").write_text("b")
    assert git_state(tmp_path / "src") == {"commit": sha, "dirty": True}


def test_write_provenance_beside_the_result(tmp_path):
    path = provenance_path(tmp_path / "sub" / "sweep.csv")
    assert path.name == "sweep.provenance.json"
    record = write_provenance(path, {"b": tmp_path, "a": 1})
    text = path.read_text()
    assert (
        json.loads(text)["parameters"] == {"a": 1, "b": str(tmp_path)} == {**record["parameters"], "b": str(tmp_path)}
    )
    assert text == json.dumps(json.loads(text), indent=2, sort_keys=True) + "\n"  # sorted, indented, one last newline
    assert [p.name for p in path.parent.iterdir()] == [path.name]


def test_a_library_not_installed_has_no_version():
    versions = library_versions(["numpy", "no-such-distribution-here"])
    assert versions == {"numpy": versions["numpy"], "no-such-distribution-here": None} and versions["numpy"]


def test_provenance_markdown_lists_commit_date_parameters_platform_and_versions():
    record = {
        "git": {"commit": "abc123", "dirty": True},
        "date": "2026-01-01T00:00:00+00:00",
        "python": "3.11.7",
        "platform": "Linux-x",
        "versions": {"numpy": "2.0", "scipy": None},
        "parameters": {"seed": 1, "n": [2, 3]},
    }
    assert provenance_markdown(record) == [
        "## Provenance",
        "",
        "- commit: `abc123` (uncommitted changes)",
        "- date (UTC): 2026-01-01T00:00:00+00:00",
        '- parameters: `{"n": [2, 3], "seed": 1}`',
        "- Python 3.11.7 on Linux-x",
        "- libraries: numpy 2.0, scipy None",
    ]
    clean = provenance_markdown({**record, "git": {"commit": None, "dirty": False}})
    assert clean[2] == "- commit: `unknown (not a git checkout)`"
