"""Every kind of input the command line reads, meshed: the inputs table.

Each example of ``experiments/surfaces/`` (a Bezier dome and a NURBS roof in
JSON, the same roof as a Rhino file, the roof with openings) is read with
:func:`equimesh.load_surface`, as ``equimesh mesh`` reads it, and meshed by
:func:`equimesh.mesh_surface` with the default optimisation ("bounded").  The
table gives the members, the share of G1 members (lattice edges on the plane,
exactly l there), the shortest and longest member over l on the surface, the
share within 0.5 % of l, the shortest and longest member of the planar
triangulation over l (Theorem 3) and the wall time.  A row whose reader needs an
optional extra that is not installed (rhino3dm for ``.3dm``) says so instead.
Adding an input is one line of :data:`INPUTS`.

Writes::

    results/inputs.csv               one row per input
    results/inputs.md                the table and a provenance block
    results/inputs.provenance.json

Usage::

    python experiments/inputs.py [--jobs 2] [--quick]
"""

import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402

from equimesh.errors import MissingDependencyError  # noqa: E402
from equimesh.io import load_surface  # noqa: E402
from equimesh.surface.pipeline import mesh_surface  # noqa: E402

NAME = "inputs"
SURFACES = Path(__file__).resolve().parent / "surfaces"
#: "Within 0.5 % of l".
BAND = 0.005


@dataclass(frozen=True)
class Input:
    """One example input: a label, its file in experiments/surfaces/, the member length, the object of a file with
    several."""

    label: str
    file: str
    length: float
    object: str | None = None


#: The inputs, one line each.
INPUTS = (
    Input("Bezier dome (JSON)", "reference_dome.json", 5.0),
    Input("NURBS roof (JSON)", "nurbs_roof.json", 3.0),
    Input("NURBS roof (Rhino .3dm)", "roof.3dm", 3.0, object="roof"),
    Input("NURBS roof with two openings (JSON holes)", "nurbs_roof_openings.json", 3.0),
    Input("vault mesh with a skylight (.obj)", "roof_mesh.obj", 1.5),
)

#: The full run: the default optimisation on the default grid.  The quick run
#: (tests): no optimisation, a coarse grid and members twice as long.
FULL = {"optimize": "bounded", "grid": (15, 15), "scale": 1.0}
QUICK = {"optimize": "none", "grid": (8, 8), "scale": 2.0}


def _measure(task):
    item, setup = task
    row = {"input": item.label, "file": item.file, "l": item.length * setup["scale"]}
    try:
        surface = load_surface(SURFACES / item.file, object=item.object)
    except MissingDependencyError as exc:
        return {**row, "note": f"not run: {exc}"}
    mesh, seconds = _common.timed(
        mesh_surface, surface, row["l"], optimize=setup["optimize"], grid=setup["grid"], max_nodes=None
    )
    ratio = mesh.edge_lengths() / row["l"]
    plane = mesh.stages.plane.edge_lengths() / row["l"]
    return {
        **row,
        "nodes": len(mesh.points),
        "members": len(ratio),
        "g1_share": float(mesh.g1_mask.mean()),
        "min_over_l": float(ratio.min()),
        "max_over_l": float(ratio.max()),
        "share_within_0.5pct": float(np.mean(np.abs(ratio - 1.0) <= BAND)),
        "plane_min_over_l": float(plane.min()),
        "plane_max_over_l": float(plane.max()),
        "seconds": seconds,
        "note": "",
    }


def summarize(df, setup, record):
    body = [
        f"Each input read as `equimesh mesh` reads it and meshed with optimize = {setup['optimize']}, "
        f"grid {setup['grid'][0]} x {setup['grid'][1]}. `G1` = members that are lattice edges on the plane "
        "(exactly l there); min and max over l are the members on the surface; the plane column gives "
        "the shortest and longest member of the planar triangulation over l (Theorem 3: within [1, 2]).",
        "",
        "| input | file | l | members | share in G1 | min / l | max / l | within 0.5 % | plane / l | time (s) |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for _, r in df.iterrows():
        if r["note"]:
            body.append(f"| {r['input']} | `{r['file']}` | {r['l']:.4g} | {r['note']} | | | | | | |")
            continue
        body.append(
            f"| {r['input']} | `{r['file']}` | {r['l']:.4g} | {int(r['members'])} | {r['g1_share']:.3f} | "
            f"{r['min_over_l']:.4f} | {r['max_over_l']:.4f} | {r['share_within_0.5pct']:.3f} | "
            f"{r['plane_min_over_l']:.4f} .. {r['plane_max_over_l']:.4f} | {r['seconds']:.1f} |"
        )
    return _common.markdown_report("Every input kind, meshed", "`python experiments/inputs.py`", body, record)


def parse_args(argv=None):
    p = _common.add_output_options(_common.parser(__doc__), fig_dir=False, jobs=True)
    p.add_argument("--quick", action="store_true", help="no optimisation, 8 x 8 grid, members twice as long")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    setup = QUICK if args.quick else FULL
    args.out_dir.mkdir(parents=True, exist_ok=True)
    rows = _common.parallel_map(_measure, [(item, setup) for item in INPUTS], args.jobs, scheduler=args.scheduler)
    df = pd.DataFrame(list(rows))
    parameters = {
        "inputs": [item.__dict__ for item in INPUTS],
        **setup,
        "band": BAND,
        "quick": args.quick,
        "jobs": args.jobs,
        "out_dir": str(args.out_dir),
    }
    _common.write_results(args.out_dir / f"{NAME}.csv", df, parameters, lambda record: summarize(df, setup, record))
    done = df[df["note"] == ""]
    print(
        f"{NAME}: {len(done)} of {len(df)} inputs meshed; members in [{done['min_over_l'].min():.4f} l, "
        f"{done['max_over_l'].max():.4f} l]"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
