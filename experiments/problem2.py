"""Problem 2 (Section 3): how many edges are exactly l, against polygon size, shape and lattice placement.

For a family of convex and non-convex polygons (square, 2:1 rectangle,
regular 12-gon, L-shape, U-shape and a wavy "flattened surface boundary")
scaled to areas of about 25, 100, 400, 1600 and 6400 l^2, run
:func:`equimesh.uniform_triangulation` with the default lattice placement
(angle 0, offset (0, 0)) and with :func:`equimesh.best_lattice_placement`,
and record the G1 share (edges of length exactly l from the lattice), the
number of non-G1 edges and ``non-G1 * l / perimeter`` (bounded by a constant:
``tests/planar/test_strip.py::test_non_g1_edges_grow_linearly_with_perimeter``), the number of distinct edge lengths
(rounded
to
1e-9 l), the shortest and longest edge (Theorem 3: in [l, 2l]), the gain of
the placement search and the run times.  A second study sweeps
``boundary_spacing`` (the Step 2 part length, in units of l) over 1.0, 1.2,
1.5, 1.8, 2.0 on the 400 l^2 polygons with the default placement, recording
the G1 share and the smallest triangle angle.

Writes (``results/`` data, ``paper_figs/`` figures)::

    results/problem2.csv               one row per (study, shape, size, placement, spacing)
    results/problem2.md                tables and a provenance block
    results/problem2.provenance.json   commit, parameters, library versions, date
    paper_figs/problem2_mesh.png, .pdf one triangulation (flattened boundary, 400 l^2), G1 edges coloured
    paper_figs/problem2_share.png, .pdf G1 share against size, drawn from the CSV only
    paper_figs/problem2_*.provenance.json

Usage::

    python experiments/problem2.py [--jobs 2] [--quick]
    python experiments/problem2.py --plot-only     # redraw the figures
"""

import math
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

import equimesh
from equimesh import G1
from equimesh.planar.lattice import lattice_basis
from equimesh.planar.polygon import as_polygon
from equimesh.planar.strip import BOUNDARY_SPACING
from equimesh.testing.generators import rectangle, regular_polygon
from equimesh.testing.shapes import flattened_square, letter_polygon

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402
from _common import timed  # noqa: E402

NAME = "problem2"
L = 1.0
SHAPES = ("square", "rectangle", "12-gon", "L-shape", "U-shape", "flattened")
AREAS = (25.0, 100.0, 400.0, 1600.0, 6400.0)
SPACINGS = (1.0, 1.2, 1.5, 1.8, 2.0)
SPACING_AREA = 400.0
#: Lattice placements of the spacing study: (angle in degrees, offset as
#: fractions of the two lattice vectors).  One placement alone moves the G1
#: share by a few points, as much as the spacing does, so the study averages.
SPACING_PLACEMENTS = tuple((a, f) for a in (0.0, 15.0) for f in ((0.0, 0.0), (0.5, 0.0), (0.0, 0.5), (0.5, 0.5)))
QUICK_AREAS = (25.0, 100.0)
QUICK_SHAPES = ("square", "L-shape", "flattened")
#: The polygon drawn in paper_figs/problem2_mesh.png.
FIGURE_POLYGON = ("flattened", 400.0)

COLUMNS = [
    "study",
    "shape",
    "target_area",
    "area",
    "perimeter",
    "placement",
    "boundary_spacing",
    "angle",
    "offset_x",
    "offset_y",
    "n_nodes",
    "n_edges",
    "n_g1",
    "g1_share",
    "non_g1",
    "non_g1_per_perimeter",
    "n_distinct_lengths",
    "min_edge",
    "max_edge",
    "min_angle_deg",
    "lattice_edges",
    "default_lattice_edges",
    "placement_gain",
    "placement_seconds",
    "seconds",
]


# --------------------------------------------------------------------------- polygons


def flattened(area):
    """A square of side ``sqrt(area)`` sampled at about 1.5 l and mapped by a smooth wave (non-convex).

    ``F(x, y) = (x + a sin(k y + 0.3), y + b sin(k x + 1.1))`` with 1.5 waves per
    side and ``a k = 0.2``, ``b k = 0.15`` (the shape, not the wave count,
    scales with the area), like the flattened boundary of a gently curved
    surface patch (paper, Fig. 3).  Edges are at least ``0.8 * 1.5 l``.
    """
    n = math.sqrt(area)
    k = 2.0 * math.pi * 1.5 / n
    return flattened_square(n, max(2, int(n / 1.5)), 0.2 / k, 0.15 / k, k, k, 0.3, 1.1)


def polygon(shape, area):
    """The polygon ``shape`` scaled to about ``area`` (l = 1)."""
    if shape == "square":
        return rectangle(math.sqrt(area), math.sqrt(area))
    if shape == "rectangle":
        return rectangle(math.sqrt(2.0 * area), math.sqrt(area / 2.0))
    if shape == "12-gon":
        radius = math.sqrt(area / 3.0)  # a regular 12-gon has area 3 R^2
        return regular_polygon(12, 2.0 * radius * math.sin(math.pi / 12.0))
    if shape == "L-shape":
        return letter_polygon("L", 1, 1) * math.sqrt(area / 3.0)
    if shape == "U-shape":
        return letter_polygon("U", 1, 1) * math.sqrt(area / 5.0)
    if shape == "flattened":
        return flattened(area)
    raise ValueError(f"unknown shape {shape!r}")


# --------------------------------------------------------------------------- measurement


def min_angle_deg(mesh):
    """Smallest interior angle over all triangles, in degrees."""
    p = mesh.points[mesh.triangles]
    worst = 180.0
    for i in range(3):
        u = p[:, (i + 1) % 3] - p[:, i]
        v = p[:, (i + 2) % 3] - p[:, i]
        ang = np.degrees(np.arctan2(np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]), np.sum(u * v, axis=1)))
        worst = min(worst, float(ang.min()))
    return worst


def row(study, shape, target, vertices, mesh, placement, spacing, seconds, search=None, search_seconds=math.nan):
    """One CSV row describing ``mesh``."""
    poly = as_polygon(vertices)
    lengths = mesh.edge_lengths()
    n_g1 = int(np.count_nonzero(mesh.edge_groups == G1))
    non_g1 = len(lengths) - n_g1
    offset = mesh.info["offset"]
    return {
        "study": study,
        "shape": shape,
        "target_area": target,
        "area": poly.area,
        "perimeter": poly.perimeter,
        "placement": placement,
        "boundary_spacing": spacing,
        "angle": mesh.info["angle"],
        "offset_x": float(offset[0]),
        "offset_y": float(offset[1]),
        "n_nodes": mesh.n_nodes,
        "n_edges": len(lengths),
        "n_g1": n_g1,
        "g1_share": n_g1 / len(lengths),
        "non_g1": non_g1,
        "non_g1_per_perimeter": non_g1 * L / poly.perimeter,
        "n_distinct_lengths": len(np.unique(np.round(lengths / L, 9))),
        "min_edge": float(lengths.min()),
        "max_edge": float(lengths.max()),
        "min_angle_deg": min_angle_deg(mesh),
        "lattice_edges": search.lattice_edges if search else math.nan,
        "default_lattice_edges": search.default_lattice_edges if search else math.nan,
        "placement_gain": search.gain if search else math.nan,
        "placement_seconds": search_seconds,
        "seconds": seconds,
    }


def measure_size(task):
    """Size study: one polygon with the default and with the searched placement."""
    shape, area = task
    v = polygon(shape, area)
    mesh, sec = timed(equimesh.uniform_triangulation, v, L)
    search, search_sec = timed(equimesh.best_lattice_placement, v, L)
    best, best_sec = timed(equimesh.uniform_triangulation, v, L, angle=search.angle, offset=search.offset)
    return [
        row("size", shape, area, v, mesh, "default", BOUNDARY_SPACING, sec),
        row("size", shape, area, v, best, "best", BOUNDARY_SPACING, best_sec, search, search_sec),
    ]


def measure_spacing(task):
    """Spacing study: one polygon at one boundary_spacing, every placement of :data:`SPACING_PLACEMENTS`."""
    shape, area, spacing = task
    v = polygon(shape, area)
    rows = []
    for angle, frac in SPACING_PLACEMENTS:
        offset = np.asarray(frac) @ lattice_basis(L, angle)
        mesh, sec = timed(equimesh.uniform_triangulation, v, L, angle=angle, offset=offset, boundary_spacing=spacing)
        label = (
            "default"
            if angle == 0.0 and frac == (0.0, 0.0)
            else f"angle {angle:g}, offset {frac[0]:g} a1 + {frac[1]:g} a2"
        )
        rows.append(row("spacing", shape, area, v, mesh, label, spacing, sec))
    return rows


def _measure(task):
    function, argument = task
    return function(argument)


def run(shapes, areas, spacings, spacing_area, jobs, progress=print, scheduler="local"):
    """All measurements, as a DataFrame in a fixed row order whatever ``jobs`` and ``scheduler`` are."""
    tasks = [(measure_size, (s, a)) for a in areas for s in shapes]
    tasks += [(measure_spacing, (s, spacing_area, b)) for s in shapes for b in spacings]
    # Largest first, so the pool is not left waiting on one big polygon at the end.
    order = sorted(range(len(tasks)), key=lambda i: -tasks[i][1][1])
    results = [None] * len(tasks)
    start = time.perf_counter()
    for i, rows in zip(order, _common.parallel_map(_measure, [tasks[i] for i in order], jobs, scheduler=scheduler)):
        results[i] = rows
    progress(f"{NAME}: {len(tasks)} tasks in {time.perf_counter() - start:.1f} s")
    return pd.DataFrame([r for rows in results for r in rows], columns=COLUMNS)


# --------------------------------------------------------------------------- summary


def _fmt(x, spec):
    return "" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


def summarize(df, record):
    """The Markdown report: size table, placement gains, spacing table, provenance."""
    size = df[df["study"] == "size"]
    default = size[size["placement"] == "default"].set_index(["shape", "target_area"])
    best = size[size["placement"] == "best"].set_index(["shape", "target_area"])
    lines = [
        "l = 1.  G1 = lattice edges of length exactly l.  `non-G1 l/P` = non-G1 edges times l over the",
        "perimeter P (bounded: tests/planar/test_strip.py proves non-G1 <= 36/pi P/l + angle terms).",
        "`lengths` = number of distinct edge lengths (rounded to 1e-9 l).  `gain` = relative change of the",
        "G1 count from the default placement (angle 0, offset 0) to `best_lattice_placement`.",
        "",
        "| shape | area | perimeter | edges | G1 share | G1 share (best) | gain | non-G1 | non-G1 l/P | lengths | "
        "min edge | max edge | time (s) | search (s) |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for (shape, target), d in default.iterrows():
        b = best.loc[(shape, target)]
        gain = b["n_g1"] / d["n_g1"] - 1.0 if d["n_g1"] else math.nan
        lines.append(
            f"| {shape} | {d['area']:.0f} | {d['perimeter']:.1f} | {d['n_edges']} | {d['g1_share']:.3f} | "
            f"{b['g1_share']:.3f} | {_fmt(gain, '+.1%')} | {d['non_g1']} | {d['non_g1_per_perimeter']:.2f} | "
            f"{d['n_distinct_lengths']} | {d['min_edge']:.9f} | {d['max_edge']:.6f} | {d['seconds']:.2f} | "
            f"{b['placement_seconds']:.2f} |"
        )
    lines += [
        "",
        f"Over all {len(size)} meshes of the size study: shortest edge {size['min_edge'].min():.12g}, "
        f"longest {size['max_edge'].max():.12g} (Theorem 3: [l, 2l]); non-G1 l/P between "
        f"{size['non_g1_per_perimeter'].min():.2f} and {size['non_g1_per_perimeter'].max():.2f}.",
    ]
    spacing = df[df["study"] == "spacing"]
    if len(spacing):
        per = spacing.groupby(["shape", "boundary_spacing"], sort=False)
        share = per["g1_share"].mean().unstack()
        angle = per["min_angle_deg"].min().unstack()
        default = spacing[spacing["placement"] == "default"].pivot(
            index="shape", columns="boundary_spacing", values="g1_share"
        )
        cols = list(share.columns)
        mean, mean_default = share.mean(axis=0), default.mean(axis=0)
        n_place = spacing.groupby(["shape", "boundary_spacing"]).size().max()
        lines += [
            "",
            f"## Boundary spacing (Step 2 part length, units of l), polygons of {spacing['target_area'].iloc[0]:.0f} "
            "l^2",
            "",
            f"Mean G1 share over {n_place} lattice placements / smallest triangle angle (degrees) over them.",
            "The flattened boundary has no edge longer than 2l, so the spacing does not change it.",
            "",
            "| shape | " + " | ".join(f"{c:g}" for c in cols) + " |",
            "|---|" + "---:|" * len(cols),
        ]
        for shape in share.index:
            cells = [f"{share.loc[shape, c]:.3f} / {angle.loc[shape, c]:.1f}" for c in cols]
            lines.append(f"| {shape} | " + " | ".join(cells) + " |")
        lines.append("| **mean** | " + " | ".join(f"{mean[c]:.3f} / {angle[c].min():.1f}" for c in cols) + " |")
        lines.append("| mean, default placement only | " + " | ".join(f"{mean_default[c]:.3f}" for c in cols) + " |")
        top = share.max(axis=1)
        winners = {
            shape: "=".join(f"{c:g}" for c in cols if share.loc[shape, c] >= top[shape] - 1e-12)
            for shape in share.index
        }
        lines += [
            "",
            f"Largest mean G1 share at spacing {float(mean.idxmax()):g} (default placement only: "
            f"{float(mean_default.idxmax()):g}; library default {BOUNDARY_SPACING:g}); spread of the means "
            f"{mean.max() - mean.min():.3f}.  Best spacing per shape: "
            + ", ".join(f"{s} {w}" for s, w in winners.items())
            + ".",
        ]
    return _common.markdown_report(
        "Problem 2: share of edges of length exactly l (G1)",
        f"`python experiments/{NAME}.py` ({_args(record)})",
        lines,
        record,
    )


def _args(record):
    p = record["parameters"]
    return ", ".join(f"{k} = {v}" for k, v in p.items() if k not in ("out_dir", "fig_dir"))


# --------------------------------------------------------------------------- figures


def plot_mesh(fig_path, shape=FIGURE_POLYGON[0], area=FIGURE_POLYGON[1]):
    """One triangulation, recomputed deterministically: lattice part shaded, G1 edges and the rest coloured."""
    from matplotlib.collections import LineCollection, PolyCollection
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    v = polygon(shape, area)
    mesh = equimesh.uniform_triangulation(v, L)
    g1 = mesh.edge_groups == G1
    seg = mesh.points[mesh.edges]
    tri = mesh.triangles
    pairs = np.sort(np.stack([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]], axis=1), axis=2)
    g1_set = {tuple(e) for e in mesh.edges[g1].tolist()}
    lattice = np.array([all(tuple(p) in g1_set for p in t) for t in pairs.tolist()])

    fig = Figure(figsize=(7.0, 7.4), layout="constrained")
    ax = fig.subplots()
    ax.add_collection(PolyCollection(mesh.points[tri[lattice]], facecolor="#dbe9f6", edgecolor="none", zorder=0))
    ax.add_collection(LineCollection(seg[~g1], colors="#d95f02", linewidths=1.1, zorder=2))
    ax.add_collection(LineCollection(seg[g1], colors="#1f5fa8", linewidths=0.6, zorder=1))
    ring = np.vstack([v, v[:1]])
    ax.plot(ring[:, 0], ring[:, 1], color="black", linewidth=1.8, zorder=3)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_axis_off()
    share = g1.mean()
    ax.set_title(
        f"Problem 2 on a flattened-surface-like boundary, area {as_polygon(v).area:.0f} l$^2$, default placement\n"
        f"{len(g1)} edges: {g1.sum()} in G1 (length exactly l, {share:.1%}), {(~g1).sum()} others in [l, 2l]",
        fontsize=10,
    )
    ax.legend(
        handles=[
            Line2D([], [], color="#1f5fa8", linewidth=1.2, label="G1 edge (lattice, length l)"),
            Line2D([], [], color="#d95f02", linewidth=1.5, label="other edge (boundary strip R)"),
            Patch(facecolor="#dbe9f6", label="lattice part K (H')"),
            Line2D([], [], color="black", linewidth=1.8, label="boundary of P"),
        ],
        loc="upper center",
        bbox_to_anchor=(0.5, -0.01),
        ncol=2,
        frameon=False,
        fontsize=9,
    )
    return _common.save_figure(
        fig, fig_path, {"shape": shape, "target_area": area, "l": L, "placement": "default"}, dpi=160
    )


def plot_share(csv_path, fig_path):
    """G1 share against area per shape (left) and 1 - share against perimeter / area (right), from the CSV."""
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    df = pd.read_csv(csv_path)
    size = df[df["study"] == "size"]
    fig = Figure(figsize=(10.0, 4.0), layout="constrained")
    left, right = fig.subplots(1, 2)
    colors = dict(zip(SHAPES, ("#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#a6761d")))
    for shape, d in size.groupby("shape", sort=False):
        for placement, style in (("default", "-"), ("best", "--")):
            p = d[d["placement"] == placement].sort_values("area")
            left.plot(p["area"], p["g1_share"], style, marker="o", ms=3.5, color=colors.get(shape), label=None)
            x = p["perimeter"] * L / p["area"]
            right.plot(x, 1.0 - p["g1_share"], style, marker="o", ms=3.5, color=colors.get(shape))
    left.axhline(0.75, color="grey", linewidth=0.8, linestyle=":")
    left.text(
        size["area"].max(),
        0.73,
        "75%: acceptance threshold of the tests (convex, 400 l$^2$)",
        fontsize=8,
        color="grey",
        ha="right",
        va="top",
    )
    left.set_xscale("log")
    left.set_xlabel("polygon area (l$^2$)")
    left.set_ylabel("G1 share (edges of length exactly l)")
    left.set_ylim(0.0, 1.0)
    left.set_title("G1 share grows with the polygon (legend: right)", fontsize=10)
    right.set_xlabel("perimeter l / area  (shrinks as 1 / size)")
    right.set_ylabel("1 - G1 share")
    right.set_xlim(left=0.0)
    right.set_ylim(bottom=0.0)
    right.set_title("non-G1 share ~ perimeter / area", fontsize=10)
    handles = [
        Line2D([], [], color=c, marker="o", ms=3.5, label=s) for s, c in colors.items() if s in set(size["shape"])
    ]
    handles += [
        Line2D([], [], color="black", linestyle="-", label="default placement"),
        Line2D([], [], color="black", linestyle="--", label="best_lattice_placement"),
    ]
    right.legend(handles=handles, frameon=False, fontsize=8, loc="upper left")
    return _common.save_figure(fig, fig_path, {"source": str(csv_path)}, dpi=160)


# --------------------------------------------------------------------------- command line


def parse_args(argv=None):
    p = _common.add_output_options(_common.parser(__doc__), jobs=True, plot_only=True)
    p.add_argument(
        "--quick", action="store_true", help="tiny configuration (3 shapes, areas 25 and 100) for smoke tests"
    )
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    csv_path = args.out_dir / f"{NAME}.csv"
    shapes = QUICK_SHAPES if args.quick else SHAPES
    areas = QUICK_AREAS if args.quick else AREAS
    spacing_area = QUICK_AREAS[-1] if args.quick else SPACING_AREA
    if not args.plot_only:
        args.out_dir.mkdir(parents=True, exist_ok=True)
        start = time.perf_counter()
        df = run(shapes, areas, SPACINGS, spacing_area, args.jobs, scheduler=args.scheduler)
        elapsed = time.perf_counter() - start
        parameters = {
            "shapes": list(shapes),
            "areas": list(areas),
            "spacings": list(SPACINGS),
            "spacing_area": spacing_area,
            "l": L,
            "default_boundary_spacing": BOUNDARY_SPACING,
            "quick": args.quick,
            "jobs": args.jobs,
            "scheduler": args.scheduler,
            "out_dir": str(args.out_dir),
            "fig_dir": str(args.fig_dir),
        }
        _common.write_results(csv_path, df, parameters, lambda record: summarize(df, record))
        size = df[df["study"] == "size"]
        print(
            f"{NAME}: {len(df)} meshes in {elapsed:.1f} s; G1 share {size['g1_share'].min():.3f} .. "
            f"{size['g1_share'].max():.3f}; non-G1 l/P {size['non_g1_per_perimeter'].min():.2f} .. "
            f"{size['non_g1_per_perimeter'].max():.2f}"
        )
    args.fig_dir.mkdir(parents=True, exist_ok=True)
    figure_area = FIGURE_POLYGON[1] if not args.quick else QUICK_AREAS[-1]
    plot_mesh(args.fig_dir / f"{NAME}_mesh.png", area=figure_area)
    plot_share(csv_path, args.fig_dir / f"{NAME}_share.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
