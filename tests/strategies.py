"""Hypothesis strategies for valid inputs of Problem 1, built by construction.

A valid input is a convex polygon with every inner angle >= 90 degrees and
every edge >= l (up to :data:`equimesh.REL_TOL`), with a positive finite l.
Nothing here filters: each family is constructed to be valid (see
:mod:`equimesh.testing.generators` for the random family), then scaled by l, rotated
and translated.  Randomness beyond hypothesis' own draws comes from
``np.random.default_rng(seed)`` with a drawn seed, never from global state.

Families, in units of l:

* squares and rectangles, side lengths on the integer lattice (cocircular
  boundary points everywhere) or arbitrary, including long thin ones of width
  exactly 1 to 3 and length up to 40;
* regular k-gons, 4 <= k <= 12 (inner angles >= 90 exactly from k = 4);
* random convex polygons with 4..12 vertices, area log-uniform up to
  :data:`MAX_AREA`, elongated or nearly regular;
* near-degenerate: edges of exactly 1, 2, 4 or 8, edge midpoints at exactly
  distance l, runs of collinear vertices (180 degree angles) and vertices
  whose inner angle is 180 degrees minus a tiny bulge (179.9 degrees and
  closer).
"""

import math

import numpy as np
from hypothesis import strategies as st

from equimesh.testing.generators import random_convex_polygon, rectangle, regular_polygon, rotate

#: Largest polygon area, in units of l^2 (the reference engine needs ~1 s at 600).
MAX_AREA = 600.0

seeds = st.integers(min_value=0, max_value=2**32 - 1)


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
def random_polygons(draw):
    """Random convex polygons with inner angles >= 90 (:func:`equimesh.testing.generators.random_convex_polygon`)."""
    rng = np.random.default_rng(draw(seeds))
    return random_convex_polygon(
        rng,
        n_vertices=draw(st.integers(4, 12)),
        area=math.exp(draw(st.floats(0.0, math.log(MAX_AREA)))),
        elongation=math.exp(draw(st.floats(0.0, math.log(40.0)))),
        length_spread=draw(st.sampled_from([1.0, 2.0, 4.0, 8.0])),
        min_turn=draw(st.sampled_from([0.0, 0.5, 0.9, 0.99])),
        max_area=MAX_AREA,
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


@st.composite
def placed(draw, polygons=unit_polygons):
    """A polygon from ``polygons`` scaled by l, rotated, translated, with a rolled start vertex.

    Returns ``(vertices, l)``, vertices counter-clockwise.
    """
    v = draw(polygons)
    l = draw(lengths())
    angle = draw(st.one_of(st.sampled_from([0.0, 0.5 * math.pi, 0.25 * math.pi]), st.floats(0.0, 2.0 * math.pi)))
    shift = np.array([draw(st.floats(-1000.0, 1000.0)), draw(st.floats(-1000.0, 1000.0))])
    start = draw(st.integers(0, len(v) - 1))
    v = np.roll(rotate(v, angle) + shift, -start, axis=0)
    return v * l, l


#: Valid inputs ``(vertices, l)`` of Problem 1.
problems = placed()
