"""Sharp corners with short sides: inputs of Problem 2 that the staggered Step 2 may or may not handle.

Unlike :mod:`strategies_simple`, these shapes are not valid by construction:
their corners of 10 to 60 degrees have sides shorter than the proven limit of
docs/proofs.md ("Sharp corners"), down to l, so some are meshed and some are
refused.  The property tests check every theorem on those that are meshed and
the kind of refusal on the others.  Families, in units of ``l = 1``
(:func:`equimesh.testing.shapes.sharp_corner_shapes` builds them):

* **thin triangle**: a tip of ``angle`` degrees with sides of 1 to ``K + 2``
  (``K l = stagger_reach``); the other corners are what they are (often sharp
  too, or shorter than l).
* **short wedge**: :func:`~equimesh.testing.shapes.sharp_wedge` with sides
  below the proven limit and a base of at least 1.2.
* **spike**: a rectangle with a triangular spike of ``angle`` degrees on its
  top side (base at least 1.2).
* **dart hole**: a rectangle with a dart-shaped hole whose notch makes a
  corner of ``angle`` degrees of the region on the hole's ring.

:func:`darts` draws arrowheads (:func:`~equimesh.testing.shapes.sharp_dart`):
three sharp corners in a row, decided jointly (planar/boundary/chain.py).

:func:`sharp_cases` places them as :func:`strategies.placed` does (rotation,
shift, rolled start vertex, scale by a drawn ``l``), holes alike.
"""

import numpy as np
from hypothesis import strategies as st
from strategies import angles, lengths, shifts

from equimesh.planar.boundary.sides import SHARP_CORNER, stagger_reach
from equimesh.testing.generators import rotate
from equimesh.testing.shapes import sharp_corner_shape, sharp_dart

#: Smallest corner angle drawn, in degrees.
MIN_SHARP = 10.0
KINDS = ("thin triangle", "short wedge", "spike", "dart hole")


@st.composite
def sharp_shapes(draw, kinds=KINDS):
    """``(kind, outer, holes)`` in units of l: one family of the module docstring, its sizes drawn."""
    kind = draw(st.sampled_from(kinds))
    angle = draw(st.floats(MIN_SHARP, SHARP_CORNER, exclude_max=True))
    reach = stagger_reach(angle, 1.0) + 2.0
    sizes = draw(st.lists(st.floats(0.0, 1.0), min_size=3, max_size=3))
    outer, holes = sharp_corner_shape(kind, angle, reach, *sizes)
    return kind, outer, holes


@st.composite
def sharp_cases(draw, kinds=KINDS):
    """``(vertices, holes, l)``: a shape of :func:`sharp_shapes` rotated, shifted, rolled and scaled by l."""
    _, outer, holes = draw(sharp_shapes(kinds))
    angle, shift, l = draw(angles), np.array(draw(shifts)), draw(lengths())
    centre = outer.mean(axis=0)

    def move(v):
        v = rotate(v - centre, angle) + shift
        return np.roll(v, -draw(st.integers(0, len(v) - 1)), axis=0) * l

    return move(outer), [move(h) for h in holes], l


@st.composite
def darts(draw):
    """``(vertices, l)``: an arrowhead with a tip and two barbs of 10 to 60 degrees, tip sides from l to where the
    tip and a barb stop sharing any point of them, placed as :func:`sharp_cases` places its shapes."""
    tip, first, second = (draw(st.floats(MIN_SHARP, SHARP_CORNER, exclude_max=True)) for _ in range(3))
    reach = stagger_reach(tip, 1.0) + max(stagger_reach(first, 1.0), stagger_reach(second, 1.0)) + 3.0
    outer = sharp_dart(tip, (first, second), 1.0 + draw(st.floats(0.0, 1.0)) * reach)
    angle, shift, l = draw(angles), np.array(draw(shifts)), draw(lengths())
    return np.roll(rotate(outer - outer.mean(axis=0), angle) + shift, -draw(st.integers(0, 3)), axis=0) * l, l
