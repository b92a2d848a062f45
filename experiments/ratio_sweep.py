"""Theorem 2 in practice: the distribution of n' / LB over random convex polygons.

For each of ``--n-polygons`` seeded random convex polygons (every inner angle
>= 90 degrees, every edge >= l = 1, :func:`equimesh.testing.generators.random_convex_polygon`)
run Algorithm INCREMENT and compare its node count n' with the proven lower
bound LB <= n* (:func:`equimesh.node_lower_bound`); Theorem 2 promises
n' <= 16/3 n*, the sweep checks the stronger n' <= 16/3 LB.

Writes (``results/`` data, ``paper_figs/`` figure drawn from the data only)::

    results/ratio_sweep.csv               one row per polygon
    results/ratio_sweep.md                summary: min / median / max ratio, worst polygon, provenance
    results/ratio_sweep.provenance.json   commit, parameters, library versions, date
    paper_figs/ratio_sweep.png, .pdf      histogram of n'/LB with the 16/3 line
    paper_figs/ratio_sweep.provenance.json

Size distribution.  The area is log-uniform on [1, ``--max-area``] l^2, and a
fraction ``--tail-fraction`` of the polygons is log-uniform on
[``--max-area``, ``--tail-max-area``]; node counts run from 4 to about
35,000.  The insertion engine is ``--engine`` (the fast one by default: the
reference engine re-triangulates after every insertion, about 1.5 s for a
polygon of 700 l^2, and kept the sweep below 700 l^2); the whole sweep
should take about a minute on two cores.  The report gives n'/LB per decade
of area and the figure draws it against the area.

Usage::

    python experiments/ratio_sweep.py [--n-polygons 2000] [--seed 20261122] [--jobs 2] [--engine fast]
    python experiments/ratio_sweep.py --plot-only      # redraw the figure from the CSV
"""

import json
import math
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

import equimesh
from equimesh import REL_TOL
from equimesh.planar.increment import validate_problem1
from equimesh.planar.insertion import DEFAULT_ENGINE, ENGINES
from equimesh.testing.generators import random_convex_polygon

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402

NAME = "ratio_sweep"
THEOREM2 = 16.0 / 3.0

#: Columns of the CSV, in order.
COLUMNS = [
    "index",
    "n_nodes",
    "lower_bound",
    "packing_upper_bound",
    "ratio",
    "area",
    "perimeter",
    "n_vertices",
    "n_boundary",
    "min_edge",
    "max_edge",
    "vertices",
]


def parse_args(argv=None):
    p = _common.parser(__doc__)
    p.add_argument("--n-polygons", type=int, default=2000, help="number of random polygons (default 2000)")
    p.add_argument("--seed", type=int, default=20261122, help="root seed (default 20261122)")
    _common.add_output_options(p, jobs=True, plot_only=True)
    p.add_argument("--max-area", type=float, default=1e4, help="upper end of the main area range, in l^2")
    p.add_argument("--tail-fraction", type=float, default=0.02, help="fraction of polygons in the large-area tail")
    p.add_argument("--tail-max-area", type=float, default=3e4, help="upper end of the tail's area range, in l^2")
    p.add_argument(
        "--engine", choices=sorted(ENGINES), default=DEFAULT_ENGINE, help=f"insertion engine (default {DEFAULT_ENGINE})"
    )
    return p.parse_args(argv)


def draw_polygon(seed_sequence, max_area, tail_fraction, tail_max_area):
    """One random valid input of Problem 1 (l = 1), determined by ``seed_sequence`` alone."""
    rng = np.random.default_rng(seed_sequence)
    lo, hi = (max_area, tail_max_area) if rng.random() < tail_fraction else (1.0, max_area)
    area = math.exp(rng.uniform(math.log(lo), math.log(hi)))
    return random_convex_polygon(
        rng,
        n_vertices=int(rng.integers(4, 13)),
        area=area,
        elongation=math.exp(rng.uniform(0.0, math.log(30.0))),
        length_spread=float(rng.choice([1.0, 2.0, 4.0, 8.0])),
        min_turn=float(rng.choice([0.0, 0.5, 0.9])),
        max_area=hi,
    )


def measure(task):
    """Run INCREMENT on polygon ``index`` and return its CSV row."""
    index, seed_sequence, options, engine = task
    vertices = draw_polygon(seed_sequence, **options)
    l = 1.0
    poly, _ = validate_problem1(vertices, l)
    mesh = equimesh.increment(vertices, l, engine=engine, max_nodes=None)
    lb = equimesh.node_lower_bound(vertices, l)
    lengths = mesh.edge_lengths()
    return {
        "index": index,
        "n_nodes": mesh.n_nodes,
        "lower_bound": lb,
        "packing_upper_bound": equimesh.packing_upper_bound(vertices, (1.0 - REL_TOL) * l),
        "ratio": mesh.n_nodes / lb,
        "area": poly.area,
        "perimeter": poly.perimeter,
        "n_vertices": len(poly.vertices),
        "n_boundary": mesh.n_boundary,
        "min_edge": float(lengths.min()),
        "max_edge": float(lengths.max()),
        "vertices": json.dumps(vertices.tolist()),
    }


def sweep(n_polygons, seed, jobs, options, engine=DEFAULT_ENGINE, progress=print, scheduler="local"):
    """Measure ``n_polygons`` polygons; rows in index order whatever ``jobs`` and ``scheduler`` are.

    Polygon ``i`` is drawn from child ``i`` of ``numpy.random.SeedSequence(seed)``,
    so a row does not depend on the number of workers or on the other rows.
    """
    children = np.random.SeedSequence(seed).spawn(n_polygons)
    tasks = [(i, child, options, engine) for i, child in enumerate(children)]
    start = time.perf_counter()
    every = max(1, n_polygons // 10)
    rows = []
    for row in _common.parallel_map(measure, tasks, jobs, chunksize=4, scheduler=scheduler):
        rows.append(row)
        if len(rows) % every == 0 or len(rows) == n_polygons:
            progress(f"{NAME}: {len(rows)}/{n_polygons} polygons, {time.perf_counter() - start:.1f} s")
    return pd.DataFrame(rows, columns=COLUMNS)


def summarize(df, record):
    """The Markdown summary of the sweep, with its provenance block."""
    worst = df.loc[df["ratio"].idxmax()]
    within = int((3 * df["n_nodes"] <= 16 * df["lower_bound"]).sum())
    packed = int((df["n_nodes"] <= df["packing_upper_bound"]).sum())
    params = record["parameters"]
    args = " ".join(f"--{k.replace('_', '-')} {v}" for k, v in params.items() if k not in ("out_dir", "fig_dir"))
    vertices = json.loads(worst["vertices"])
    return _common.markdown_report(
        "Ratio sweep: node count of Algorithm INCREMENT against the lower bound",
        f"`python experiments/{NAME}.py {args}`",
        [
            "Theorem 2 of the paper: n' <= 16/3 n*.  LB = `equimesh.node_lower_bound` <= n*,",
            "so n' <= 16/3 LB is the stronger statement checked here.",
            "",
            "| polygons | n' range | min n'/LB | median n'/LB | max n'/LB | n' <= 16/3 LB | n' <= packing bound |",
            "|---:|---:|---:|---:|---:|---:|---:|",
            f"| {len(df)} | {df['n_nodes'].min()} .. {df['n_nodes'].max()} | {df['ratio'].min():.4f} "
            f"| {df['ratio'].median():.4f} | {df['ratio'].max():.4f} | {within} / {len(df)} | {packed} / {len(df)} |",
            "",
            f"Edge lengths over all meshes (l = 1): min {df['min_edge'].min():.12g}, max {df['max_edge'].max():.12g}.",
            "",
            "## n'/LB against the area",
            "",
            *by_area(df),
            "",
            f"## Worst polygon (index {int(worst['index'])})",
            "",
            f"n' = {int(worst['n_nodes'])}, LB = {int(worst['lower_bound'])}, n'/LB = {worst['ratio']:.4f}, "
            f"area {worst['area']:.6g}, perimeter {worst['perimeter']:.6g}, {int(worst['n_vertices'])} vertices, l = "
            "1:",
            "",
            "```",
            json.dumps(vertices),
            "```",
        ],
        record,
    )


def by_area(df):
    """Markdown table of n'/LB per decade of area (in l^2)."""
    decade = np.floor(np.log10(df["area"])).astype(int)
    lines = [
        "| area (l^2) | polygons | n' range | min n'/LB | median n'/LB | max n'/LB |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for d, g in df.groupby(decade):
        lines.append(
            f"| 10^{d} .. 10^{d + 1} | {len(g)} | {g['n_nodes'].min()} .. {g['n_nodes'].max()} | "
            f"{g['ratio'].min():.4f} | {g['ratio'].median():.4f} | {g['ratio'].max():.4f} |"
        )
    return lines


def plot(csv_path, fig_path):
    """Histogram of n'/LB with the 16/3 line of Theorem 2, drawn from the CSV only.

    Writes ``fig_path`` with suffix ``.png`` and ``.pdf`` and a provenance
    JSON beside them.
    """
    from matplotlib.figure import Figure

    df = pd.read_csv(csv_path)
    fig = Figure(figsize=(9.0, 3.6), layout="constrained")
    hist, scatter = fig.subplots(1, 2)
    bins = np.arange(0.95, max(THEOREM2, df["ratio"].max()) + 0.1, 0.05)
    hist.hist(df["ratio"], bins=bins, color="tab:blue", edgecolor="white", linewidth=0.4)
    hist.axvline(THEOREM2, color="tab:red", linestyle="--", label="16/3 (Theorem 2)")
    hist.axvline(df["ratio"].median(), color="black", linewidth=1.0, label=f"median {df['ratio'].median():.2f}")
    hist.set_xlabel("n' / LB  (INCREMENT nodes / lower bound on the optimum)")
    hist.set_ylabel("polygons")
    hist.set_title(f"{len(df)} random convex polygons, inner angles >= 90 deg", fontsize=10)
    hist.legend(frameon=False, fontsize=8)
    scatter.scatter(df["area"], df["ratio"], s=4, alpha=0.5, color="tab:blue", linewidths=0)
    scatter.axhline(THEOREM2, color="tab:red", linestyle="--")
    scatter.set_xscale("log")
    scatter.set_xlabel("area of the polygon (l^2)")
    scatter.set_ylabel("n' / LB")
    scatter.set_ylim(0.9, THEOREM2 + 0.3)
    scatter.set_title("ratio against area", fontsize=10)
    return _common.save_figure(fig, fig_path, {"source": str(csv_path)}, dpi=150)


def main(argv=None):
    args = parse_args(argv)
    csv_path = args.out_dir / f"{NAME}.csv"
    fig_path = args.fig_dir / f"{NAME}.png"
    if not args.plot_only:
        options = {"max_area": args.max_area, "tail_fraction": args.tail_fraction, "tail_max_area": args.tail_max_area}
        start = time.perf_counter()
        df = sweep(args.n_polygons, args.seed, args.jobs, options, args.engine, scheduler=args.scheduler)
        elapsed = time.perf_counter() - start
        parameters = {k: (str(v) if isinstance(v, Path) else v) for k, v in vars(args).items() if k != "plot_only"}
        _common.write_results(csv_path, df, parameters, lambda record: summarize(df, record))
        print(
            f"{NAME}: {len(df)} polygons in {elapsed:.1f} s; n'/LB min {df['ratio'].min():.4f}, "
            f"median {df['ratio'].median():.4f}, max {df['ratio'].max():.4f}"
        )
    plot(csv_path, fig_path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
