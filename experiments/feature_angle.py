"""The corners of a triangle mesh's boundary loops at the scale of l: how they turn, and what each feature angle keeps.

A dome (``equimesh.testing.meshes.roof_mesh``, a plan of n x n cells of size
1 rising n / 10) has one opening cut out of it by removing the triangles whose
centroid lies inside a plan outline: a circle or a 2:1 ellipse, whose rim is a
staircase of mesh edges, or a polygon whose sides run along grid lines and the
cells' diagonals, so that its corners are vertices of the mesh (a square, a
hexagon turning by 45 and 90 degrees, a right triangle turning by 90 and 135).
For each grid, each l (in mesh edges, ``l / h``) and each opening size (its
diameter, minor axis or side, in units of l) that leaves the opening at least
2l from the border, the mesh is flattened (eq. (1)) and
both loops measured by ``equimesh.surface.mesh_outline``: the smallest turn at
the scale of l of the polygon's corners and of the outer boundary's four
corners (``scale_turns``), the largest turn of every other vertex farther than
l from them (the staircase, the curve), and for each feature angle of
:data:`FEATURE_ANGLES` what step 3 (``mesh_outline``) makes of the loops: the
corners it keeps, real and spurious (the vertex a loop without corners starts
at is neither), or its refusal.  The default feature angle
(``DEFAULT_FEATURE_ANGLE``) is chosen from this table
(docs/decisions.md, "Corners of a mesh's loops").

Writes::

    results/feature_angle.csv                one row per mesh, l, opening and feature angle
    results/feature_angle.md                 the summary tables and a provenance block
    results/feature_angle.provenance.json

Usage::

    python experiments/feature_angle.py [--jobs 2] [--quick]
"""

import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402

from equimesh import TriangulatedSurface  # noqa: E402
from equimesh.errors import InvalidSurfaceError  # noqa: E402
from equimesh.planar.strip import BOUNDARY_SPACING  # noqa: E402
from equimesh.surface.charts.mesh_chart import MeshChart, flatten_mesh  # noqa: E402
from equimesh.surface.mesh_outline import DEFAULT_FEATURE_ANGLE, mesh_outline, scale_turns  # noqa: E402
from equimesh.testing.meshes import ellipse, roof_mesh  # noqa: E402

NAME = "feature_angle"
#: The feature angles tried (degrees).
FEATURE_ANGLES = (20.0, 30.0, 40.0, 44.0, 60.0)
#: Grid cells per side, l in mesh edges, and the openings with their sizes in units of l.
GRIDS = (60, 90, 120)
EDGES_PER_L = (6, 9, 12)
OPENINGS = {
    "circle": (1.5, 2.0, 3.0, 5.0),
    "ellipse": (1.5, 2.5),
    "square": (1.5, 3.0),
    "hexagon": (2.0, 3.0),
    "triangle": (2.0, 4.0),
}
QUICK = {"grids": (40,), "edges": (6,), "openings": {"circle": (2.0,), "square": (1.5,)}}
#: Refusals of step 3 by their messages.
REFUSALS = {"narrow": "is narrower than l", "small": "is too small for l", "short": "has a part"}
COLUMNS = [
    "cells",
    "edges_per_l",
    "opening",
    "size",
    "feature_angle",
    "corner_turn_min",
    "curve_turn_max",
    "outer_turn_min",
    "outer_curve_max",
    "corners",
    "corners_kept",
    "spurious",
    "outer_kept",
    "outer_spurious",
    "outcome",
]


def plan_outline(kind, size, l, centre):
    """The opening's plan outline and its corners (None for a curve); polygon vertices on grid nodes."""
    if kind == "circle":
        return ellipse(centre, size * l / 2, size * l / 2), None
    if kind == "ellipse":
        return ellipse(centre, size * l, size * l / 2), None
    s = int(round(size * l))
    a = s // 2
    shape = {
        "square": [(0, 0), (s, 0), (s, s), (0, s)],
        "hexagon": [(0, 0), (a, 0), (s, s - a), (s, s), (s - a, s), (0, a)],
        "triangle": [(0, 0), (s, 0), (s, s)],
    }[kind]
    corners = np.array(shape, dtype=float) + np.floor(np.asarray(centre) - s / 2)
    return corners, corners


def _measure(task):
    cells, edges, kind, size = task
    l = float(edges)  # cells of size 1: l / h = edges
    outline, polygon = plan_outline(kind, size, l, (cells / 2, cells / 2))
    surface = TriangulatedSurface(*roof_mesh(cells, cells, (cells, cells), cells / 10, cut=[outline]))
    chart = MeshChart(surface, flatten_mesh(surface).points)
    square = np.array([[0.0, 0.0], [cells, 0.0], [cells, cells], [0.0, cells]])
    loops = {"outer": (chart.outer, square), "opening": (1 - chart.outer, polygon)}
    turns = {}
    for name, (k, corners) in loops.items():
        loop = surface.loops[k]
        xy = chart.plane[loop]
        turn = np.abs(scale_turns(xy, l))
        real = _at(surface.vertices[loop, :2], corners)
        far = np.ones(len(loop), dtype=bool)
        for i in real:
            far &= np.linalg.norm(xy - xy[i], axis=1) > l
        turns[name] = (loop, real, turn[real].min() if len(real) else np.nan, turn[far].max() if far.any() else np.nan)
    rows = []
    for angle in FEATURE_ANGLES:
        row = {
            "cells": cells,
            "edges_per_l": edges,
            "opening": kind,
            "size": size,
            "feature_angle": angle,
            "corner_turn_min": turns["opening"][2],
            "curve_turn_max": turns["opening"][3],
            "outer_turn_min": turns["outer"][2],
            "outer_curve_max": turns["outer"][3],
            "corners": len(turns["opening"][1]),
        }
        try:
            result = mesh_outline(chart, l, BOUNDARY_SPACING, angle)
        except InvalidSurfaceError as exc:
            outcome = next((k for k, text in REFUSALS.items() if text in str(exc)), "other")
            rows.append({**row, "outcome": outcome})
            continue
        counts = {}
        for name, (k, _) in loops.items():
            loop, real, _, _ = turns[name]
            at = result.order.index(k)
            kept = np.flatnonzero(np.isin(result.loops[at].arc[:-1], result.corners[at]))
            hits = int(np.isin(real, kept).sum())
            start = int(len(kept) == 1 and not hits)  # the one corner a loop without corners starts at
            counts[name] = (hits, len(kept) - hits - start)
        rows.append(
            {
                **row,
                "corners_kept": counts["opening"][0],
                "spurious": counts["opening"][1],
                "outer_kept": counts["outer"][0],
                "outer_spurious": counts["outer"][1],
                "outcome": "ring",
            }
        )
    return rows


def _at(plan, corners):
    """Indices of the loop vertices (plan coordinates ``plan``) at the points ``corners`` (none for a curve)."""
    if corners is None:
        return np.zeros(0, dtype=np.int64)
    return np.array([int(np.argmin(np.linalg.norm(plan - c, axis=1))) for c in corners])


def summarize(df, record):
    default = df[df["feature_angle"] == DEFAULT_FEATURE_ANGLE]
    polygons = df[df["corners"] > 0]
    body = [
        "Turns at the scale of l (degrees, `scale_turns`): of the polygons' corners and of the outer boundary's "
        "four corners (the smallest), and of every other vertex farther than l from them (the largest), over every "
        "grid and l.",
        "",
        "| opening | size / l | corner turn (min) | curve turn (max) | outer corner turn (min) | outer curve (max) |",
        "|---|---|---|---|---|---|",
    ]
    first = df[df["feature_angle"] == FEATURE_ANGLES[0]]
    for (kind, size), g in first.groupby(["opening", "size"], sort=False):
        corner = f"{g['corner_turn_min'].min():.1f}" if g["corners"].max() else "-"
        body.append(
            f"| {kind} | {size:g} | {corner} | {g['curve_turn_max'].max():.1f} | {g['outer_turn_min'].min():.1f} | "
            f"{g['outer_curve_max'].max():.1f} |"
        )
    body += [
        "",
        "What step 3 keeps at each feature angle, over every case: the polygons' corners kept (of all), spurious "
        "corners on the openings and on the outer boundary, and the cases refused.",
        "",
        "| feature angle | polygon corners kept | spurious on openings | spurious on the outer boundary | "
        "outer corners kept | refused |",
        "|---|---|---|---|---|---|",
    ]
    for angle, g in df.groupby("feature_angle"):
        ring = g[g["outcome"] == "ring"]
        kept = polygons[(polygons["feature_angle"] == angle) & (polygons["outcome"] == "ring")]
        refused = ", ".join(f"{n} {k}" for k, n in g[g["outcome"] != "ring"]["outcome"].value_counts().items())
        body.append(
            f"| {angle:g} | {int(kept['corners_kept'].sum())} of {int(kept['corners'].sum())} | "
            f"{int(ring['spurious'].sum())} | {int(ring['outer_spurious'].sum())} | "
            f"{int(ring['outer_kept'].sum())} of {4 * len(ring)} | {refused or 'none'} |"
        )
    body += [
        "",
        f"At the default feature angle ({DEFAULT_FEATURE_ANGLE:g} degrees), the openings with spurious corners, by "
        "grid and l:",
        "",
        "| opening | size / l | cells | l / h | spurious corners |",
        "|---|---|---|---|---|",
    ]
    for _, r in default[default["spurious"] > 0].iterrows():
        body.append(f"| {r['opening']} | {r['size']:g} | {r['cells']} | {r['edges_per_l']} | {int(r['spurious'])} |")
    return _common.markdown_report(
        "Corners of a mesh's loops at the scale of l", "`python experiments/feature_angle.py`", body, record
    )


def parse_args(argv=None):
    p = _common.add_output_options(_common.parser(__doc__), fig_dir=False, jobs=True)
    p.add_argument("--quick", action="store_true", help="one coarse grid, one l, two openings")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    grids, edges, openings = (
        (QUICK["grids"], QUICK["edges"], QUICK["openings"]) if args.quick else (GRIDS, EDGES_PER_L, OPENINGS)
    )
    tasks = [
        (n, e, kind, size)
        for n in grids
        for e in edges
        for kind, sizes in openings.items()
        for size in sizes
        if (2 if kind == "ellipse" else 1) * size * e + 4 * e <= n  # the opening at least 2l from the border
    ]
    args.out_dir.mkdir(parents=True, exist_ok=True)
    rows = [row for rows in _common.parallel_map(_measure, tasks, args.jobs, scheduler=args.scheduler) for row in rows]
    df = pd.DataFrame(rows, columns=COLUMNS)
    parameters = {
        "grids": list(grids),
        "edges_per_l": list(edges),
        "openings": {k: list(v) for k, v in openings.items()},
        "feature_angles": list(FEATURE_ANGLES),
        "default": DEFAULT_FEATURE_ANGLE,
        "quick": args.quick,
        "jobs": args.jobs,
        "out_dir": str(args.out_dir),
    }
    _common.write_results(args.out_dir / f"{NAME}.csv", df, parameters, lambda record: summarize(df, record))
    default = df[df["feature_angle"] == DEFAULT_FEATURE_ANGLE]
    made = int((default["outcome"] == "ring").sum())
    print(
        f"{NAME}: {len(tasks)} meshes; at {DEFAULT_FEATURE_ANGLE:g} degrees {made} outlines made, "
        f"{int(default['spurious'].sum())} spurious corners"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
