"""Provenance records and atomic writes (every result file is complete or absent)."""

import json
import subprocess

from equimesh.io.provenance import git_state, provenance, provenance_path, write_provenance


def test_provenance_records_code_platform_versions_and_parameters():
    record = provenance({"seed": 1, "n": 2})
    assert record["parameters"] == {"seed": 1, "n": 2}
    assert set(record["git"]) == {"commit", "dirty"}
    assert record["date"].endswith("+00:00")
    for name in ("equimesh", "numpy", "scipy", "shapely", "triangle", "pandas", "matplotlib"):
        assert name in record["versions"]
    json.dumps(record)


def test_git_state_outside_a_repository_is_none(tmp_path):
    assert git_state(tmp_path) == {"commit": None, "dirty": None}


def test_git_state_dirty_means_code_not_outputs(tmp_path):
    """Rewritten results/ and paper_figs/ do not mark the code dirty; any other change does."""
    git = ["git", "-c", "user.name=t", "-c", "user.email=t@t", "-C", str(tmp_path)]
    for folder in ("results", "paper_figs", "src"):
        (tmp_path / folder).mkdir()
        (tmp_path / folder / "f.txt").write_text("a")
    subprocess.run([*git, "init", "-q"], check=True)
    subprocess.run([*git, "add", "-A"], check=True)
    subprocess.run([*git, "commit", "-qm", "init"], check=True)
    assert git_state(tmp_path / "src")["dirty"] is False
    (tmp_path / "results" / "f.txt").write_text("b")
    (tmp_path / "paper_figs" / "new.png").write_text("b")
    assert git_state(tmp_path / "src")["dirty"] is False
    (tmp_path / "src" / "f.txt").write_text("b")
    assert git_state(tmp_path / "src")["dirty"] is True


def test_write_provenance_beside_the_result(tmp_path):
    path = provenance_path(tmp_path / "sub" / "sweep.csv")
    assert path.name == "sweep.provenance.json"
    write_provenance(path, {"a": 1})
    assert json.loads(path.read_text())["parameters"] == {"a": 1}
    assert [p.name for p in path.parent.iterdir()] == [path.name]
