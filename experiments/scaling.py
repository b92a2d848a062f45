"""Scaling of Problem 1 and of ``equimesh mesh``: time and peak memory against the size, beside their peers.

Problem 1 (the default)
-----------------------

For each target size n (about n output points), each method runs in a fresh
process (so that its peak memory is its own), on the unit square:

* ``fast``, ``reference``: ``equimesh.increment(unit square, l, engine=...)``
  with ``l = sqrt(0.68 / n)`` (farthest-point insertion places about
  ``0.68 / l^2`` points per unit area); the whole call, validation, Step 2 and
  the Theorem 1 check included.  The reference engine runs only while its
  predicted time (the last run's, or :data:`REFERENCE_START`'s 0.44 s at 308 nodes,
  scaled by ``(n / n_last)^2.5``, :data:`REFERENCE_EXPONENT`) stays under ``--reference-limit`` seconds (a minute with
  ``--full``, 5 s in the default range, which should take about a minute);
* ``triangle``: Triangle's own quality refinement
  ``triangle.triangulate(square, "pqa<area>Q")``, the area bound set from n
  and corrected once to the vertex count of the fast engine (Triangle's
  "about the same number of vertices");
* ``scipy``: ``scipy.spatial.Delaunay`` of n uniformly random points (seeded),
  an unconstrained triangulation without insertion: the floor any mesh
  generator pays.

Each call is timed by the wall clock (``seconds``, what the user waits) and
by the CPU time of its process (``cpu_seconds``, less sensitive to other jobs
on a shared machine).  Peak memory is the process's resident high-water mark (``ru_maxrss``) after
the call minus the same before it (imports and the input), in MB.  The
exponent of each method is fitted by least squares on the logs
(``np.polyfit(log n, log t, 1)``) over the sizes where its time is above
``--fit-floor`` seconds (timer and start-up noise below).

Writes (``results/`` data, ``paper_figs/`` figure drawn from the data only)::

    results/scaling.csv, .md, .provenance.json    one row per (method, size); fitted exponents;
                                                  the fast engine's time per point against Triangle's
    paper_figs/scaling.png, .pdf, .provenance.json  log-log time and memory against n

Section 4 (``--pipeline``)
--------------------------
``equimesh mesh experiments/surfaces/reference_dome.json --length L --max-nodes none``
with the default objective, in a fresh process per run, once per installed
factorisation of the optimisation (:data:`equimesh.surface.optimize.solver.INSTALLED`,
each chosen by the environment variable ``EQUIMESH_FACTORISATION`` in that process
alone), with ``L`` set from the target member count (:data:`PIPELINE_MEMBERS`
members at ``L = 0.5``, about ``1 / L^2``); beside it gmsh's Frontal-Delaunay on
the same Bezier patch at the same size (``experiments/compare_peers.py``'s call,
when gmsh is installed).  A run records the wall time of the command in its
process (``seconds``, the call of ``equimesh._cli.main``: reading, every stage,
writing the mesh; ``cpu_seconds``, the CPU time of its process, less sensitive to
other jobs on a shared machine), each stage's time from the command's progress lines, and
the process's peak resident memory (``peak_mb``, not above a baseline: what the
machine must have).  A run predicted (from the last size, as ``n^PIPELINE_EXPONENT``)
above ``--pipeline-limit`` seconds is skipped.  Exponents are fitted as above, on the
CPU times.

Writes::

    results/pipeline_scaling.csv, .md, .provenance.json   one row per (method, size); exponents; ratios to gmsh
    paper_figs/pipeline_scaling.png, .pdf, .provenance.json  log-log time and memory against members

Usage::

    python experiments/scaling.py            # 10^2 .. 3 10^4, about a minute
    python experiments/scaling.py --full     # 10^2 .. 10^6 (several minutes, ~1 GB)
    python experiments/scaling.py --plot-only
    python experiments/scaling.py --pipeline         # 2,500 .. 10^4 members, under a minute
    python experiments/scaling.py --pipeline --full  # 10^4, 10^5, 10^6 members (an hour or more)
    python experiments/scaling.py --pipeline --sizes 1000000 --methods "equimesh cholmod" "gmsh Frontal-Delaunay"
"""

import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402

NAME = "scaling"
METHODS = ("fast", "reference", "triangle", "scipy")
DEFAULT_SIZES = (100, 300, 1000, 3000, 10000, 30000)
FULL_SIZES = (100, 300, 1000, 3000, 10000, 30000, 100000, 300000, 1000000)
#: Points per unit area of farthest-point insertion at spacing l = 1 (measured on squares).
DENSITY = 0.68
#: Exponent used to predict the reference engine's next run, and the run it starts from
#: before it has run (a measured start: 0.44 s for 308 nodes).
REFERENCE_EXPONENT = 2.5
REFERENCE_START = {"n_target": 308, "seconds": 0.44}
COLUMNS = ["method", "n_target", "n_points", "seconds", "cpu_seconds", "us_per_point", "peak_mb", "first_call_s"]

SQUARE = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]

PIPELINE_NAME = "pipeline_scaling"
DOME = Path(__file__).resolve().parent / "surfaces" / "reference_dome.json"
#: Members of the reference dome at l = 0.5 (`equimesh mesh ... --length 0.5`); about 1 / l^2 at other l.
PIPELINE_MEMBERS = 110_082
PIPELINE_SIZES = (2500, 5000, 10000)
PIPELINE_FULL_SIZES = (10_000, 100_000, 1_000_000)
#: Exponent that predicts a pipeline run's time from the last size's (measured: about 1.3 with CHOLMOD).
PIPELINE_EXPONENT = 1.5
PIPELINE_COLUMNS = ["method", "n_target", "length", "nodes", "members", "seconds", "cpu_seconds", "peak_mb", "stages"]
GMSH = "gmsh Frontal-Delaunay"


def _peak_mb():
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _clocked(function, *args, **kwargs):
    """``(result, wall seconds, CPU seconds of this process)`` of one call."""
    cpu = time.process_time()
    out, seconds = _common.timed(function, *args, **kwargs)
    return out, seconds, time.process_time() - cpu


def measure(method, n, like=None):
    """One method at one size, in this process: a dict of the columns (``like``: Triangle's target vertex count)."""
    first_s = 0.0
    if method in ("fast", "reference"):
        import equimesh

        first, first_s = _common.timed(equimesh.increment, [[0, 0], [3, 0], [3, 3], [0, 3]], 1.0, engine=method)
        base = _peak_mb()
        mesh, seconds, cpu = _clocked(equimesh.increment, SQUARE, math.sqrt(DENSITY / n), engine=method, max_nodes=None)
        points = mesh.n_nodes
    elif method == "triangle":
        import triangle

        square = {"vertices": np.array(SQUARE), "segments": [[0, 1], [1, 2], [2, 3], [3, 0]]}
        target = like or n
        area = 1.0 / target
        base = _peak_mb()
        for _ in range(2):  # the second run with the area bound corrected to the target vertex count
            out, seconds, cpu = _clocked(triangle.triangulate, square, f"pqa{area:.20f}Q")
            points = len(out["vertices"])
            area *= points / target
    else:
        from scipy.spatial import Delaunay

        xy = np.random.default_rng(n).random((n, 2))
        base = _peak_mb()
        _, seconds, cpu = _clocked(Delaunay, xy)
        points = n
    return {
        "method": method,
        "n_target": n,
        "n_points": int(points),
        "seconds": seconds,
        "cpu_seconds": cpu,
        "us_per_point": 1e6 * seconds / points,
        "peak_mb": _peak_mb() - base,
        "first_call_s": first_s,
    }


def _run(method, n, like=None):
    """:func:`measure` in a fresh interpreter (its own peak memory); the row."""
    args = [sys.executable, __file__, "--one", method, str(n)] + ([str(like)] if like else [])
    proc = subprocess.run(args, capture_output=True, text=True, check=True)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def pipeline_length(members):
    """The member length at which the reference dome has about ``members`` members."""
    return 0.5 * math.sqrt(PIPELINE_MEMBERS / members)


def measure_pipeline(method, members):
    """``equimesh mesh`` (method ``equimesh <factorisation>``) or gmsh at ``members``, in this process: the row.

    The factorisation is the one named by ``EQUIMESH_FACTORISATION`` in this
    process's environment (:func:`_run_pipeline` sets it).
    """
    import io
    from contextlib import redirect_stderr, redirect_stdout

    l = pipeline_length(members)
    if method == GMSH:
        import compare_peers

        import equimesh

        surface = equimesh.load_surface(DOME)
        (points, triangles), seconds, cpu = _clocked(
            compare_peers._gmsh(compare_peers.GMSH_ALGORITHMS["Frontal-Delaunay"]), surface, l
        )
        from equimesh.mesh import unique_edges

        nodes, count, stages = len(points), len(unique_edges(triangles)), {}
    else:
        from equimesh._cli import main as cli
        from equimesh.surface.optimize.solver import DEFAULT_FACTORISATION

        if method != f"equimesh {DEFAULT_FACTORISATION}":  # the environment chose another: the row would lie
            raise RuntimeError(f"{method} measured with the factorisation {DEFAULT_FACTORISATION}")
        with tempfile.TemporaryDirectory() as folder:
            err = io.StringIO()
            argv = ["mesh", str(DOME), "--length", repr(l), "--max-nodes", "none", "-o", str(Path(folder) / "m.vtu")]
            with redirect_stderr(err), redirect_stdout(io.StringIO()):
                code, seconds, cpu = _clocked(cli, argv)
        text = err.getvalue()
        if code != 0:
            raise RuntimeError(f"equimesh mesh exited {code}: {text.strip()}")
        stages = {m[1]: float(m[2]) for m in re.finditer(r"^  (.+): ([0-9.]+) s$", text, re.M)}
        nodes, count = (int(v) for v in re.search(r": (\d+) nodes, (\d+) members", text).groups())
    return {
        "method": method,
        "n_target": members,
        "length": l,
        "nodes": nodes,
        "members": count,
        "seconds": seconds,
        "cpu_seconds": cpu,
        "peak_mb": _peak_mb(),
        "stages": json.dumps(stages),
    }


def pipeline_methods():
    """The methods of the pipeline sweep: ``equimesh <factorisation>`` for each installed one, then gmsh if there."""
    from equimesh.surface.optimize.solver import INSTALLED

    try:
        import gmsh  # noqa: F401
    except ImportError:
        return [f"equimesh {name}" for name in INSTALLED]
    return [f"equimesh {name}" for name in INSTALLED] + [GMSH]


def _run_pipeline(method, members):
    """:func:`measure_pipeline` in a fresh interpreter with the method's factorisation; the row."""
    from equimesh.surface.optimize.solver import FACTORISATION_VARIABLE

    env = dict(os.environ)
    if method != GMSH:
        env[FACTORISATION_VARIABLE] = method.split()[-1]
    args = [sys.executable, __file__, "--one-pipeline", method, str(members)]
    proc = subprocess.run(args, capture_output=True, text=True, check=True, env=env)
    return json.loads(proc.stdout.strip().splitlines()[-1])


#: Members of the untimed run before a sweep: it compiles equimesh's kernels into numba's on-disk cache, so that the
#: first timed method does not pay the compilation (about 20 s, once per installation) that the others would not.
PIPELINE_WARM_UP = 1_000


def pipeline_sweep(sizes, limit, methods=None, progress=print):
    """Rows for every pipeline method (of ``methods``, all by default) and size, smallest size first; a run predicted
    above ``limit`` s is skipped.  An untimed run of :data:`PIPELINE_WARM_UP` members goes first."""
    chosen = [m for m in pipeline_methods() if methods is None or m in methods]
    if any(m != GMSH for m in chosen):
        _run_pipeline(next(m for m in chosen if m != GMSH), PIPELINE_WARM_UP)
    rows, last = [], {}
    for n in sizes:
        for method in chosen:
            if method in last and last[method]["seconds"] * (n / last[method]["n_target"]) ** PIPELINE_EXPONENT > limit:
                continue
            last[method] = _run_pipeline(method, n)
            rows.append(last[method])
        progress(
            f"{n} members: " + ", ".join(f"{r['method']} {r['seconds']:.3g} s" for r in rows if r["n_target"] == n)
        )
    return pd.DataFrame(rows, columns=PIPELINE_COLUMNS)


def pipeline_exponents(frame):
    """Fitted exponent of CPU time (what other jobs on the machine change least) against members per method:
    ``{method: (slope, n_sizes)}``."""
    renamed = frame.drop(columns="seconds").rename(columns={"members": "n_points", "cpu_seconds": "seconds"})
    return exponents(renamed, 0.0)


def pipeline_report(frame, record):
    body = _exponent_table("CPU time ~ members^k", pipeline_exponents(frame))
    body += ["", "## Each run against gmsh Frontal-Delaunay at the same size", ""]
    body += [
        "| members (target) | method | members | nodes | seconds | CPU seconds | ratio to gmsh | ratio of CPU time | "
        "peak MB | optimisation (s) |"
    ]
    body += ["|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for n, group in frame.groupby("n_target"):
        peer = group[group["method"] == GMSH]
        wall, cpu = (float(peer[c].iloc[0]) if len(peer) else float("nan") for c in ("seconds", "cpu_seconds"))
        for row in group.itertuples(index=False):
            stages = json.loads(row.stages)
            optimisation = stages.get("optimisation of inner nodes", float("nan"))
            body.append(
                f"| {n:,} | {row.method} | {row.members:,} | {row.nodes:,} | {row.seconds:.3g} | "
                f"{row.cpu_seconds:.3g} | {row.seconds / wall:.2f} | {row.cpu_seconds / cpu:.2f} | "
                f"{row.peak_mb:.0f} | {optimisation:.3g} |"
            )
    body += ["", "## Stage times (s)", "", "| members (target) | method | stages |", "|---:|---|---|"]
    body += [
        f"| {row.n_target:,} | {row.method} | "
        + ", ".join(f"{k} {v:.3g}" for k, v in json.loads(row.stages).items())
        + " |"
        for row in frame.itertuples(index=False)
        if row.method != GMSH
    ]
    return _common.markdown_report(
        "Scaling of equimesh mesh (reference dome, default objective) against gmsh",
        "`python experiments/scaling.py --pipeline`",
        body,
        record,
    )


def pipeline_plot(frame, fig_dir, parameters):
    _plot(
        frame,
        ("members", "cpu_seconds", "CPU seconds", "equimesh mesh against gmsh"),
        "peak resident memory (MB)",
        Path(fig_dir) / PIPELINE_NAME,
        parameters,
    )


def _plot(frame, axes, memory, path, parameters):
    """Log-log time and peak memory against size per method; ``axes`` = (size column, time column, its label,
    title), ``memory`` the memory axis's label."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    size, time_column, time_label, title = axes
    fig, (ax_t, ax_m) = plt.subplots(1, 2, figsize=(10, 4))
    for method, group in frame.groupby("method", sort=False):
        ax_t.loglog(group[size], group[time_column], "o-", label=method)
        ax_m.loglog(group[size], np.maximum(group["peak_mb"], 0.1), "o-", label=method)
    ax_t.set(xlabel=size, ylabel=time_label, title=title)
    ax_m.set(xlabel=size, ylabel=memory, title="memory")
    ax_t.legend()
    fig.tight_layout()
    _common.save_figure(fig, path, parameters, dpi=120)
    plt.close(fig)


def sweep(sizes, reference_limit, progress=print):
    """Rows for every method and size, smallest size first."""
    rows, last_reference = [], REFERENCE_START
    for n in sizes:
        fast = _run("fast", n)
        rows.append(fast)
        rows.append(_run("triangle", n, fast["n_points"]))
        rows.append(_run("scipy", n))
        if last_reference["seconds"] * (n / last_reference["n_target"]) ** REFERENCE_EXPONENT < reference_limit:
            last_reference = _run("reference", n)
            rows.append(last_reference)
        progress(f"n = {n}: " + ", ".join(f"{r['method']} {r['seconds']:.3g} s" for r in rows if r["n_target"] == n))
    return pd.DataFrame(rows, columns=COLUMNS)


def exponents(frame, floor):
    """Fitted exponent of time against points per method: ``{method: (slope, n_sizes)}`` (nan below two sizes)."""
    out = {}
    for method, group in frame.groupby("method", sort=False):
        g = group[group["seconds"] >= floor]
        slope = np.polyfit(np.log(g["n_points"]), np.log(g["seconds"]), 1)[0] if len(g) >= 2 else float("nan")
        out[method] = (float(slope), len(g))
    return out


def _exponent_table(law, fits):
    """The Markdown lines of the fitted exponents ``fits`` (:func:`exponents`) of the power ``law``."""
    lines = [
        f"## Fitted exponents ({law}, least squares on the logs)",
        "",
        "| method | k | sizes fitted |",
        "|---|---|---|",
    ]
    return lines + [f"| {m} | {k:.3f} | {c} |" for m, (k, c) in fits.items()]


def report(frame, floor, record):
    body = _exponent_table("time ~ n^k", exponents(frame, floor))
    body += [
        "",
        "## Fast engine against Triangle's quality refinement (time per output point)",
        "",
        "| n (fast) | fast us/point | n (Triangle) | Triangle us/point | ratio | ratio of CPU time per point | fast "
        "peak MB |",
        "|---|---|---|---|---|---|---|",
    ]
    for n, group in frame.groupby("n_target"):
        f = group[group["method"] == "fast"].iloc[0]
        t = group[group["method"] == "triangle"].iloc[0]
        body.append(
            f"| {f.n_points} | {f.us_per_point:.3g} | {t.n_points} | {t.us_per_point:.3g} | "
            f"{f.us_per_point / t.us_per_point:.2f} | "
            f"{(f.cpu_seconds / f.n_points) / (t.cpu_seconds / t.n_points):.2f} | {f.peak_mb:.0f} |"
        )
    body += ["", "## All runs", "", "| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    body += [
        "| " + " | ".join(f"{v:.4g}" if isinstance(v, float) else str(v) for v in row) + " |"
        for row in frame.itertuples(index=False)
    ]
    return _common.markdown_report(
        "Scaling of Problem 1 (unit square)", "`python experiments/scaling.py`", body, record
    )


def plot(frame, fig_dir, parameters):
    _plot(
        frame,
        ("n_points", "seconds", "seconds", "time"),
        "peak memory above baseline (MB)",
        Path(fig_dir) / NAME,
        parameters,
    )


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["--one"]:
        print(json.dumps(measure(argv[1], int(argv[2]), int(argv[3]) if len(argv) > 3 else None)))
        return 0
    if argv[:1] == ["--one-pipeline"]:
        print(json.dumps(measure_pipeline(argv[1], int(argv[2]))))
        return 0
    p = _common.add_output_options(_common.parser(__doc__), plot_only=True)
    p.add_argument("--full", action="store_true", help="sizes 10^2 .. 10^6 (default: 10^2 .. 3 10^4)")
    p.add_argument("--sizes", type=int, nargs="+", help="explicit target sizes (overrides --full)")
    p.add_argument(
        "--reference-limit",
        type=float,
        help="skip a reference run predicted above this (default 60 s with --full, else 5 s)",
    )
    p.add_argument("--fit-floor", type=float, default=0.01, help="fit exponents on times above this (s)")
    p.add_argument("--pipeline", action="store_true", help="equimesh mesh on the reference dome against gmsh")
    p.add_argument(
        "--pipeline-limit",
        type=float,
        default=3600.0,
        help="skip a pipeline run predicted above this many seconds (default 3600)",
    )
    p.add_argument("--methods", nargs="+", help="the pipeline methods to run, e.g. 'equimesh cholmod' (default: all)")
    args = p.parse_args(argv)
    if args.pipeline:
        return pipeline_main(args)
    csv = args.out_dir / f"{NAME}.csv"
    sizes = args.sizes or (FULL_SIZES if args.full else DEFAULT_SIZES)
    limit = args.reference_limit if args.reference_limit is not None else (60.0 if args.full else 5.0)
    parameters = {"sizes": list(sizes), "reference_limit": limit, "fit_floor": args.fit_floor}
    if args.plot_only:
        frame = pd.read_csv(csv)
    else:
        frame = sweep(sizes, limit)
        args.out_dir.mkdir(parents=True, exist_ok=True)
        _common.write_results(csv, frame, parameters, lambda record: report(frame, args.fit_floor, record))
    args.fig_dir.mkdir(parents=True, exist_ok=True)
    plot(frame, args.fig_dir, parameters)
    for method, (k, count) in exponents(frame, args.fit_floor).items():
        print(f"{method}: time ~ n^{k:.2f} ({count} sizes)")
    return 0


def pipeline_main(args):
    """``--pipeline``: the sweep of ``equimesh mesh``, its report and figure."""
    csv = args.out_dir / f"{PIPELINE_NAME}.csv"
    sizes = args.sizes or (PIPELINE_FULL_SIZES if args.full else PIPELINE_SIZES)
    parameters = {
        "sizes": list(sizes),
        "pipeline_limit": args.pipeline_limit,
        "methods": args.methods,
        "surface": DOME.name,
    }
    if args.plot_only:
        frame = pd.read_csv(csv)
    else:
        frame = pipeline_sweep(sizes, args.pipeline_limit, args.methods)
        args.out_dir.mkdir(parents=True, exist_ok=True)
        _common.write_results(csv, frame, parameters, lambda record: pipeline_report(frame, record))
    args.fig_dir.mkdir(parents=True, exist_ok=True)
    pipeline_plot(frame, args.fig_dir, parameters)
    for method, (k, count) in pipeline_exponents(frame).items():
        print(f"{method}: time ~ members^{k:.2f} ({count} sizes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
