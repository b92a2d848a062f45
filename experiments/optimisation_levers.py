"""Levers on the work of "bounded"'s optimisation, each solved beside today's in one run: starts and round constants.

The rounds of the default objective (docs/decisions.md, "The bounded objective") are most of a run's time, one
factorisation per iteration (docs/performance.md, "The final optimisation").  On the reference dome (15 x 15 grid,
default lattice placement, no size limit) at each l, :func:`equimesh.mesh_surface` gives bounded's result and its
remapped start; :func:`equimesh.optimize_uv` then solves "bounded" again, boundary nodes sliding as in the pipeline,

* from the remapped mesh, as the pipeline solves it ("today": its Jacobians must be the pipeline's, else this
  script is not measuring what the pipeline runs, and it stops);
* from bounded's own result: the floor of any start;
* from the remapped mesh moved by bounded's displacement smoothed by ``SMOOTHINGS`` Jacobi steps of the mesh's
  graph Laplacian (``d <- (d + mean of the neighbours' d) / 2``, boundary nodes held at their remapped place): what
  a start that carries only the smooth part of the answer can save (a coarse-to-fine solve, a flattening that
  targets lengths on the surface, a global local-global pass);
* from the optimum of the paper's objective (``optimize="paper"``, boundary fixed);
* from the remapped mesh with one constant of the rounds changed (``CONSTANTS``: fewer iterations per round, a
  larger trust region per node, a looser end of a series).

Each row: the solver's Jacobian evaluations (``njev``, one factorisation each), the share of members within 0.5 %
of l, whether every member is in [l, 2l], the solve's wall seconds, and both counts over today's.  Run with nothing
else on the machine (the seconds; the Jacobians do not depend on it).

Writes::

    results/optimisation_levers.csv               one row per l and lever
    results/optimisation_levers.md                the table, provenance
    results/optimisation_levers.provenance.json

Usage::

    python experiments/optimisation_levers.py [--lengths 2.5 1.0] [--quick]
"""

import contextlib
import json
import sys
import time
from pathlib import Path
from unittest import mock

import numpy as np
import pandas as pd
import scipy.sparse

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402

import equimesh  # noqa: E402
from equimesh.errors import EquimeshError  # noqa: E402
from equimesh.surface.optimize import objectives, solver  # noqa: E402
from equimesh.surface.optimize.members import Members  # noqa: E402

NAME = "optimisation_levers"
DOME = Path(__file__).resolve().parent / "surfaces" / "reference_dome.json"
LENGTHS = (2.5, 1.0)
QUICK_LENGTHS = (5.0,)
#: Jacobi steps of the smoothing of bounded's displacement (a few edges, and about ten).
SMOOTHINGS = (10, 100)
#: Constants of the rounds (:mod:`equimesh.tolerance`, as :mod:`~equimesh.surface.optimize.objectives` reads them)
#: and the value each is tried at (today's in brackets in the report).
CONSTANTS = (("BOUNDED_ROUND_ITERATIONS", 2), ("BOUNDED_STEP", 0.2), ("BOUNDED_LOSS_TOL", 1e-2))
#: Members within this relative deviation of l count as exact (the 0.5 % of every share).
BAND = 0.005
COLUMNS = [
    "l",
    "nodes",
    "members",
    "lever",
    "outcome",
    "jacobians",
    "jacobians_over_today",
    "within_band",
    "in_band",
    "seconds",
    "seconds_over_today",
]


def smoothed(displacement, edges, n_boundary, steps):
    """``displacement`` after ``steps`` Jacobi steps ``d <- (d + A d / deg) / 2`` on the graph of ``edges``, the first
    ``n_boundary`` rows (the boundary nodes) held at zero."""
    n = len(displacement)
    adjacency = scipy.sparse.csr_matrix(
        (np.ones(2 * len(edges)), (edges.ravel(order="F"), edges[:, ::-1].ravel(order="F"))), shape=(n, n)
    )
    degree = np.asarray(adjacency.sum(axis=1)).ravel()
    d = np.array(displacement, dtype=float)
    d[:n_boundary] = 0.0
    for _ in range(steps):
        d = 0.5 * d + 0.5 * (adjacency @ d) / degree[:, None]
        d[:n_boundary] = 0.0
    return d


def solve(surface, mesh, start, objective="bounded", constant=None):
    """``objective`` by :func:`equimesh.optimize_uv` from ``start`` (the (u, v) of every node of ``mesh``'s plane),
    its boundary as the pipeline treats it (sliding, or fixed for "paper"), one module constant of the rounds
    replaced if ``constant`` is a ``(name, value)``."""
    plane = mesh.stages.plane
    if objectives.OBJECTIVES[objective].slides:
        slides, fixed = mesh.stages.outline.slides(plane, start)
    else:
        slides, fixed = (), np.arange(plane.n_boundary)
    with mock.patch.object(objectives, *constant) if constant else contextlib.nullcontext():
        return equimesh.optimize_uv(
            surface,
            start,
            plane.edges,
            plane.edge_groups,
            mesh.length,
            fixed=fixed,
            slides=slides,
            triangles=plane.triangles,
            objective=objective,
        )


def ratios(surface, uv, edges, length):
    """Every member's length over ``length`` with the nodes at ``uv``."""
    points = surface.evaluate(uv[:, 0], uv[:, 1])
    return np.linalg.norm(points[edges[:, 1]] - points[edges[:, 0]], axis=1) / length


def lever_row(surface, mesh, lever, start, constant=None):
    """The row of one lever: bounded solved from ``start`` (``constant`` patched), or its refusal, and the time."""
    plane = mesh.stages.plane
    row = {"l": mesh.length, "nodes": len(plane.points), "members": len(plane.edges), "lever": lever}
    began = time.perf_counter()
    try:
        result = solve(surface, mesh, start, constant=constant)
    except EquimeshError as refusal:  # no mesh in [l, 2l] found from this start: the refusal, and its time
        row.update(outcome=str(refusal).split(";")[0], seconds=time.perf_counter() - began)
        return row
    ratio = ratios(surface, result.uv, plane.edges, mesh.length)
    row.update(
        outcome="meshed",
        jacobians=result.njev,
        within_band=float(np.mean(np.abs(ratio - 1.0) <= BAND)),
        in_band=Members.inside(ratio),
        seconds=time.perf_counter() - began,
    )
    return row


def measure(length):
    """The rows of one l: today's solve first (checked against the pipeline's), then each lever."""
    surface = equimesh.surface_from_dict(json.loads(DOME.read_text()))
    mesh = equimesh.mesh_surface(surface, length, placement="default", max_nodes=None)
    remapped, plane = mesh.stages.remapped_uv, mesh.stages.plane
    today = lever_row(surface, mesh, "today (the remapped mesh)", remapped)
    if today.get("jacobians") != mesh.stages.optimization.njev:
        raise RuntimeError(
            f"l = {length}: bounded from the remapped mesh took {today.get('jacobians')} Jacobians here, "
            f"{mesh.stages.optimization.njev} in mesh_surface"
        )
    paper = solve(surface, mesh, remapped, "paper")  # on bounded's plane (meshed again for sound joints)
    displacement = mesh.uv - remapped
    levers = [("start: its own result", mesh.uv, None)]
    levers += [
        (
            f"start: its displacement smoothed {k} times",
            remapped + smoothed(displacement, plane.edges, plane.n_boundary, k),
            None,
        )
        for k in SMOOTHINGS
    ]
    levers.append(("start: the paper's optimum (optimize='paper')", paper.uv, None))
    levers += [
        (f"{name} = {value:g} ({getattr(objectives, name):g})", remapped, (name, value)) for name, value in CONSTANTS
    ]
    rows = [today] + [lever_row(surface, mesh, *lever) for lever in levers]
    for row in rows:
        row["jacobians_over_today"] = row.get("jacobians", np.nan) / today["jacobians"]
        row["seconds_over_today"] = row["seconds"] / today["seconds"]
    return rows


def summarize(df, record):
    body = [
        '"bounded" on the reference dome solved again from each start, or with one constant of its rounds changed '
        "(today's value in brackets), in one run; Jacobians: the solver's Jacobian evaluations, one factorisation "
        "each; over today: the lever's Jacobians and seconds over those of the solve from the remapped mesh at the "
        "same l; within 0.5 %: the share of members within 0.5 % of l; in [l, 2l]: every member.",
        "",
        "| l | nodes | lever | Jacobians | over today | within 0.5 % | in [l, 2l] | seconds | over today |",
        "|---:|---:|---|---:|---:|---:|---|---:|---:|",
    ]
    for _, r in df.iterrows():
        if r["outcome"] == "meshed":
            work = (
                f"{r['jacobians']:.0f} | {r['jacobians_over_today']:.2f} | {r['within_band']:.4f} "
                f"| {'yes' if r['in_band'] else 'no'}"
            )
        else:
            work = f"{r['outcome']} | | |"
        body.append(
            f"| {r['l']:g} | {r['nodes']:,} | {r['lever']} | {work} | {r['seconds']:.2f} "
            f"| {r['seconds_over_today']:.2f} |"
        )
    return _common.markdown_report(
        "Levers on the work of the bounded objective", "`python experiments/optimisation_levers.py`", body, record
    )


def parse_args(argv=None):
    p = _common.add_output_options(_common.parser(__doc__), fig_dir=False)
    p.add_argument("--lengths", type=float, nargs="+", default=list(LENGTHS), help="member lengths l")
    p.add_argument("--quick", action="store_true", help=f"l = {QUICK_LENGTHS[0]:g} only (a smoke test)")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    lengths = list(QUICK_LENGTHS) if args.quick else args.lengths
    args.out_dir.mkdir(parents=True, exist_ok=True)
    df = pd.DataFrame([row for length in lengths for row in measure(length)], columns=COLUMNS)
    parameters = {
        "lengths": lengths,
        "smoothings": list(SMOOTHINGS),
        "constants": [list(c) for c in CONSTANTS],
        "factorisation": solver.DEFAULT_FACTORISATION,
        "quick": args.quick,
    }
    _common.write_results(args.out_dir / f"{NAME}.csv", df, parameters, lambda record: summarize(df, record))
    print(f"{NAME}: {len(lengths)} lengths, {len(df)} rows")
    return 0


if __name__ == "__main__":
    sys.exit(main())
