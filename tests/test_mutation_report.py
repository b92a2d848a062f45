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
    module = {
        "module": "src/m.py",
        "tests": ["tests/test_m.py"],
        "mutants": 10,
        "killed": 8,
        "survived": 2,
        "timeout": 0,
        "no tests": 0,
        "equivalent": 1,
        "score": 8 / 9,
        "seconds": 5,
        "survivors": survivors,
    }
    record = {
        "git": {"commit": "abc", "dirty": False},
        "date": "2026-01-01",
        "parameters": {},
        "python": "3.11",
        "platform": "linux",
        "versions": {},
    }
    text = mutation.report([module], record)
    assert "| `src/m.py` | tests/test_m.py | 10 | 8 | 2 | 1 | 0 | 0 | 88.9 % | 5 s |" in text
    assert "`m__mutmut_1`: `x = 1` — the value is never read" in text
    assert "`m__mutmut_2`: `y = 2` — **not explained: a test is missing**" in text


def test_kernel_modules_run_as_python_and_say_so(mutation):
    """The numba kernels' mutants run with NUMBA_DISABLE_JIT=1, and their row of the table says so."""
    kernels = [
        m
        for m in mutation.MODULES
        if m.endswith(("/insertion/predicates.py", "/insertion/cdt.py", "/insertion/fast.py"))
    ]
    assert len(kernels) == 3
    assert all(mutation.ENVIRONMENT[m] == {"NUMBA_DISABLE_JIT": "1"} for m in kernels)
    assert "src/equimesh/planar/bounds.py" not in mutation.ENVIRONMENT
    module = {
        "module": "src/k.py",
        "tests": ["tests/a.py", "tests/b.py"],
        "environment": {"NUMBA_DISABLE_JIT": "1"},
        "mutants": 1,
        "killed": 1,
        "survived": 0,
        "timeout": 0,
        "no tests": 0,
        "equivalent": 0,
        "score": 1.0,
        "seconds": 5,
        "survivors": [],
    }
    record = {
        "git": {"commit": "abc", "dirty": False},
        "date": "2026-01-01",
        "parameters": {},
        "python": "3.11",
        "platform": "linux",
        "versions": {},
    }
    assert "| `src/k.py` | NUMBA_DISABLE_JIT=1 tests/a.py, tests/b.py | 1 | 1 |" in mutation.report([module], record)
    module["not checked"] = 1
    assert "Interrupted: 1 of 1 mutants not run" in mutation.report([module], record)


def test_unexplained_reruns_only_the_survivors_not_argued_equivalent(mutation, monkeypatch, tmp_path):
    """``--unexplained`` runs again only the last run's survivors not argued equivalent (mutmut stubbed)."""
    module = "src/equimesh/planar/bounds.py"
    monkeypatch.setitem(mutation.EQUIVALENT, (module, "argued"), "equivalent: stand-in")
    (tmp_path / "mutants" / "src" / "equimesh" / "planar").mkdir(parents=True)
    (tmp_path / "mutants" / (module + ".meta")).write_text('{"hash_by_function_name": {}}')
    runs = []
    monkeypatch.setattr(mutation, "prepare", lambda *args: tmp_path)
    monkeypatch.setattr(mutation, "mutmut", lambda folder, *args, environment=None: runs.append(args))
    monkeypatch.setattr(
        mutation, "statuses", lambda folder: {"m_1": "survived", "m_2": "survived", "m_3": "survived", "m_4": "killed"}
    )
    lines = {"m_1": "argued", "m_2": "a", "m_3": "b"}
    monkeypatch.setattr(mutation, "mutated_line", lambda folder, name: lines[name])
    row = mutation.run_module(module, tmp_path, 1, "survivors", 50, lambda text: None, unexplained=True)
    assert runs == [("run", "--max-children", "1", "m_2", "m_3")]
    assert (row["mutants"], row["killed"], row["survived"], row["equivalent"], row["seconds"]) == (4, 1, 3, 1, 50)


def test_functions_name_their_mutants(mutation):
    """--functions names a function as mutmut mangles it: a plain function or Class.method."""
    assert mutation._function("equimesh.planar.polygon.x__run__mutmut_3") == "_run"
    assert mutation._function("equimesh.planar.polygon.xǁPolygonǁinner_angle__mutmut_12") == "Polygon.inner_angle"
    assert mutation._function("xǁPolygonǁarea") == "Polygon.area"
    module = "src/equimesh/planar/polygon.py"
    assert mutation._glob(module, "_run") == "equimesh.planar.polygon.x__run__mutmut_*"
    assert mutation._glob(module, "Polygon.area") == "equimesh.planar.polygon.xǁPolygonǁarea__mutmut_*"


def _row(mutation, status, hashes, survivors):
    counts = {s: sum(v == s for v in status.values()) for s in mutation.STATUSES}
    return mutation._scored(
        {
            "module": "src/m.py",
            "tests": ["tests/test_m.py"],
            "environment": {},
            "mutants": len(status),
            **counts,
            "seconds": 60,
            "survivors": [{"mutant": n, "line": line} for n, line in survivors],
            "by_function": mutation._by_function(status, hashes),
        }
    )


def test_a_run_of_some_functions_replaces_their_verdicts_only(mutation):
    """The functions named get the new verdicts; the others keep the full run's; one gone is dropped."""
    full = _row(
        mutation,
        {
            "m.x_f__mutmut_1": "killed",
            "m.x_f__mutmut_2": "survived",
            "m.x_g__mutmut_1": "survived",
            "m.x_gone__mutmut_1": "survived",
            "m.x_gone__mutmut_2": "timeout",
        },
        {"x_f": "f1", "x_g": "g1", "x_gone": "h1"},
        [("m.x_f__mutmut_2", "a"), ("m.x_g__mutmut_1", "b"), ("m.x_gone__mutmut_1", "c")],
    )
    assert (full["mutants"], full["survived"], full["score"]) == (5, 3, 2 / 5)
    part = _row(
        mutation,
        {
            "m.x_g__mutmut_1": "killed",
            "m.x_g__mutmut_2": "killed",
            "m.x_g__mutmut_3": "survived",
            "m.x_new__mutmut_1": "killed",
        },
        {"x_f": "f1", "x_g": "g2", "x_new": "n1"},
        [("m.x_g__mutmut_3", "d")],
    )
    part["by_function"]["f"] = {"hash": "f1"}  # f's mutants were not run: not in this run's verdicts
    row = mutation.merged(full, part, ["g", "new"])
    assert [s["mutant"] for s in row["survivors"]] == ["m.x_f__mutmut_2", "m.x_g__mutmut_3"]
    assert (row["mutants"], row["killed"], row["survived"], row["timeout"]) == (6, 4, 2, 0)
    assert row["score"] == 4 / 6 and row["rerun"] == {"functions": ["g", "new"], "mutants": 4, "seconds": 60}
    with pytest.raises(SystemExit, match="f changed since its full run"):
        mutation.merged(full, {**part, "by_function": {**part["by_function"], "f": {"hash": "f2"}}}, ["g", "new"])
    with pytest.raises(SystemExit, match="no function 'h'"):
        mutation.merged(full, part, ["g", "new", "h"])
    with pytest.raises(SystemExit, match="no verdicts per function"):
        mutation.merged({k: v for k, v in full.items() if k != "by_function"}, part, ["g"])
    record = {
        "git": {"commit": "abc", "dirty": False},
        "date": "2026-01-01",
        "parameters": {},
        "python": "3.11",
        "platform": "linux",
        "versions": {},
    }
    assert "Only the mutants of `g`, `new` (4) were run again (`--functions`, the last run 60 s)" in mutation.report(
        [row], record
    )
    again = mutation.merged(
        row,
        {**part, "survivors": [], "by_function": {**part["by_function"], "new": {"hash": "n1", "killed": 1}}},
        ["new"],
    )
    assert again["rerun"]["functions"] == ["g", "new"] and again["survivors"] == row["survivors"]  # accumulated


def test_functions_need_one_module(mutation, capsys):
    """--functions takes a comma-separated list (so that make's MUTATION_ARGS may come before the module)."""
    args = mutation.parse_args(["--functions", "_run,Polygon.area", "src/equimesh/planar/polygon.py"])
    assert args.functions == ["_run", "Polygon.area"] and args.modules == ["src/equimesh/planar/polygon.py"]
    with pytest.raises(SystemExit):
        mutation.parse_args(["--functions", "_run"])
    assert "--functions needs exactly one module, and no --resume" in capsys.readouterr().err
