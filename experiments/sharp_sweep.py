"""Sharp corners drawn at random: how many of each family Problem 2 meshes, and how it refuses the others.

Draws ``--count`` shapes of each family of ``tests/strategies_sharp.py``
(:func:`equimesh.testing.shapes.sharp_corner_shape`: thin triangle, short
wedge, spike, dart hole) with the corner angle uniform in [10, 60) degrees
and the sizes ``u, v, w`` uniform in [0, 1] (``numpy.random.default_rng(seed)``),
and as many triangles with two sharp corners sharing their base: angles
``10 + 50 (angle, u)`` degrees at its ends, the base ``1 + v (K_1 + K_2 + 2)``
long (``K l`` = ``stagger_reach``, so up to where the two corners stop
sharing any point of it), and as many darts (arrowheads,
:func:`equimesh.testing.shapes.sharp_dart`: a tip of ``angle`` degrees, barbs
of ``10 + 50 u`` and ``10 + 50 v`` degrees, tip sides ``1 + w (K_tip + K_barb + 3)``
long with ``K_barb`` the larger barb's: three sharp corners in a row),
runs ``uniform_triangulation`` with l = 1 (fast engine) and classifies each
refusal by its message as ``experiments/sharp_corners.py`` does.  The count
that matters is "not handled": a ring where nothing is proven either way
(docs/proofs.md, "Sharp corners"; docs/decisions.md, "Refusals at a corner say what is proven").
Writes results/sharp_sweep.csv and .md.
"""

import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, sharp_corners.py
import _common  # noqa: E402
from sharp_corners import KINDS as SHAPES  # noqa: E402
from sharp_corners import REFUSALS, triangulate

from equimesh.planar.boundary.sides import stagger_reach  # noqa: E402
from equimesh.testing.shapes import sharp_corner_shape, sharp_dart  # noqa: E402

NAME = "sharp_sweep"
PAIR, DART = "two-corner triangle", "dart"
KINDS = (*SHAPES, PAIR, DART)
COLUMNS = ["kind", "angle", "u", "v", "w", "outcome"]


def measure(case):
    """One row of the CSV for ``(kind, angle, u, v, w)``."""
    kind, angle, *sizes = case
    if kind in (PAIR, DART):
        outer, holes = (_pair_triangle if kind == PAIR else _dart)(angle, *sizes), []
    else:
        outer, holes = sharp_corner_shape(kind, angle, stagger_reach(angle, 1.0) + 2.0, *sizes)
    outcome = triangulate(outer, holes)
    return dict(zip(COLUMNS, (*case, outcome if isinstance(outcome, str) else "meshed")))


def _pair_triangle(angle, u, v, w):
    """The triangle of the module docstring: corners of ``angle`` and ``10 + 50 u`` degrees on a base of ``1 + v (K_1 +
    K_2 + 2)``."""
    other = 10.0 + 50.0 * u
    base = 1.0 + v * (stagger_reach(angle, 1.0) + stagger_reach(other, 1.0) + 2.0)
    a, b = np.radians(angle), np.radians(other)
    side = base * np.sin(b) / np.sin(a + b)
    return np.array([[0.0, 0.0], [base, 0.0], [side * np.cos(a), side * np.sin(a)]])


def _dart(angle, u, v, w):
    """The dart of the module docstring: a tip of ``angle`` degrees, barbs of ``10 + 50 u`` and ``10 + 50 v``
    degrees."""
    barbs = (10.0 + 50.0 * u, 10.0 + 50.0 * v)
    return sharp_dart(
        angle, barbs, 1.0 + w * (stagger_reach(angle, 1.0) + max(stagger_reach(b, 1.0) for b in barbs) + 3.0)
    )


def cases(count, seed, kinds=KINDS):
    """``count`` draws per family of ``kinds``: ``(kind, angle, u, v, w)``, each family's the same whatever ``kinds``
    are."""
    rng = np.random.default_rng(seed)
    draws = rng.uniform(size=(len(KINDS), count, 4))
    return [
        (kind, 10.0 + 50.0 * a, u, v, w)
        for kind, rows in zip(KINDS, draws)
        if kind in kinds
        for a, u, v, w in rows.tolist()
    ]


def summarize(df, record, count, seed):
    body = [
        f"{count} shapes per family, seed {seed}, l = 1: angle uniform in [10, 60) degrees, sizes uniform.",
        "",
        "| family | cases | meshed | " + " | ".join(REFUSALS) + " |",
        "|---|---|---|" + "---|" * len(REFUSALS),
    ]
    for kind, group in df.groupby("kind", sort=False):
        counts = [int((group["outcome"] == name).sum()) for name in ("meshed", *REFUSALS)]
        body.append(f"| {kind} | {len(group)} | " + " | ".join(map(str, counts)) + " |")
    return _common.markdown_report(
        "Sharp corners drawn at random (Problem 2)", "`python experiments/sharp_sweep.py`", body, record
    )


def parse_args(argv=None):
    p = _common.add_output_options(_common.parser(__doc__), fig_dir=False, jobs=True)
    p.add_argument("--count", type=int, default=100, help="shapes per family (default 100)")
    p.add_argument("--seed", type=int, default=0, help="seed of the draws (default 0)")
    p.add_argument("--kinds", nargs="+", choices=KINDS, default=list(KINDS), help="families (default all)")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    args.out_dir.mkdir(parents=True, exist_ok=True)
    df = pd.DataFrame(
        _common.parallel_map(measure, cases(args.count, args.seed, args.kinds), args.jobs, scheduler=args.scheduler),
        columns=COLUMNS,
    )
    parameters = {
        "count": args.count,
        "seed": args.seed,
        "kinds": list(args.kinds),
        "l": 1.0,
        "jobs": args.jobs,
        "scheduler": args.scheduler,
        "out_dir": str(args.out_dir),
    }
    _common.write_results(
        args.out_dir / f"{NAME}.csv", df, parameters, lambda record: summarize(df, record, args.count, args.seed)
    )
    print(
        f"{NAME}: {len(df)} cases, "
        + ", ".join(f"{name} {int((df['outcome'] == name).sum())}" for name in ("meshed", *REFUSALS))
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
