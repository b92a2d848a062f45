"""Inputs and oracles shared by the tests of the insertion engines (``tests/planar/insertion/``,
``tests/planar/test_engines.py``).

* recording the :class:`~equimesh.planar.insertion.Insertion` of each engine run of Problems 1 and 2, and the
  bit-for-bit comparison of two runs;
* the reference engine's hand-built triangles (a circumcentre at a known distance from its constraint);
* coordinates of the fast engine's frame, quadruples of points (random, on lattices, cocircular), and the exact
  rational orientation and in-circle determinants the predicates are checked against;
* square rings of boundary points (with or without a hole) and their constrained Delaunay triangulation, the
  input of the CDT kernels.
"""

import math
from contextlib import contextmanager
from fractions import Fraction

import numpy as np
import pytest
import strategies
from hypothesis import strategies as st

import equimesh
import equimesh.planar.increment
import equimesh.planar.strip
from equimesh._geometry import circumcenters, point_segment_distance
from equimesh.planar.insertion import ENGINES, insert
from equimesh.planar.insertion.predicates import orient2d
from equimesh.planar.insertion.region import constrained_delaunay
from equimesh.testing.generators import regular_polygon
from equimesh.tolerance import REL_TOL, SLIVER_GAP

ENGINE_NAMES = sorted(ENGINES)

# --------------------------------------------------------------------------- recording the engine's output


@contextmanager
def recorded(module):
    """Record the :class:`Insertion` of every ``insert`` call made by ``module``."""
    runs = []

    def recording(region, l, engine):
        runs.append(insert(region, l, engine=engine))
        return runs[-1]

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(module, "insert", recording)
        yield runs


def problem1_runs(vertices, l):
    """``{engine: (mesh, insertion)}`` of Algorithm INCREMENT."""
    out = {}
    for name in ENGINE_NAMES:
        with recorded(equimesh.planar.increment) as runs:
            out[name] = equimesh.increment(vertices, l, engine=name), runs[0]
    return out


def problem2_runs(vertices, l, angle):
    """``{engine: (mesh, insertion)}`` of the Problem 2 pipeline."""
    out = {}
    for name in ENGINE_NAMES:
        with recorded(equimesh.planar.strip) as runs:
            out[name] = equimesh.uniform_triangulation(vertices, l, angle=angle, engine=name), runs[0]
    return out


def assert_same_insertion(runs):
    """Same points in the same order, same values, same constraints, same triangles (as sets), bit for bit."""
    (mesh_a, a), (mesh_b, b) = runs["reference"], runs["fast"]
    assert a.points.shape == b.points.shape, f"{len(a.points)} points against {len(b.points)}"
    assert a.points.tobytes() == b.points.tobytes(), "the engines inserted different points"
    assert a.values.tobytes() == b.values.tobytes(), "the engines report different values"
    assert a.segments.tolist() == b.segments.tolist()
    assert {tuple(sorted(t)) for t in a.triangles.tolist()} == {tuple(sorted(t)) for t in b.triangles.tolist()}
    assert mesh_a.points.tobytes() == mesh_b.points.tobytes()


def circle_triangle(gap, radius):
    """Points A, B, C on the circle of ``radius`` about (0, gap), with AB on the x axis; AB is the constraint."""
    half = np.sqrt(radius**2 - gap**2)
    return np.array([[-half, 0.0], [half, 0.0], [0.0, gap + radius]]), np.array([[0, 1]])


# (gap from the constraint in units of l, circumradius in units of l, listed?)
NEAR_CONSTRAINT = [
    (0.5 * REL_TOL, 1.5, False),  # closer than REL_TOL l: left to the midpoint of the constraint
    (4.0 * REL_TOL, 1.5, True),
    (0.5 * SLIVER_GAP, 1.0, False),  # closer than SLIVER_GAP l with value l: would leave a sliver
    (0.5 * SLIVER_GAP, 1.0 + 0.5 * REL_TOL, False),  # value l up to REL_TOL counts as l
    (0.5 * SLIVER_GAP, 1.0 + 4.0 * REL_TOL, True),  # value above l: inserted
    (2.0 * SLIVER_GAP, 1.0, True),
]


def at_exactly(tol, radius):
    """``circle_triangle(1/2, radius / (2 tol))`` and the l for which ``tol * l`` is the computed gap exactly."""
    points, segments = circle_triangle(0.5, radius * 0.5 / tol)
    centre, _ = circumcenters(points[[0]], points[[1]], points[[2]])
    gap = float(point_segment_distance(centre, points[0], points[1])[0])
    l = gap / tol
    while tol * l != gap:
        l = np.nextafter(l, np.inf if tol * l < gap else -np.inf)
    return points, segments, l


coordinates = strategies.frame_coordinates


points = st.tuples(coordinates, coordinates)


def sign(x):
    return int(x > 0) - int(x < 0)


def exact_orient(a, b, c):
    """``orient(a, b, c)`` in rational arithmetic and its permanent ``|ax - cx||by - cy| + |ay - cy||bx - cx|``."""
    (ax, ay), (bx, by), (cx, cy) = ((Fraction(x), Fraction(y)) for x, y in (a, b, c))
    left, right = (ax - cx) * (by - cy), (ay - cy) * (bx - cx)
    return left - right, abs(left) + abs(right)


def exact_incircle(a, b, c, d):
    """The in-circle determinant of ``abcd`` in rational arithmetic and its permanent."""
    dx, dy = Fraction(d[0]), Fraction(d[1])
    (ax, ay), (bx, by), (cx, cy) = rows = [(Fraction(p[0]) - dx, Fraction(p[1]) - dy) for p in (a, b, c)]
    la, lb, lc = (x * x + y * y for x, y in rows)
    det = la * (bx * cy - by * cx) + lb * (cx * ay - cy * ax) + lc * (ax * by - ay * bx)
    permanent = (
        la * (abs(bx * cy) + abs(by * cx)) + lb * (abs(cx * ay) + abs(cy * ax)) + lc * (abs(ax * by) + abs(ay * bx))
    )
    return det, permanent


@st.composite
def lattice_quadruples(draw):
    """Four points of a scaled, shifted integer or triangular lattice (many collinear and cocircular)."""
    h = draw(st.sampled_from([1.0, 0.1, 1.7, 2.0**-10]))
    shift = np.array([draw(coordinates), draw(coordinates)])
    ij = np.array(draw(st.lists(st.tuples(st.integers(-3, 3), st.integers(-3, 3)), min_size=4, max_size=4)), float)
    if draw(st.booleans()):
        ij = np.column_stack([ij[:, 0] + 0.5 * ij[:, 1], ij[:, 1] * math.sqrt(3.0) / 2.0])
    return [tuple(map(float, p)) for p in ij * h + shift]


@st.composite
def cocircular_quadruples(draw):
    """Four vertices of a regular k-gon (cocircular up to rounding), in ccw order."""
    k = draw(st.integers(4, 12))
    v = regular_polygon(k, draw(st.floats(0.1, 10.0)), center=(draw(coordinates), draw(coordinates)))
    idx = sorted(draw(st.lists(st.integers(0, k - 1), min_size=4, max_size=4, unique=True)))
    return [tuple(map(float, v[i])) for i in idx]


quadruples = st.one_of(st.lists(points, min_size=4, max_size=4), lattice_quadruples(), cocircular_quadruples())


# --------------------------------------------------------------------------- the CDT operations


def contains(P, V, t, x, y):
    a, b, c = P[V[t]]
    return min(orient2d(*a, *b, x, y), orient2d(*b, *c, x, y), orient2d(*c, *a, x, y)) >= 0.0


def points_along(corners, step):
    """Points every ``step`` along the closed polygon ``corners`` (side lengths multiples of ``step``)."""
    out = []
    for a, b in zip(corners, corners[1:] + corners[:1]):
        k = round(math.dist(a, b) / step)
        out += [(a[0] + (b[0] - a[0]) * i / k, a[1] + (b[1] - a[1]) * i / k) for i in range(k)]
    return out


def square_ring(size, step, hole, inner=()):
    """A ``size`` square with (or without) a square hole of a third of its size in the middle, boundary points
    ``step`` apart, and the points ``inner``: ``(P, V, SA, SB)``, points, the CDT's triangles, the constraint
    segments' ends."""
    a, b = size / 3.0, 2.0 * size / 3.0
    rings = [points_along([(0.0, 0.0), (size, 0.0), (size, size), (0.0, size)], step)]
    rings += [points_along([(a, a), (a, b), (b, b), (b, a)], step)] if hole else []
    P = np.array([p for ring in rings for p in ring] + list(inner))
    segments, start = [], 0
    for ring in rings:
        segments += [(start + i, start + (i + 1) % len(ring)) for i in range(len(ring))]
        start += len(ring)
    segments = np.array(segments, dtype=np.int64)
    holes = np.array([[size / 2.0, size / 2.0]]) if hole else np.empty((0, 2))
    V = np.ascontiguousarray(constrained_delaunay(P, segments, holes), dtype=np.int64)
    return P, V, segments[:, 0].copy(), segments[:, 1].copy()


@st.composite
def square_rings(draw):
    """A 6 x 6 square with (or without) a 2 x 2 square hole, boundary points 1 apart, and generic interior points
    (:func:`square_ring`)."""
    hole = draw(st.booleans())
    inner = draw(st.lists(st.tuples(st.floats(0.3, 5.7), st.floats(0.3, 5.7)), max_size=6))
    return square_ring(6.0, 1.0, hole, [p for p in inner if not (hole and 1.7 <= p[0] <= 4.3 and 1.7 <= p[1] <= 4.3)])
