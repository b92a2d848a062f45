"""Sharp corners with short sides: what Problem 2 meshes, what it refuses and why, and the quality near the corner.

For each family of ``tests/strategies_sharp.py`` (thin triangle, short wedge,
spike, dart-shaped hole; :func:`equimesh.testing.shapes.sharp_corner_shape`),
each corner angle and each side length from l to past the proven limit of the
staggered Step 2 (docs/proofs.md, "Sharp corners"), ``uniform_triangulation``
runs with l = 1 and both insertion engines.  A refusal is classified by its
message: proven impossible (a side shorter than l, or the sector lemma), no
boundary resampling can meet Lemma 3 (1) (a limit of the paper's method: its
first points, or all its points decided on a grid), not handled by this
method (nothing proven either way), or a neck.  For a mesh:
the smallest triangle angle, overall and among the triangles with a node
within ``stagger_reach + l`` of the sharp corner, and the share of G1 edges
(lattice edges of length l), overall and among the edges near the corner.
Writes results/sharp_corners.csv and .md (docs/decisions.md, "Refusals at a corner say what is proven").
"""

import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402

import equimesh  # noqa: E402
from equimesh import G1  # noqa: E402
from equimesh.metrics import triangle_angles  # noqa: E402
from equimesh.planar.boundary.sides import stagger_reach  # noqa: E402
from equimesh.testing.shapes import sharp_corner_shape  # noqa: E402

NAME = "sharp_corners"
KINDS = ("thin triangle", "short wedge", "spike", "dart hole")
ANGLES = (10.0, 15.0, 20.0, 30.0, 45.0)
SIZES = tuple(np.linspace(0.0, 1.0, 6))
QUICK_ANGLES, QUICK_SIZES = (20.0,), (0.0, 1.0)
#: Where each family puts its sharp corner: (ring, vertex) with ring 0 the outer boundary, 1 the hole.
CORNER = {"thin triangle": (0, 0), "short wedge": (0, 0), "spike": (0, 4), "dart hole": (1, 3)}
REFUSALS = {
    "impossible": "no mesh with every edge in [l, 2l] exists",
    "no separation": "cannot meet Lemma 3 (1)",
    "not handled": "is not handled for l",
    "neck": "is too narrow for l",
}
COLUMNS = [
    "kind",
    "angle",
    "size",
    "outcome",
    "reference",
    "n_nodes",
    "min_angle",
    "min_angle_near",
    "g1_share",
    "g1_share_near",
]


def triangulate(outer, holes, engine="fast"):
    """Problem 2 with l = 1 on ``outer`` and ``holes``: the mesh, or the kind of its refusal (a key of
    :data:`REFUSALS`)."""
    try:
        return equimesh.uniform_triangulation(outer, 1.0, holes=holes or None, engine=engine)
    except equimesh.InvalidPolygonError as error:
        return next(kind for kind, marker in REFUSALS.items() if marker in str(error))


def measure(case):
    """One row of the CSV for ``(kind, angle, size)``."""
    kind, angle, size = case
    outer, holes = sharp_corner_shape(kind, angle, stagger_reach(angle, 1.0) + 2.0, size, 0.5, 0.5)
    row = dict(zip(COLUMNS, (kind, angle, size)))
    mesh, reference = (triangulate(outer, holes, engine) for engine in ("fast", "reference"))
    row["outcome"] = mesh if isinstance(mesh, str) else "meshed"
    row["reference"] = reference if isinstance(reference, str) else "meshed"
    if isinstance(mesh, str):
        return row
    ring, vertex = CORNER[kind]
    corner = ([outer] + list(holes))[ring][vertex]
    near = np.linalg.norm(mesh.points - corner, axis=1) <= stagger_reach(angle, 1.0) + 1.0
    angles = triangle_angles(mesh.points, mesh.triangles)
    edges = mesh.edges
    close = near[edges].any(axis=1)
    g1 = mesh.edge_groups == G1
    row.update(
        n_nodes=len(mesh.points),
        min_angle=float(angles.min()),
        min_angle_near=float(angles[near[mesh.triangles].any(axis=1)].min()),
        g1_share=float(g1.mean()),
        g1_share_near=float(g1[close].mean()),
    )
    return row


def run(angles, sizes, jobs, scheduler="local"):
    cases = [(kind, angle, float(size)) for kind in KINDS for angle in angles for size in sizes]
    return pd.DataFrame(_common.parallel_map(measure, cases, jobs, scheduler=scheduler), columns=COLUMNS)


def summarize(df, record):
    body = [
        "Sides of the sharp corner from l (size 0) to stagger_reach + 2 l (size 1), l = 1; the other sizes at",
        "their middle.  Counts of meshes and refusals by kind; angles in degrees over the meshed cases; 'near'",
        "means within stagger_reach + l of the sharp corner.  Both engines agree on every outcome when",
        "'engines agree' is yes.",
        "",
        "| family | corner | cases | meshed | impossible | no separation | not handled | neck | min angle | min angle "
        "near | G1 share | G1 share near | engines agree |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for (kind, angle), group in df.groupby(["kind", "angle"], sort=False):
        meshed = group[group["outcome"] == "meshed"]
        counts = [int((group["outcome"] == name).sum()) for name in ("meshed", *REFUSALS)]
        stats = [meshed[c].min() for c in ("min_angle", "min_angle_near")] + [
            meshed[c].mean() for c in ("g1_share", "g1_share_near")
        ]
        shown = " | ".join("-" if np.isnan(x) else f"{x:.3g}" for x in stats)
        agree = "yes" if (group["outcome"] == group["reference"]).all() else "no"
        body.append(
            f"| {kind} | {angle:g} | {len(group)} | " + " | ".join(map(str, counts)) + f" | {shown} | {agree} |"
        )
    return _common.markdown_report(
        "Sharp corners with short sides (Problem 2)", "`python experiments/sharp_corners.py`", body, record
    )


def parse_args(argv=None):
    p = _common.add_output_options(_common.parser(__doc__), fig_dir=False, jobs=True)
    p.add_argument("--quick", action="store_true", help="tiny configuration (one angle, two sizes) for smoke tests")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    angles, sizes = (QUICK_ANGLES, QUICK_SIZES) if args.quick else (ANGLES, SIZES)
    args.out_dir.mkdir(parents=True, exist_ok=True)
    df = run(angles, sizes, args.jobs, args.scheduler)
    parameters = {
        "angles": list(angles),
        "sizes": [float(s) for s in sizes],
        "kinds": list(KINDS),
        "l": 1.0,
        "quick": args.quick,
        "jobs": args.jobs,
        "scheduler": args.scheduler,
        "out_dir": str(args.out_dir),
    }
    _common.write_results(args.out_dir / f"{NAME}.csv", df, parameters, lambda record: summarize(df, record))
    print(f"{NAME}: {len(df)} cases, {int((df['outcome'] == 'meshed').sum())} meshed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
