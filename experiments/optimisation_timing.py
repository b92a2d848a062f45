"""Time of the final optimisation (Section 4, last step) on the reference dome at one member length.

Runs :func:`equimesh.mesh_surface` on ``experiments/surfaces/reference_dome.json``
(15 x 15 grid, default lattice placement, no size limit) and prints, for each
objective, the members, the solver's Jacobian evaluations (one per iteration) and final cost, the share of
members within 0.5 % of l, the factorisation used (the first installed of PARDISO, CHOLMOD
and SuperLU, or the one named by the environment variable ``EQUIMESH_FACTORISATION``),
the wall time of each stage and the CPU time of the whole call.  It writes no file:
it is the command behind the optimisation timings of docs/performance.md.  To compare two checkouts in the same
run, start it once per checkout, side by side::

    PYTHONPATH=/path/to/old/src python experiments/optimisation_timing.py --length 0.52 &
    PYTHONPATH=src python experiments/optimisation_timing.py --length 0.52

``--trace`` also prints one JSON line per solve of the optimisation (a
round of ``"bounded"``, the paper's stage): its iterations, evaluations,
final damping, and the share of all members within 0.5 % of l and in
[l, 2l] where it ended (docs/decisions.md, "A trust region per node"), in the order the solves end: bounded's second
start, solved beside the first series (docs/decisions.md, "Bounded's second start on a second core"), among its rounds.

Usage::

    python experiments/optimisation_timing.py [--length 0.52] [--objective paper bounded] [--trace]
"""

import argparse
import contextlib
import json
import sys
import time
from pathlib import Path

import numpy as np

import equimesh
from equimesh.surface.optimize import OBJECTIVES, driver, members
from equimesh.surface.optimize import solver as _solver

DOME = Path(__file__).resolve().parent / "surfaces" / "reference_dome.json"
#: Members within this relative deviation of l count as exact (the 0.5 % of every share).
BAND = 0.005


def measure(length, objective):
    """One optimisation of the reference dome at member length ``length``: a dict of what it printed."""
    surface = equimesh.surface_from_dict(json.loads(DOME.read_text()))
    cpu = time.process_time()
    mesh = equimesh.mesh_surface(surface, length, optimize=objective, placement="default", max_nodes=None)
    cpu = time.process_time() - cpu
    ratio = mesh.edge_lengths() / length
    result = mesh.stages.optimization
    return {
        "objective": objective,
        "length": length,
        "members": len(mesh.edges),
        "nodes": len(mesh.uv),
        "jacobians": result.njev,
        "cost": result.cost_after,
        "within_band": float(np.mean(np.abs(ratio - 1.0) <= BAND)),
        "factorisation": getattr(_solver, "DEFAULT_FACTORISATION", "superlu"),  # a checkout from before the choice
        "seconds": {stage: round(s, 3) for stage, s in mesh.stages.seconds.items()},
        "cpu_seconds": round(cpu, 3),  # the whole mesh_surface call, less sensitive to other jobs than the wall times
    }


@contextlib.contextmanager
def traced(length):
    """Print a JSON line after every solve of :func:`equimesh.surface.optimize.optimize_uv` while inside."""
    every = {}
    terms, solver = members.edge_length_terms, driver.least_squares

    def edge_length_terms(problem, edges):
        lengths, jacobian = terms(problem, edges)
        if len(edges) == len(problem.edges):  # the lengths of all members (the bounded objective asks for them)
            every["lengths"] = lengths
        return lengths, jacobian

    def least_squares(*args, **kwargs):
        solution = solver(*args, **kwargs)
        every["solves"] = every.get("solves", 0) + 1
        record = {
            "solve": every["solves"],
            "iterations": solution.iterations,
            "evaluations": solution.evaluations,
            "damping": solution.damping,
        }
        if "lengths" in every:
            ratio = every["lengths"](solution.x) / length
            record.update(
                within_band=float(np.mean(np.abs(ratio - 1.0) <= BAND)),
                inside=bool(np.all((ratio >= 1.0) & (ratio <= 2.0))),
            )
        print(json.dumps(record), flush=True)
        return solution

    members.edge_length_terms, driver.least_squares = edge_length_terms, least_squares
    try:
        yield
    finally:
        members.edge_length_terms, driver.least_squares = terms, solver


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--length", type=float, default=0.52, help="member length l (default 0.52: about 10^5 members)")
    p.add_argument("--objective", nargs="+", default=["paper"], choices=sorted(OBJECTIVES))
    p.add_argument("--trace", action="store_true", help="also print a JSON line per solve (round or stage)")
    args = p.parse_args(argv)
    for objective in args.objective:
        with traced(args.length) if args.trace else contextlib.nullcontext():
            record = measure(args.length, objective)
        print(json.dumps(record), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
