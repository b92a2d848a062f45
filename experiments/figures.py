"""Figs. 1-4 of the paper (Section 4), and a fifth: the optimised mesh coloured by deviation from l.

Draws only: every array comes from ``results/table1_mesh.npz``, written by
``experiments/table1.py`` (run that first).  The paper's captions:

* Fig. 1 "Auxiliary triangulation of the surface."   -> fig1_auxiliary_surface
* Fig. 2 "Auxiliary triangulation of the plane."     -> fig2_auxiliary_plane
  (the flattened boundary is highlighted: it is not convex)
* Fig. 3 "Triangulation on the plane."               -> fig3_plane_triangulation
  (G1 members, the other members and the boundary polygon of step 3)
* Fig. 4 "Remapping of triangulation to the surface." -> fig4_remapped_surface
* beyond the paper: the mesh after the final optimisation, each member
  coloured by its deviation from l                    -> fig5_optimised_deviation

Writes ``paper_figs/<name>.png`` and ``.pdf`` for each, with
``paper_figs/<name>.provenance.json`` beside them.

Usage::

    python experiments/figures.py [--data results/table1_mesh.npz] [--fig-dir paper_figs]
"""

import json
import sys
import time
from pathlib import Path

import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.colors import TwoSlopeNorm
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from mpl_toolkits.mplot3d.art3d import Line3DCollection
from scipy.spatial import ConvexHull

from equimesh import G1
from equimesh.io.provenance import provenance_path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402

NAME = "figures"
DEFAULT_DATA = Path("results") / "table1_mesh.npz"

#: Colours: G1 members, the other members, boundaries.
G1_COLOUR = "tab:blue"
OTHER_COLOUR = "tab:orange"
BOUNDARY_COLOUR = "tab:red"
SURFACE_COLOUR = "0.85"
VIEW = {"elev": 28.0, "azim": -58.0}


def parse_args(argv=None):
    p = _common.parser(__doc__)
    p.add_argument(
        "--data",
        type=Path,
        default=DEFAULT_DATA,
        help="stage arrays written by experiments/table1.py (default results/table1_mesh.npz)",
    )
    return _common.add_output_options(p, out_dir=False).parse_args(argv)


class MissingDataError(RuntimeError):
    """The data file written by experiments/table1.py is missing."""


def load(path):
    """The arrays of ``results/table1_mesh.npz`` as a dict; a clear error if table1.py has not run."""
    path = Path(path)
    if not path.is_file():
        raise MissingDataError(f"{path} not found: run experiments/table1.py first (it writes the mesh data)")
    with np.load(path, allow_pickle=False) as data:
        return {k: data[k] for k in data.files}


# --------------------------------------------------------------------------- helpers


def _segments(points, edges):
    return np.asarray(points)[np.asarray(edges)]


def _setup_3d(fig, points, position=111):
    """A 3D axes with equal scale on x, y, z, orthographic view from :data:`VIEW`, drawn in zorder."""
    ax = fig.add_subplot(position, projection="3d")
    lo, hi = points.min(axis=0), points.max(axis=0)
    span = np.maximum(hi - lo, 1e-9 * max(1.0, float(np.max(hi - lo))))
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(span)  # equal scale on x, y and z
    ax.set_proj_type("ortho")  # so that _hidden() below sees what the reader sees
    ax.view_init(**VIEW)
    ax.computed_zorder = False  # hidden members, surface, visible members: drawn in that order
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z", labelpad=-2)
    ax.tick_params(labelsize=7, pad=0)
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.pane.set_alpha(0.0)
    ax.grid(False)
    return ax


def _eye_direction():
    """Unit vector from the scene towards the viewer for :data:`VIEW` (as in ``Axes3D.get_proj``)."""
    e, a = np.radians(VIEW["elev"]), np.radians(VIEW["azim"])
    return np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])


def _hidden(points, triangles, edges, chunk=256):
    """(E,) bool: the midpoint of each edge is hidden from the viewer by a triangle of the mesh.

    Hidden-line removal for the 3D figures (matplotlib sorts whole collections,
    not segments, by depth): a ray from the midpoint towards the eye
    (orthographic view) is tested against every triangle (Moller-Trumbore).
    """
    d = _eye_direction()
    p = np.asarray(points, dtype=float)
    v0, v1, v2 = (p[triangles[:, k]] for k in range(3))
    e1, e2 = v1 - v0, v2 - v0
    pvec = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, pvec)
    ok = np.abs(det) > 1e-12
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    mid = p[edges].mean(axis=1)
    eps = 1e-6 * float(np.ptp(p, axis=0).max())
    hidden = np.zeros(len(mid), dtype=bool)
    for start in range(0, len(mid), chunk):
        o = mid[start : start + chunk, None, :] - v0[None]
        u = np.einsum("kij,ij->ki", o, pvec) * inv
        q = np.cross(o, e1[None])
        v = np.einsum("kij,j->ki", q, d) * inv
        t = np.einsum("kij,ij->ki", q, e2) * inv
        hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > eps)
        hidden[start : start + chunk] = hit.any(axis=1)
    return hidden


def _members(ax, points, triangles, edges, width, colors=None, values=None, cmap=None, norm=None, linestyle="solid"):
    """Draw members: visible ones on top of the surface, hidden ones faint beneath it.  Returns the visible
    collection."""
    seg = _segments(points, edges)
    hidden = _hidden(points, triangles, edges)
    made = []
    for mask, zorder, alpha, lw in ((hidden, 0, 0.35, 0.5 * width), (~hidden, 3, 1.0, width)):
        c = Line3DCollection(seg[mask], linewidths=lw, alpha=alpha, zorder=zorder, linestyles=linestyle)
        if values is not None:
            c.set_cmap(cmap)
            c.set_norm(norm)
            c.set_array(values[mask])
        else:
            c.set_color(colors)
        ax.add_collection3d(c)
        made.append(c)
    return made[1]


def _shade(ax, points, triangles, color=SURFACE_COLOUR):
    """A pale surface between the hidden and the visible members."""
    ax.plot_trisurf(
        points[:, 0],
        points[:, 1],
        points[:, 2],
        triangles=triangles,
        color=color,
        alpha=0.55,
        linewidth=0.0,
        antialiased=True,
        shade=True,
        zorder=1,
    )


def _setup_2d(fig, points, position=111):
    ax = fig.add_subplot(position)
    ax.set_aspect("equal")
    pad = 0.03 * float(np.ptp(points, axis=0).max())
    ax.set_xlim(points[:, 0].min() - pad, points[:, 0].max() + pad)
    ax.set_ylim(points[:, 1].min() - pad, points[:, 1].max() + pad)
    ax.set_xlabel("x (plane)")
    ax.set_ylabel("y (plane)")
    ax.tick_params(labelsize=8)
    return ax


def _closed(points):
    return np.vstack([points, points[:1]])


def _boundary_edges(d):
    loop = d["aux_boundary"]
    return np.column_stack([loop, np.roll(loop, -1)])


def _save(fig, fig_dir, name, data_path):
    """Write ``name``.png and .pdf and the provenance JSON beside them, naming the data's own provenance."""
    parameters = {"script": "experiments/figures.py", "figure": name, "source": str(data_path)}
    source_record = provenance_path(Path(data_path).with_name("table1.csv"))
    if source_record.is_file():
        record = json.loads(source_record.read_text(encoding="utf-8"))
        parameters["source_provenance"] = {
            "file": str(source_record),
            "git": record.get("git"),
            "date": record.get("date"),
            "parameters": record.get("parameters"),
        }
    return _common.save_figure(
        fig, Path(fig_dir) / f"{name}.png", parameters, dpi=200, bbox_inches="tight", pad_inches=0.08
    )


def _grid_text(d):
    nu, nv = (int(x) for x in d["grid"])
    return f"{nu} x {nv}"


# --------------------------------------------------------------------------- figures


def fig1_auxiliary_surface(d):
    """Fig. 1: the auxiliary triangulation (step 1) on the surface."""
    p, tri = d["aux_points"], d["aux_triangles"]
    fig = Figure(figsize=(7.6, 5.4), layout="constrained")
    ax = _setup_3d(fig, p)
    _shade(ax, p, tri)
    _members(ax, p, tri, d["aux_edges"], 0.8, colors="navy")
    _members(ax, p, tri, _boundary_edges(d), 1.8, colors=BOUNDARY_COLOUR)
    lengths = np.linalg.norm(np.diff(_segments(p, d["aux_edges"]), axis=1)[:, 0], axis=1)
    fig.suptitle(
        f"Fig. 1  Auxiliary triangulation of the surface\n{_grid_text(d)} grid on [0,1]$^2$, each cell cut into two "
        f"triangles: {len(d['aux_edges'])} members, lengths {lengths.min():.2f} to {lengths.max():.2f} "
        f"(l = {float(d['length']):g})",
        fontsize=10,
    )
    ax.legend(
        handles=[
            Line2D([], [], color="navy", lw=1.0, label="auxiliary members"),
            Line2D([], [], color=BOUNDARY_COLOUR, lw=1.6, label="surface boundary"),
        ],
        loc="upper left",
        fontsize=8,
        frameon=False,
    )
    return fig


def fig2_auxiliary_plane(d):
    """Fig. 2: the auxiliary triangulation flattened by eq. (1); its boundary is not convex."""
    x = d["flat_points"]
    loop = x[d["aux_boundary"]]
    hull = x[ConvexHull(x).vertices]
    fig = Figure(figsize=(6.6, 6.4), layout="constrained")
    ax = _setup_2d(fig, x)
    ax.add_collection(LineCollection(_segments(x, d["aux_edges"]), colors="0.45", linewidths=0.6))
    ax.plot(*_closed(hull).T, color="0.2", lw=1.0, ls="--", label="convex hull (for comparison)")
    ax.plot(*_closed(loop).T, color=BOUNDARY_COLOUR, lw=2.0, label="boundary of the flattened triangulation")
    gap = _max_gap_to_hull(loop, hull)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.08), ncol=2, fontsize=8, frameon=False)
    ax.set_title(
        "Fig. 2  Auxiliary triangulation of the plane (flattened by eq. (1))\n"
        f"the boundary is not convex: it lies up to {gap:.2f} (= {gap / float(d['length']):.2f} l) inside its convex "
        "hull",
        fontsize=10,
    )
    return fig


def _max_gap_to_hull(loop, hull):
    """Largest distance from a boundary point to the convex hull's boundary (0 for a convex loop)."""
    a, b = hull, np.roll(hull, -1, axis=0)
    ab = b - a
    t = np.clip(np.einsum("kij,ij->ki", loop[:, None, :] - a[None], ab) / np.einsum("ij,ij->i", ab, ab), 0.0, 1.0)
    nearest = a[None] + t[..., None] * ab[None]
    return float(np.linalg.norm(loop[:, None, :] - nearest, axis=2).min(axis=1).max())


def _group_collections(points, edges, groups, g1_width=0.9, other_width=1.1):
    seg = _segments(points, edges)
    g1 = groups == G1
    return (
        LineCollection(seg[~g1], colors=OTHER_COLOUR, linewidths=other_width),
        LineCollection(seg[g1], colors=G1_COLOUR, linewidths=g1_width),
    )


def _group_legend(d, extra=()):
    g1 = d["edge_groups"] == G1
    l = float(d["length"])
    return [
        Line2D([], [], color=G1_COLOUR, lw=1.5, label=f"G1: {int(g1.sum())} members of length l = {l:g} on the plane"),
        Line2D([], [], color=OTHER_COLOUR, lw=1.5, label=f"other: {int((~g1).sum())} members (boundary strip)"),
        *extra,
    ]


def fig3_plane_triangulation(d):
    """Fig. 3: Problem 2's triangulation of the flattened boundary polygon, G1 members marked."""
    x, outline = d["plane_points"], d["outline_vertices"]
    fig = Figure(figsize=(6.6, 6.6), layout="constrained")
    ax = _setup_2d(fig, np.vstack([x, d["flat_points"]]))
    for c in _group_collections(x, d["edges"], d["edge_groups"]):
        ax.add_collection(c)
    ax.plot(*_closed(outline).T, color="black", lw=1.6)
    ax.plot(*outline.T, "o", color="black", ms=2.5)
    extra = [
        Line2D(
            [], [], color="black", lw=1.6, marker="o", ms=3, label=f"boundary polygon (step 3): {len(outline)} vertices"
        )
    ]
    ax.legend(
        handles=_group_legend(d, extra),
        loc="upper center",
        bbox_to_anchor=(0.5, -0.08),
        ncol=1,
        fontsize=8,
        frameon=False,
    )
    ax.set_title(
        f"Fig. 3  Triangulation on the plane (Problem 2)\n{len(x)} nodes, {len(d['triangles'])} triangles, "
        f"{len(d['edges'])} members; lattice rotated {float(d['placement_angle']):.1f} deg",
        fontsize=10,
    )
    return fig


def fig4_remapped_surface(d):
    """Fig. 4: the plane triangulation remapped to the surface by eqs. (2)-(3), before optimisation."""
    p = d["remapped_points"]
    fig = Figure(figsize=(7.6, 5.4), layout="constrained")
    ax = _setup_3d(fig, p)
    _shade(ax, p, d["triangles"])
    g1 = d["edge_groups"] == G1
    _members(ax, p, d["triangles"], d["edges"][~g1], 1.1, colors=OTHER_COLOUR)
    _members(ax, p, d["triangles"], d["edges"][g1], 0.9, colors=G1_COLOUR)
    lengths = np.linalg.norm(np.diff(_segments(p, d["edges"]), axis=1)[:, 0], axis=1)
    ax.legend(handles=_group_legend(d), loc="upper left", fontsize=8, frameon=False)
    fig.suptitle(
        "Fig. 4  Remapping of the triangulation to the surface (eqs. (2)-(3), before optimisation)\n"
        f"G1 lengths {lengths[g1].min():.2f} to {lengths[g1].max():.2f}, std. dev. {lengths[g1].std():.3f}",
        fontsize=10,
    )
    return fig


def fig5_optimised_deviation(d):
    """Beyond the paper: the optimised mesh, each member coloured by (L - l) / l, diverging around 0."""
    p, l = d["optimised_points"], float(d["length"])
    seg = _segments(p, d["edges"])
    lengths = np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1)
    dev = 100.0 * (lengths - l) / l
    g1 = d["edge_groups"] == G1
    # Colour scale: symmetric, set by the G1 members (the optimised ones); others beyond it saturate.
    lim = float(np.max(np.abs(dev[g1]))) if g1.any() else float(np.max(np.abs(dev)))
    lim = max(lim, 1e-6)
    norm = TwoSlopeNorm(vcenter=0.0, vmin=-lim, vmax=lim)
    cmap = "RdBu_r"

    fig = Figure(figsize=(11.0, 6.6), layout="constrained")
    gs = fig.add_gridspec(2, 2, width_ratios=[2.0, 1.0])
    ax = _setup_3d(fig, p, gs[:, 0])
    _shade(ax, p, d["triangles"], color="0.55")  # mid grey: the white (zero deviation) members stay visible
    tri = d["triangles"]
    _members(ax, p, tri, d["edges"][~g1], 1.0, values=dev[~g1], cmap=cmap, norm=norm, linestyle=(0, (2.0, 1.2)))
    members = _members(ax, p, tri, d["edges"][g1], 1.4, values=dev[g1], cmap=cmap, norm=norm)
    bar = fig.colorbar(members, ax=ax, location="bottom", shrink=0.6, pad=0.02, aspect=40, extend="both")
    bar.set_label("member length deviation (L - l) / l  [%]")
    ax.legend(
        handles=[
            Line2D([], [], color="0.3", lw=1.4, label=f"G1 members ({int(g1.sum())})"),
            Line2D(
                [],
                [],
                color="0.3",
                lw=1.0,
                ls=(0, (2.0, 1.2)),
                label=f"other members ({int((~g1).sum())}); colour saturates beyond the bar",
            ),
        ],
        loc="upper left",
        fontsize=8,
        frameon=False,
    )

    top, bottom = fig.add_subplot(gs[0, 1]), fig.add_subplot(gs[1, 1])
    top.hist(dev[g1], bins=np.linspace(-lim, lim, 41), color=G1_COLOUR)
    top.axvline(0.0, color="black", lw=0.8)
    top.set_title(
        f"G1 members: std. dev. {lengths[g1].std():.3f} (= {100 * lengths[g1].std() / l:.1f} % of l)", fontsize=9
    )
    top.set_ylabel("members")
    other_dev = dev[~g1] if (~g1).any() else np.zeros(1)
    bottom.hist(
        other_dev, bins=np.arange(np.floor(other_dev.min() / 5) * 5, other_dev.max() + 5.0, 5.0), color=OTHER_COLOUR
    )
    bottom.axvline(0.0, color="black", lw=0.8)
    bottom.axvspan(-lim, lim, color="0.88", zorder=0, label="range of the colour bar")
    bottom.set_title("other members (not in the objective)", fontsize=9)
    bottom.set_xlabel("(L - l) / l  [%]")
    bottom.set_ylabel("members")
    bottom.legend(fontsize=8, frameon=False)
    fig.suptitle(
        f"Fig. 5 (beyond the paper)  Optimised mesh on the surface: deviation of each member from l = {l:g}\n"
        f"G1 members {lengths[g1].min():.2f} to {lengths[g1].max():.2f}; all members {lengths.min():.2f} to "
        f"{lengths.max():.2f}",
        fontsize=10,
    )
    return fig


#: Figure name -> drawing function, in the paper's order.
FIGURES = {
    "fig1_auxiliary_surface": fig1_auxiliary_surface,
    "fig2_auxiliary_plane": fig2_auxiliary_plane,
    "fig3_plane_triangulation": fig3_plane_triangulation,
    "fig4_remapped_surface": fig4_remapped_surface,
    "fig5_optimised_deviation": fig5_optimised_deviation,
}


def main(argv=None):
    args = parse_args(argv)
    try:
        d = load(args.data)
    except MissingDataError as exc:
        print(f"{NAME}: error: {exc}", file=sys.stderr)
        return 2
    args.fig_dir.mkdir(parents=True, exist_ok=True)
    for name, draw in FIGURES.items():
        start = time.perf_counter()
        outputs = _save(draw(d), args.fig_dir, name, args.data)
        print(f"{NAME}: wrote {', '.join(outputs)} in {time.perf_counter() - start:.1f} s", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
