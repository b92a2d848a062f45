"""Beyond the paper: the classes objective's narrowing Cauchy scale against a constant one, on patches no constant
was chosen on.

``CLASSES_SCALE_START`` and ``CLASSES_SCALE_DECAY`` (:func:`equimesh.surface.optimize.class_rounds.class_scale`) were
chosen on the four surfaces of ``experiments/fabrication.py``; this sweep checks them on others: ``COUNT`` random
80 x 80 bicubic Bezier patches (:func:`patch`: two in three doubly curved, control heights drawn in [-12, 30] with the
corners at 0; one in three developable, a vault of a random profile along one side), each meshed by
``mesh_surface(..., optimize="classes")`` at l = span / 16, and the doubly curved ones at span / 24 and 30 too, once
as it is and once with the scale held at half the tolerance from the first round (``CLASSES_SCALE_START = 0.5``, the
objective before the narrowing).  Each row: length classes at 0.5 %, the share of the members in the ten largest
classes, the share within 0.5 % of l, the smallest angle, the seconds; the report gives them side by side and their
means.

Writes::

    results/classes_sweep.csv               one row per patch, l and scale
    results/classes_sweep.md                the table, the means, provenance
    results/classes_sweep.provenance.json

Usage::

    python experiments/classes_sweep.py [--count 24] [--jobs 2]
"""

import contextlib
import sys
from pathlib import Path
from unittest import mock

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, fabrication.py, also when loaded by path
import _common  # noqa: E402
import fabrication  # noqa: E402

from equimesh.metrics import comparison_figures  # noqa: E402
from equimesh.surface.optimize import class_rounds  # noqa: E402
from equimesh.surface.pipeline import mesh_surface  # noqa: E402

NAME = "classes_sweep"
COUNT = 24
#: The first patch's seed (the patches are ``FIRST_SEED``, ``FIRST_SEED + 1``, ...).
FIRST_SEED = 200
#: The scales compared: the objective's, and half the tolerance throughout (``CLASSES_SCALE_START`` at 0.5).
SCALES = {"narrowing": None, "constant": 0.5}
COLUMNS = [
    "seed",
    "kind",
    "divisor",
    "scale",
    "members",
    "classes_05",
    "top10_05",
    "within_05",
    "angle_min",
    "seconds",
    "status",
]


def patch(seed):
    """``(kind, surface)`` of patch ``seed``: developable when ``seed % 3 == 2`` (a vault whose profile has two
    random inner control heights in [10, 30]), else doubly curved (inner and edge control heights in [-12, 30],
    corners 0)."""
    rng = np.random.default_rng(seed)
    if seed % 3 == 2:
        profile = np.concatenate([[0.0], rng.uniform(10.0, 30.0, 2), [0.0]])
        return "developable", fabrication._net(np.tile(profile, (4, 1)).T)
    heights = rng.uniform(-12.0, 30.0, (4, 4))
    heights[[0, 0, 3, 3], [0, 3, 0, 3]] = 0.0
    return "doubly curved", fabrication._net(heights)


def tasks(count):
    """(seed, divisor, scale) of every run: span / 16 on every patch, span / 24 and 30 on the doubly curved ones."""
    out = []
    for seed in range(FIRST_SEED, FIRST_SEED + count):
        kind, _ = patch(seed)
        for divisor in fabrication.DIVISORS if kind == "doubly curved" else fabrication.DIVISORS[:1]:
            out += [(seed, divisor, scale) for scale in SCALES]
    return out


def measure(task):
    """One run: the classes objective on patch ``seed`` at l = span / ``divisor`` with the scale named ``scale``."""
    seed, divisor, scale = task
    kind, surface = patch(seed)
    l = fabrication.SPAN / divisor
    row = {"seed": seed, "kind": kind, "divisor": divisor, "scale": scale}
    start = SCALES[scale]
    held = contextlib.nullcontext() if start is None else mock.patch.object(class_rounds, "CLASSES_SCALE_START", start)
    try:
        with held:
            mesh, seconds = _common.timed(mesh_surface, surface, l, optimize="classes", max_nodes=None)
    except Exception as exc:  # a refusal is a result, not a crash
        return {**row, "status": f"failed: {type(exc).__name__}: {' '.join(str(exc).split())[:160]}"}
    figures = comparison_figures(mesh.points, mesh.triangles, l)
    return {
        **row,
        "members": figures["members"],
        "classes_05": figures["classes_0.5pct"],
        "top10_05": figures["top10_0.5pct"],
        "within_05": figures["within_0.5pct"],
        "angle_min": figures["angle_min"],
        "seconds": seconds,
        "status": "ok",
    }


def summarize(df, record):
    ok = df[df["status"] == "ok"]
    wide = ok.pivot_table(
        index=["seed", "kind", "divisor"], columns="scale", values=["classes_05", "top10_05", "within_05"]
    )
    body = [
        "The classes objective on random 80 x 80 bicubic patches (seeds from "
        f"{FIRST_SEED}), with its narrowing Cauchy scale and with half the tolerance throughout; classes: length "
        "classes at 0.5 %; top 10: the share of the members in the ten largest; within: the share within 0.5 % of l.",
        "",
        "| seed | kind | l | classes (narrowing / constant) | top 10 (%) | within 0.5 % (%) |",
        "|---:|---|---|---|---|---|",
    ]
    for (seed, kind, divisor), r in wide.iterrows():
        body.append(
            f"| {seed} | {kind} | span / {divisor} | {r[('classes_05', 'narrowing')]:.0f} / "
            f"{r[('classes_05', 'constant')]:.0f} | {100 * r[('top10_05', 'narrowing')]:.1f} / "
            f"{100 * r[('top10_05', 'constant')]:.1f} | {100 * r[('within_05', 'narrowing')]:.1f} / "
            f"{100 * r[('within_05', 'constant')]:.1f} |"
        )
    body += ["", "## Means", "", "| kind | l | runs | classes | top 10 (%) | within 0.5 % (%) | fewer / equal / more |"]
    body.append("|---|---|---:|---|---|---|---|")
    for (kind, divisor), part in wide.groupby(level=["kind", "divisor"]):
        fewer = part[("classes_05", "narrowing")] - part[("classes_05", "constant")]
        body.append(
            f"| {kind} | span / {divisor} | {len(part)} | {part[('classes_05', 'narrowing')].mean():.1f} / "
            f"{part[('classes_05', 'constant')].mean():.1f} | {100 * part[('top10_05', 'narrowing')].mean():.1f} / "
            f"{100 * part[('top10_05', 'constant')].mean():.1f} | {100 * part[('within_05', 'narrowing')].mean():.1f}"
            f" / {100 * part[('within_05', 'constant')].mean():.1f} | {(fewer < 0).sum()} / {(fewer == 0).sum()} / "
            f"{(fewer > 0).sum()} |"
        )
    failed = df[df["status"] != "ok"]
    if len(failed):
        body += ["", "Refused:", ""] + [
            f"- seed {r.seed}, span / {r.divisor}, {r.scale}: {r.status}" for r in failed.itertuples()
        ]
    return _common.markdown_report(
        "The classes objective's narrowing scale on untuned patches",
        "`python experiments/classes_sweep.py`",
        body,
        record,
    )


def parse_args(argv=None):
    p = _common.add_output_options(_common.parser(__doc__), fig_dir=False, jobs=True)
    p.add_argument("--count", type=int, default=COUNT, help=f"patches (default {COUNT})")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    args.out_dir.mkdir(parents=True, exist_ok=True)
    rows = list(_common.parallel_map(measure, tasks(args.count), args.jobs, scheduler=args.scheduler))
    df = pd.DataFrame(rows, columns=COLUMNS)
    parameters = {
        "count": args.count,
        "first_seed": FIRST_SEED,
        "scales": SCALES,
        "divisors": list(fabrication.DIVISORS),
    }
    _common.write_results(args.out_dir / f"{NAME}.csv", df, parameters, lambda record: summarize(df, record))
    print(f"{NAME}: {args.count} patches, {len(df)} runs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
