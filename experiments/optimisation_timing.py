"""Time of the final optimisation (Section 4, last step) on the reference dome at one member length.

Runs :func:`equimesh.mesh_surface` on ``experiments/surfaces/reference_dome.json``
(15 x 15 grid, default lattice placement, no size limit) and prints, for each
objective, the members, the solver's Jacobian evaluations (one per iteration) and final cost, the share of
members within 0.5 % of l, the factorisation used (PARDISO where the extra ``fast`` is
installed, else SuperLU) and the wall time of each stage.  It writes no file:
it is the command behind the optimisation timings of docs/decisions.md (items
40, 41 and 56) and docs/performance.md.  To compare two checkouts in the same
run, start it once per checkout, side by side::

    PYTHONPATH=/path/to/old/src python experiments/optimisation_timing.py --length 0.52 &
    PYTHONPATH=src python experiments/optimisation_timing.py --length 0.52

Usage::

    python experiments/optimisation_timing.py [--length 0.52] [--objective paper bounded]
"""

import argparse
import json
import sys
from pathlib import Path

import numpy as np

import equimesh
from equimesh.surface import _solver
from equimesh.surface.optimize import OBJECTIVES

DOME = Path(__file__).resolve().parent / "surfaces" / "reference_dome.json"
#: Members within this relative deviation of l count as exact (the issue's 0.5 %).
BAND = 0.005


def measure(length, objective):
    """One optimisation of the reference dome at member length ``length``: a dict of what it printed."""
    surface = equimesh.surface_from_dict(json.loads(DOME.read_text()))
    mesh = equimesh.mesh_surface(surface, length, optimize=objective, placement="default", max_nodes=None)
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
    }


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--length", type=float, default=0.52, help="member length l (default 0.52: about 10^5 members)")
    p.add_argument("--objective", nargs="+", default=["paper"], choices=sorted(OBJECTIVES))
    args = p.parse_args(argv)
    for objective in args.objective:
        print(json.dumps(measure(args.length, objective)), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
