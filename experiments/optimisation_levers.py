"""Levers on the work of "bounded"'s optimisation, each solved beside the pipeline's in one run: starts, constants.

The rounds of the default objective (docs/decisions.md, "The bounded objective") are most of a run's time, one
factorisation per iteration (docs/performance.md, "The final optimisation").  On the reference dome (15 x 15 grid,
default lattice placement, no size limit) at each l, :func:`equimesh.mesh_surface` gives bounded's result and its
remapped start; :func:`equimesh.optimize_uv` then solves "bounded" again, boundary nodes sliding as in the pipeline,

* from the remapped mesh, as the pipeline solves it (its Jacobians must be the pipeline's, else this
  script is not measuring what the pipeline runs, and it stops);
* from bounded's own result: the floor of any start;
* from the remapped mesh moved by bounded's displacement smoothed by ``SMOOTHINGS`` Jacobi steps of the mesh's
  graph Laplacian (``d <- (d + mean of the neighbours' d) / 2``, boundary nodes held at their remapped place): what
  a start that carries only the smooth part of the answer can save (a coarse-to-fine solve, a flattening that
  targets lengths on the surface, a global local-global pass);
* from the end of ``LOCAL_GLOBAL`` iterations of a local-global pass on the members from the remapped mesh
  (projective dynamics, Bouaziz et al. 2014; Liu et al. 2013: the global step's matrix factorised once,
  :func:`local_global`);
* from the optimum of the paper's objective (``optimize="paper"``, boundary fixed);
* from the remapped mesh with one constant of the rounds changed (``CONSTANTS``: fewer iterations per round, a
  larger trust region per node, a looser end of a series).

Each row: the solver's Jacobian evaluations (``njev``, one factorisation each), the share of members within 0.5 %
of l, whether every member is in [l, 2l], the solve's wall seconds, and both over the pipeline's.  Run with nothing
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
import scipy.sparse.linalg

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402

import equimesh  # noqa: E402
from equimesh.errors import EquimeshError  # noqa: E402
from equimesh.mesh import edge_lengths  # noqa: E402
from equimesh.metrics import share_within  # noqa: E402
from equimesh.surface.optimize import objectives, solver  # noqa: E402
from equimesh.surface.optimize.jacobian import signed_areas  # noqa: E402
from equimesh.surface.optimize.members import Members  # noqa: E402
from equimesh.surface.optimize.problem import parameter_box  # noqa: E402

NAME = "optimisation_levers"
DOME = Path(__file__).resolve().parent / "surfaces" / "reference_dome.json"
LENGTHS = (2.5, 1.0)
QUICK_LENGTHS = (5.0,)
#: Jacobi steps of the smoothing of bounded's displacement (a few edges, and about ten).
SMOOTHINGS = (10, 100)
#: Iterations of the local-global pass tried as starts.
LOCAL_GLOBAL = (50, 100)
#: The local-global pass's weight of a node's pull to the surface (a member's is one).
SURFACE_WEIGHT = 1.0
#: Its local step sends a member within this relative deviation of the target to the target, the others into the band.
SNAP = 0.05
#: The weight that holds the chart's corners in its global step.
CORNER_WEIGHT = 1e8
#: Constants of the rounds (:mod:`equimesh.tolerance`, as :mod:`~equimesh.surface.optimize.objectives` reads them)
#: and the value each is tried at (the default in brackets in the report).
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
    "jacobians_ratio",
    "within_band",
    "in_band",
    "start_seconds",
    "seconds",
    "seconds_ratio",
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


def local_global(surface, uv, edges, length, iterations):
    """``iterations`` of a local-global pass (Bouaziz et al. 2014, "Projective dynamics"; Liu et al. 2013) on the
    nodes in space, from the (u, v) ``uv``: the (u, v) of the nodes' last projection on the surface.

    Local step: each member's vector ``d_e`` along its direction, ``t l`` long (``t = Members.target``) if within
    ``SNAP`` of it, else its length clipped to ``[t, Members.high] l``; each node's point ``p_i`` on the surface
    (:func:`_projected`).  Global step: the nodes minimising ``sum_e |x_a - x_b - d_e|^2 + SURFACE_WEIGHT sum_i
    |x_i - p_i|^2`` (the corners at ``CORNER_WEIGHT``), whose matrix depends on the mesh only: factorised once,
    each iteration three solves.
    """
    lower, upper = parameter_box(surface)
    uv = np.array(uv, dtype=float)
    held = (uv == lower) | (uv == upper)
    n, m = len(uv), len(edges)
    difference = scipy.sparse.csr_matrix(
        (np.repeat([1.0, -1.0], m), (np.tile(np.arange(m), 2), edges.ravel(order="F"))), shape=(m, n)
    )
    weight = np.where(held.all(axis=1), CORNER_WEIGHT, SURFACE_WEIGHT)
    solve_global = scipy.sparse.linalg.factorized((difference.T @ difference + scipy.sparse.diags(weight)).tocsc())
    target, high = Members.target * length, Members.high * length
    x = surface.evaluate(uv[:, 0], uv[:, 1])
    for _ in range(iterations):
        vectors = difference @ x
        lengths = np.linalg.norm(vectors, axis=1)
        goal = np.where(np.abs(lengths - target) <= SNAP * target, target, np.clip(lengths, target, high))
        uv = _projected(surface, uv, x, held, lower, upper)
        rhs = difference.T @ (vectors * (goal / lengths)[:, None]) + weight[:, None] * surface.evaluate(
            uv[:, 0], uv[:, 1]
        )
        x = np.column_stack([solve_global(rhs[:, k]) for k in range(3)])
    return _projected(surface, uv, x, held, lower, upper)


def _projected(surface, uv, x, held, lower, upper):
    """The (u, v) one Gauss-Newton step from ``uv`` towards the points ``x``, the coordinates ``held`` (on a side of
    the parameter box) kept, so the boundary nodes stay on their sides and the corners in place."""
    su, sv = surface.derivatives(uv[:, 0], uv[:, 1])
    gap = x - surface.evaluate(uv[:, 0], uv[:, 1])
    normal = np.stack(
        [np.stack([(su * su).sum(1), (su * sv).sum(1)], 1), np.stack([(su * sv).sum(1), (sv * sv).sum(1)], 1)], 1
    )
    normal[held[:, 0], 0, :], normal[held[:, 1], 1, :] = 0.0, 0.0
    normal[held[:, 0], :, 0], normal[held[:, 1], :, 1] = 0.0, 0.0
    normal[held[:, 0], 0, 0], normal[held[:, 1], 1, 1] = 1.0, 1.0
    gradient = np.where(held, 0.0, np.stack([(su * gap).sum(1), (sv * gap).sum(1)], 1))
    return np.clip(uv + np.linalg.solve(normal, gradient[:, :, None])[:, :, 0], lower, upper)


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
    return edge_lengths(surface.evaluate(uv[:, 0], uv[:, 1]), edges) / length


def lever_row(surface, mesh, lever, start, constant=None, start_seconds=np.nan):
    """The row of one lever: bounded solved from ``start`` (``constant`` patched), or its refusal, and the time;
    ``start_seconds``: what making the start took (none for the remapped mesh and the starts made of bounded's
    result)."""
    plane = mesh.stages.plane
    row = {"l": mesh.length, "nodes": len(plane.points), "members": len(plane.edges), "lever": lever}
    row["start_seconds"] = start_seconds
    folds = int(np.count_nonzero(signed_areas(start, plane.triangles) <= 0.0))
    if folds:  # the solver keeps the orientation a start has: a folded one is no start
        row.update(outcome=f"the start folds {folds} triangles", seconds=0.0)
        return row
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
        within_band=share_within(ratio, 1.0, BAND),
        in_band=Members.inside(ratio),
        seconds=time.perf_counter() - began,
    )
    return row


def measure(length):
    """The rows of one l: the solve from the remapped mesh first (checked against the pipeline's), then each lever."""
    surface = equimesh.surface_from_dict(json.loads(DOME.read_text()))
    mesh = equimesh.mesh_surface(surface, length, placement="default", max_nodes=None)
    remapped, plane = mesh.stages.remapped_uv, mesh.stages.plane
    pipeline = lever_row(surface, mesh, "the pipeline's (from the remapped mesh)", remapped)
    if pipeline.get("jacobians") != mesh.stages.optimization.njev:
        raise RuntimeError(
            f"l = {length}: bounded from the remapped mesh took {pipeline.get('jacobians')} Jacobians here, "
            f"{mesh.stages.optimization.njev} in mesh_surface"
        )
    paper, paper_seconds = _common.timed(solve, surface, mesh, remapped, "paper")  # on bounded's plane
    displacement = mesh.uv - remapped
    levers = [("start: its own result", mesh.uv, None, np.nan)]
    levers += [
        (
            f"start: its displacement smoothed {k} times",
            remapped + smoothed(displacement, plane.edges, plane.n_boundary, k),
            None,
            np.nan,
        )
        for k in SMOOTHINGS
    ]
    for k in LOCAL_GLOBAL:
        start, seconds = _common.timed(local_global, surface, remapped, plane.edges, length, k)
        levers.append((f"start: {k} local-global iterations", start, None, seconds))
    levers.append(("start: the paper's optimum (optimize='paper')", paper.uv, None, paper_seconds))
    levers += [
        (f"{name} = {value:g} ({getattr(objectives, name):g})", remapped, (name, value), np.nan)
        for name, value in CONSTANTS
    ]
    rows = [pipeline] + [lever_row(surface, mesh, *lever) for lever in levers]
    for row in rows:
        row["jacobians_ratio"] = row.get("jacobians", np.nan) / pipeline["jacobians"]
        row["seconds_ratio"] = (row["seconds"] + np.nan_to_num(row["start_seconds"])) / pipeline["seconds"]
    return rows


def _seconds(value):
    return "" if np.isnan(value) else f"{value:.2f}"


def summarize(df, record):
    body = [
        '"bounded" on the reference dome solved again from each start, or with one constant of its rounds changed '
        "(the default in brackets), in one run; Jacobians: the solver's Jacobian evaluations, one factorisation "
        "each; start: the seconds making the start took (none for the remapped mesh, nor where it is made of "
        "bounded's own result, which no start can know); ratio: the lever's Jacobians, and its seconds with the "
        "start's, over those of the solve from the remapped mesh at the same l (the pipeline's); within 0.5 %: the "
        "share of members within 0.5 % of l; in [l, 2l]: every member.",
        "",
        "| l | nodes | lever | Jacobians | ratio | within 0.5 % | in [l, 2l] | start (s) | seconds | ratio |",
        "|---:|---:|---|---:|---:|---:|---|---:|---:|---:|",
    ]
    for _, r in df.iterrows():
        if r["outcome"] == "meshed":
            work = (
                f"{r['jacobians']:.0f} | {r['jacobians_ratio']:.2f} | {r['within_band']:.4f} "
                f"| {'yes' if r['in_band'] else 'no'}"
            )
        else:
            work = f"{r['outcome']} | | |"
        body.append(
            f"| {r['l']:g} | {r['nodes']:,} | {r['lever']} | {work} | {_seconds(r['start_seconds'])} "
            f"| {r['seconds']:.2f} | {r['seconds_ratio']:.2f} |"
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
        "local_global": {"iterations": list(LOCAL_GLOBAL), "surface_weight": SURFACE_WEIGHT, "snap": SNAP},
        "constants": [list(c) for c in CONSTANTS],
        "factorisation": solver.DEFAULT_FACTORISATION,
        "quick": args.quick,
    }
    _common.write_results(args.out_dir / f"{NAME}.csv", df, parameters, lambda record: summarize(df, record))
    print(f"{NAME}: {len(lengths)} lengths, {len(df)} rows")
    return 0


if __name__ == "__main__":
    sys.exit(main())
