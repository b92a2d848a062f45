"""PARDISO on one thread and on two: the measurement behind ``PARDISO_THREADS_FROM`` (``surface/optimize/solver.py``).

For each member length l, "bounded" on the reference dome (15 x 15 grid, default lattice placement, no size limit)
until its optimisation's fifth factorisation of more than ``MIN_VARIABLES`` variables; that normal matrix (the
first rounds', boundary sliding) is then factorised and solved ``REPEATS`` times in each of PARDISO's modes
(:data:`~equimesh.surface.optimize.solver.FACTORISATIONS` ``["pardiso"]``), the modes taking turns: sequential
(iparm 34 = 0) on one thread and on two, and reproducible for two threads (iparm 34 = 2) on one and on two.  It
gives the median milliseconds of a factorisation and of a solve, and whether the solution has the bits of the
mode's run on one thread (a hash of the solution of one right-hand side); and reproducibly with two solves at once
(on two threads of the interpreter, as the driver's solve beside the others runs), each on two threads or each on
one.  Run with nothing else on the machine.

Writes::

    results/pardiso_threads.csv               one row per l and mode
    results/pardiso_threads.md                the table, provenance
    results/pardiso_threads.provenance.json

Usage::

    python experiments/pardiso_threads.py [--lengths 3.5 2.5 1.8 1.25 0.88 0.52]
"""

import hashlib
import json
import statistics
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402

import equimesh  # noqa: E402
from equimesh.surface.optimize import solver  # noqa: E402

NAME = "pardiso_threads"
DOME = Path(__file__).resolve().parent / "surfaces" / "reference_dome.json"
LENGTHS = (3.5, 2.5, 1.8, 1.25, 0.88, 0.52)
#: The normal matrices of the flattening and of Problem 2's small solves are not the optimisation's.
MIN_VARIABLES = 1_000
CAPTURED = 5
REPEATS = 15
#: (mode, reproducible for this many threads (iparm 34), threads run on, solves at once).
MODES = (
    ("sequential", 0, 1, 1),
    ("sequential", 0, 2, 1),
    ("reproducible", 2, 1, 1),
    ("reproducible", 2, 2, 1),
    ("reproducible", 2, 2, 2),
    ("reproducible", 2, 1, 2),
)
COLUMNS = [
    "l",
    "variables",
    "upper_nonzeros",
    "mode",
    "threads",
    "at_once",
    "factorisation_ms",
    "solve_ms",
    "bits",
    "same_bits",
]


class _Captured(Exception):
    """The normal matrix was captured: the run ends here."""


def normal_matrix(length):
    """``(rows, cols, values, n)`` of the optimisation's :data:`CAPTURED`-th factorisation of more than
    :data:`MIN_VARIABLES` variables, "bounded" on the reference dome at ``length``."""
    original = solver.FACTORISATIONS["pardiso"]
    seen = []

    class Capture(original):
        def __init__(self, rows, cols, n, **options):
            super().__init__(rows, cols, n, **options)
            self._captured = (rows, cols, n)

        def factorise(self, values):
            rows, cols, n = self._captured
            if n > MIN_VARIABLES:
                seen.append(1)
                if len(seen) == CAPTURED:
                    raise _Captured(rows, cols, np.array(values), n)
            return super().factorise(values)

    surface = equimesh.surface_from_dict(json.loads(DOME.read_text()))
    solver.FACTORISATIONS["pardiso"] = Capture
    try:
        equimesh.mesh_surface(surface, length, optimize="bounded", placement="default", max_nodes=None)
    except _Captured as captured:
        return captured.args
    finally:
        solver.FACTORISATIONS["pardiso"] = original
    raise RuntimeError(f"fewer than {CAPTURED} factorisations of more than {MIN_VARIABLES} variables at l = {length}")


def timed_once(factor, values, rhs):
    """Seconds of one factorisation and of one solve, and the solution."""
    start = time.perf_counter()
    solve = factor.factorise(values)
    middle = time.perf_counter()
    x = solve(rhs)
    return middle - start, time.perf_counter() - middle, x


def measure(length):
    """The rows of one l: each mode of :data:`MODES` on its normal matrix (with two at once, the first solve's).

    The modes take turns, one factorisation and solve each per turn, :data:`REPEATS` turns: a change of the
    machine's load falls on every mode alike."""
    rows, cols, values, n = normal_matrix(length)
    rhs = np.arange(n, dtype=float) % 7 - 3
    pardiso = solver.FACTORISATIONS["pardiso"]
    factors = [
        [pardiso(rows, cols, n, threads=threads, reproducible=reproducible) for _ in range(at_once)]
        for _, reproducible, threads, at_once in MODES
    ]
    times = [[] for _ in MODES]
    with ThreadPoolExecutor(max_workers=2) as pool:
        for _ in range(REPEATS):
            for mode, group in enumerate(factors):
                runs = [pool.submit(timed_once, factor, values, rhs) for factor in group]
                times[mode].append(runs[0].result())
                for run in runs[1:]:
                    run.result()
    out, one_thread = [], {}
    for (mode, reproducible, threads, at_once), timed, group in zip(MODES, times, factors):
        bits = hashlib.sha256(np.ascontiguousarray(timed[-1][2]).tobytes()).hexdigest()[:12]
        factorisation, solve = (1e3 * statistics.median(t[k] for t in timed) for k in (0, 1))
        one_thread.setdefault(mode, bits)
        row = [length, n, len(values), mode, threads, at_once, factorisation, solve, bits, bits == one_thread[mode]]
        out.append(row)
        for factor in group:
            factor.release()
    return out


def summarize(df, record):
    body = [
        'The normal matrix of "bounded" on the reference dome at each l (its optimisation\'s fifth factorisation), '
        f"factorised and solved {REPEATS} times per mode, the modes in turn: median milliseconds; at once: solves "
        "running together, each on its threads (the first one's times); bits: the first hex digits of the "
        "solution's SHA-256; same bits: as the mode's run on one thread.",
        "",
        "| l | variables | upper nonzeros | mode | threads | at once | factorisation (ms) | solve (ms) | both (ms) "
        "| bits | same bits |",
        "|---:|---:|---:|---|---:|---:|---:|---:|---:|---|---|",
    ]
    for _, r in df.iterrows():
        both = r["factorisation_ms"] + r["solve_ms"]
        body.append(
            f"| {r['l']:g} | {r['variables']:,} | {r['upper_nonzeros']:,} | {r['mode']} | {r['threads']} "
            f"| {r['at_once']} "
            f"| {r['factorisation_ms']:.2f} | {r['solve_ms']:.2f} | {both:.2f} | `{r['bits']}` "
            f"| {'yes' if r['same_bits'] else 'no'} |"
        )
    return _common.markdown_report(
        "PARDISO on one thread and on two", "`python experiments/pardiso_threads.py`", body, record
    )


def parse_args(argv=None):
    p = _common.add_output_options(_common.parser(__doc__), fig_dir=False)
    p.add_argument("--lengths", type=float, nargs="+", default=list(LENGTHS), help="member lengths l")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    if "pardiso" not in solver.INSTALLED:
        print(f"{NAME}: pypardiso is not installed (extra mkl): nothing to measure", file=sys.stderr)
        return 0
    args.out_dir.mkdir(parents=True, exist_ok=True)
    df = pd.DataFrame([row for length in args.lengths for row in measure(length)], columns=COLUMNS)
    parameters = {"lengths": args.lengths, "repeats": REPEATS, "captured": CAPTURED, "out_dir": str(args.out_dir)}
    _common.write_results(args.out_dir / f"{NAME}.csv", df, parameters, lambda record: summarize(df, record))
    print(f"{NAME}: {len(args.lengths)} lengths, {len(df)} rows")
    return 0


if __name__ == "__main__":
    sys.exit(main())
