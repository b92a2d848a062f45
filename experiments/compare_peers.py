"""Side by side with other surface meshers: how many members are (nearly) exactly l, and in [l, 2l].

The benchmark set (:data:`equimesh.testing.benchmark.BENCHMARK`: five 80 x 80
bicubic Bezier surfaces, each with its target length l = 5 = span / 16) is
meshed by every method of one table (:func:`methods`), each a function
``(surface, l) -> (points, triangles)``:

* equimesh, ``optimize="paper"`` and every other objective of
  :data:`equimesh.surface.optimize.OBJECTIVES` (``"bounded"`` when present);
* gmsh through its Python API, from the same Bezier net
  (``gmsh.model.occ.addBezierSurface``), with the algorithms MeshAdapt,
  Delaunay, Frontal-Delaunay and Packing of Parallelograms, the mesh size fixed
  to l (``Mesh.MeshSizeMin = Mesh.MeshSizeMax = l``) and curvature sizing off;
* pymeshlab's isotropic explicit remeshing with target length l, started from a
  fine triangulation of the same surface (``FINE_GRID`` cells, re-projected on it);
* every function of an ``equimesh.methods`` entry point, and every
  ``--method package.module:function`` (docs/benchmark.md);

and every mesh is measured by the one function
:func:`equimesh.metrics.comparison_figures` (shares within 0.5 %, 1 %, 5 % of l,
share in [l, 2l], length classes at 0.5 % and 1 %, length std, angle range),
plus the wall time of the meshing call.  gmsh and pymeshlab are optional (the
``[peers]`` extra); a mesher that cannot be imported is listed as skipped and
the rest is compared.  A method that fails on a surface is a row with its
reason; a ``--method`` that cannot be imported, or a method that returns no
triangle mesh, ends the run with one line and exit code 2, nothing written.

Writes::

    results/compare_peers.csv                one row per (surface, method)
    results/compare_peers.md                 the table, what was skipped, provenance
    results/compare_peers.provenance.json
    results/compare_peers_histograms.csv     member counts per L/l bin of width 0.01 (for the figures)
    paper_figs/compare_peers_<method>.{png,pdf}   member-length histograms, one panel per surface

Usage::

    python experiments/compare_peers.py [--length L] [--surfaces NAME ...] [--methods NAME ...]
                                        [--method package.module:function ...] [--jobs 2]
                                        [--out-dir results] [--fig-dir paper_figs] [--plot-only]
"""

import os
import re
import sys
from importlib import metadata
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from equimesh.errors import InvalidMethodError
from equimesh.mesh import edge_lengths, unique_edges
from equimesh.metrics import COMPARISON_COLUMNS, comparison_figures
from equimesh.surface.auxiliary import auxiliary_grid
from equimesh.surface.optimize import OBJECTIVES
from equimesh.surface.pipeline import mesh_surface
from equimesh.surface.regularity import evaluate
from equimesh.testing.benchmark import BENCHMARK, SPAN, entry_point_methods, load_method, triangle_mesh

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402

NAME = "compare_peers"

#: Cells of the fine triangulation pymeshlab starts from (per side): 0.25 l at the default l.
FINE_GRID = 64

#: Histogram bins of L / l: width 0.01, centred on multiples of 0.01 (the bin at 1 is +-0.5 %).
BIN_WIDTH = 0.01
BIN_RANGE = (0.295, 3.305)

SURFACES = tuple(BENCHMARK)


# --------------------------------------------------------------------------- meshers: (surface, l) -> (points,
# triangles)


def _equimesh(objective):
    def run(surface, l):
        mesh = mesh_surface(surface, l, optimize=objective)
        return mesh.points, mesh.triangles

    return run


#: gmsh's 2-D algorithms by their option value (gmsh manual, Mesh.Algorithm).
GMSH_ALGORITHMS = {"MeshAdapt": 1, "Delaunay": 5, "Frontal-Delaunay": 6, "Packing of Parallelograms": 9}


def _gmsh(algorithm):
    def run(surface, l):
        import gmsh

        gmsh.initialize(readConfigFiles=False)
        try:
            for option, value in (
                ("General.Terminal", 0),
                ("General.NumThreads", 1),
                ("Mesh.Algorithm", algorithm),
                ("Mesh.MeshSizeMin", l),
                ("Mesh.MeshSizeMax", l),
                ("Mesh.MeshSizeFromCurvature", 0),
                ("Mesh.MeshSizeFromPoints", 0),
                ("Mesh.MeshSizeExtendFromBoundary", 0),
            ):
                gmsh.option.setNumber(option, value)
            net = surface.control_points
            rows, cols, _ = net.shape
            tags = [gmsh.model.occ.addPoint(*map(float, net[i, j])) for j in range(cols) for i in range(rows)]
            gmsh.model.occ.addBezierSurface(tags, rows)
            gmsh.model.occ.remove([(0, t) for t in tags])
            gmsh.model.occ.synchronize()
            gmsh.model.mesh.generate(2)
            node_tags, coords, _ = gmsh.model.mesh.getNodes()
            _, _, element_nodes = gmsh.model.mesh.getElements(2)
        finally:
            gmsh.finalize()
        index = np.full(int(node_tags.max()) + 1, -1, dtype=np.int64)
        index[node_tags.astype(np.int64)] = np.arange(node_tags.size)
        triangles = index[np.concatenate(element_nodes).astype(np.int64)].reshape(-1, 3)
        return coords.reshape(-1, 3), triangles

    return run


def _pymeshlab(surface, l):
    import pymeshlab

    grid = auxiliary_grid(FINE_GRID, FINE_GRID)
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=evaluate(surface, grid.uv), face_matrix=grid.triangles.astype(np.int32)))
    ms.meshing_isotropic_explicit_remeshing(targetlen=pymeshlab.PureValue(l), iterations=10)
    mesh = ms.current_mesh()
    return mesh.vertex_matrix(), mesh.face_matrix()


def methods(added=()):
    """``({method: run}, {method: why skipped})``: the one table of methods, in table order.

    The meshers of this script this machine can run, then the functions of
    the ``equimesh.methods`` entry points (by entry-point name), then each
    ``package.module:function`` of ``added`` (by that text).
    """
    run, skipped = {}, {}
    for objective in ("paper", "bounded"):
        if objective in OBJECTIVES:
            run[f"equimesh {objective}"] = _equimesh(objective)
        else:
            skipped[f"equimesh {objective}"] = f"this equimesh has no objective {objective!r}"
    for module, entries in (
        ("gmsh", {f"gmsh {k}": _gmsh(v) for k, v in GMSH_ALGORITHMS.items()}),
        ("pymeshlab", {"pymeshlab isotropic": _pymeshlab}),
    ):
        try:
            __import__(module)
        except ImportError as exc:
            skipped.update({name: f"cannot import {module} ({exc}); pip install 'equimesh[peers]'" for name in entries})
        else:
            run.update(entries)
    run.update(entry_point_methods())
    run.update({spec: load_method(spec) for spec in added})
    return run, skipped


# --------------------------------------------------------------------------- measuring


def measure(task):
    """One (surface, method) run: its figures (:data:`equimesh.metrics.COMPARISON_COLUMNS`) and L/l histogram.

    ``task`` is ``(surface name, method name, l, added)``, ``added`` the
    ``--method`` specs (so that a worker process builds the same table).
    Raises :class:`equimesh.errors.InvalidMethodError` when the method's
    answer is no triangle mesh: the method is wrong, not the surface.
    """
    surface_name, method, l, added = task
    run = methods(added)[0][method]
    row = {"surface": surface_name, "method": method}
    try:
        result, seconds = _common.timed(run, BENCHMARK[surface_name].surface, l)
    except Exception as exc:  # a peer failing on a surface is a result of the comparison, not a crash
        return {
            **row,
            **dict.fromkeys(COMPARISON_COLUMNS, np.nan),
            "nodes": 0,
            "seconds": np.nan,
            "status": f"failed: {type(exc).__name__}: {' '.join(str(exc).split())[:120]}",
        }, None
    points, triangles = triangle_mesh(result, method)
    figures = comparison_figures(points, triangles, l)
    ratios = edge_lengths(points, unique_edges(triangles)) / l
    return {**row, **figures, "nodes": int(len(points)), "seconds": seconds, "status": "ok"}, _histogram(ratios)


def _histogram(ratios):
    edges = np.arange(BIN_RANGE[0], BIN_RANGE[1] + BIN_WIDTH / 2, BIN_WIDTH)
    counts, _ = np.histogram(np.clip(ratios, edges[0], edges[-1]), bins=edges)
    return edges, counts


# --------------------------------------------------------------------------- outputs


def histogram_frame(runs):
    """Long table of the non-empty bins: surface, method, bin centre (L / l), count."""
    records = []
    for row, hist in runs:
        if hist is None:
            continue
        edges, counts = hist
        centres = np.round(0.5 * (edges[:-1] + edges[1:]), 6)
        records += [(row["surface"], row["method"], c, int(n)) for c, n in zip(centres, counts) if n]
    return pd.DataFrame(records, columns=["surface", "method", "ratio", "count"])


def markdown(df, skipped, lengths, record):
    pct = lambda x: "" if pd.isna(x) else f"{100 * x:.1f}"  # noqa: E731
    if len(set(lengths.values())) == 1:
        l = next(iter(lengths.values()))
        target = f"Target length l = {l:g} on 80 x 80 surfaces (span / {SPAN / l:g})"
    else:
        target = "Target lengths " + ", ".join(f"l = {v:g} ({k})" for k, v in lengths.items()) + " on 80 x 80 surfaces"
    body = [
        f"{target}. Shares in % of all members; "
        "classes: fewest length classes at +-0.5 % and +-1 % of l (equimesh.classes); std relative to l; "
        "time: the meshing call alone (equimesh: mesh_surface end to end; pymeshlab: from a "
        f"{FINE_GRID} x {FINE_GRID} grid). In [l, 2l] is strict (up to REL_TOL = 1e-9 relative): a member "
        "0.1 % shorter than l counts as outside, so a mesher aiming at l on average has about half its members "
        "outside.",
        "",
        "| surface | method | members | within 0.5 % | within 1 % | within 5 % | in [l, 2l] | classes 0.5 % "
        "| classes 1 % | std / l | min angle | max angle | time (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in df.itertuples(index=False):
        if r.status != "ok":
            body.append(f"| {r.surface} | {r.method} | {r.status} |" + " |" * 10)
            continue
        body.append(
            f"| {r.surface} | {r.method} | {r.members} | {pct(r.within_05)} | {pct(r.within_1)} | {pct(r.within_5)} "
            f"| {pct(r.in_l_2l)} | {r.classes_05} | {r.classes_1} | {r.length_std:.3f} | {r.angle_min:.1f} "
            f"| {r.angle_max:.1f} | {r.seconds:.2f} |"
        )
    if skipped:
        body += ["", "Not compared on this machine:", ""] + [f"- {k}: {v}" for k, v in skipped.items()]
    return _common.markdown_report("Comparison with other surface meshers", f"experiments/{NAME}.py", body, record)


def plot(hist, fig_dir, parameters):
    """One figure per method: a histogram of L / l on each surface, l and 2l marked."""
    written = []
    for method, part in hist.groupby("method", sort=False):
        surfaces = list(dict.fromkeys(part["surface"]))
        fig = Figure(figsize=(3.0 * len(surfaces), 2.6))
        axes = fig.subplots(1, len(surfaces), squeeze=False, sharey=False)[0]
        for ax, name in zip(axes, surfaces):
            s = part[part["surface"] == name]
            ax.bar(s["ratio"], s["count"], width=BIN_WIDTH, color="tab:blue")
            for x in (1.0, 2.0):
                ax.axvline(x, color="tab:red", lw=0.6, ls="--")
            ax.set_title(name, fontsize=9)
            ax.set_xlabel("member length / l", fontsize=8)
            ax.set_xlim(BIN_RANGE)
        axes[0].set_ylabel("members", fontsize=8)
        fig.suptitle(method, fontsize=10)
        fig.tight_layout()
        slug = re.sub(r"[^a-z0-9]+", "_", method.lower()).strip("_")
        written += _common.save_figure(fig, Path(fig_dir) / f"{NAME}_{slug}", parameters, dpi=120)
    return written


#: Column names of compare_peers.csv (the metric keys, renamed where a dot or a % would not be an identifier).
COLUMNS = ["surface", "method", "nodes", *COMPARISON_COLUMNS, "seconds", "status"]
_IDENTIFIERS = {
    "within_0.5pct": "within_05",
    "within_1pct": "within_1",
    "within_5pct": "within_5",
    "classes_0.5pct": "classes_05",
    "classes_1pct": "classes_1",
}


def _peer_versions():
    """Installed versions of the optional meshers (provenance records only equimesh's own dependencies)."""
    versions = {}
    for package in ("gmsh", "pymeshlab"):
        try:
            versions[package] = metadata.version(package)
        except metadata.PackageNotFoundError:
            versions[package] = None
    return versions


def parse_args(argv=None):
    p = _common.parser(__doc__)
    p.add_argument(
        "--length",
        type=float,
        default=None,
        help="target member length l on every surface (default: each surface's own, "
        + ", ".join(sorted({f"{s.length:g}" for s in BENCHMARK.values()}))
        + ")",
    )
    p.add_argument(
        "--surfaces",
        nargs="+",
        choices=SURFACES,
        default=list(SURFACES),
        metavar="NAME",
        help=f"surfaces to mesh (default all: {', '.join(SURFACES)})",
    )
    p.add_argument(
        "--methods",
        nargs="+",
        default=None,
        metavar="METHOD",
        help="only these methods of the table (names as in the table, e.g. 'gmsh Delaunay'; default all available)",
    )
    p.add_argument(
        "--method",
        action="append",
        default=[],
        metavar="PACKAGE.MODULE:FUNCTION",
        dest="added",
        help="add a mesher, a function (surface, l) -> (points, triangles), to the table; repeatable "
        "(docs/benchmark.md)",
    )
    return _common.add_output_options(p, jobs=True, plot_only=True).parse_args(argv)


def main(argv=None):
    try:
        return _main(parse_args(argv))
    except InvalidMethodError as exc:  # a --method that cannot be loaded or answers no triangle mesh
        print(f"{NAME}: error: {exc}", file=sys.stderr)
        return 2


def _main(args):
    out_dir, fig_dir = Path(args.out_dir), Path(args.fig_dir)
    hist_path = out_dir / f"{NAME}_histograms.csv"
    lengths = {s: BENCHMARK[s].length if args.length is None else args.length for s in args.surfaces}
    parameters = {"lengths": lengths, "surfaces": args.surfaces, "fine_grid": FINE_GRID}
    if args.plot_only:
        plot(pd.read_csv(hist_path), fig_dir, parameters)
        print(f"{NAME}: redrew the figures from {hist_path}")
        return 0
    if args.added:
        sys.path.insert(0, os.getcwd())  # a researcher's module beside them, as `python -m` finds it
    available, skipped = methods(tuple(args.added))
    chosen = [m for m in available if args.methods is None or m in args.methods or m in args.added]
    parameters.update(methods=chosen, peer_versions=_peer_versions())
    tasks = [(s, m, lengths[s], tuple(args.added)) for s in args.surfaces for m in chosen]
    runs = []
    for row, hist in _common.parallel_map(measure, tasks, args.jobs, scheduler=args.scheduler):
        print(
            f"{NAME}: {row['surface']}, {row['method']}: {row['status']}, "
            f"{100 * row['within_0.5pct']:.1f} % within 0.5 % of l, {row['seconds']:.2f} s",
            flush=True,
        )
        runs.append((row, hist))
    df = pd.DataFrame([r for r, _ in runs], columns=COLUMNS).rename(columns=_IDENTIFIERS)
    hist = histogram_frame(runs)
    out_dir.mkdir(parents=True, exist_ok=True)
    with _common.atomic_path(hist_path) as tmp:
        hist.to_csv(tmp, index=False)
    _common.write_results(
        out_dir / f"{NAME}.csv",
        df,
        parameters,
        lambda record: markdown(df, skipped, lengths, record),
        float_format="%.10g",
    )
    plot(hist, fig_dir, parameters)
    for name, why in skipped.items():
        print(f"{NAME}: skipped {name}: {why}")
    print(f"{NAME}: wrote {out_dir / NAME}.csv, .md, {hist_path.name} and the figures in {fig_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
