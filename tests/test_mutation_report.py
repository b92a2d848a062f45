"""experiments/mutation_report.py (``make mutation``): its module table, mutmut set-up and report, without running mutmut."""

import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def mutation(load_experiment):
    return load_experiment("mutation_report")


def test_every_module_and_test_file_exists(mutation):
    for module, tests in mutation.MODULES.items():
        assert (ROOT / module).is_file(), module
        assert tests and all((ROOT / t).is_file() for t in tests), tests


def test_mutmut_table_mutates_one_module_against_its_tests(mutation):
    module = "src/equimesh/planar/bounds.py"
    table = tomllib.loads(mutation.mutmut_table(module))["tool"]["mutmut"]
    assert table["only_mutate"] == [module]
    assert table["pytest_add_cli_args_test_selection"] == mutation.MODULES[module]
    assert table["timeout_multiplier"] == mutation.TIMEOUT_MULTIPLIER


def test_unknown_module_is_refused(mutation, capsys):
    with pytest.raises(SystemExit) as exit_:
        mutation.parse_args(["src/equimesh/nowhere.py"])
    assert exit_.value.code == 2 and "unknown module" in capsys.readouterr().err


def test_report_explains_or_flags_every_survivor(mutation):
    """An equivalent survivor carries its argument; any other is flagged as a missing test."""
    survivors = [
        {"mutant": "m__mutmut_1", "line": "x = 1", "equivalent": "the value is never read"},
        {"mutant": "m__mutmut_2", "line": "y = 2", "equivalent": None},
    ]
    module = {"module": "src/m.py", "tests": ["tests/test_m.py"], "mutants": 10, "killed": 8, "survived": 2,
              "timeout": 0, "no tests": 0, "equivalent": 1, "score": 8 / 9, "seconds": 5, "survivors": survivors}
    record = {"git": {"commit": "abc", "dirty": False}, "date": "2026-01-01", "parameters": {},
              "python": "3.11", "platform": "linux", "versions": {}}
    text = mutation.report([module], record)
    assert "| `src/m.py` | tests/test_m.py | 10 | 8 | 2 | 1 | 0 | 0 | 88.9 % | 5 s |" in text
    assert "`m__mutmut_1`: `x = 1` — the value is never read" in text
    assert "`m__mutmut_2`: `y = 2` — **not explained: a test is missing**" in text


def test_kernel_modules_run_as_python_and_say_so(mutation):
    """The numba kernels' mutants run with NUMBA_DISABLE_JIT=1, and their row of the table says so."""
    kernels = [m for m in mutation.MODULES if m.endswith(("/insertion/_predicates.py", "/insertion/_cdt.py", "/insertion/fast.py"))]
    assert len(kernels) == 3
    assert all(mutation.ENVIRONMENT[m] == {"NUMBA_DISABLE_JIT": "1"} for m in kernels)
    assert "src/equimesh/planar/bounds.py" not in mutation.ENVIRONMENT
    module = {"module": "src/k.py", "tests": ["tests/a.py", "tests/b.py"], "environment": {"NUMBA_DISABLE_JIT": "1"},
              "mutants": 1, "killed": 1, "survived": 0, "timeout": 0, "no tests": 0, "equivalent": 0, "score": 1.0,
              "seconds": 5, "survivors": []}
    record = {"git": {"commit": "abc", "dirty": False}, "date": "2026-01-01", "parameters": {},
              "python": "3.11", "platform": "linux", "versions": {}}
    assert "| `src/k.py` | NUMBA_DISABLE_JIT=1 tests/a.py, tests/b.py | 1 | 1 |" in mutation.report([module], record)
    module["not checked"] = 1
    assert "Interrupted: 1 of 1 mutants not run" in mutation.report([module], record)


def test_survivors_rerun_from_the_json_row_keeps_every_other_verdict(mutation, monkeypatch, tmp_path):
    """With no scratch copy left, ``--unexplained`` runs again only the previous row's survivors not argued
    equivalent, in a fresh copy, and the row keeps the previous verdicts of every other mutant (mutmut stubbed)."""
    module = "src/equimesh/planar/bounds.py"
    monkeypatch.setitem(mutation.EQUIVALENT, (module, "argued"), "equivalent: stand-in")
    previous = {"module": module, "mutants": 10, "killed": 6, "survived": 3, "timeout": 1, "seconds": 50, "survivors": [
        {"mutant": "m_1", "line": "argued", "equivalent": "equivalent: stand-in"},
        {"mutant": "m_2", "line": "a", "equivalent": None}, {"mutant": "m_3", "line": "b", "equivalent": None}]}
    runs = []
    monkeypatch.setattr(mutation, "prepare", lambda *args: tmp_path)
    monkeypatch.setattr(mutation, "mutmut", lambda folder, *args, environment=None: runs.append(args))
    monkeypatch.setattr(mutation, "statuses", lambda folder: {"m_1": "not checked", "m_2": "killed", "m_3": "survived",
                                                              "m_4": "not checked"})
    lines = {"m_1": "argued", "m_3": "b"}
    monkeypatch.setattr(mutation, "mutated_line", lambda folder, name: lines[name])
    row = mutation.run_module(module, tmp_path, 1, "survivors", 50, lambda text: None, previous, unexplained=True)
    assert runs == [("run", "--max-children", "1", "m_2", "m_3")]
    assert (row["mutants"], row["killed"], row["survived"], row["timeout"], row["equivalent"], row["seconds"]) == (10, 7, 2, 1, 1, 50)
    assert [s["mutant"] for s in row["survivors"]] == ["m_1", "m_3"] and row["score"] == 8 / 9
