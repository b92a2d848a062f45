"""Running mutmut on one module, or on some of its functions, in a scratch copy of the project.

Each module runs in its own copy of ``src/``, ``tests/`` and ``pyproject.toml`` under the work folder
(default ``.mutation/``, gitignored), whose ``[tool.mutmut]`` table names only that module and its tests
(:data:`~tools.mutation.modules.MODULES`).  A run's row counts the mutants per status, lists every
survivor with its statements (:mod:`tools.mutation.mutants`) and keeps the verdicts per function with
mutmut's hash of the function's syntax tree, so that the mutants of some functions can be run again
(:func:`merged`) while the others' verdicts stand.  The row records the commit of the code it measured
(``measured``): the commit when the copy was made, and whether ``src/`` or ``tests/`` differed from it.
"""

import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

from .modules import ENVIRONMENT, MODULES
from .mutants import function_of, module_mutants, pattern

ROOT = Path(__file__).resolve().parents[2]

#: pytest options for every mutant run: stop at the first failure.
PYTEST_ARGS = ["-p", "no:cacheprovider", "-q", "-x"]

#: mutmut stops a mutant after ``2 * TIMEOUT_MULTIPLIER * (its tests' time + 1 s)`` of CPU time (timed
#: out, counted as killed).  mutmut's default, 15, let a mutant that never stops inserting run for 4 minutes
#: on a loaded machine; a surviving mutant runs its tests in their own time, so 3 leaves a margin of 6.
TIMEOUT_MULTIPLIER = 3.0

#: mutmut's verdicts, and "not checked" for the mutants of an interrupted run not reached.
STATUSES = ("killed", "survived", "timeout", "no tests", "suspicious", "skipped", "segfault", "not checked")

#: What a scratch copy of the project holds, besides mutmut's own files.
_COPIED = ("src", "tests")


def mutmut_table(module):
    """The ``[tool.mutmut]`` table that mutates ``module`` only, against its tests."""

    def toml_list(items):
        return "[" + ", ".join(json.dumps(i) for i in items) + "]"

    return "\n".join(
        [
            "",
            "[tool.mutmut]",
            'source_paths = ["src"]',
            f"only_mutate = {toml_list([module])}",
            f"pytest_add_cli_args_test_selection = {toml_list(MODULES[module])}",
            f"pytest_add_cli_args = {toml_list(PYTEST_ARGS)}",
            f"timeout_multiplier = {TIMEOUT_MULTIPLIER}",
            "",
        ]
    )


def code_state(root=ROOT):
    """``{"commit": HEAD, "dirty": whether src/ or tests/ differ from it}`` of the checkout at ``root``."""

    def git(*args):
        return subprocess.run(["git", *args], cwd=root, capture_output=True, text=True, check=True).stdout.strip()

    return {"commit": git("rev-parse", "HEAD"), "dirty": bool(git("status", "--porcelain", "--", *_COPIED))}


def prepare(module, work_dir, keep=None):
    """The copy of the project for ``module``'s mutants; returns its folder.

    ``keep=None`` makes a fresh copy (and records :func:`code_state` in it); ``"resume"`` and ``"so-far"``
    keep an existing one with its tests; ``"survivors"`` keeps it with the current tests.  Either way the
    ``[tool.mutmut]`` table is the current one (mutmut resets the verdicts its change can alter).
    """
    folder = work_dir / re.sub(r"[^A-Za-z0-9]+", "_", module)
    fresh = keep is None or not folder.exists()
    if fresh:
        shutil.rmtree(folder, ignore_errors=True)
        folder.mkdir(parents=True)
        shutil.copytree(ROOT / "src", folder / "src", ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
        (folder / "measured.json").write_text(json.dumps(code_state()) + "\n")
    if fresh or keep == "survivors":
        shutil.copytree(
            ROOT / "tests", folder / "tests", ignore=shutil.ignore_patterns("__pycache__", "*.pyc"), dirs_exist_ok=True
        )
    text = (ROOT / "pyproject.toml").read_text()
    (folder / "pyproject.toml").write_text(text + mutmut_table(module))
    return folder


def mutmut(folder, *args, environment=None):
    """Run ``mutmut *args`` in ``folder`` with ``environment`` added; its standard output."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}  # mutmut puts mutants/src first itself
    env.update(environment or {})
    done = subprocess.run([sys.executable, "-m", "mutmut", *args], cwd=folder, env=env, capture_output=True, text=True)
    if done.returncode:
        raise SystemExit(f"mutmut {' '.join(args)} failed in {folder}: {done.stderr.strip().splitlines()[-1:]}")
    return done.stdout


def statuses(folder):
    """Mutant name -> status (killed, survived, ...) of the mutants in ``folder``."""
    return dict(re.findall(r"^\s*(\S+): (.+)$", mutmut(folder, "results", "--all", "true"), re.M))


def by_function(status, hashes):
    """Function -> its hash and the count of its mutants per status (only those present)."""
    rows = {function_of(f): {"hash": h} for f, h in hashes.items()}
    for name, verdict in status.items():
        row = rows.setdefault(function_of(name), {"hash": None})
        row[verdict] = row.get(verdict, 0) + 1
    return rows


def _hashes(folder, module):
    """mutmut's hash of each function of ``module`` (mangled name -> hash) in the scratch copy ``folder``."""
    meta = folder / "mutants" / (module + ".meta")
    return json.loads(meta.read_text())["hash_by_function_name"]


def survivor(mutant):
    """A survivor's entry in a row: its name, function and statements (:class:`~tools.mutation.mutants.Mutant`)."""
    return {"mutant": mutant.name, "function": mutant.function, "original": mutant.original, "mutated": mutant.mutated}


def natural(name):
    """Sort key: mutant names with their numbers compared as numbers."""
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", name)]


#: The functions the last run in a copy's folder was limited to (``--functions``); absent after a run of them all.
_COVERED = "functions.json"


def _record_covered(folder, functions):
    """Note in ``folder`` the functions a run there is limited to (none: every function)."""
    path = folder / _COVERED
    if functions:
        path.write_text(json.dumps(sorted(functions)) + "\n")
    else:
        path.unlink(missing_ok=True)


def _check_covered(folder, module, functions):
    """Refuse to run again mutants the last run in ``folder`` did not cover: outside the functions it was limited
    to, mutmut's verdicts are "not checked", and a row from them would replace the module's with a part of it."""
    path = folder / _COVERED
    if not path.exists():
        return
    covered = json.loads(path.read_text())
    outside = sorted(set(functions or ()) - set(covered))
    if not functions or outside:
        names = ",".join(covered)
        raise SystemExit(
            f"mutation: the last run of {module} covered only the mutants of {names}: run them again with "
            f"--functions {names}, or the module afresh"
        )


def merged(before, part, functions):
    """The row of a full run ``before`` with the verdicts of ``functions`` replaced by those of ``part``.

    ``part`` is :func:`run_module`'s row of a run of those functions only.  Functions gone from the module
    are dropped; one not named must have the hash it had in ``before`` (its verdicts still hold), else
    SystemExit.  The functions run again since the full run accumulate in ``rerun``, with the test files each was
    run against last (the row's ``tests`` stay the full run's, which the other verdicts come from).
    """
    module = before["module"]
    if "by_function" not in before:
        raise SystemExit(f"mutation: the row of {module} has no verdicts per function: run the module in full first")
    now = part["by_function"]
    missing = sorted(set(functions) - set(now))
    if missing:
        raise SystemExit(f"mutation: {module} has no function {missing[0]!r}")
    stale = [f for f in now if f not in functions and before["by_function"].get(f, {}).get("hash") != now[f]["hash"]]
    if stale:
        raise SystemExit(f"mutation: {module}: {', '.join(stale)} changed since its full run: name it in --functions")
    verdicts = {f: now[f] if f in functions else before["by_function"][f] for f in now}
    counts = {s: sum(row.get(s, 0) for row in verdicts.values()) for s in STATUSES}
    kept = [s for s in before["survivors"] if s["function"] in verdicts and s["function"] not in functions]
    survivors = sorted(kept + part["survivors"], key=lambda s: natural(s["mutant"]))
    named = [f for f in dict.fromkeys([*before.get("rerun", {}).get("functions", ()), *functions]) if f in verdicts]
    mutants = sum(count for f in named for s, count in verdicts[f].items() if s != "hash")
    earlier = before.get("rerun", {}).get("tests", {})
    tests = {f: part["tests"] if f in functions else earlier.get(f, before["tests"]) for f in named}
    rerun = {"functions": named, "mutants": mutants, "seconds": part["seconds"], "tests": tests}
    return {
        **before,
        "mutants": sum(counts.values()),
        **counts,
        "survivors": survivors,
        "by_function": verdicts,
        "rerun": rerun,
        "measured": part["measured"],
    }


def run_module(module, work_dir, max_children, keep=None, seconds=None, progress=print, functions=None, again=None):
    """Mutate ``module``, run its tests on every mutant; its row: counts, survivors, verdicts per function.

    With ``keep="so-far"`` nothing runs: the row counts the mutants that an interrupted run checked (the
    rest are "not checked", outside the score), and its time is the sum of mutmut's times of the mutants
    run (their last runs), a little below the wall time.  With ``keep="survivors"`` only the survivors of
    the last run are run again (:func:`prepare`; the test selection must be the same, or mutmut resets
    every verdict), and ``seconds`` is the time of that last full run.  mutmut maps each test to the
    functions it calls once, when it first sees the test: a survivor is run against new tests and the tests
    that reached its function before, so kill it with a new test (or run the module afresh).  ``again``,
    if given, chooses which of those survivors run (a predicate on their
    :class:`~tools.mutation.mutants.Mutant`).  With ``functions`` only their mutants run, and the row counts
    those only (:func:`merged` puts it in the module's row).
    """
    folder = prepare(module, work_dir, keep)
    full = keep not in ("survivors", "so-far") or not (folder / "mutants").exists()
    if full:
        _record_covered(folder, functions)
    else:
        _check_covered(folder, module, functions)
    made = {m.name: m for m in module_mutants(module, (folder / module).read_text())}
    rerun = [] if full else [n for n, s in statuses(folder).items() if s == "survived"]
    rerun = sorted(
        n for n in rerun if (not functions or function_of(n) in functions) and (again is None or again(made[n]))
    )
    progress(
        f"mutation: {module} against {' '.join(MODULES[module])}"
        + ("" if full else ", so far" if keep == "so-far" else f", {len(rerun)} survivors again")
    )
    start = time.perf_counter()
    if keep == "so-far":
        if full:
            raise SystemExit(f"mutation: no interrupted run of {module} in {folder}")
        meta = [json.loads(f.read_text()) for f in (folder / "mutants").rglob("*.meta")]
        seconds = sum(d or 0.0 for m in meta for d in m["durations_by_key"].values())
    elif full or rerun:
        names = rerun or [pattern(module, f) for f in functions or ()]
        mutmut(folder, "run", "--max-children", str(max_children), *names, environment=ENVIRONMENT.get(module))
    if full or seconds is None:
        seconds = time.perf_counter() - start
    status = statuses(folder)
    verdicts = by_function(status, _hashes(folder, module))
    if functions:
        status = {n: s for n, s in status.items() if function_of(n) in functions}
    unknown = sorted(set(status) - set(made))
    if unknown:
        raise SystemExit(f"mutation: mutmut ran {unknown[0]}, a mutant not made again in process: another mutmut?")
    counts = {s: sum(v == s for v in status.values()) for s in STATUSES}
    progress(
        f"mutation: {module}: {len(status)} mutants, {counts['killed']} killed, {counts['survived']} survived, "
        f"{seconds:.0f} s"
    )
    return {
        "module": module,
        "tests": MODULES[module],
        "environment": ENVIRONMENT.get(module, {}),
        "max_children": max_children,
        "mutants": len(status),
        **counts,
        "seconds": round(seconds),
        "survivors": [
            survivor(made[n]) for n in sorted((n for n, s in status.items() if s == "survived"), key=natural)
        ],
        "by_function": verdicts,
        "measured": json.loads((folder / "measured.json").read_text()),
    }
