"""Beyond the paper: fewest member types and sound joints, equimesh against other meshers on untuned surfaces.

The paper's aim is "to reduce the different number of edge lengths".  On four
surfaces that no constant of equimesh was chosen on (80 x 80 bicubic Bezier
patches: two doubly curved, two developable) at l = span / 16, and the
doubly curved ones also at span / 24 and span / 30 (the finest l of the
targets), every method is measured by
:func:`equimesh.metrics.comparison_figures`:

* equimesh ``optimize="paper"``, ``"bounded"`` and ``"classes"`` (the fewest
  length classes), the last with nodes on the surface and with a surface
  tolerance D of 0.25, 0.5, 1 and 2 % of l (the frontier: how many member
  types a deviation from the design surface buys);
* the lever "Step 2's spacing on the surface": the classes objective solved
  with the outline's nodes at equal arc lengths of each side on the surface,
  held (:func:`_outline_held`);
* the lever "the strip's connectivity": the classes objective's mesh with
  its inner members more than the tolerance from every nominal length of
  the ten largest classes flipped where the other diagonal comes nearer one
  of them (:func:`strip_flips`), solved again, and beside it the same mesh
  solved again unflipped (:func:`_solved_again`);
* gmsh's four algorithms and pymeshlab's isotropic remeshing, exactly as
  ``experiments/compare_peers.py`` runs them (its peers, reused).

Figures: length classes at +-0.5 % and +-1 % of l, the share of members in
the largest class and in the ten largest, the share within 0.5 % of l, the
smallest and largest triangle angle, the share of triangles with an angle
below 30 degrees, the nodes' deviation from the surface (max, mean) and the
wall time of the meshing call.

Writes::

    results/fabrication.csv                  one row per (surface, l, method)
    results/fabrication.md                   the table, the targets, provenance
    results/fabrication.provenance.json
    results/fabrication_classes.csv          the class sizes of every mesh, largest first (for the figure)
    paper_figs/fabrication_frontier.{png,pdf}      classes and top-10 share against D
    paper_figs/fabrication_member_types.{png,pdf}  share of the members in the k largest classes, per method

Usage::

    python experiments/fabrication.py [--jobs 2] [--quick] [--surfaces NAME ...] [--methods METHOD ...]
                                       [--out-dir results] [--fig-dir paper_figs] [--plot-only]
"""

import sys
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, compare_peers.py, also when loaded by path
import _common  # noqa: E402
import compare_peers  # noqa: E402

from equimesh.classes import length_classes  # noqa: E402
from equimesh.mesh import G1, OTHER, edge_keys, edge_lengths, half_edges, unique_edges  # noqa: E402
from equimesh.metrics import (  # noqa: E402
    COMPARISON_COLUMNS,
    MEMBER_KINDS,
    TOP_CLASSES,
    classes_by_kind,
    comparison_figures,
    share_within,
    triangle_angles,
)
from equimesh.surface.charts.bezier import BezierSurface  # noqa: E402
from equimesh.surface.optimize import optimize_uv  # noqa: E402
from equimesh.surface.optimize.jacobian import signed_areas  # noqa: E402
from equimesh.surface.optimize.joints import joint_bounds  # noqa: E402
from equimesh.surface.output_checks import check_joints, check_members, check_orientation  # noqa: E402
from equimesh.surface.pipeline import mesh_surface  # noqa: E402
from equimesh.tolerance import JOINT_ANGLE  # noqa: E402

NAME = "fabrication"
SPAN = 80.0
#: l = span / divisor; the later ones only on the doubly curved surfaces (and without the peers' gmsh variants).
DIVISORS = (16, 24, 30)
#: Surface tolerances D of the frontier, as fractions of l.
SURFACE_TOLERANCES = (0.0, 0.0025, 0.005, 0.01, 0.02)
#: The method of :func:`_outline_held`, and its points per side.
OUTLINE_HELD = "equimesh classes, outline held equal"
SIDE_SAMPLES = 2001
#: The methods of :func:`_solved_again`: the classes objective's mesh solved again as it is, and with its strip
#: flipped (:func:`strip_flips`).
SOLVED_AGAIN, STRIP_FLIPPED = "equimesh classes, solved again", "equimesh classes, strip flipped"
#: How near (in units of l) a nominal length of the ten largest classes a flipped member's new diagonal must come.
FLIP_REACH = 0.05
#: The targets of the fewest-classes objective (with the default equimesh mesh, nodes on the surface).
TARGETS = {"classes vs gmsh Frontal-Delaunay": 0.5, "top-10 share": 0.95, "within 0.5 %": (0.5, 0.75)}


def _net(heights):
    """A bicubic net over SPAN x SPAN with the (4, 4) control heights ``heights`` (first axis along u = x)."""
    t = np.linspace(0.0, SPAN, 4)
    x, y = np.meshgrid(t, t, indexing="ij")
    return BezierSurface(np.stack([x, y, np.asarray(heights, dtype=float)], axis=-1))


def _cone():
    """A conical vault: rulings from a cubic arch at y = 0 towards an apex beyond y = SPAN, cut at y = SPAN (degree
    (3, 1), developable: every ruling passes through the apex)."""
    arch = np.stack([np.linspace(0.0, SPAN, 4), np.zeros(4), [0.0, 30.0, 30.0, 0.0]], axis=-1)
    apex = np.array([SPAN / 2, 2.5 * SPAN, 0.0])
    far = apex + 0.6 * (arch - apex)  # the arch scaled towards the apex: the same cone
    return BezierSurface(np.stack([arch, far], axis=1))


def surfaces():
    """(name, developable, surface): the four untuned surfaces."""
    return [
        ("asymmetric dome", False, _net([[0, 8, 8, 0], [6, 26, 20, 4], [4, 22, 16, 2], [0, 6, 6, 0]])),
        ("anticlastic roof", False, _net(np.outer([10, -4, -4, 10], [1, 1, 1, 1]) + np.outer([1] * 4, [0, 9, 9, 0]))),
        ("cylinder vault", True, _net(np.tile([0.0, 24.0, 24.0, 0.0], (4, 1)).T)),
        ("cone vault", True, _cone()),
    ]


def _equimesh(objective, fraction=0.0):
    def run(surface, l):
        mesh = mesh_surface(surface, l, optimize=objective, surface_tolerance=fraction * l, max_nodes=None)
        remapped = edge_lengths(mesh.stages.remapped_points, mesh.edges) / l
        dev_max, dev_mean = mesh.deviation()
        within = share_within(remapped, 1.0, 0.005)
        return mesh.points, mesh.triangles, {"deviation_max": dev_max, "deviation_mean": dev_mean, REMAPPED: within}

    return run


def _outline_held(surface, l):
    """The classes objective from the remapped mesh with the outline's nodes at equal arc lengths of each side on
    the surface (``SIDE_SAMPLES`` points per side), held: the members of a side are chords of one arc length, one
    length to the curvature's effect, whatever the flattening did to them; the outputs of :func:`_equimesh`, the
    pipeline's checks run on the mesh.  The sides are straight in (u, v) between the four corners of the parameter
    rectangle, as on every surface here (a surface with openings is refused).  The meshing call is timed less the
    pipeline's own optimisation, which only gives this one its plane and start."""
    mesh = mesh_surface(surface, l, optimize="classes", max_nodes=None)
    plane, start = mesh.stages.plane, np.array(mesh.stages.remapped_uv)
    n = plane.n_boundary
    corners = np.sort(mesh.stages.outline.slides(plane, start)[1])
    if len(plane.info["boundary_rings"]) != 1 or len(corners) != 4:
        raise ValueError("the outline held equal needs one ring with the parameter rectangle's four corners")
    for a, b in zip(corners, np.append(corners[1:], corners[0] + n)):
        side = np.arange(a, b + 1) % n
        chord = start[side[-1]] - start[side[0]]
        t = np.linspace(0.0, 1.0, SIDE_SAMPLES)
        points = surface.evaluate(start[side[0], 0] + t * chord[0], start[side[0], 1] + t * chord[1])
        arc = np.append(0.0, np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1)))
        start[side] = start[side[0]] + np.interp(np.linspace(0.0, arc[-1], len(side)), arc, t)[:, None] * chord
    check_orientation(start, plane.triangles, "the outline held equal")
    points = _classes_from(surface, l, mesh, start, plane.triangles, np.arange(n))
    within = share_within(edge_lengths(surface.evaluate(start[:, 0], start[:, 1]), plane.edges) / l, 1.0, 0.005)
    uncounted = mesh.stages.seconds["optimisation of inner nodes"]
    return (
        points,
        plane.triangles,
        {"deviation_max": 0.0, "deviation_mean": 0.0, REMAPPED: within, UNCOUNTED: uncounted},
    )


def _classes_from(surface, l, mesh, start, triangles, fixed, slides=()):
    """The classes objective solved from ``start`` on ``triangles`` (G1: the edges of the pipeline's ``mesh`` in
    its G1), ``fixed`` and ``slides`` as the pipeline passes them, and the pipeline's output checks on the result:
    its points."""
    edges = unique_edges(triangles)
    n = len(mesh.uv)
    g1 = np.isin(edge_keys(edges, n)[0], edge_keys(mesh.edges[mesh.edge_groups == G1], n)[0])
    result = optimize_uv(
        surface,
        start,
        edges,
        np.where(g1, G1, OTHER).astype(mesh.edge_groups.dtype),
        l,
        fixed=fixed,
        slides=slides,
        triangles=triangles,
        objective="classes",
    )
    check_orientation(result.uv, triangles, "the optimisation")
    points = surface.evaluate(result.uv[:, 0], result.uv[:, 1])
    check_members(points, edges, l)
    check_joints(points, triangles, joint_bounds(surface, mesh.stages.remapped_uv, triangles))
    return points


def strip_flips(points, uv, triangles, l):
    """``(triangles, flips)``: ``triangles`` with inner members flipped one at a time while one is left more than the
    tolerance (0.5 % of l) from every nominal length of the ten largest classes at 0.5 % (of ``points``' members,
    fixed at the start) whose other diagonal comes nearer one of them, within :data:`FLIP_REACH` l of it; the new
    diagonal in [l, 2l], both new triangles counter-clockwise in ``uv`` and their angles at least 30 degrees (sound
    joints; with two angles of at least 30 the third is at most 120); the largest gain first, ties to the first
    member in sorted order.  Each flip lowers the members' summed distance to the nearest of these nominals, so the
    flips end."""
    triangles = np.array(triangles, dtype=np.int64)
    found = length_classes(edge_lengths(points, unique_edges(triangles)), l, 0.005)
    nominals = found.nominal[found.largest(TOP_CLASSES)]

    def gap(a, b):
        return float(np.min(np.abs(nominals - np.linalg.norm(points[a] - points[b]))))

    flips = 0
    while True:
        directed = half_edges(triangles)
        side = {(int(a), int(b)): k for k, (a, b) in enumerate(directed)}  # half-edge k: side k // M of triangle k % M
        best = None
        for (a, b), k in sorted(side.items()):
            if a > b or (b, a) not in side:
                continue
            t, s = k % len(triangles), side[(b, a)] % len(triangles)
            c = int(np.setdiff1d(triangles[t], (a, b))[0])
            d = int(np.setdiff1d(triangles[s], (a, b))[0])
            old, new = gap(a, b), gap(c, d)
            if old <= 0.005 * l or new > FLIP_REACH * l or new >= old or (best is not None and old - new <= best[0]):
                continue
            first, second = _flipped(triangles[t], a, b, d)
            quad = np.array([first, second])
            angles = triangle_angles(points, quad)
            length = np.linalg.norm(points[c] - points[d]) / l
            if 1.0 <= length <= 2.0 and np.all(signed_areas(uv, quad) > 0) and angles.min() >= JOINT_ANGLE:
                best = (old - new, t, s, first, second)
        if best is None:
            return triangles, flips
        _, t, s, first, second = best
        triangles[t], triangles[s] = first, second
        flips += 1


def _flipped(triangle, a, b, d):
    """The two triangles that replace ``triangle`` (which runs ``a -> b``) and its neighbour across ``a b`` (whose
    third node is ``d``) when ``a b`` is flipped, both in ``triangle``'s turning sense."""
    k = list(triangle).index(a)
    a, b, c = (int(triangle[(k + i) % 3]) for i in range(3))
    return (c, a, d), (c, d, b)


def _solved_again(flip):
    """The classes objective's mesh solved again from its own result, its boundary sliding as in the pipeline:
    unflipped, or with :func:`strip_flips` first (the count in the extras' ``flips``).  The meshing call is timed
    less the pipeline's own optimisation, which gives it its start."""

    def run(surface, l):
        mesh = mesh_surface(surface, l, optimize="classes", max_nodes=None)
        triangles, flips = strip_flips(mesh.points, mesh.uv, mesh.triangles, l) if flip else (mesh.triangles, np.nan)
        slides, fixed = mesh.stages.outline.slides(mesh.stages.plane, mesh.uv)
        points = _classes_from(surface, l, mesh, mesh.uv, triangles, fixed, slides)
        uncounted = mesh.stages.seconds["optimisation of inner nodes"]
        extras = {"deviation_max": 0.0, "deviation_mean": 0.0, REMAPPED: np.nan, UNCOUNTED: uncounted}
        return points, triangles, {**extras, FLIPS: flips}

    return run


def _peer(run):
    def meshed(surface, l):
        points, triangles = run(surface, l)
        return points, triangles, dict.fromkeys(("deviation_max", "deviation_mean", REMAPPED), np.nan)

    return meshed


def methods():
    """({method: run}, {method: why skipped}): equimesh's objectives and the frontier, then compare_peers' peers."""
    run = {"equimesh paper": _equimesh("paper"), "equimesh bounded": _equimesh("bounded")}
    run.update({_classes_name(d): _equimesh("classes", d) for d in SURFACE_TOLERANCES})
    run[OUTLINE_HELD] = _outline_held
    run[SOLVED_AGAIN], run[STRIP_FLIPPED] = _solved_again(False), _solved_again(True)
    peers, skipped = compare_peers.methods()
    run.update({name: _peer(f) for name, f in peers.items() if not name.startswith("equimesh")})
    return run, {name: why for name, why in skipped.items() if not name.startswith("equimesh")}


def _classes_name(fraction):
    return "equimesh classes" if fraction == 0 else f"equimesh classes D={100 * fraction:g}% l"


def tasks(quick=False, surface_names=None, method_names=None):
    """(surface, divisor, method) of every run: all methods at the first divisor; at the later ones, on the doubly
    curved surfaces, equimesh bounded, classes and gmsh Frontal-Delaunay (the reference of the targets).  ``quick``
    keeps the first two surfaces at the first divisor; ``surface_names`` and ``method_names`` keep those given."""
    names = [m for m in methods()[0] if method_names is None or m in method_names]
    second = [m for m in ("equimesh bounded", "equimesh classes", "gmsh Frontal-Delaunay") if m in names]
    out = []
    for name, developable, _ in surfaces()[: 2 if quick else None]:
        if surface_names is not None and name not in surface_names:
            continue
        out += [(name, DIVISORS[0], m) for m in names]
        if not developable and not quick:
            out += [(name, divisor, m) for divisor in DIVISORS[1:] for m in second]
    return out


def measure(task):
    """One (surface, divisor, method) run: its figures, its class sizes (largest first)."""
    name, divisor, method = task
    entry = {n: (d, s) for n, d, s in surfaces()}[name]
    l = SPAN / divisor
    row = {"surface": name, "developable": entry[0], "l": l, "divisor": divisor, "method": method}
    try:
        (points, triangles, extras), seconds = _common.timed(methods()[0][method], entry[1], l)
    except Exception as exc:  # a method failing on a surface is a result, not a crash
        reason = f"failed: {type(exc).__name__}: {' '.join(str(exc).split())[:160]}"
        return {**row, **dict.fromkeys((*COMPARISON_COLUMNS, *KIND_COLUMNS), np.nan), "status": reason}, np.zeros(
            0, dtype=np.int64
        )
    figures = comparison_figures(points, triangles, l)
    for kind, values in classes_by_kind(points, triangles, l).items():
        figures.update({f"{kind}_{figure}": value for figure, value in zip(KIND_FIGURES, values)})
    sizes = np.sort(length_classes(edge_lengths(points, unique_edges(triangles)), l, 0.005).count)[::-1]
    seconds -= extras.pop(UNCOUNTED, 0.0)
    extra = {**extras, "seconds": seconds, "status": "ok"}
    return {**row, **figures, **extra}, sizes


#: The CSV column of the remapped mesh's share within 0.5 % of l (equimesh only).
REMAPPED = "remapped_within_05"
#: The CSV column of the flips :func:`strip_flips` made (its method only).
FLIPS = "flips"
#: The seconds of a method's call that are not its own (:func:`_outline_held`), not counted in its time.
UNCOUNTED = "uncounted_seconds"
#: Per kind of member (:func:`equimesh.metrics.classes_by_kind`): its members, the classes it needs alone, its share in
#: the mesh's 10 largest classes, its share within 5 % of l.
KIND_FIGURES = ("members", "classes", "in_top10", "within_5")
#: The CSV columns of :data:`KIND_FIGURES`, per kind.
KIND_COLUMNS = tuple(f"{kind}_{figure}" for kind in MEMBER_KINDS for figure in KIND_FIGURES)
COLUMNS = [
    "surface",
    "developable",
    "l",
    "divisor",
    "method",
    *COMPARISON_COLUMNS,
    *KIND_COLUMNS,
    "deviation_max",
    "deviation_mean",
    REMAPPED,
    FLIPS,
    "seconds",
    "status",
]
#: CSV column names: the metric keys without the dot and "pct" ("within_0.5pct" is "within_05").
_IDENTIFIERS = {k: k.replace(".", "").replace("pct", "") for k in COMPARISON_COLUMNS}


def _pct(x):
    return "" if pd.isna(x) else f"{100 * x:.1f}"


def markdown(df, skipped, record):
    body = [
        "Four 80 x 80 bicubic Bezier patches none of equimesh's constants was chosen on (two doubly curved, two "
        "developable), at l = span / 16 (all methods), span / 24 and span / 30 (doubly curved, three methods). "
        "Classes: the fewest length classes at +-0.5 % and +-1 % of l (equimesh.length_classes); largest / top 10: "
        "share of the members in the largest class and in the 10 largest at +-0.5 %; within: share within 0.5 % of l; "
        "< 30 deg: share of triangles with an angle below 30 degrees; deviation: the nodes' distance from the "
        "surface (max / mean, in units of l; peers' nodes are not measured); time: the meshing call.",
        "",
        "| surface | l | method | members | classes 0.5 % | classes 1 % | largest | top 10 | within 0.5 % "
        "| min angle | max angle | < 30 deg | deviation / l | time (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in df.itertuples(index=False):
        if r.status != "ok":
            body.append(f"| {r.surface} | span / {r.divisor} | {r.method} | {r.status} |" + " |" * 11)
            continue
        dev = "" if pd.isna(r.deviation_max) else f"{r.deviation_max / r.l:.4f} / {r.deviation_mean / r.l:.4f}"
        body.append(
            f"| {r.surface} | span / {r.divisor} | {r.method} | {int(r.members)} | {int(r.classes_05)} "
            f"| {int(r.classes_1)} | {_pct(r.largest_05)} | {_pct(r.top10_05)} | {_pct(r.within_05)} "
            f"| {r.angle_min:.1f} | {r.angle_max:.1f} | {_pct(r.below_30deg)} | {dev} | {r.seconds:.2f} |"
        )
    body += ["", "## The targets of the fewest-classes objective", "", *targets(df)]
    body += ["", "## Where the classes go", "", *kinds(df)]
    body += ["", "## Flips in the strip", "", *flipped(df)]
    if skipped:
        body += ["", "Not compared on this machine:", ""] + [f"- {k}: {v}" for k, v in skipped.items()]
    return _common.markdown_report("Fewest member types and sound joints", f"experiments/{NAME}.py", body, record)


def targets(df):
    """One line per (surface, l): what ``equimesh classes`` (D = 0) reaches against each target."""
    lines = [
        "Targets with nodes on the surface: every member in [l, 2l]; every angle in [30, 120] degrees; classes at "
        "0.5 % at most half of gmsh Frontal-Delaunay's; at least 95 % of the members in the 10 largest classes; at "
        "least 50 % (doubly curved) or 75 % (developable) within 0.5 % of l.",
        "",
        "| surface | l | in [l, 2l] | angles | classes (gmsh FD) | top 10 | within 0.5 % |",
        "|---|---|---|---|---|---|---|",
    ]
    ok = df[df["status"] == "ok"]
    for (surface, divisor), part in ok.groupby(["surface", "divisor"], sort=False):
        ours = part[part["method"] == "equimesh classes"]
        peer = part[part["method"] == "gmsh Frontal-Delaunay"]
        if ours.empty:
            continue
        r = ours.iloc[0]
        need = 0.75 if r["developable"] else 0.5
        gmsh = f" ({int(peer['classes_05'].iloc[0])})" if not peer.empty else ""
        half = not peer.empty and r["classes_05"] <= 0.5 * peer["classes_05"].iloc[0]

        def mark(good):
            return "met" if good else "not met"

        lines.append(
            f"| {surface} | span / {divisor} | {_pct(r['in_l_2l'])} % ({mark(r['in_l_2l'] == 1)}) "
            f"| {r['angle_min']:.1f}-{r['angle_max']:.1f} ({mark(r['angle_min'] >= 30 - 1e-9)}) "
            f"| {int(r['classes_05'])}{gmsh} ({mark(half)}) | {_pct(r['top10_05'])} % ({mark(r['top10_05'] >= 0.95)}) "
            f"| {_pct(r['within_05'])} % ({mark(r['within_05'] >= need)}) |"
        )
    return lines


def kinds(df):
    """One line per (surface, l, method) of equimesh classes (D = 0, and the outline held equal) and gmsh
    Frontal-Delaunay: per kind of member (:func:`equimesh.metrics.classes_by_kind`) its members, the classes it
    needs alone, its share in the mesh's 10 largest classes and its share within 5 % of l."""
    lines = [
        "Per kind of member (equimesh.metrics.classes_by_kind): along the outline, in the boundary strip (the other "
        "members with a node on the outline) and inside; each cell: members / the classes at 0.5 % they need alone "
        "/ their share in the mesh's 10 largest classes / their share within 5 % of l. The ten largest classes at "
        "0.5 % cover lengths spanning at most 0.1 l in all: members whose lengths spread over [l, 2l] mostly fall "
        "outside them unless their lengths repeat. Remapped: the share of the remapped mesh's members (step 4, "
        "before the optimisation) within 0.5 % of l, what decides a second series of the classes' rounds "
        "(equimesh.tolerance.CLASSES_REMAP_SHARE).",
        "",
        "| surface | l | method | classes | along the outline | strip | inside | remapped |",
        "|---|---|---|---|---|---|---|---|",
    ]
    shown = df[(df["status"] == "ok") & df["method"].isin(["equimesh classes", OUTLINE_HELD, "gmsh Frontal-Delaunay"])]
    for r in shown.to_dict("records"):
        cells = [
            f"{int(r[f'{k}_members'])} / {int(r[f'{k}_classes'])} / {_pct(r[f'{k}_in_top10'])} % / "
            f"{_pct(r[f'{k}_within_5'])} %"
            for k in MEMBER_KINDS
        ]
        lines.append(
            f"| {r['surface']} | span / {r['divisor']} | {r['method']} | {int(r['classes_05'])} | "
            + " | ".join(cells)
            + f" | {_pct(r[REMAPPED])} |"
        )
    return lines


def flipped(df):
    """One line per (surface, l) with the strip flipped: the flips made and the classes and top-10 share of the
    classes objective's mesh, of it solved again and of it flipped and solved again."""
    lines = [
        "The classes objective's mesh with its inner members more than the tolerance from every nominal length of the "
        f"ten largest classes flipped where the other diagonal comes nearer one of them, within {FLIP_REACH:g} l, the "
        "new triangles' angles in [30, 120] degrees (experiments/fabrication.py strip_flips), then solved again; "
        "beside it the mesh solved again unflipped, what the second solve alone gives. Flips: those made, one after "
        "another. Each cell: classes at 0.5 % / top-10 share.",
        "",
        "| surface | l | flips | classes | solved again | strip flipped, solved again |",
        "|---|---|---|---|---|---|",
    ]
    ok = df[df["status"] == "ok"].set_index(["surface", "divisor", "method"])
    for surface, divisor, _ in ok.index[ok.index.get_level_values("method") == STRIP_FLIPPED]:
        cells = []
        for method in ("equimesh classes", SOLVED_AGAIN, STRIP_FLIPPED):
            r = ok.loc[(surface, divisor, method)] if (surface, divisor, method) in ok.index else None
            cells.append("" if r is None else f"{int(r['classes_05'])} / {_pct(r['top10_05'])} %")
        flips = int(ok.loc[(surface, divisor, STRIP_FLIPPED), FLIPS])
        lines.append(f"| {surface} | span / {divisor} | {flips} | " + " | ".join(cells) + " |")
    return lines


def class_frame(runs):
    """Long table of the class sizes: surface, divisor, method, rank (1 = largest), count."""
    records = [
        (row["surface"], row["divisor"], row["method"], rank, int(n))
        for row, sizes in runs
        for rank, n in enumerate(sizes, start=1)
    ]
    return pd.DataFrame(records, columns=["surface", "divisor", "method", "rank", "count"])


def plot(df, classes, fig_dir, parameters):
    """The frontier (classes and top-10 share against D) and the member types (cumulative share of the k largest
    classes) per method, both at the first divisor."""
    first = df[(df["divisor"] == DIVISORS[0]) & (df["status"] == "ok")]
    fig = Figure(figsize=(9.0, 3.4))
    ax_classes, ax_top = fig.subplots(1, 2)
    percent = {_classes_name(d): 100 * d for d in SURFACE_TOLERANCES}  # the frontier's methods, D in % of l
    frontier = first[first["method"].isin(list(percent))].copy()
    frontier["D"] = frontier["method"].map(percent)
    for name, part in frontier.groupby("surface", sort=False):
        part = part.sort_values("D")
        (line,) = ax_classes.plot(part["D"], part["classes_05"], marker="o", label=name)
        ax_top.plot(part["D"], 100 * part["top10_05"], marker="o", color=line.get_color())
        peer = first[(first["surface"] == name) & (first["method"] == "gmsh Frontal-Delaunay")]
        if not peer.empty:
            ax_classes.axhline(peer["classes_05"].iloc[0], color=line.get_color(), ls=":", lw=0.8)
    ax_classes.set_xlabel("surface tolerance D (% of l)")
    ax_classes.set_ylabel("length classes at +-0.5 %")
    ax_classes.set_title("classes (dotted: gmsh Frontal-Delaunay)", fontsize=9)
    ax_top.set_xlabel("surface tolerance D (% of l)")
    ax_top.set_ylabel("members in the 10 largest classes (%)")
    ax_top.axhline(95.0, color="k", ls="--", lw=0.6)
    ax_classes.legend(fontsize=7)
    fig.tight_layout()
    written = _common.save_figure(fig, Path(fig_dir) / f"{NAME}_frontier", parameters, dpi=120)

    sizes = classes[classes["divisor"] == DIVISORS[0]]
    shown = [m for m in dict.fromkeys(sizes["method"]) if "D=" not in m and m not in (SOLVED_AGAIN, STRIP_FLIPPED)]
    fig = Figure(figsize=(3.0 * len(shown), 2.8))
    axes = fig.subplots(1, len(shown), squeeze=False, sharey=True)[0]
    colour = {name: f"C{k}" for k, (name, _, _) in enumerate(surfaces())}  # a surface's colour in every panel
    for ax, method in zip(axes, shown):
        for name, part in sizes[sizes["method"] == method].groupby("surface", sort=False):
            share = 100 * np.cumsum(part["count"].to_numpy()) / part["count"].sum()
            ax.step(part["rank"], share, where="post", label=name, color=colour[name])
        ax.axvline(10, color="k", ls=":", lw=0.6)
        ax.set_xscale("log")
        ax.set_title(method, fontsize=8)
        ax.set_xlabel("k largest classes", fontsize=8)
    axes[0].set_ylabel("members (%)", fontsize=8)
    axes[0].legend(fontsize=6)
    fig.tight_layout()
    written += _common.save_figure(fig, Path(fig_dir) / f"{NAME}_member_types", parameters, dpi=120)
    return written


def parse_args(argv=None):
    p = _common.parser(__doc__)
    p.add_argument("--quick", action="store_true", help="two surfaces, one l (a smoke test)")
    p.add_argument("--surfaces", nargs="+", metavar="NAME", help="surfaces to mesh (default all)")
    p.add_argument("--methods", nargs="+", metavar="METHOD", help="methods to run (default all this machine has)")
    return _common.add_output_options(p, jobs=True, plot_only=True).parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    out_dir, fig_dir = Path(args.out_dir), Path(args.fig_dir)
    classes_path = out_dir / f"{NAME}_classes.csv"
    parameters = {"divisors": list(DIVISORS), "surface_tolerances": list(SURFACE_TOLERANCES), "quick": args.quick}
    if args.plot_only:
        plot(pd.read_csv(out_dir / f"{NAME}.csv"), pd.read_csv(classes_path), fig_dir, parameters)
        print(f"{NAME}: redrew the figures from {out_dir}")
        return 0
    available, skipped = methods()
    todo = tasks(args.quick, args.surfaces, args.methods)
    ran = [m for m in available if args.methods is None or m in args.methods]
    parameters.update(surfaces=args.surfaces, methods=ran, peer_versions=compare_peers._peer_versions())
    runs = []
    for row, sizes in _common.parallel_map(measure, todo, args.jobs, scheduler=args.scheduler):
        print(f"{NAME}: {row['surface']}, span / {row['divisor']}, {row['method']}: {row['status']}", flush=True)
        runs.append((row, sizes))
    df = pd.DataFrame([r for r, _ in runs], columns=COLUMNS)
    classes = class_frame(runs)
    out_dir.mkdir(parents=True, exist_ok=True)
    with _common.atomic_path(classes_path) as tmp:
        classes.to_csv(tmp, index=False)
    renamed = df.rename(columns=_IDENTIFIERS)
    _common.write_results(
        out_dir / f"{NAME}.csv",
        renamed,
        parameters,
        lambda record: markdown(renamed, skipped, record),
        float_format="%.10g",
    )
    plot(renamed, classes, fig_dir, parameters)
    print(f"{NAME}: wrote {out_dir / NAME}.csv, .md, {classes_path.name} and the figures in {fig_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
