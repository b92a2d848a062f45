"""The work of the final optimisation, and how far its start is from [l, 2l]: the measurement behind its bounds.

Every objective of :data:`equimesh.surface.optimize.OBJECTIVES` on the repository's surfaces: the reference dome
at l = 0.5 to 2, the examples of ``experiments/surfaces/`` at their l of ``experiments/inputs.py`` and half of it,
the 101 domes of ``experiments/bounded_sweep.py`` (with "paper" and "bounded", as there), and closed-ended tubes and
spherical caps, which the flattening stretches to several times their area
(:func:`equimesh.testing.meshes.closed_tube`, :func:`~equimesh.testing.meshes.spherical_cap`).  Each surface is
meshed by :func:`equimesh.mesh_surface` (default placement, no size limit) once without optimisation, for the start
of the optimisation (the remapped mesh: the share of its members shorter than ``REACH_LENGTH`` l on the surface,
:func:`~equimesh.surface.optimize.members.short_share`, and its shortest and longest member over l), then with each
objective (``"classes"`` only up to its node limit): the solver's Jacobian evaluations (the result's ``njev``, the
unit of ``Objective.max_jacobians``) and the mesh's nodes, or the refusal (with the start's nodes).  An objective
with sound joints may mesh the plane again at a larger spacing (docs/decisions.md, "Sound joints"): its nodes are
then fewer than the start's, whose share of short members is the one given.  The work bounds and ``REACH_SHARE``
are set from this table (docs/decisions.md, "A work bound for the optimisation").

Writes::

    results/optimisation_work.csv               one row per surface, l and objective
    results/optimisation_work.md                the largest counts per objective, the refusals, provenance
    results/optimisation_work.provenance.json

Usage::

    python experiments/optimisation_work.py [--jobs 2] [--quick]
"""

import json
import sys
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402
import bounded_sweep  # noqa: E402
import inputs  # noqa: E402

from equimesh import TriangulatedSurface  # noqa: E402
from equimesh.errors import EquimeshError  # noqa: E402
from equimesh.io import load_surface, surface_from_dict  # noqa: E402
from equimesh.surface.optimize import OBJECTIVES  # noqa: E402
from equimesh.surface.optimize.members import short_share  # noqa: E402
from equimesh.surface.pipeline import mesh_surface  # noqa: E402
from equimesh.testing.meshes import closed_tube, spherical_cap  # noqa: E402
from equimesh.testing.surfaces import dome  # noqa: E402
from equimesh.tolerance import REACH_SHARE  # noqa: E402

NAME = "optimisation_work"
SURFACES = Path(__file__).resolve().parent / "surfaces"
DOME_LENGTHS = (0.5, 0.75, 1.0, 1.5, 2.0)
#: Closed-ended tubes (radius, length) and spherical caps (radius, degrees), meshed at l = 0.5.
TUBES = ((1.0, 4.0), (1.0, 17.0), (1.0, 20.0), (1.0, 24.0), (2.0, 12.0))
CAPS = ((3.0, 60.0), (3.0, 120.0), (3.0, 170.0))
STRETCHED_LENGTH = 0.5
#: The domes of experiments/bounded_sweep.py, meshed by "paper" and "bounded" only (as there).
SWEEP_DOMES = 101
QUICK = ("reference dome", 5.0), ("closed tube 1 x 17", 1.0)
COLUMNS = [
    "surface",
    "l",
    "objective",
    "nodes",
    "members",
    "start_short_share",
    "start_min_over_l",
    "start_max_over_l",
    "jacobians",
    "max_jacobians",
    "outcome",
]


def surfaces():
    """Every case's ``(name, l)`` and a function building its surface, keyed by name."""
    built = {"reference dome": lambda: surface_from_dict(json.loads((SURFACES / "reference_dome.json").read_text()))}
    cases = [("reference dome", l) for l in DOME_LENGTHS]
    for item in inputs.INPUTS:
        if item.file.endswith(".3dm"):  # the same roof as nurbs_roof.json, and an optional extra to read
            continue
        built[item.file] = lambda item=item: load_surface(SURFACES / item.file, object=item.object)
        cases += [(item.file, item.length), (item.file, item.length / 2)]
    for index, rise, seed, l in bounded_sweep.cases(SWEEP_DOMES):
        name = f"sweep dome {index}"
        built[name] = lambda rise=rise, seed=seed: dome(rise=rise, seed=seed, jitter=1.0)
        cases.append((name, l))
    for radius, length in TUBES:
        name = f"closed tube {radius:g} x {length:g}"
        built[name] = lambda radius=radius, length=length: TriangulatedSurface(*closed_tube(radius, length))
        cases.append((name, STRETCHED_LENGTH))
    for radius, degrees in CAPS:
        name = f"spherical cap {radius:g}, {degrees:g} degrees"
        built[name] = lambda radius=radius, degrees=degrees: TriangulatedSurface(*spherical_cap(radius, degrees))
        cases.append((name, STRETCHED_LENGTH))
    return cases, built


def measure(case):
    """The rows of one ``(name, l)``: the start, then each objective's Jacobians or refusal."""
    name, l = case
    surface = surfaces()[1][name]()
    row = {"surface": name, "l": l}
    try:
        start = mesh_surface(surface, l, optimize="none", placement="default", max_nodes=None)
    except EquimeshError as error:
        return [{**row, "objective": "none", "outcome": f"refused: {error}"}]
    ratio = start.edge_lengths() / l
    row |= {
        "nodes": len(start.uv),
        "members": len(start.edges),
        "start_short_share": short_share(ratio),
        "start_min_over_l": float(ratio.min()),
        "start_max_over_l": float(ratio.max()),
    }
    rows = []
    for objective, record in OBJECTIVES.items():
        if objective == "classes" and (len(start.uv) > record.node_limit() or name.startswith("sweep dome")):
            continue
        result = {**row, "objective": objective, "max_jacobians": record.max_jacobians, "jacobians": -1}
        try:
            mesh = mesh_surface(surface, l, optimize=objective, placement="default", max_nodes=None)
        except EquimeshError as error:
            rows.append({**result, "outcome": f"refused: {error}"})
            continue
        rows.append(
            {**result, "nodes": len(mesh.uv), "jacobians": int(mesh.stages.optimization.njev), "outcome": "meshed"}
        )
    return rows


def summarize(df, record):
    """The largest work per objective on the meshes returned, the largest start share among them, the refusals."""
    meshed = df[df["outcome"] == "meshed"]
    body = [
        "Jacobian evaluations of the meshes returned, per objective (the work bound is `max_jacobians`), and the "
        f"largest share of the start's members shorter than l / 2 among them (refused at once above {REACH_SHARE:g}).",
        "",
        "| objective | meshes | Jacobians (median) | Jacobians (max) | at (surface, l, nodes) | work bound | "
        "start share short (max) |",
        "|---|---:|---:|---:|---|---:|---:|",
    ]
    for objective, g in meshed.groupby("objective", sort=False):
        top = g.loc[g["jacobians"].idxmax()]
        body.append(
            f"| {objective} | {len(g)} | {g['jacobians'].median():g} | {top['jacobians']} | {top['surface']}, "
            f"{top['l']:g}, {top['nodes']} | {top['max_jacobians']} | {g['start_short_share'].max():.4f} |"
        )
    body += [
        "",
        "Refusals:",
        "",
        "| surface | l | objective | nodes | start share short | refusal |",
        "|---|---:|---|---:|---:|---|",
    ]
    for _, r in df[df["outcome"] != "meshed"].iterrows():
        share = "" if pd.isna(r["start_short_share"]) else f"{r['start_short_share']:.4f}"
        body.append(f"| {r['surface']} | {r['l']:g} | {r['objective']} | {r['nodes']} | {share} | {r['outcome']} |")
    return _common.markdown_report(
        "The work of the final optimisation", "`python experiments/optimisation_work.py`", body, record
    )


def parse_args(argv=None):
    p = _common.add_output_options(_common.parser(__doc__), fig_dir=False, jobs=True)
    p.add_argument("--quick", action="store_true", help="the reference dome at l = 5 and one closed tube at l = 1")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    cases = list(QUICK) if args.quick else surfaces()[0]
    args.out_dir.mkdir(parents=True, exist_ok=True)
    rows = [row for rows in _common.parallel_map(measure, cases, args.jobs, scheduler=args.scheduler) for row in rows]
    df = pd.DataFrame(rows, columns=COLUMNS)
    df["nodes"] = df["nodes"].astype("Int64")
    df["members"] = df["members"].astype("Int64")
    df["jacobians"] = df["jacobians"].astype("Int64")
    df["max_jacobians"] = df["max_jacobians"].astype("Int64")
    parameters = {"cases": len(cases), "quick": args.quick, "jobs": args.jobs, "out_dir": str(args.out_dir)}
    _common.write_results(args.out_dir / f"{NAME}.csv", df, parameters, lambda record: summarize(df, record))
    meshed = df[df["outcome"] == "meshed"]
    print(
        f"{NAME}: {len(cases)} cases, {len(meshed)} meshes returned, at most {meshed['jacobians'].max()} Jacobians, "
        f"{int((df['outcome'] != 'meshed').sum())} refusals"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
