"""``results/mutation.md`` and ``results/mutation.json``: the rows of the modules measured, with provenance.

A row is what :func:`tools.mutation.run.run_module` returns: the counts per status, every survivor with its
statements, the verdicts per function and the commit measured.  Each time the files are written the
survivors are matched again to the arguments of ``equivalent.toml`` (:func:`scored`), so an argument added
or re-keyed shows without a run.  Score = (killed + timed out) / (mutants - equivalent survivors - mutants no
test reaches - mutants skipped or not checked).  A module of the table without a row is listed as not
measured.
"""

import json
from pathlib import Path

from equimesh.io._atomic import atomic_write_text
from equimesh.io.provenance import provenance_markdown, provenance_path, write_provenance

from .modules import MODULES

NAME = "mutation"
COMMAND = "`make mutation` (`python -m tools.mutation`)"


def scored(row, arguments):
    """``row`` with its survivors' arguments, the equivalent count and the score filled in."""
    survivors = [
        {**s, "equivalent": arguments.why(row["module"], s["function"], s["original"], s["mutated"])}
        for s in row["survivors"]
    ]
    equivalent = sum(s["equivalent"] is not None for s in survivors)
    left_out = equivalent + row["no tests"] + row["skipped"] + row.get("not checked", 0)
    relevant = row["mutants"] - left_out
    score = (row["killed"] + row["timeout"]) / relevant if relevant else 1.0
    return {**row, "survivors": survivors, "equivalent": equivalent, "score": score}


def read_rows(json_path):
    """Module -> its row in ``json_path`` (from earlier runs; empty if there is none)."""
    return {m["module"]: m for m in json.loads(json_path.read_text())["modules"]} if json_path.exists() else {}


def _measured(row):
    """The "measured at" cell: the commit, whether its code had changes, and the path it had then."""
    measured = row["measured"]
    text = f"`{measured['commit'][:7]}`" + (" + changes" if measured.get("dirty") else "")
    return text + (f" as `{measured['path']}`" if measured.get("path", row["module"]) != row["module"] else "")


def markdown(rows, record, table=MODULES):
    """The Markdown report of ``rows`` (module -> scored row), every module of ``table`` in its order."""
    body = [
        "A mutant is killed when one of its module's tests fails.  Score = (killed + timed out) /",
        "(mutants - equivalent survivors - mutants no test reaches).  Goal: >= 90 % per module.",
        "A row measured at an earlier commit, or under another path, holds for the current code only",
        "where that code is the same but for formatting (`--carry` checks it, function by function);",
        "a module marked not measured has no row for its current code (`make mutation MODULES=...`).",
        "",
        "| module | tests | mutants | killed | survived | equivalent | timed out | no tests | score | time "
        "| measured at |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|",
    ]
    for module, tests in table.items():
        m = rows.get(module)
        if m is None:
            body.append(f"| `{module}` | {', '.join(tests)} | not measured |  |  |  |  |  |  |  |  |")
            continue
        tests = " ".join([*(f"{k}={v}" for k, v in m.get("environment", {}).items()), ", ".join(m["tests"])])
        body.append(
            f"| `{m['module']}` | {tests} | {m['mutants']} | {m['killed']} | {m['survived']} "
            f"| {m['equivalent']} | {m['timeout']} | {m['no tests']} | {100 * m['score']:.1f} % | {m['seconds']} s "
            f"| {_measured(m)} |"
        )
    for m in (rows[module] for module in table if module in rows):
        body += ["", f"## Survivors in `{m['module']}`", ""]
        if "tests changed" in m["measured"]:
            changed = ", ".join(m["measured"]["tests changed"]) or "none"
            body += [
                f"Measured at {_measured(m)} and carried (`--carry`): its functions and the statements outside them "
                "are the same now but for formatting, docstrings and imports.  Test files of its selection changed "
                f"since (the verdicts are those of the tests then): {changed}.",
                "",
            ]
        if m.get("rerun"):
            tests = m["rerun"].get("tests", {})
            other = [
                f"`{f}` against {', '.join(tests[f])}"
                for f in m["rerun"]["functions"]
                if tests.get(f, m["tests"]) != m["tests"]
            ]
            against = f"; {'; '.join(other)}" if other else ""
            body += [
                f"Only the mutants of {', '.join(f'`{f}`' for f in m['rerun']['functions'])} "
                f"({m['rerun']['mutants']}) were run again (`--functions`, the last run {m['rerun']['seconds']} s"
                f"{against}); the other functions' verdicts, the test files in the table and the time are from the "
                "module's last full run.",
                "",
            ]
        if m.get("not checked"):
            how = (
                "`--functions` with the functions left runs them" if m.get("rerun") else "`--resume` continues the run"
            )
            body += [
                f"Interrupted: {m['not checked']} of {m['mutants']} mutants not run (not in the score; {how}).",
                "",
            ]
        if not m["survivors"]:
            body.append("None.")
        for s in m["survivors"]:
            why = s["equivalent"] or "**not explained: a test is missing**"
            body.append(f"- `{s['mutant']}`: `{s['mutated']}` — {why}")
    return "\n".join(
        [
            "# Mutation testing of the algorithm modules",
            "",
            f"Generated by {COMMAND}; do not edit by hand.",
            "",
            *body,
            "",
            *provenance_markdown(record),
        ]
    )


def write(out_dir, rows, arguments, parameters):
    """Write ``mutation.json``, its provenance and ``mutation.md`` for ``rows`` of modules in the table."""
    scored_rows = {module: scored(rows[module], arguments) for module in MODULES if module in rows}
    json_path = Path(out_dir) / f"{NAME}.json"
    atomic_write_text(json_path, json.dumps({"modules": list(scored_rows.values())}, indent=1) + "\n")
    record = write_provenance(provenance_path(json_path), {**parameters, "modules": list(scored_rows)})
    atomic_write_text(json_path.with_suffix(".md"), markdown(scored_rows, record) + "\n")
