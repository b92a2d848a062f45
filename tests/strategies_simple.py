"""Valid inputs of Problem 2 by construction: simple polygons, convex or not.

Problem 2 (Section 3 of the paper) takes any simple polygon whose edges are
at least l long and whose mutually visible boundary points (after the Step 2
resampling) are at least l apart (Lemma 3 (1)).  Every strategy here builds
such a polygon directly from drawn values, in units of ``l = 1``; none of them
filters.  :func:`cases` places it as every property test does
(:func:`strategies.placed`: rotate, translate, roll the start vertex, scale
by a drawn ``l``).  Why each family is valid:

* **convex** (:func:`strategies.random_polygons` with elongation at most 3,
  regular k-gons, equilateral triangles): every inner angle is at least 60 degrees and
  every edge at least 1, so Step 2 points on adjacent edges are at least one
  part (>= 1) apart, and a convex polygon with inner angles >= 90 degrees
  needs nothing more (:func:`equimesh.planar.boundary.resample.resample_boundary`).
* **orthogonal** (columns on a grid, L, U, T, plus, dumbbells): all edges are
  axis-parallel and every two distinct x coordinates (and every two distinct
  y coordinates) of the vertices differ by at least ``u >= 1.2``.  Then two
  edges that do not touch are at least ``u`` apart (their gap is a
  difference of two such coordinates), and points on two edges meeting at a
  convex (90 degree) corner are at least one part apart.  Necks (corridor
  widths) are ``u`` times a whole number, so at least 1.2.
* **stars with wide arms**: k arms of half-width ``w >= 0.6`` whose two sides
  diverge towards the centre (``r sin(pi / k) >= w``), so every inner angle
  at a tip is above 90 degrees, the narrowest part of an arm is its tip
  (``2 w >= 1.2``) and the reflex valleys face the exterior.
* **flattened surface boundaries**: the boundary of ``[0, n]^2`` sampled at
  spacing ``h`` and mapped by ``F(x, y) = (x + a sin(ky y + p), y + b sin(kx x + q))``
  with Lipschitz constant ``L = max(a ky, b kx) <= 0.25`` of ``F - id``, so
  ``F`` is injective, every edge is at least ``(1 - L) h >= 1.2`` long and
  every corner angle is within ``2 atan(L) < 29`` degrees of 90 (points on
  the two edges at a corner are then at least ``2 sin(30.5 deg) 1.2 > 1``
  apart).  ``a`` is large enough to make the boundary wavy, i.e. non-convex.
* **sharp wedges and rhombi** (docs/proofs.md, sharp corners): tips of 10 to 60 degrees whose
  sides are at least ``stagger_reach(angle) + 2`` long, the proven limit of
  the staggered Step 2 (docs/proofs.md, "Sharp corners") with one l to
  spare, and at least 1.2 wide across the shape away from the tips; the
  other corners are at least 90 degrees.

The placement keeps the construction facts above (up to rounding that stays
far below :data:`equimesh.REL_TOL`).  The constructors live in
:mod:`equimesh.testing.shapes`, shared with ``experiments/problem2.py``.
"""

import math

import numpy as np
from hypothesis import strategies as st
from strategies import angles, lengths, placed, random_polygons, shifts

from equimesh.planar.boundary.sides import SHARP_CORNER, stagger_reach
from equimesh.testing.generators import regular_polygon, rotate
from equimesh.testing.shapes import (
    column_polygon,
    dumbbell_polygon,
    flattened_square,
    letter_polygon,
    perforated_rectangle,
    sharp_rhombus,
    sharp_wedge,
    star_polygon,
)

#: Smallest grid unit, corridor and arm width, in units of l.
MIN_FEATURE = 1.2


# --------------------------------------------------------------------------- strategies

units = st.floats(MIN_FEATURE, 3.0)
phases = st.floats(0.0, 2.0 * math.pi)


@st.composite
def convex_polygons(draw, max_area=400.0):
    """Convex polygons: random (inner angles >= 90), regular k-gons, equilateral triangles."""
    kind = draw(st.sampled_from(["random", "random", "regular", "triangle"]))
    if kind == "random":
        return draw(random_polygons(max_area, max_elongation=3.0))
    if kind == "regular":
        k = draw(st.integers(4, 12))
        edge_max = math.sqrt(max_area * 4.0 * math.tan(math.pi / k) / k)
        return regular_polygon(k, draw(st.floats(1.0, max(1.0, edge_max))))
    return regular_polygon(3, draw(st.floats(1.0, max(1.0, math.sqrt(4.0 * max_area / math.sqrt(3.0))))))


@st.composite
def column_polygons(draw, max_area=400.0):
    """Random orthogonal x-monotone polygons on a grid of unit ``u >= 1.2`` (reflex corners, notches)."""
    ux, uy = draw(units), draw(units)
    n = draw(st.integers(2, 8))
    intervals = [(0, draw(st.integers(2, 7)))]
    for _ in range(n - 1):
        lo, hi = intervals[-1]
        # The next interval overlaps [lo, hi] in at least one unit.
        new_lo = draw(st.integers(lo - 3, hi - 1))
        base = max(lo, new_lo)
        intervals.append((new_lo, draw(st.integers(base + 1, base + 6))))
    v = column_polygon(intervals) * np.array([ux, uy])
    return _fit(v, max_area, min(ux, uy))


@st.composite
def letter_polygons(draw, max_area=400.0):
    """L, U, T and plus shapes with arms at least 1.2 wide (reflex corners)."""
    kind = draw(st.sampled_from(["L", "U", "T", "plus"]))
    u = draw(units)
    arm = draw(st.integers(1, 4))
    length = draw(st.integers(1, 6))
    return _fit(letter_polygon(kind, arm, length) * u, max_area, u)


@st.composite
def dumbbells(draw, max_area=600.0):
    """Two square blobs joined by a corridor 1.2 to 3 wide (a thin neck; the lattice part may split)."""
    u = draw(units)
    left, right = draw(st.integers(3, 8)), draw(st.integers(3, 8))
    v = dumbbell_polygon(left, right, draw(st.integers(1, 5)), draw(st.integers(-1, 1))) * u
    return _fit(v, max_area, u)


@st.composite
def stars(draw, max_area=400.0):
    """Stars with 3 to 7 wide arms (reflex valleys, acute exterior gaps)."""
    k = draw(st.integers(3, 7))
    w = draw(st.floats(0.6, 1.5))
    inner = w / math.sin(math.pi / k) * draw(st.floats(1.05, 2.0))
    outer = inner + draw(st.floats(1.5, 8.0))
    return star_polygon(k, w, inner, outer)


@st.composite
def flattened_boundaries(draw, max_area=400.0):
    """A wavy, non-convex image of the boundary of a square, as a flattened surface boundary."""
    n = draw(st.floats(4.0, max(4.0, math.sqrt(max_area) * 0.95)))
    lip = draw(st.floats(0.1, 0.25))
    spacing_min = 1.2 / (1.0 - lip)
    parts = max(2, int(n / draw(st.floats(spacing_min, 2.0 * spacing_min))))
    parts = min(parts, max(2, int(n / spacing_min)))
    wavelength_y, wavelength_x = draw(st.floats(3.0, 12.0)), draw(st.floats(3.0, 12.0))
    ky, kx = 2.0 * math.pi / wavelength_y, 2.0 * math.pi / wavelength_x
    a = lip / ky * draw(st.floats(0.5, 1.0))
    b = lip / kx * draw(st.floats(0.0, 1.0))
    return flattened_square(n, parts, a, b, ky, kx, draw(phases), draw(phases))


#: Smallest corner angle drawn by the sharp families, in degrees (the sharp-corner property tests go down to 10).
MIN_SHARP = 10.0


def _sharp_side(angle, width):
    """A side long enough for the staggered Step 2 at ``angle`` (with one l to spare against the rounding of
    the angle) and for a width of at least 1.2 across the shape (``width`` is the width per unit of side)."""
    return max(stagger_reach(angle, 1.0) + 2.0, MIN_FEATURE / width)


@st.composite
def sharp_wedges(draw, max_area=400.0):
    """A tip of 10 to 60 degrees closed by a rectangle (:func:`~equimesh.testing.shapes.sharp_wedge`)."""
    angle = draw(st.floats(MIN_SHARP, SHARP_CORNER))
    side = _sharp_side(angle, math.sin(math.radians(angle) / 2.0)) * draw(st.floats(1.0, 1.3))
    return sharp_wedge(angle, side, draw(st.floats(MIN_FEATURE, 6.0)))


@st.composite
def sharp_rhombi(draw, max_area=400.0):
    """A rhombus with two tips of 10 to 60 degrees (:func:`~equimesh.testing.shapes.sharp_rhombus`)."""
    angle = draw(st.floats(MIN_SHARP, SHARP_CORNER))
    return sharp_rhombus(angle, _sharp_side(angle, math.sin(math.radians(angle))) * draw(st.floats(1.0, 1.3)))


FAMILIES = {
    "convex": convex_polygons,
    "columns": column_polygons,
    "letters": letter_polygons,
    "dumbbell": dumbbells,
    "star": stars,
    "flattened": flattened_boundaries,
    "sharp wedge": sharp_wedges,
    "sharp rhombus": sharp_rhombi,
}


@st.composite
def hole_shapes(draw):
    """One hole in units of l: a regular 3- to 6-gon with edges of 1.2 to 2.5, or an L of unit 1.2 to 2."""
    if draw(st.booleans()):
        return regular_polygon(draw(st.integers(3, 6)), draw(st.floats(MIN_FEATURE, 2.5)), rotation=draw(phases))
    return np.asarray(letter_polygon("L", 1, draw(st.integers(1, 2))), dtype=float) * draw(st.floats(MIN_FEATURE, 2.0))


@st.composite
def perforated_cases(draw):
    """``(vertices, holes, l)``: a rectangle with 1 to 3 holes (:func:`~equimesh.testing.shapes.perforated_rectangle`).

    Holes are regular polygons (convex, so every corner of the region at a
    hole vertex is reflex) or L shapes (one 90 degree corner of the region),
    every edge at least 1.2, at least ``gap >= 1.2`` from each other and from
    the rectangle.  Placed by the convention of :func:`strategies.placed`
    (rotation about the outer polygon's mean, shift, rolled start vertices,
    scale by l), holes in either orientation.
    """
    holes = draw(st.lists(hole_shapes(), min_size=1, max_size=3))
    outer, holes = perforated_rectangle(holes, draw(st.floats(MIN_FEATURE, 2.5)))
    angle, shift, l = draw(angles), np.array(draw(shifts)), draw(lengths())
    centre = outer.mean(axis=0)

    def move(v):
        v = rotate(v - centre, angle) + shift
        v = np.roll(v, -draw(st.integers(0, len(v) - 1)), axis=0)
        return (v[::-1] if draw(st.booleans()) else v) * l

    return move(outer), [move(h) for h in holes], l


def simple_polygons(max_area=400.0, families=None):
    """Any of the families above (units of l = 1)."""
    names = sorted(FAMILIES) if families is None else list(families)
    return st.one_of([FAMILIES[name](max_area=max_area) for name in names])


def cases(max_area=400.0, families=None):
    """``(vertices, l)``: a polygon of :func:`simple_polygons` placed by :func:`strategies.placed`."""
    return placed(simple_polygons(max_area, families))


def _area(v):
    x, y = v[:, 0], v[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _fit(v, max_area, unit):
    """Shrink ``v`` towards ``max_area`` but never its grid unit below :data:`MIN_FEATURE`."""
    area = _area(v)
    if area <= max_area:
        return v
    return v * max(math.sqrt(max_area / area), MIN_FEATURE / unit)
