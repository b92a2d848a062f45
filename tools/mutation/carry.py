"""Carrying a row to a module that moved or was reformatted since it was measured, where the code is the same.

A row says which commit it measured (``measured``; a row written before rows said so measured the commit
that first held it in ``results/mutation.json``).  :func:`carried` moves it to the module's current path only
if the current module is that commit's module up to formatting, docstrings and imports: every function (and
method) has the same syntax tree, docstrings aside, and so has every statement outside them but the imports.
Then mutmut makes the same mutants, in the same order, of both; each survivor is checked to be the same
mutant (the same function and statements) and is renamed to its current name.  The row keeps its commit and
records its old path; the test files of its selection that changed since that commit (other than in
formatting, docstrings and imports) are listed with it, their verdicts being those of that commit's tests.
"""

import ast
import copy
import json
import subprocess

from .modules import ENVIRONMENT, MODULES
from .mutants import dotted, function_of, module_mutants
from .run import ROOT, STATUSES, survivor

#: Where the rows are kept, from the repository's root.
RESULTS = "results/mutation.json"


def _git(*args):
    return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=True).stdout


def _verdicts(row):
    """What a row measured: its counts and its survivors' names (not the arguments, reworded at times)."""
    return row["mutants"], [row.get(s, 0) for s in STATUSES], sorted(s["mutant"] for s in row["survivors"])


def introduced(module, row):
    """The first commit whose ``results/mutation.json`` holds ``row``'s verdicts for ``module``."""
    for commit in _git("log", "--reverse", "--topo-order", "--format=%H", "--", RESULTS).split():
        rows = {m["module"]: m for m in json.loads(_git("show", f"{commit}:{RESULTS}"))["modules"]}
        if module in rows and _verdicts(rows[module]) == _verdicts(row):
            return commit
    raise SystemExit(f"mutation: no commit holds the row of {module}")


def _without_docstrings(node):
    """``ast.dump`` of ``node`` without the docstrings of its functions and classes."""
    node = copy.deepcopy(node)
    for n in ast.walk(node):
        body = getattr(n, "body", None)
        if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and body:
            if isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                n.body = body[1:] or [ast.Pass()]
    return ast.dump(node, annotate_fields=False)


def shape(code):
    """What formatting, docstrings and imports leave of ``code``: function -> its tree, and the rest in order."""
    functions, rest = {}, []
    for node in ast.parse(code).body:
        if isinstance(node, (ast.Import, ast.ImportFrom)) or (
            isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)
        ):
            continue
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            functions[node.name] = _without_docstrings(node)
        elif isinstance(node, ast.ClassDef):
            methods = [m for m in node.body if isinstance(m, (ast.FunctionDef, ast.AsyncFunctionDef))]
            functions.update((f"{node.name}.{m.name}", _without_docstrings(m)) for m in methods)
            shell = copy.copy(node)
            shell.body = [n for n in node.body if n not in methods] or [ast.Pass()]
            rest.append(_without_docstrings(shell))
        else:
            rest.append(ast.dump(node, annotate_fields=False))
    return functions, rest


def carried(row, new):
    """``row`` (of a module measured at some commit, at some path) as the row of ``new``, the same code now.

    SystemExit if the code differs, or if a survivor is not the same mutant now.
    """
    old = row["module"]
    commit = row.get("measured", {}).get("commit") or introduced(old, row)
    then, now = _git("show", f"{commit}:{old}"), (ROOT / new).read_text()
    (functions_then, rest_then), (functions_now, rest_now) = shape(then), shape(now)
    changed = sorted(
        f for f in functions_then.keys() | functions_now.keys() if functions_then.get(f) != functions_now.get(f)
    )
    if changed or rest_then != rest_now:
        what = ", ".join(changed) or "the code outside its functions"
        raise SystemExit(f"mutation: {new} is not {old} of {commit[:7]} but for formatting: {what} changed")
    if row["tests"] != MODULES[new]:
        raise SystemExit(f"mutation: {old} was measured against {row['tests']}, {new} is against {MODULES[new]}")
    made_then = {m.name: m for m in module_mutants(old, then)}
    made_now = {m.name: m for m in module_mutants(new, now)}
    survivors = []
    for s in row["survivors"]:
        name = dotted(new) + s["mutant"][len(dotted(old)) :]
        before, after = made_then.get(s["mutant"]), made_now.get(name)
        if before is None or after is None or before[1:] != after[1:]:
            raise SystemExit(f"mutation: survivor {s['mutant']} of {old} is not {name} of {new}")
        survivors.append(survivor(after))
    tests_changed = [t for t in row["tests"] if shape(_git("show", f"{commit}:{t}")) != shape((ROOT / t).read_text())]
    carried_row = {k: v for k, v in row.items() if k not in ("equivalent", "score")}
    if "by_function" in row:
        from mutmut.mutation.file_mutation import compute_function_hashes

        hashes = {function_of(f): h for f, h in compute_function_hashes(now).items()}
        carried_row["by_function"] = {f: {**v, "hash": hashes.get(f)} for f, v in row["by_function"].items()}
    return {
        **carried_row,
        "module": new,
        "environment": ENVIRONMENT.get(new, {}),
        "survivors": survivors,
        "measured": {**row.get("measured", {}), "commit": commit, "path": old, "tests changed": tests_changed},
    }
