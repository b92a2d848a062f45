"""``python -m tools.mutation``: run mutmut on the algorithm modules, check the arguments, write the report.

Usage (from the repository's root, in an environment with the ``[mutation]`` extra; ``make mutation`` makes
one in ``.venv`` and passes ``MUTATION_ARGS`` and ``MODULES``)::

    python -m tools.mutation [--max-children 2] [MODULE ...]      # run (default: every module of the table)
    python -m tools.mutation --functions sharp_run,_grid_chain src/equimesh/planar/boundary/sides.py
    python -m tools.mutation --check                               # argued mutants the code no longer makes
    python -m tools.mutation --report                              # write the report again, run nothing
    python -m tools.mutation --carry OLD=NEW[,OLD=NEW...]          # a row to a moved or formatted module

The report is rewritten after each module, and the rows of modules run before are kept, so the modules can
be run one at a time.  ``--resume`` continues an interrupted module where mutmut stopped, ``--so-far``
writes the row of an interrupted module from the mutants it ran, ``--survivors`` runs only the survivors of
the module's last run again against the current tests (after adding the tests that should kill them), and
``--unexplained`` only those not argued in ``equivalent.toml``.  ``--functions F,G,...`` runs only the
mutants of the functions named (after they changed): their verdicts replace theirs in the module's row, and
every other function's stand from the last full run if its hash is unchanged (else it is refused).
"""

import argparse
import sys
from pathlib import Path

from . import carry, equivalent, report, run
from .modules import MODULES
from .mutants import module_mutants


def parse_args(argv=None):
    p = argparse.ArgumentParser(
        prog="python -m tools.mutation",
        description=__doc__.split("\n\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("modules", nargs="*", help="module paths (default: every module of the table)")
    p.add_argument("--max-children", type=int, default=2, help="parallel mutant runs (default 2)")
    p.add_argument("--work-dir", type=Path, default=run.ROOT / ".mutation", help="scratch folder (default .mutation/)")
    p.add_argument("--out-dir", type=Path, default=Path("results"), help="report folder (default results)")
    p.add_argument("--resume", action="store_true", help="keep the scratch copy of a module and its finished mutants")
    p.add_argument(
        "--so-far", action="store_true", help="write the rows of interrupted modules from the mutants already run"
    )
    p.add_argument(
        "--survivors",
        action="store_true",
        help="run only the last run's survivors again, against the current tests (keeps the other verdicts)",
    )
    p.add_argument(
        "--unexplained", action="store_true", help="as --survivors, but only the survivors not argued equivalent"
    )
    p.add_argument(
        "--functions",
        type=lambda text: text.split(","),
        metavar="F,G,...",
        help="run only the mutants of these functions of one module (comma-separated; Class.method for a "
        "method); the others keep the verdicts of its last full run",
    )
    p.add_argument(
        "--check",
        action="store_true",
        help="list the argued mutants the current code does not make (exit 1 if any); runs no test",
    )
    p.add_argument("--report", action="store_true", help="write the report again from the rows, with the arguments")
    p.add_argument(
        "--carry",
        type=lambda text: [tuple(pair.split("=", 1)) for pair in text.split(",")],
        metavar="OLD=NEW,...",
        help="carry the row of OLD to NEW (the same path if the module only changed its formatting), if every "
        "function and every statement outside them is the same as at the commit measured",
    )
    args = p.parse_args(argv)
    unknown = [m for m in args.modules + [new for _, new in args.carry or ()] if m not in MODULES]
    if unknown:
        p.error(f"unknown module {unknown[0]!r}; known: {', '.join(MODULES)}")
    if args.functions and (len(args.modules) != 1 or args.resume):
        p.error("--functions needs exactly one module, and no --resume")
    if any(len(pair) != 2 for pair in args.carry or ()):
        p.error("--carry takes OLD=NEW pairs")
    return args


def check(arguments):
    """Print the orphans and the wrong hints of ``arguments``; 1 if an argued mutant is an orphan, else 0."""
    try:
        import mutmut  # noqa: F401
    except ImportError:
        orphans, hints = equivalent.missing_originals(arguments), []
        print("mutation: mutmut not installed: only the original statements are checked")
    else:
        orphans, hints = equivalent.check(
            arguments, lambda m: module_mutants(m, (run.ROOT / m).read_text()) if m in MODULES else None
        )
    for module, function, original, mutated in orphans:
        print(f"orphan: {module} {function}: {original!r} -> {mutated!r}")
    for module, function, original, mutated, functions in hints:
        print(f"hint: {module}: {original!r} -> {mutated!r} is in {', '.join(functions)}, not {function}")
    print(f"mutation: {len(arguments.entries)} argued mutants, {len(orphans)} orphans, {len(hints)} wrong hints")
    return 1 if orphans else 0


def _unexplained(arguments, module):
    """Whether a mutant of ``module`` is argued by none of ``arguments`` (``--unexplained``)."""
    return lambda m: arguments.why(module, m.function, m.original, m.mutated) is None


def main(argv=None):
    args = parse_args(argv)
    arguments = equivalent.load()
    if args.check:
        return check(arguments)
    json_path = args.out_dir / f"{report.NAME}.json"
    args.out_dir.mkdir(parents=True, exist_ok=True)
    parameters = {"pytest_args": run.PYTEST_ARGS}
    if args.report or args.carry:
        rows = report.read_rows(json_path)
        for old, new in args.carry or ():
            if old not in rows:
                raise SystemExit(f"mutation: no row of {old} in {json_path}")
            rows[new] = carry.carried(rows.pop(old), new)
        report.write(args.out_dir, rows, arguments, parameters)
        return 0
    flags = ((args.survivors or args.unexplained, "survivors"), (args.resume, "resume"), (args.so_far, "so-far"))
    keep = next((kind for flag, kind in flags if flag), None)
    for module in args.modules or list(MODULES):
        again = _unexplained(arguments, module) if args.unexplained else None
        before = report.read_rows(json_path).get(module, {})
        seconds = (before.get("rerun", {}) if args.functions else before).get("seconds")
        row = run.run_module(
            module, args.work_dir, args.max_children, keep, seconds, functions=args.functions, again=again
        )
        rows = report.read_rows(json_path)  # read again: another process may have run other modules meanwhile
        if args.functions:
            if module not in rows:
                raise SystemExit(f"mutation: no full run of {module} in {json_path}: run it without --functions first")
            row = run.merged(rows[module], row, args.functions)
        rows[module] = row
        report.write(args.out_dir, rows, arguments, parameters)
    return 0


if __name__ == "__main__":
    sys.exit(main())
