"""Step 2's corner rules (``planar/polygon.py``) exactly at their thresholds.

What must hold: a corner is refused as unmeshable or unseparable only when
the distance it is decided by is *below* ``(1 - REL_TOL) l`` (a distance of
exactly that is accepted, like every edge check); a segment between two
boundary points that leaves P by less than ``REL_TOL l`` (in units of l, not
``REL_TOL / l``) counts as inside P, both for the separation check and for
the corner triangle of ``_unseparable_corner``; a short side tries the
candidates with the fewest multiples of l from a corner that is not sharp
first.  The floats are built so that the distance is exactly the threshold
(asserted), at l far from 1 so that l and 1 / l differ.
"""

import math

import numpy as np
import pytest

from equimesh.errors import InvalidPolygonError
from equimesh.planar import polygon
from equimesh.planar.polygon import Boundary, as_polygon, check_boundary_separation, side_positions
from equimesh.tolerance import REL_TOL


def first_corner(vertices, l):
    """The polygon and its first corner ``(ring, i, theta, leaving, arriving)`` (local lengths)."""
    poly = as_polygon(np.array(vertices), l)
    return poly, next(polygon._corners(poly))


def chord(a, b, theta):
    """Law of cosines: points ``a`` and ``b`` from a corner of ``theta`` radians, on its two sides."""
    return math.sqrt(max(a * a + b * b - 2.0 * a * b * math.cos(theta), 0.0))


@pytest.mark.parametrize("beta, refused", [(1.2981954331865397, False), (1.2982, True), (1.2981, False)])
def test_unmeshable_corner_exactly_at_the_threshold(beta, refused):
    """A 25-degree corner with a side of beta ~ 1.278 l (l = 1.015625): the sector's far point (radius 2l, widened by
    REL_TOL) is exactly (1 - REL_TOL) l from the side's end at beta = 1.2981954331865397 (one float lower it is
    farther): not refused; at 1.2982 it is closer, refused; at 1.2981 farther."""
    l, a = 1.015625, math.radians(25.0)
    poly, (_, _, theta, leaving, _) = first_corner([(0.0, 0.0), (beta, 0.0), (10 * l * math.cos(a), 10 * l * math.sin(a))], l)
    lp = poly.local_length(l)
    far = max(chord(r, leaving, theta) for r in ((1.0 - REL_TOL) * lp, 2.0 * lp * (1.0 + REL_TOL)))
    assert (far == (1.0 - REL_TOL) * lp) == (beta == 1.2981954331865397)
    error = polygon._unmeshable_corner(poly, l)
    assert (error is not None) == refused
    if refused:
        assert str(error).startswith("no mesh with every edge in [l, 2l] exists for l = 1.015625: "
                                     "at the corner at vertex 0 at (0, 0)")


@pytest.mark.parametrize("a, refused", [(2.250271104332659, False), (2.2502, True), (2.2503, False)])
def test_unseparable_corner_exactly_at_the_threshold(a, refused):
    """A 38.94-degree corner between sides a ~ 2.25 and 2.25 (single parts at l = 1.5): the first points of its two
    sides are its neighbours, exactly (1 - REL_TOL) l apart at a = 2.250271104332659: not refused; closer at
    a = 2.2502, refused; farther at 2.2503."""
    l, t = 1.5, math.radians(38.94)
    poly, (_, _, theta, leaving, arriving) = first_corner([(0.0, 0.0), (a, 0.0), (2.25 * math.cos(t), 2.25 * math.sin(t))], l)
    assert (chord(leaving, arriving, theta) == (1.0 - REL_TOL) * poly.local_length(l)) == (a == 2.250271104332659)
    error = polygon._unseparable_corner(poly, l)
    assert (error is not None) == refused
    if refused:
        assert str(error).startswith("the corner at vertex 0 at (0, 0) (38.94 degrees) cannot meet Lemma 3 (1) for l = 1.5")


def dented(dent):
    """A 30-degree corner at (0, 0) between sides 2 long whose far ends p, q are 1.035 apart, with a fourth vertex
    ``dent`` inside the triangle, from the middle of pq towards the corner: the segment pq leaves P by ``dent``."""
    p, q = np.array([2.0, 0.0]), 2.0 * np.array([math.cos(math.radians(30.0)), math.sin(math.radians(30.0))])
    m = (p + q) / 2.0
    return np.array([(0.0, 0.0), p, m - dent * m / np.linalg.norm(m), q])


@pytest.mark.parametrize("dent, inside", [(1.1e-9, True), (2e-9, False)])
def test_a_segment_leaving_p_by_less_than_rel_tol_l_is_inside(dent, inside):
    """At l = 1.5 a segment leaving P by 1.1e-9 is inside P grown by REL_TOL l = 1.5e-9 (and not REL_TOL / l = 6.7e-10);
    2e-9 is outside.  So the boundary points p and q, 1.035 < l apart, see each other across the dent (the separation
    check refuses them), and the corner triangle (0, 0), p, q lies in P (the corner is unseparable)."""
    l = 1.5
    vertices = dented(dent)
    poly = as_polygon(vertices, l)
    assert np.array_equal(poly.rings[0].local, vertices)  # the local frame is the caller's at l = 1.5
    pq = Boundary(vertices[[1, 3]], np.array([True, True]), np.array([1, 3]), np.array([0, 0]))
    if inside:
        with pytest.raises(InvalidPolygonError, match=r"^the corner at vertex 0 at \(0, 0\) \(30 degrees\) cannot meet"):
            check_boundary_separation(poly, pq, l)
        assert polygon._unseparable_corner(poly, l) is not None
    else:
        assert check_boundary_separation(poly, pq, l) is None
        assert polygon._unseparable_corner(poly, l) is None


def test_a_short_side_takes_the_fewest_multiples_from_a_corner_that_is_not_sharp():
    """The triangle (0, 0), (2.42, 0), (4.64, 2.35) at l = 1, spacing 1.5: corners of 26.9 (sharp), 133.4 (not) and
    19.8 degrees (sharp).  Side 1 (3.23 long, from the 133-degree corner to the 19.8-degree one) is separated with
    one multiple of l from its first corner and one staggered point from its last: points at 0, 1 and length - 1;
    the candidate with two multiples (0, 1, 2) is tried after it."""
    poly = as_polygon(np.array([(0.0, 0.0), (2.42, 0.0), (4.64, 2.35)]), 1.0)
    ring = poly.rings[0]
    angles = [ring.inner_angle(i) for i in range(3)]
    np.testing.assert_allclose(angles, [26.861, 133.371, 19.769], atol=1e-3)
    lengths = ring.local_edge_lengths
    numerators, denominator = side_positions(lengths, angles, 1.0, 1.5)[1]
    assert denominator == lengths[1]
    np.testing.assert_allclose(numerators, [0.0, 1.0, lengths[1] - 1.0], atol=1e-12)
