"""What evaluating a chart costs by its degree, and what reading a NURBS net costs by its size: the limits' measure.

For each degree (p, q) of ``--nurbs`` and ``--bezier``, a surface of that
degree over 20 x 15 (a NURBS one of a single knot span, the worst case: every
point needs every basis function) is evaluated at ``--points`` random (u, v):
the value and the first partials, as every stage of Section 4 asks for them.
Printed: the best of three wall times per point, the peak memory per point
(tracemalloc, in a separate call), and the ratio to the first degree of the
list, measured in the same run.  For each size n of ``--nets``, a NURBS JSON
file of n x n control points (degree 2) is written and read back by
:func:`equimesh.load_surface`: its seconds, or the refusal and its seconds
above the limit.  With ``--length L``, one :func:`equimesh.mesh_surface` run
("bounded") on the biquadratic surface counts the points it evaluates, and each
degree's cost per point is projected onto that count.

It writes no file: it is the command behind the limits ``MAX_DEGREE`` of
``surface/charts/nurbs.py`` and ``surface/charts/bezier.py`` and ``MAX_NET_POINTS``
(docs/decisions.md, "Charts bounded by what evaluation costs").

Usage::

    python experiments/chart_timing.py [--nurbs 2,2 25,25 399,2] [--bezier 3,3 100,100] [--nets 316 317]
        [--points 1000] [--length 1.0]
"""

import argparse
import contextlib
import json
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np

import equimesh
from equimesh.surface.charts import bezier, nurbs

NURBS_DEGREES = ["2,2", "3,3", "11,11", "25,25", "25,2", "100,2", "399,2"]
BEZIER_DEGREES = ["3,3", "25,25", "100,100", "150,150", "1000,1000"]
NETS = [100, 316, 317, 1000]


def net(rows, cols):
    """A dome over 20 x 15 rising 3: (rows, cols, 3) control points."""
    x, y = np.meshgrid(np.linspace(0.0, 20.0, rows), np.linspace(0.0, 15.0, cols), indexing="ij")
    return np.stack([x, y, 3.0 * np.sin(np.pi * x / 20.0) * np.sin(np.pi * y / 15.0)], axis=-1)


def clamped(degree, count):
    """A clamped uniform knot vector of ``count`` control points."""
    return np.concatenate([np.zeros(degree), np.linspace(0.0, 1.0, count - degree + 1), np.ones(degree)])


def surface(kind, p, q):
    """The dome as a NURBS surface of one knot span, or as a Bezier surface, of degree (p, q)."""
    if kind == "bezier":
        return equimesh.BezierSurface(net(p + 1, q + 1))
    return nurbs.NurbsSurface((p, q), clamped(p, p + 1), clamped(q, q + 1), net(p + 1, q + 1))


@contextlib.contextmanager
def beyond_the_limits():
    """Lift the charts' degree bounds while inside: the costs beyond them are what this script measures."""
    saved = bezier.MAX_DEGREE, nurbs.MAX_DEGREE
    bezier.MAX_DEGREE = nurbs.MAX_DEGREE = 10**6
    try:
        yield
    finally:
        bezier.MAX_DEGREE, nurbs.MAX_DEGREE = saved


def cost(kind, p, q, points):
    """Seconds and bytes per point of value + first partials at ``points`` random (u, v) (best of three)."""
    with beyond_the_limits():
        s = surface(kind, p, q)
    u, v = np.random.default_rng(0).uniform(0.0, 1.0, (2, points))
    s.derivatives(u[:2], v[:2])  # compiled kernels and caches warm
    best = np.inf
    for _ in range(3):
        start = time.perf_counter()
        s.evaluate(u, v)
        s.derivatives(u, v)
        best = min(best, time.perf_counter() - start)
    tracemalloc.start()
    s.evaluate(u, v)
    s.derivatives(u, v)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return best / points, peak / points


def load(n, folder):
    """Megabytes of an n x n NURBS net in JSON (every digit, one number a line), the seconds to read it, and the
    refusal if there is one."""
    path = Path(folder) / f"net{n}.json"
    weights = np.random.default_rng(n).uniform(0.5, 2.0, (n, n))
    d = {
        "type": "nurbs",
        "degree": [2, 2],
        "knots_u": clamped(2, n).tolist(),
        "knots_v": clamped(2, n).tolist(),
        "control_points": net(n, n).tolist(),
        "weights": weights.tolist(),
    }
    path.write_text(json.dumps(d, indent=1))
    start = time.perf_counter()
    try:
        equimesh.load_surface(path)
        refused = None
    except equimesh.InvalidSurfaceError as exc:
        refused = str(exc)
    return path.stat().st_size / 1e6, time.perf_counter() - start, refused


def count_points(length):
    """Nodes of a "bounded" run on the biquadratic dome at ``length``, and the points it evaluates."""
    counted = [0]
    s = surface("nurbs", 2, 2)
    rational = s._rational

    def counting(u, v, order):
        counted[0] += np.broadcast(np.asarray(u), np.asarray(v)).size
        return rational(u, v, order)

    s._rational = counting
    mesh = equimesh.mesh_surface(s, length, optimize="bounded")
    return len(mesh.points), counted[0]


def _degree(text):
    p, q = (int(x) for x in text.split(","))
    return p, q


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--nurbs", nargs="*", type=_degree, default=[_degree(d) for d in NURBS_DEGREES])
    parser.add_argument("--bezier", nargs="*", type=_degree, default=[_degree(d) for d in BEZIER_DEGREES])
    parser.add_argument("--nets", nargs="*", type=int, default=NETS, help="NURBS nets of n x n points to read")
    parser.add_argument("--points", type=int, default=1000, help="(u, v) evaluated per degree (default 1000)")
    parser.add_argument("--length", type=float, help="count the points a bounded run at this l evaluates")
    args = parser.parse_args(argv)
    run = count_points(args.length) if args.length else None
    if run:
        print(json.dumps({"run": "bounded", "length": args.length, "nodes": run[0], "points_evaluated": run[1]}))
    for kind, degrees in (("nurbs", args.nurbs), ("bezier", args.bezier)):
        first = None
        for p, q in degrees:
            seconds, memory = cost(kind, p, q, args.points)
            first = first or seconds
            record = {
                "chart": kind,
                "degree": [p, q],
                "us_per_point": round(seconds * 1e6, 2),
                "kB_per_point": round(memory / 1e3, 2),
                "ratio_to_first": round(seconds / first, 2),
            }
            if run:
                record["run_seconds_projected"] = round(seconds * run[1], 1)
            print(json.dumps(record), flush=True)
    with tempfile.TemporaryDirectory() as folder:
        load(3, folder)  # the first read imports what reading needs
        for n in args.nets:
            megabytes, seconds, refused = load(n, folder)
            record = {"net": [n, n], "points": n * n, "MB": round(megabytes, 1), "load_seconds": round(seconds, 3)}
            if refused:
                record["refused"] = refused
            print(json.dumps(record), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
