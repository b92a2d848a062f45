"""Frozen, deterministic benchmark inputs.

APPEND-ONLY.  asv compares timings across commits, so an input that changes
silently breaks every comparison with the past.  Never edit a function or
constant here in a way that changes what it returns: add a new one instead.
``tests/tools/test_benchmarks.py`` pins a fingerprint of every input below.

All lengths are in units of the target edge length ``L`` (= 1), so a polygon
of area ``A`` has area ``A l^2``.  Random shapes were drawn once from a seeded
``numpy.random.Generator`` and are stored here as literals, so that neither a
change in numpy's random streams nor one in equimesh's own polygon generators
can move them.
"""

import json
import math
from pathlib import Path

import numpy as np

#: Target edge length l used by every Problem 1 benchmark.
L = 1.0

#: Polygon areas in units of l^2 (smallest first: the smoke test runs it).
POLYGON_AREAS = (25, 100, 400)

#: Polygon shapes, see :func:`polygon`.
SHAPES = ("square", "rectangle_8to1", "random_convex")

#: The ``random_convex`` shape at unit area, counter-clockwise, centroid of the
#: vertices at the origin.  Drawn once with ``numpy.random.default_rng(20240601)``
#: by the exterior-angle construction (turns of at most 0.95 * 90 degrees, edge
#: lengths closed by two consecutive edges), rounded to 12 decimals.  Inner
#: angles 110-149 degrees; scaled to area 25 its shortest edge is 1.395 l.
RANDOM_CONVEX_7GON = np.array(
    [
        [-0.529441088815, 0.452477551900],
        [-0.645123910637, -0.054701523171],
        [-0.329686249884, -0.438039413357],
        [0.420766628488, -0.520672769384],
        [0.544280451947, -0.270402811292],
        [0.501910938928, 0.230760791919],
        [0.037293229973, 0.600578173386],
    ]
)


def rectangle(width, height):
    """Axis-parallel rectangle with a corner at the origin, counter-clockwise."""
    return np.array([[0.0, 0.0], [width, 0.0], [width, height], [0.0, height]])


def square(side):
    """Axis-parallel square with a corner at the origin, counter-clockwise."""
    return rectangle(side, side)


def polygon_area(vertices):
    """Shoelace area of a counter-clockwise polygon."""
    x, y = np.asarray(vertices, dtype=float).T
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def polygon(shape, area):
    """The frozen benchmark polygon ``shape`` (one of :data:`SHAPES`) of area ``area`` l^2.

    * ``square``: side ``sqrt(area)``, 4 vertices.
    * ``rectangle_8to1``: long thin rectangle, sides ``sqrt(8 area)`` by
      ``sqrt(area / 8)``, 4 vertices.
    * ``random_convex``: :data:`RANDOM_CONVEX_7GON` scaled by ``sqrt(area)``,
      7 vertices.
    """
    if shape == "square":
        return square(math.sqrt(area))
    if shape == "rectangle_8to1":
        return rectangle(math.sqrt(8.0 * area), math.sqrt(area / 8.0))
    if shape == "random_convex":
        return math.sqrt(area) * RANDOM_CONVEX_7GON
    raise ValueError(f"unknown benchmark shape {shape!r}; expected one of {SHAPES}")


# --- Section 4 (Table 1) --------------------------------------------------------

#: The repository root (this file is benchmarks/benchmarks/common.py).
REPO = Path(__file__).resolve().parents[2]

#: The reference surface of Table 1 (bicubic Bezier dome, see its "description"),
#: relative to the repository, and the paper's parameters for it.
REFERENCE_SURFACE_JSON = REPO / "experiments" / "surfaces" / "reference_dome.json"
SURFACE_LENGTH = 5.0
SURFACE_GRID = (15, 15)


def reference_surface_json():
    """The parsed reference surface JSON (``{"type": "bezier", "control_points": ...}``)."""
    return json.loads(REFERENCE_SURFACE_JSON.read_text(encoding="utf-8"))


# --- Engines and sizes ----------------------------------------------------------

#: The insertion engines compared by the size-parametrised suites.
ENGINES = ("fast", "reference")

#: Output sizes (about this many nodes) of the Problem 1 scaling suite, smallest first.
NODE_COUNTS = (1000, 10000, 100000)

#: Problem 2 polygon areas in units of l^2, smallest first.
PROBLEM2_AREAS = (100, 1000, 10000)

#: The reference engine is benchmarked only up to these sizes (a run of a few seconds;
#: it grows about as n^2.5).
REFERENCE_MAX_NODES = 1000
REFERENCE_MAX_AREA = 1000

#: Nodes per unit area of farthest-point insertion at l = 1 on a square (measured).
INSERTION_DENSITY = 0.68


def square_for_nodes(n):
    """The axis-parallel square on which INCREMENT at l = L places about ``n`` nodes."""
    return square(math.sqrt(n / INSERTION_DENSITY))


# --- The pipeline end to end and the factorisations ------------------------------

#: Member length at which the reference surface has about 10^4 members (9,392 in the default run at l = 1.66).
PIPELINE_LENGTH = 1.66

#: The factorisations of the optimisation's normal equations, SuperLU first (always installed: the smoke test runs
#: it); one whose library is missing is skipped.
FACTORISATIONS = ("superlu", "cholmod", "pardiso")
