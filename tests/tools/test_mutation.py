"""tools/mutation (``make mutation``): its module table, the keys of its arguments, its runs and its report.

Nothing here runs mutmut's tests.  The tests that make mutants in process need mutmut (the ``[mutation]``
extra) and are skipped without it; the check that every argument still names a statement of the code needs
the standard library only.
"""

import tomllib
from pathlib import Path

import pytest

from tools.mutation import __main__ as cli
from tools.mutation import carry, equivalent, report, run
from tools.mutation.modules import ENVIRONMENT, MODULES
from tools.mutation.mutants import Mutant, function_of, normalised, pattern, statements

ROOT = Path(__file__).resolve().parents[2]

RECORD = {
    "git": {"commit": "abc", "dirty": False},
    "date": "2026-01-01",
    "parameters": {},
    "python": "3.11",
    "platform": "linux",
    "versions": {},
}

#: One function as written by hand and as ``ruff format`` writes it (line length 120).
BY_HAND = '''
def f(a, b=2.0):
    """Doc."""
    x = np.asarray(a, dtype = float) # the array
    if (x.max() > b and
            x.min() < 0):
        return {'key': (x,
                        b)}
    return None
'''
FORMATTED = '''
def f(a, b=2.0):
    """Doc."""
    x = np.asarray(a, dtype=float)  # the array
    if x.max() > b and x.min() < 0:
        return {"key": (x, b)}
    return None
'''


def _row(**fields):
    counts = {s: 0 for s in run.STATUSES}
    return {
        "module": "src/m.py",
        "tests": ["tests/test_m.py"],
        "environment": {},
        "mutants": 0,
        **counts,
        "seconds": 5,
        "survivors": [],
        "measured": {"commit": "0123456789abcdef", "dirty": False},
        **fields,
    }


def _markdown(row, arguments=equivalent.Arguments([])):
    """The report of ``row`` alone, among the modules of the table."""
    return report.markdown(
        {row["module"]: report.scored(row, arguments)}, RECORD, {row["module"]: row["tests"], **MODULES}
    )


def test_every_module_and_test_file_exists():
    for module, tests in MODULES.items():
        assert (ROOT / module).is_file(), module
        assert tests and all((ROOT / t).is_file() for t in tests), tests


def test_mutmut_table_mutates_one_module_against_its_tests():
    module = "src/equimesh/planar/bounds.py"
    table = tomllib.loads(run.mutmut_table(module))["tool"]["mutmut"]
    assert table["only_mutate"] == [module]
    assert table["pytest_add_cli_args_test_selection"] == MODULES[module]
    assert table["timeout_multiplier"] == run.TIMEOUT_MULTIPLIER


def test_unknown_module_is_refused(capsys):
    with pytest.raises(SystemExit) as exit_:
        cli.parse_args(["src/equimesh/nowhere.py"])
    assert exit_.value.code == 2 and "unknown module" in capsys.readouterr().err


def test_functions_need_one_module(capsys):
    """--functions takes a comma-separated list (so that make's MUTATION_ARGS may come before the module)."""
    args = cli.parse_args(["--functions", "sharp_run,Polygon.area", "src/equimesh/planar/boundary/sides.py"])
    assert args.functions == ["sharp_run", "Polygon.area"] and args.modules == ["src/equimesh/planar/boundary/sides.py"]
    with pytest.raises(SystemExit):
        cli.parse_args(["--functions", "sharp_run"])
    assert "--functions needs exactly one module, and no --resume" in capsys.readouterr().err


def test_a_statement_formatted_two_ways_has_one_key():
    """Spaces, line breaks, quotes, redundant parentheses, trailing commas and comments do not count."""
    assert normalised("x = np.asarray(a, dtype = float) # c") == normalised("x = np.asarray(a, dtype=float)")
    assert normalised("return {'k': (x,\n    b)}") == normalised(
        'return {\n    "k": (\n        x,\n        b,\n    )\n}'
    )
    assert normalised("x = np.asarray(a, )") == "x = np.asarray(a)"
    assert normalised("if (a <\n        b):\n    y = 1\nelse:\n    y = 2") == "if a < b:"
    assert normalised("def f(a, b=3.0):\n    return a") == "def f(a, b=3.0):"
    assert normalised("x = 1") != normalised("x = 2")


def test_statements_are_those_of_the_code_whatever_its_formatting():
    """:func:`statements` (the cheap check) gives the same statements of both formattings, per function."""
    assert statements(BY_HAND) == statements(FORMATTED)
    found = statements(FORMATTED + "\nclass C:\n    def m(self):\n        for i in range(3):\n            pass\n")
    assert found["f"] >= {"def f(a, b=2.0):", "x = np.asarray(a, dtype=float)", "if x.max() > b and x.min() < 0:"}
    assert found["C.m"] == {"def m(self):", "for i in range(3):", "for i in range(3): pass", "pass"}


def test_mutants_of_two_formattings_are_the_same():
    """mutmut makes the same mutants, with the same names and statements, of both formattings."""
    pytest.importorskip("mutmut")
    from tools.mutation.mutants import module_mutants

    by_hand, formatted = (module_mutants("src/pkg/m.py", code) for code in (BY_HAND, FORMATTED))
    assert by_hand == formatted and len(by_hand) > 10
    assert Mutant("pkg.m.x_f__mutmut_1", "f", "def f(a, b=2.0):", "def f(a, b=3.0):") in formatted
    names = {m.mutated for m in formatted}
    assert "x = np.asarray(a, dtype=None)" in names and "if x.max() >= b and x.min() < 0:" in names


def test_every_argument_names_a_statement_of_the_code():
    """Each argued mutant's original statement is in its module: no orphan by the cheap check (no mutmut)."""
    arguments = equivalent.load()
    assert arguments.entries and {e[0] for e in arguments.entries} <= set(MODULES)
    assert equivalent.missing_originals(arguments) == []


def test_every_argued_mutant_is_made_by_the_code():
    """mutmut, in process, still makes every argued mutant, in the function named: no orphan, no wrong hint."""
    pytest.importorskip("mutmut")
    from tools.mutation.mutants import module_mutants

    orphans, hints = equivalent.check(equivalent.load(), lambda m: module_mutants(m, (ROOT / m).read_text()))
    assert orphans == [] and hints == []


def test_arguments_match_on_the_statements_with_the_function_as_a_hint():
    """The function decides only between arguments of one statement and mutation; a renamed one still matches."""
    statement = {"module": "src/m.py", "original": "x = 1", "mutated": ["x = 2"]}
    arguments = equivalent.Arguments(
        [
            {"why": "in f", "statement": [{**statement, "function": "f"}]},
            {"why": "in g", "statement": [{**statement, "function": "g"}]},
            {"why": "in h", "statement": [{**statement, "function": "h", "original": "y = 1", "mutated": ["y = 2"]}]},
            {"why": "gone", "statement": [{**statement, "function": "f", "original": "z = 1", "mutated": ["z = 2"]}]},
        ]
    )
    assert arguments.why("src/m.py", "g", "x = 1", "x = 2") == "in g"
    assert arguments.why("src/m.py", "renamed_h", "y = 1", "y = 2") == "in h"
    assert arguments.why("src/m.py", "renamed_f", "x = 1", "x = 2") is None  # two arguments, no hint
    assert arguments.why("src/other.py", "h", "y = 1", "y = 2") is None
    made = [Mutant("m.x_f__mutmut_1", "f", "x = 1", "x = 2"), Mutant("m.x_k__mutmut_1", "k", "y = 1", "y = 2")]
    orphans, hints = equivalent.check(arguments, lambda module: made)
    assert orphans == [("src/m.py", "f", "z = 1", "z = 2")]
    assert hints == [("src/m.py", "g", "x = 1", "x = 2", ["f"]), ("src/m.py", "h", "y = 1", "y = 2", ["k"])]


def test_report_explains_or_flags_every_survivor():
    """An equivalent survivor carries its argument; any other is flagged as a missing test."""
    survivors = [
        {"mutant": "m.x_f__mutmut_1", "function": "f", "original": "x = 0", "mutated": "x = 1"},
        {"mutant": "m.x_f__mutmut_2", "function": "f", "original": "y = 0", "mutated": "y = 2"},
    ]
    row = _row(mutants=10, killed=8, survived=2, survivors=survivors)
    arguments = equivalent.Arguments(
        [
            {
                "why": "the value is never read",
                "statement": [{**survivors[0], "module": "src/m.py", "mutated": ["x = 1"]}],
            }
        ]
    )
    scored = report.scored(row, arguments)
    assert (scored["equivalent"], scored["score"]) == (1, 8 / 9)
    text = _markdown(row, arguments)
    assert "| `src/m.py` | tests/test_m.py | 10 | 8 | 2 | 1 | 0 | 0 | 88.9 % | 5 s | `0123456` |" in text
    assert "`m.x_f__mutmut_1`: `x = 1` — the value is never read" in text
    assert "`m.x_f__mutmut_2`: `y = 2` — **not explained: a test is missing**" in text
    assert "| `src/equimesh/planar/bounds.py` | tests/planar/test_bounds.py | not measured |" in text


def test_a_carried_row_says_where_and_when_it_was_measured():
    measured = {"commit": "0123456789", "path": "src/old.py", "tests changed": ["tests/test_m.py"]}
    text = _markdown(_row(measured=measured))
    assert "| 5 s | `0123456` as `src/old.py` |" in text
    assert "Measured at `0123456` as `src/old.py` and carried" in text and "since (the verdicts" in text


def test_kernel_modules_run_as_python_and_say_so():
    """The numba kernels' mutants run with NUMBA_DISABLE_JIT=1, and their row of the table says so."""
    kernels = [
        m for m in MODULES if m.endswith(("/insertion/predicates.py", "/insertion/cdt.py", "/insertion/fast.py"))
    ]
    assert len(kernels) == 3
    assert all(ENVIRONMENT[m] == {"NUMBA_DISABLE_JIT": "1"} for m in kernels)
    assert "src/equimesh/planar/bounds.py" not in ENVIRONMENT
    row = _row(module="src/k.py", tests=["tests/a.py", "tests/b.py"], environment={"NUMBA_DISABLE_JIT": "1"}, mutants=1)
    row["killed"] = 1
    text = _markdown(row)
    assert "| `src/k.py` | NUMBA_DISABLE_JIT=1 tests/a.py, tests/b.py | 1 | 1 |" in text
    row["not checked"] = 1
    text = _markdown(row)
    assert "Interrupted: 1 of 1 mutants not run" in text


def test_the_all_or_nothing_writes_are_mutated():
    """mutmut skips decorated functions: the context managers of io/_atomic.py, made by a call, have mutants."""
    pytest.importorskip("mutmut")
    from tools.mutation.mutants import module_mutants

    module = "src/equimesh/io/_atomic.py"
    functions = {m.function for m in module_mutants(module, (ROOT / module).read_text())}
    assert {"atomic_paths", "atomic_path", "interrupts_held"} <= functions


def _stubbed_copy(monkeypatch, folder, status, made):
    """A copy of the project for bounds.py in ``folder`` with mutmut's verdicts ``status`` and the mutants ``made``,
    mutmut stubbed; the module and the list its runs' arguments are appended to."""
    module = "src/equimesh/planar/bounds.py"
    (folder / "mutants" / "src" / "equimesh" / "planar").mkdir(parents=True)
    (folder / "mutants" / (module + ".meta")).write_text('{"hash_by_function_name": {}}')
    (folder / "measured.json").write_text('{"commit": "abc", "dirty": false}')
    (folder / module).parent.mkdir(parents=True)
    (folder / module).write_text("")
    runs = []
    monkeypatch.setattr(run, "prepare", lambda *args: folder)
    monkeypatch.setattr(run, "mutmut", lambda folder, *args, environment=None: runs.append(args))
    monkeypatch.setattr(run, "statuses", lambda folder: status)
    monkeypatch.setattr(run, "module_mutants", lambda module, code: made)
    return module, runs


def test_unexplained_reruns_only_the_survivors_not_argued_equivalent(monkeypatch, tmp_path):
    """``--unexplained`` runs again only the last run's survivors not argued equivalent (mutmut stubbed)."""
    status = {"m_1": "survived", "m_2": "survived", "m_3": "survived", "m_4": "killed"}
    made = [Mutant(f"m_{i}", "f", "x = 0", f"x = {i}") for i in range(1, 5)]
    module, runs = _stubbed_copy(monkeypatch, tmp_path, status, made)
    row = run.run_module(module, tmp_path, 1, "survivors", 50, lambda text: None, again=lambda m: m.name != "m_1")
    assert runs == [("run", "--max-children", "1", "m_2", "m_3")]
    assert (row["mutants"], row["killed"], row["survived"], row["seconds"]) == (4, 1, 3, 50)
    assert row["survivors"][1] == {"mutant": "m_2", "function": "f", "original": "x = 0", "mutated": "x = 2"}
    assert row["measured"] == {"commit": "abc", "dirty": False}


def test_survivors_run_again_only_within_the_functions_the_last_run_covered(monkeypatch, tmp_path):
    """After a run of some functions the copy holds no verdicts of the others ("not checked"): running the
    survivors of the whole module, or of another function, is refused; those of the functions run are run again."""
    status = {"m.x_f__mutmut_1": "not checked", "m.x_g__mutmut_1": "survived", "m.x_g__mutmut_2": "killed"}
    made = [Mutant(n, function_of(n), "x = 0", "x = 1") for n in status]
    module, runs = _stubbed_copy(monkeypatch, tmp_path, status, made)
    monkeypatch.setattr(run, "_hashes", lambda folder, module: {"x_f": "f1", "x_g": "g1"})
    quiet = dict(progress=lambda text: None)
    run.run_module(module, tmp_path, 1, functions=["g"], **quiet)
    for functions in (None, ["f"], ["f", "g"]):
        with pytest.raises(SystemExit, match="covered only the mutants of g: run them again with --functions g"):
            run.run_module(module, tmp_path, 1, "survivors", 50, functions=functions, **quiet)
    runs.clear()
    row = run.run_module(module, tmp_path, 1, "survivors", 50, functions=["g"], **quiet)
    assert runs == [("run", "--max-children", "1", "m.x_g__mutmut_1")]
    assert (row["mutants"], row["killed"], row["survived"]) == (2, 1, 1)
    run.run_module(module, tmp_path, 1, **quiet)  # a run of every function: its survivors may run again
    run.run_module(module, tmp_path, 1, "survivors", 50, **quiet)


def test_functions_name_their_mutants():
    """--functions names a function as mutmut mangles it: a plain function or Class.method."""
    assert function_of("equimesh.planar.boundary.sides.x_sharp_run__mutmut_3") == "sharp_run"
    assert function_of("equimesh.planar.polygon.xǁPolygonǁinner_angle__mutmut_12") == "Polygon.inner_angle"
    assert function_of("xǁPolygonǁarea") == "Polygon.area"
    module = "src/equimesh/planar/polygon.py"
    assert pattern(module, "_check_simple") == "equimesh.planar.polygon.x__check_simple__mutmut_*"
    assert pattern(module, "Polygon.area") == "equimesh.planar.polygon.xǁPolygonǁarea__mutmut_*"


def _full_row(status, hashes, survivors, seconds=60):
    counts = {s: sum(v == s for v in status.values()) for s in run.STATUSES}
    return _row(
        mutants=len(status),
        **counts,
        seconds=seconds,
        survivors=[{"mutant": n, "function": function_of(n), "original": "o", "mutated": m} for n, m in survivors],
        by_function=run.by_function(status, hashes),
    )


def test_a_run_of_some_functions_replaces_their_verdicts_only():
    """The functions named get the new verdicts; the others keep the full run's; one gone is dropped."""
    full = _full_row(
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
    part = _full_row(
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
    row = run.merged(full, part, ["g", "new"])
    assert [s["mutant"] for s in row["survivors"]] == ["m.x_f__mutmut_2", "m.x_g__mutmut_3"]
    assert (row["mutants"], row["killed"], row["survived"], row["timeout"]) == (6, 4, 2, 0)
    tests = {"g": ["tests/test_m.py"], "new": ["tests/test_m.py"]}
    assert row["rerun"] == {"functions": ["g", "new"], "mutants": 4, "seconds": 60, "tests": tests}
    assert report.scored(row, equivalent.Arguments([]))["score"] == 4 / 6
    with pytest.raises(SystemExit, match="f changed since its full run"):
        run.merged(full, {**part, "by_function": {**part["by_function"], "f": {"hash": "f2"}}}, ["g", "new"])
    with pytest.raises(SystemExit, match="no function 'h'"):
        run.merged(full, part, ["g", "new", "h"])
    with pytest.raises(SystemExit, match="no verdicts per function"):
        run.merged({k: v for k, v in full.items() if k != "by_function"}, part, ["g"])
    text = _markdown(row)
    assert "Only the mutants of `g`, `new` (4) were run again (`--functions`, the last run 60 s)" in text
    both = ["tests/test_m.py", "tests/test_n.py"]
    wider = run.merged(full, {**part, "tests": both}, ["g", "new"])
    assert wider["tests"] == ["tests/test_m.py"] and wider["rerun"]["tests"] == {"g": both, "new": both}
    text = _markdown(wider)
    assert "(`--functions`, the last run 60 s; `g` against tests/test_m.py, tests/test_n.py; `new` against" in text
    back = run.merged(wider, part, ["new"])  # g keeps the files it was run against, new takes this run's
    assert back["rerun"]["tests"] == {"g": both, "new": ["tests/test_m.py"]}
    again = run.merged(
        row,
        {**part, "survivors": [], "by_function": {**part["by_function"], "new": {"hash": "n1", "killed": 1}}},
        ["new"],
    )
    assert again["rerun"]["functions"] == ["g", "new"] and again["survivors"] == row["survivors"]  # accumulated


#: A module at the commit measured, and the same code moved, reformatted, with other docstrings and imports.
THEN = '''"""Old."""
from ._a import g

LIMIT = 3


def f(x):
    """Old words."""
    return g(x) + LIMIT
'''
NOW = '''"""New."""

from .a import g

LIMIT = 3


def f(x):
    """New words."""
    return (
        g(x)
        + LIMIT
    )
'''


def test_a_row_is_carried_only_to_the_same_code(monkeypatch, tmp_path):
    """--carry moves a row to the module's new path if its functions and other statements are unchanged."""
    assert carry.shape(THEN) == carry.shape(NOW)
    assert carry.shape(THEN) != carry.shape(THEN.replace("LIMIT = 3", "LIMIT = 4"))
    assert carry.shape(THEN) != carry.shape(THEN.replace("+ LIMIT", "- LIMIT"))
    (tmp_path / "src" / "pkg").mkdir(parents=True)
    (tmp_path / "src" / "pkg" / "new.py").write_text(NOW)
    (tmp_path / "tests").mkdir()
    (tmp_path / "tests" / "test_m.py").write_text("def test(): pass\n")
    files = {"src/pkg/_old.py": THEN, "tests/test_m.py": "def test():\n    pass\n"}
    monkeypatch.setattr(carry, "ROOT", tmp_path)
    monkeypatch.setattr(carry, "_git", lambda *args: files[args[1].split(":")[1]])
    monkeypatch.setitem(MODULES, "src/pkg/new.py", ["tests/test_m.py"])

    def made(module, code):
        prefix = module[4:-3].replace("/", ".")
        return [Mutant(f"{prefix}.x_f__mutmut_1", "f", "return g(x) + LIMIT", "return g(x) - LIMIT")]

    monkeypatch.setattr(carry, "module_mutants", made)
    survivor = {"mutant": "pkg._old.x_f__mutmut_1", "line": "return g(x) - LIMIT"}
    row = _row(module="src/pkg/_old.py", mutants=1, survived=1, survivors=[survivor])
    moved = carry.carried(row, "src/pkg/new.py")
    assert moved["module"] == "src/pkg/new.py"
    assert moved["survivors"] == [
        {
            "mutant": "pkg.new.x_f__mutmut_1",
            "function": "f",
            "original": "return g(x) + LIMIT",
            "mutated": "return g(x) - LIMIT",
        }
    ]
    assert moved["measured"] == {
        "commit": "0123456789abcdef",
        "dirty": False,
        "path": "src/pkg/_old.py",
        "tests changed": [],
    }
    (tmp_path / "src" / "pkg" / "new.py").write_text(NOW.replace("+ LIMIT", "- LIMIT"))
    with pytest.raises(SystemExit, match="is not src/pkg/_old.py of 0123456 but for formatting: f changed"):
        carry.carried(row, "src/pkg/new.py")
