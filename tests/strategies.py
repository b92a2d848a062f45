"""Hypothesis strategies for valid inputs of Problem 1, built by construction, and the one placement.

A valid input is a convex polygon with every inner angle >= 90 degrees and
every edge >= l (up to :data:`equimesh.REL_TOL`), with a positive finite l.
Nothing here filters: each family is built in units of ``l = 1`` from values
hypothesis draws (integers, lists of turn fractions and edge lengths), so a
failing example shrinks to a smaller, more regular polygon; :func:`placed` then
scales it by l, rotates, translates and rolls its start vertex.  No numpy
random generator is involved (``seeds`` is only for tests of
:func:`equimesh.testing.generators.random_convex_polygon` itself).

Families, in units of l:

* squares and rectangles, side lengths on the integer lattice (cocircular
  boundary points everywhere) or arbitrary, including long thin ones of width
  exactly 1 to 3 and length up to 40;
* regular k-gons, 4 <= k <= 12 (inner angles >= 90 exactly from k = 4);
* random convex polygons with 4..12 vertices from drawn turn fractions and
  edge lengths (:func:`equimesh.testing.generators.turns_from_fractions`,
  :func:`~equimesh.testing.generators.convex_polygon`), area log-uniform up
  to :data:`MAX_AREA`, elongated or nearly regular; all fractions equal
  (where shrinking goes) is the regular polygon;
* near-degenerate: edges of exactly 1, 2, 4 or 8, edge midpoints at exactly
  distance l, runs of collinear vertices (180 degree angles) and vertices
  whose inner angle is 180 degrees minus a tiny bulge (179.9 degrees and
  closer).

The placement convention, shared with ``tests/strategies_simple.py``: rotate
about the mean of the vertices by any angle (often exactly 0, 45 or 90
degrees), move that mean to a shift of at most :data:`MAX_SHIFT` in units of
l, a multiple of 1/64 (never a tiny nonzero coordinate, whose products
underflow in Triangle's exact predicates; see tests/planar/test_increment.py), roll the
start vertex, and multiply by ``l`` drawn log-uniformly from 2^-8 to 2^9.
"""

import math

import numpy as np
from hypothesis import strategies as st

from equimesh.testing.generators import convex_polygon, rectangle, regular_polygon, turns_from_fractions
from equimesh.testing.shapes import place

#: Largest polygon area, in units of l^2 (the reference engine needs ~1 s at 600).
MAX_AREA = 600.0
#: Largest translation of a placed polygon, in units of l.
MAX_SHIFT = 100.0

seeds = st.integers(min_value=0, max_value=2**32 - 1)

#: Coordinates of the fast engine's frame (l about 1): zero or of magnitude 1e-6 to 1e3, so no product
#: of the exact predicates' fallback underflows (their documented range).
frame_coordinates = st.one_of(st.just(0.0), st.floats(1e-6, 1e3), st.floats(-1e3, -1e-6))


@st.composite
def lengths(draw):
    """The target length l: a float in [1, 2) times a power of two in 2^-8 .. 2^8."""
    return draw(st.floats(1.0, 2.0, exclude_max=True)) * 2.0 ** draw(st.integers(-8, 8))


def _sizes(lo, hi):
    """A side length in units of l: an integer (lattice) or any float in [lo, hi]."""
    return st.one_of(st.integers(math.ceil(lo), math.floor(hi)).map(float), st.floats(lo, hi))


@st.composite
def squares(draw):
    """Squares of side 1 to 24."""
    side = draw(_sizes(1.0, 24.0))
    return rectangle(side, side)


@st.composite
def rectangles(draw):
    """Rectangles, among them long thin ones: width 1 to 3 (often exactly 1, 2 or 3), length 1 to 40."""
    width = draw(st.one_of(st.sampled_from([1.0, 2.0, 3.0]), st.floats(1.0, 3.0)))
    length = draw(_sizes(1.0, 40.0))
    if draw(st.booleans()):
        width = max(width, draw(_sizes(1.0, 15.0)))
    return rectangle(length, width)


@st.composite
def regular_polygons(draw):
    """Regular k-gons, k = 4..12, edge exactly 1, 2 or 4, or any float in [1, 6]."""
    k = draw(st.integers(4, 12))
    edge = draw(st.one_of(st.sampled_from([1.0, 2.0, 4.0]), st.floats(1.0, 6.0)))
    return regular_polygon(k, edge)


@st.composite
def random_polygons(draw, max_area=MAX_AREA, max_elongation=40.0):
    """Convex polygons with inner angles >= 90 and edges >= 1, from drawn turns and edge lengths.

    ``k`` turn fractions in (0, 1] give the exterior turns; ``k`` fractions in
    [0, 1] times a drawn spread up to log 8 give the log raw edge lengths; then
    ``min_turn`` (0 allows nearly straight angles, 0.99 is nearly regular),
    the elongation up to ``max_elongation`` and the area (log-uniform up to
    ``max_area``).
    """
    k = draw(st.integers(4, 12))
    fractions = draw(st.lists(st.floats(0.0, 1.0, exclude_min=True), min_size=k, max_size=k))
    raw = draw(st.lists(st.floats(0.0, 1.0), min_size=k, max_size=k))
    spread = draw(st.floats(0.0, math.log(8.0)))
    return convex_polygon(
        turns_from_fractions(fractions, draw(st.floats(0.0, 0.99))),
        spread * np.array(raw),
        axis=draw(st.floats(0.0, math.pi)),
        elongation=math.exp(draw(st.floats(0.0, math.log(max_elongation)))),
        area=math.exp(draw(st.floats(0.0, math.log(max_area)))),
        max_area=max_area,
    )


@st.composite
def near_degenerate(draw):
    """Exact edge lengths, collinear runs of vertices and almost straight angles."""
    kind = draw(st.sampled_from(["exact", "collinear", "bulge"]))
    w = draw(st.sampled_from([1.0, 2.0, 4.0, 8.0]))
    h = draw(st.sampled_from([1.0, 2.0, 4.0, 8.0, 16.0]))
    if kind == "exact":
        return rectangle(w, h)
    if kind == "collinear":
        # Every lattice point of the boundary is a vertex: 180 degree angles.
        step = draw(st.sampled_from([1.0, 2.0]))
        w, h = max(w, step), max(h, step)
        bottom = [(x, 0.0) for x in np.arange(0.0, w, step)]
        right = [(w, y) for y in np.arange(0.0, h, step)]
        top = [(w - x, h) for x in np.arange(0.0, w, step)]
        left = [(0.0, h - y) for y in np.arange(0.0, h, step)]
        return np.array(bottom + right + top + left)
    # A vertex pushed out of the middle of the bottom edge: inner angle 180 - 2 delta degrees.
    w = max(w, 2.0)
    delta = draw(st.sampled_from([0.05, 1e-3, 1e-6, 1e-9]))
    sag = 0.5 * w * math.tan(math.radians(delta))
    return np.array([[0.0, 0.0], [0.5 * w, -sag], [w, 0.0], [w, h], [0.0, h]])


#: Every family of unit-l polygons.
unit_polygons = st.one_of(squares(), rectangles(), regular_polygons(), random_polygons(), near_degenerate())

#: Rotation angles of :func:`placed`: often exactly axis-parallel or diagonal, else any.
angles = st.one_of(st.sampled_from([0.0, 0.5 * math.pi, 0.25 * math.pi]), st.floats(0.0, 2.0 * math.pi))
#: Shift coordinates of :func:`placed`, in units of l: multiples of 1/64 up to :data:`MAX_SHIFT`.
shifts = st.tuples(*[st.integers(-64 * int(MAX_SHIFT), 64 * int(MAX_SHIFT)).map(lambda i: i / 64.0)] * 2)


@st.composite
def placed(draw, polygons=unit_polygons):
    """A unit-l polygon from ``polygons`` rotated, translated, with a rolled start vertex, scaled by l.

    Returns ``(vertices, l)``, vertices in the orientation ``polygons`` gives
    (counter-clockwise for every family here).
    """
    v = place(draw(polygons), draw(angles), draw(shifts))
    v = np.roll(v, -draw(st.integers(0, len(v) - 1)), axis=0)
    l = draw(lengths())
    return v * l, l


#: Valid inputs ``(vertices, l)`` of Problem 1.
problems = placed()
