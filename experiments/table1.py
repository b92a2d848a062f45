"""Table 1 of the paper (Section 4): member lengths of a surface mesh, stage by stage.

Meshes the reference surface with :func:`equimesh.surface.pipeline.mesh_surface`
(auxiliary grid, flattening by eq. (1), Problem 2 on the plane, remapping by
eqs. (2)-(3), optimisation of the inner nodes) and tabulates the paper's seven
rows with the paper's five columns, the paper's own values beside ours:

* ``initial surf.``      the edges of the auxiliary triangulation on the surface;
* ``plane (G1)``, ``plane (total)``   the triangulation on the plane (Problem 2);
  G1 is "the group of edges that have the same length on the plane";
* ``final surf. (G1)``, ``final surf. (total)``   remapped to the surface,
  before the optimisation;
* ``final opt. (G1)``, ``final opt (total)``      after the optimisation
  (the labels are spelled as in the paper).

The paper's surface is not published (no control points), so ours differs;
``results/table1.md`` says what matches and what does not.

Writes (data only; ``experiments/figures.py`` draws from the .npz)::

    results/table1.csv              the seven rows, ours and the paper's (column "source")
    results/table1_quality.csv      beyond Table 1, per row: share within 1 % / 5 % of l,
                                    distinct lengths at +/-1 %, triangle angle range
    results/table1.md               both tables, run summary, comparison, provenance
    results/table1.provenance.json  commit, parameters, library versions, date
    results/table1_mesh.npz         every stage's arrays (read by experiments/figures.py)

Usage::

    python experiments/table1.py [--surface experiments/surfaces/reference_dome.json]
                                 [--length 5] [--grid 15 15] [--out-dir results]
"""

import io
import math
import sys
import time
import zipfile
from pathlib import Path

import numpy as np
import pandas as pd

from equimesh.io import load_surface
from equimesh.io._atomic import atomic_path
from equimesh.metrics import (
    FABRICATION_COLUMNS,
    TABLE1_COLUMNS,
    TABLE1_HEADINGS,
    edge_lengths,
    fabrication_figures,
    length_stats,
    table1_row,
)
from equimesh.surface.pipeline import mesh_surface

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402

NAME = "table1"
REPO = Path(__file__).resolve().parents[1]
DEFAULT_SURFACE = REPO / "experiments" / "surfaces" / "reference_dome.json"

#: The paper's row labels, in its order (``final opt (total)`` has no period in the paper).
ROWS = (
    "initial surf.",
    "plane (G1)",
    "plane (total)",
    "final surf. (G1)",
    "final surf. (total)",
    "final opt. (G1)",
    "final opt (total)",
)

#: The paper's Table 1, copied digit for digit: (no. of members, mean, min., max., std. dev.).
#: Its surface: a bicubic Bezier surface, 15 x 15 auxiliary grid, l = 5.
PAPER_TABLE1 = {
    "initial surf.": (645, 6.8173, 5.0000, 10.0000, 1.6711),
    "plane (G1)": (774, 5.0000, 5.0000, 5.0000, 0.0000),
    "plane (total)": (954, 5.3633, 4.5893, 9.9727, 0.9888),
    "final surf. (G1)": (774, 5.0775, 4.2043, 6.1972, 0.2780),
    "final surf. (total)": (954, 5.4280, 4.2043, 10.6405, 1.0605),
    "final opt. (G1)": (774, 4.9597, 4.3490, 5.3982, 0.1915),
    "final opt (total)": (954, 5.4765, 4.3490, 13.3777, 1.4842),
}
PAPER_LENGTH = 5.0
PAPER_GRID = (15, 15)

#: Column headings of table1.csv: the row label, who computed it, then the paper's columns.
HEADINGS = [TABLE1_HEADINGS[k] for k in TABLE1_COLUMNS]
COLUMNS = ["row", "source", *HEADINGS]

#: Columns of table1_quality.csv (beyond Table 1).
QUALITY_COLUMNS = ["row", *FABRICATION_COLUMNS]


def parse_args(argv=None):
    p = _common.parser(__doc__)
    p.add_argument(
        "--surface",
        type=Path,
        default=DEFAULT_SURFACE,
        help="surface JSON (default experiments/surfaces/reference_dome.json)",
    )
    p.add_argument("--length", type=float, default=PAPER_LENGTH, help="target member length l (default 5)")
    p.add_argument(
        "--grid",
        type=int,
        nargs=2,
        default=list(PAPER_GRID),
        metavar=("NU", "NV"),
        help="auxiliary grid cells along u and v (default 15 15)",
    )
    return _common.add_output_options(p, fig_dir=False).parse_args(argv)


# --------------------------------------------------------------------------- data


def row_lengths(mesh):
    """The member lengths behind each of the seven rows, as ``{row: (lengths, points, triangles)}``.

    ``points``/``triangles`` are the mesh the lengths are measured on (for the
    angle range); they are None for the G1 rows, whose members do not form
    whole triangles.
    """
    st = mesh.stages
    g1 = mesh.g1_mask
    aux = edge_lengths(st.auxiliary_points, st.grid.edges)
    plane = edge_lengths(st.plane.points, mesh.edges)
    remapped = edge_lengths(st.remapped_points, mesh.edges)
    final = edge_lengths(mesh.points, mesh.edges)
    tri = mesh.triangles
    return {
        "initial surf.": (aux, st.auxiliary_points, st.grid.triangles),
        "plane (G1)": (plane[g1], None, None),
        "plane (total)": (plane, st.plane.points, tri),
        "final surf. (G1)": (remapped[g1], None, None),
        "final surf. (total)": (remapped, st.remapped_points, tri),
        "final opt. (G1)": (final[g1], None, None),
        "final opt (total)": (final, mesh.points, tri),
    }


def table1_frame(rows):
    """Table 1: for each row ours (source "equimesh") then the paper's (source "paper")."""
    records = []
    for name in ROWS:
        ours = table1_row(name, rows[name][0])
        records.append([name, "equimesh", *(ours[k] for k in TABLE1_COLUMNS)])
        records.append([name, "paper", *PAPER_TABLE1[name]])
    df = pd.DataFrame(records, columns=COLUMNS)
    return df.astype({HEADINGS[0]: int})


def quality_frame(rows, l):
    """Beyond Table 1, per row: shares within 1 % / 5 % of l, distinct lengths at +/-1 %, angle range."""
    records = []
    for name in ROWS:
        lengths, points, triangles = rows[name]
        records.append({"row": name, **fabrication_figures(lengths, l, points, triangles)})
    return pd.DataFrame(records, columns=QUALITY_COLUMNS)


def run_summary(mesh, surface, surface_path, grid):
    """Scalars of the run: sizes, lattice placement, flattening energy, optimisation, timings."""
    st = mesh.stages
    opt = st.optimization
    place = st.placement
    aux_boundary_edges = 2 * (grid[0] + grid[1])
    aux = edge_lengths(st.auxiliary_points, st.grid.edges)
    interior = _interior_edge_mask(st.grid)
    return {
        "surface": _display_path(surface_path),
        "surface_kind": _surface_kind(surface),
        "length": mesh.length,
        "grid": list(grid),
        "auxiliary_nodes": int(st.grid.n_nodes),
        "auxiliary_edges": int(len(st.grid.edges)),
        "auxiliary_boundary_edges": aux_boundary_edges,
        "auxiliary_interior_stats": length_stats(aux[interior]),
        "outline_vertices": int(len(st.outline.vertices)),
        "nodes": int(len(mesh.points)),
        "boundary_nodes": int(mesh.n_boundary),
        "triangles": int(len(mesh.triangles)),
        "members": int(len(mesh.edges)),
        "g1_members": int(mesh.g1_mask.sum()),
        "placement": None
        if place is None
        else {
            "angle_deg": float(place.angle),
            "offset": [float(x) for x in place.offset],
            "lattice_edges": int(place.lattice_edges),
            "default_lattice_edges": int(place.default_lattice_edges),
            "gain": float(place.gain),
            "evaluations": int(place.evaluations),
        },
        "flattening_energy": float(st.flattening.energy),
        "flattening_nfev": int(st.flattening.nfev),
        "optimisation": None
        if opt is None
        else {
            "objective": opt.objective,
            "cost_before": float(opt.cost_before),
            "cost_after": float(opt.cost_after),
            "nfev": int(opt.nfev),
            "converged": bool(opt.converged),
            "message": opt.message,
        },
        "seconds": {k: float(v) for k, v in st.seconds.items()},
    }


def _surface_kind(surface):
    degree = getattr(surface, "degree", None)
    if degree is None:
        return f"a {type(surface).__name__} surface"
    names = {1: "bilinear", 2: "biquadratic", 3: "bicubic"}
    if degree[0] == degree[1] and degree[0] in names:
        return f"a {names[degree[0]]} Bezier patch, like the paper's"
    return f"a Bezier patch of degree {tuple(int(d) for d in degree)}"


def _interior_edge_mask(grid):
    """Edges of the auxiliary grid not on the boundary of [0, 1]^2."""
    uv = grid.uv[grid.edges]
    on_side = ((uv[:, 0, 0] == uv[:, 1, 0]) & np.isin(uv[:, 0, 0], (0.0, 1.0))) | (
        (uv[:, 0, 1] == uv[:, 1, 1]) & np.isin(uv[:, 0, 1], (0.0, 1.0))
    )
    return ~on_side


def _display_path(path):
    path = Path(path).resolve()
    try:
        return str(path.relative_to(REPO))
    except ValueError:
        return str(path)


def mesh_arrays(mesh):
    """Every array experiments/figures.py needs, by name (plain numpy arrays)."""
    st = mesh.stages
    place = st.placement
    return {
        "length": np.float64(mesh.length),
        "grid": np.array([st.grid.n_u, st.grid.n_v]),
        "aux_uv": st.grid.uv,
        "aux_triangles": st.grid.triangles,
        "aux_edges": st.grid.edges,
        "aux_boundary": st.grid.boundary,
        "aux_points": st.auxiliary_points,
        "flat_points": st.flattening.points,
        "outline_vertices": st.outline.vertices,
        "plane_points": st.plane.points,
        "triangles": mesh.triangles,
        "edges": mesh.edges,
        "edge_groups": mesh.edge_groups,
        "n_boundary": np.int64(mesh.n_boundary),
        "remapped_uv": st.remapped_uv,
        "remapped_points": st.remapped_points,
        "optimised_uv": mesh.uv,
        "optimised_points": mesh.points,
        "placement_angle": np.float64(place.angle if place is not None else 0.0),
        "placement_offset": np.asarray(place.offset if place is not None else (0.0, 0.0), dtype=float),
    }


def save_npz(path, arrays):
    """``numpy.savez_compressed`` with fixed zip timestamps, so equal data give equal bytes; atomic."""
    with atomic_path(path) as tmp, zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as zf:
        for name in sorted(arrays):
            buf = io.BytesIO()
            np.lib.format.write_array(buf, np.asanyarray(arrays[name]), allow_pickle=False)
            info = zipfile.ZipInfo(f"{name}.npy", date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            zf.writestr(info, buf.getvalue())


# --------------------------------------------------------------------------- report


def _ours(df, row, col):
    return df[(df["row"] == row) & (df["source"] == "equimesh")][TABLE1_HEADINGS[col]].iloc[0]


def _grids_with_edge_count(count, limit=400):
    """All n_u <= n_v with 3 n_u n_v + n_u + n_v == count (edges of an n_u x n_v auxiliary grid)."""
    return [(a, b) for a in range(1, limit) for b in range(a, limit) if 3 * a * b + a + b == count]


def comparison(df, run):
    """The comparison with the paper, as Markdown bullets; every claim is computed from the numbers."""
    l = run["length"]
    nu, nv = run["grid"]
    P = PAPER_TABLE1
    idx = {c: i for i, c in enumerate(TABLE1_COLUMNS)}

    def paper(row, col):
        return P[row][idx[col]]

    def ours(row, col):
        return _ours(df, row, col)

    out = [
        f"- **Different surface.** The paper does not publish its surface's control points; ours is "
        f"`{run['surface']}` ({run['surface_kind']}), so only the kinds of numbers and "
        f"their changes from row to row can be compared, not the digits.",
    ]
    # initial surf.: member count.
    n_aux = ours("initial surf.", "members")
    formula = 3 * nu * nv + nu + nv
    grids = _grids_with_edge_count(P["initial surf."][0])
    sentence = (
        f"- **initial surf., no. of members.** An n_u x n_v auxiliary triangulation has "
        f"3 n_u n_v + n_u + n_v edges: {formula} for our {nu} x {nv} grid (counted: {n_aux}). "
        f"The paper lists {P['initial surf.'][0]} for its 15 x 15 grid, which does not match "
        f"{3 * 15 * 15 + 30}"
    )
    sentence += (
        f"; the only grids with {P['initial surf.'][0]} edges are " + ", ".join(f"{a} x {b}" for a, b in grids)
        if grids
        else f"; no grid has exactly {P['initial surf.'][0]} edges"
    )
    diff = 3 * 15 * 15 + 30 - P["initial surf."][0]
    if diff == 2 * (15 + 15):
        sentence += (
            f". {3 * 15 * 15 + 30} - {P['initial surf.'][0]} = {diff} is exactly the number of boundary edges of a "
            f"15 x 15 grid, so the paper may have counted interior edges only (it does not say)"
        )
        if (nu, nv) == PAPER_GRID:
            s = run["auxiliary_interior_stats"]
            sentence += (
                f"; our interior edges alone: {s['members']} members, mean {s['mean']:.4f}, "
                f"min. {s['min']:.4f}, max. {s['max']:.4f}, std. dev. {s['std']:.4f}"
            )
    out.append(sentence + ".")
    # initial surf.: range.
    lo, hi = ours("initial surf.", "min"), ours("initial surf.", "max")
    inside = lo >= l * (1 - 1e-9) and hi <= 2 * l * (1 + 1e-9)
    out.append(
        f"- **initial surf., lengths.** The paper's auxiliary members span exactly "
        f"[{paper('initial surf.', 'min'):.4f}, {paper('initial surf.', 'max'):.4f}] = [l, 2l]; ours span "
        f"[{lo:.4f}, {hi:.4f}], {'inside' if inside else 'not inside'} [l, 2l] = [{l:g}, {2 * l:g}], "
        f"mean {ours('initial surf.', 'mean'):.4f} (paper {paper('initial surf.', 'mean'):.4f}), "
        f"std. dev. {ours('initial surf.', 'std'):.4f} (paper {paper('initial surf.', 'std'):.4f})."
    )
    # plane (G1).
    g1_dev = max(abs(ours("plane (G1)", "min") - l), abs(ours("plane (G1)", "max") - l))
    out.append(
        f"- **plane (G1) matches.** Every G1 member has length l on the plane: ours to within "
        f"{g1_dev:.1e} (std. dev. {ours('plane (G1)', 'std'):.1e}), the paper's to its four printed decimals."
    )
    # G1 share and placement.
    share = ours("plane (G1)", "members") / ours("plane (total)", "members")
    paper_share = P["plane (G1)"][0] / P["plane (total)"][0]
    text = (
        f"- **Share of G1.** {ours('plane (G1)', 'members')} of {ours('plane (total)', 'members')} members "
        f"({100 * share:.1f} %) are in G1; the paper has {P['plane (G1)'][0]} of {P['plane (total)'][0]} "
        f"({100 * paper_share:.1f} %)."
    )
    place = run["placement"]
    if place is not None:
        text += (
            f" Our lattice placement is searched (beyond the paper): angle {place['angle_deg']:.2f} deg, "
            f"{place['lattice_edges']} lattice edges against {place['default_lattice_edges']} at the default "
            f"placement (angle 0, offset 0), a gain of {100 * place['gain']:+.1f} %."
        )
    out.append(text)
    # plane (total): Theorem 3.
    lo, hi = ours("plane (total)", "min"), ours("plane (total)", "max")
    plo, phi = paper("plane (total)", "min"), paper("plane (total)", "max")
    ours_ok = lo >= l * (1 - 1e-9) and hi <= 2 * l * (1 + 1e-9)
    paper_ok = plo >= l and phi <= 2 * l
    text = (
        f"- **plane (total), Theorem 3.** Theorem 3 puts every member of the planar triangulation in "
        f"[l, 2l]. Ours span [{lo:.4f}, {hi:.4f}]: {'inside' if ours_ok else 'NOT inside'} [l, 2l]."
    )
    if not paper_ok:
        text += (
            f" The paper's span [{plo:.4f}, {phi:.4f}]: its min. {plo:.4f} < l = {PAPER_LENGTH:g}, so its own "
            f"planar triangulation has members shorter than Theorem 3 allows."
        )
    out.append(text)
    # final surf.
    out.append(
        f"- **final surf.** Remapping to the surface spreads the G1 lengths: std. dev. "
        f"{ours('final surf. (G1)', 'std'):.4f}, range [{ours('final surf. (G1)', 'min'):.4f}, "
        f"{ours('final surf. (G1)', 'max'):.4f}], mean {ours('final surf. (G1)', 'mean'):.4f} "
        f"(paper: {paper('final surf. (G1)', 'std'):.4f}, [{paper('final surf. (G1)', 'min'):.4f}, "
        f"{paper('final surf. (G1)', 'max'):.4f}], {paper('final surf. (G1)', 'mean'):.4f})."
    )
    # final opt. (G1).
    sb, sa = ours("final surf. (G1)", "std"), ours("final opt. (G1)", "std")
    psb, psa = paper("final surf. (G1)", "std"), paper("final opt. (G1)", "std")
    rb = ours("final surf. (G1)", "max") - ours("final surf. (G1)", "min")
    ra = ours("final opt. (G1)", "max") - ours("final opt. (G1)", "min")
    prb = paper("final surf. (G1)", "max") - paper("final surf. (G1)", "min")
    pra = paper("final opt. (G1)", "max") - paper("final opt. (G1)", "min")
    verdict = "decreases" if sa < sb else "does NOT decrease"
    out.append(
        f"- **final opt. (G1).** The optimisation {verdict} the G1 std. dev. from {sb:.4f} to {sa:.4f} "
        f"({100 * (sa / sb - 1):+.1f} %; paper {psb:.4f} to {psa:.4f}, {100 * (psa / psb - 1):+.1f} %) and the G1 "
        f"range max. - min. from {rb:.4f} to {ra:.4f} (paper {prb:.4f} to {pra:.4f})."
    )
    opt = run["optimisation"]
    if opt is not None and not opt["converged"]:
        out.append(
            f"- **Optimiser stopped early.** The solver ended at its iteration guard "
            f'({opt["nfev"]} evaluations: "{opt["message"]}"), not at a convergence tolerance; the final opt. rows '
            f"are where it stopped."
        )
    # final opt (total).
    g1min = ours("final opt. (G1)", "min")
    tmin, tmax = ours("final opt (total)", "min"), ours("final opt (total)", "max")
    text = (
        f"- **final opt (total).** Members outside G1 are not in the paper's objective, so nothing keeps them "
        f"in [l, 2l]: the largest grows from {ours('final surf. (total)', 'max'):.4f} to {tmax:.4f} "
        f"(paper {paper('final surf. (total)', 'max'):.4f} to {paper('final opt (total)', 'max'):.4f}) and the "
        f"total std. dev. from {ours('final surf. (total)', 'std'):.4f} to {ours('final opt (total)', 'std'):.4f} "
        f"(paper {paper('final surf. (total)', 'std'):.4f} to {paper('final opt (total)', 'std'):.4f})."
    )
    if tmin < g1min - 1e-9:
        text += (
            f" Our shortest member after optimisation, {tmin:.4f} = {tmin / l:.2f} l, is outside G1 and shorter "
            f"than every G1 member (G1 min. {g1min:.4f}); in the paper the total min. equals the G1 min. "
            f"({paper('final opt (total)', 'min'):.4f})."
        )
    out.append(text)
    return out


def _fmt(x, decimals=4):
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    return f"{x:.{decimals}f}"


def markdown(df, quality, run, record, command):
    """The Markdown report: Table 1 beside the paper's, extras, run summary, comparison, provenance."""
    l = run["length"]
    lines = [
        f"Surface `{run['surface']}`, l = {l:g}, auxiliary grid {run['grid'][0]} x {run['grid'][1]}; "
        f"the paper: its own (unpublished) bicubic Bezier surface, l = {PAPER_LENGTH:g}, grid 15 x 15.",
        "Each cell reads **ours / paper**: our value, then the paper's, copied from its Table 1.",
        "",
        "| | " + " | ".join(HEADINGS) + " |",
        "|---|" + "---:|" * len(HEADINGS),
    ]
    for name in ROWS:
        mine = df[(df["row"] == name) & (df["source"] == "equimesh")].iloc[0]
        theirs = df[(df["row"] == name) & (df["source"] == "paper")].iloc[0]
        cells = [f"{_fmt(mine[h])} / {_fmt(theirs[h])}" for h in HEADINGS]
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    lines += [
        "",
        "G1: the members of length exactly l on the plane (lattice edges of Problem 2). initial surf.: the edges "
        "of the auxiliary triangulation on the surface; final surf.: remapped, before the optimisation; "
        "final opt.: after it. Std. dev. is the population standard deviation.",
        "",
        "## Comparison with the paper",
        "",
        *comparison(df, run),
        "",
        "## Beyond Table 1",
        "",
        "Share of members within 1 % and 5 % of l, the number of distinct member lengths needed at a "
        "+/-1 % (of l) fabrication tolerance, and the range of triangle angles (degrees; whole-mesh rows "
        "only). Ours only: the paper reports none of these.",
        "",
        "| | within 1 % of l | within 5 % of l | distinct lengths (+/-1 %) | min. angle | max. angle |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for r in quality.itertuples(index=False):
        lines.append(
            f"| {r.row} | {100 * r.within_1pct:.1f} % | {100 * r.within_5pct:.1f} % | {r.distinct_lengths_1pct} "
            f"| {_fmt(r.angle_min, 1)} | {_fmt(r.angle_max, 1)} |"
        )
    place, opt = run["placement"], run["optimisation"]
    lines += [
        "",
        "## Run",
        "",
        "| quantity | value |",
        "|---|---|",
        f"| auxiliary triangulation | {run['auxiliary_nodes']} nodes, {run['auxiliary_edges']} edges "
        f"({run['auxiliary_boundary_edges']} on the boundary) |",
        f"| flattening energy E, eq. (1) | {run['flattening_energy']:.6g} ({run['flattening_nfev']} evaluations) |",
        f"| boundary polygon (step 3) | {run['outline_vertices']} vertices |",
        f"| plane triangulation | {run['nodes']} nodes ({run['boundary_nodes']} on the boundary), "
        f"{run['triangles']} triangles, {run['members']} members, {run['g1_members']} in G1 |",
    ]
    if place is None:
        lines.append("| lattice placement | default: angle 0, offset (0, 0) |")
    else:
        lines.append(
            f"| lattice placement (searched, beyond the paper) | angle {place['angle_deg']:.4f} deg, offset "
            f"({place['offset'][0]:.4f}, {place['offset'][1]:.4f}); {place['lattice_edges']} lattice edges against "
            f"{place['default_lattice_edges']} at angle 0, offset (0, 0): gain {100 * place['gain']:+.2f} % "
            f"({place['evaluations']} placements tried) |"
        )
    if opt is not None:
        lines.append(
            f"| optimisation ({opt['objective']}: G1 deviation from l) | cost {opt['cost_before']:.6g} -> "
            f"{opt['cost_after']:.6g}, {opt['nfev']} evaluations, {opt['message']} |"
        )
    for stage, sec in run["seconds"].items():
        lines.append(f"| time: {stage} | {sec:.2f} s |")
    lines += [
        f"| time: total | {sum(run['seconds'].values()):.2f} s |",
        "",
        "Timings are wall-clock seconds of this run and vary from machine to machine.",
    ]
    return _common.markdown_report(
        "Table 1: member lengths of the surface mesh, stage by stage", f"`{command}`", lines, record
    )


# --------------------------------------------------------------------------- main


def main(argv=None):
    args = parse_args(argv)
    out_dir = args.out_dir
    if not out_dir.is_dir():
        out_dir.mkdir(parents=True, exist_ok=True)
    grid = tuple(int(n) for n in args.grid)
    surface = load_surface(args.surface)
    print(f"{NAME}: meshing {_display_path(args.surface)} with l = {args.length:g}, grid {grid[0]} x {grid[1]}")
    start = time.perf_counter()

    def progress(stage, seconds):
        print(f"{NAME}:   {stage}: {seconds:.2f} s", flush=True)

    mesh = mesh_surface(surface, args.length, grid=grid, optimize="paper", progress=progress)
    rows = row_lengths(mesh)
    df = table1_frame(rows)
    quality = quality_frame(rows, mesh.length)
    run = run_summary(mesh, surface, args.surface, grid)

    parameters = {
        "surface": _display_path(args.surface),
        "length": args.length,
        "grid": list(grid),
        "optimize": "paper",
        "placement": "best",
        "out_dir": str(out_dir),
    }
    csv_path = out_dir / f"{NAME}.csv"
    with atomic_path(out_dir / f"{NAME}_quality.csv") as tmp:
        quality.to_csv(tmp, index=False, float_format="%.10g")
    save_npz(out_dir / f"{NAME}_mesh.npz", mesh_arrays(mesh))
    command = (
        f"python experiments/{NAME}.py --surface {parameters['surface']} --length {args.length:g} "
        f"--grid {grid[0]} {grid[1]}"
    )
    _common.write_results(
        csv_path, df, parameters, lambda record: markdown(df, quality, run, record, command), float_format="%.10g"
    )
    g1 = rows["final opt. (G1)"][0]
    print(
        f"{NAME}: wrote {csv_path}, {NAME}_quality.csv, {NAME}.md, {NAME}_mesh.npz in "
        f"{time.perf_counter() - start:.1f} s; {len(mesh.edges)} members, {int(mesh.g1_mask.sum())} in G1, "
        f"G1 std. dev. {np.std(rows['final surf. (G1)'][0]):.4f} -> {np.std(g1):.4f} after optimisation"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
