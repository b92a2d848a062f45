"""Step 2 of Algorithm INCREMENT (``planar/boundary/resample.py``): boundary points whose parts are in [l, 2l].

What must hold: consecutive boundary points are l to 2l apart and all of them pairwise at least l (convex
input, inner angles >= 90 degrees); the spacing sets the longest part; at a sharp corner the staggered
points of its two sides are l apart (docs/proofs.md, "Sharp corners").
"""

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial.distance import pdist
from strategies import problems

from equimesh import REL_TOL
from equimesh.planar.boundary.resample import resample_boundary
from equimesh.planar.boundary.sides import stagger_reach
from equimesh.planar.increment import validate_problem1
from equimesh.planar.polygon import as_polygon
from equimesh.testing.generators import rectangle
from equimesh.testing.shapes import sharp_wedge


@given(problems)
def test_step2_boundary_points_are_between_l_and_2l(problem):
    """Step 2: consecutive boundary points are in [l, 2l], all boundary points pairwise >= l.

    The pairwise bound is the docstring argument of ``resample_boundary``
    (convexity and inner angles >= 90 degrees).
    """
    vertices, l = problem
    poly, l = validate_problem1(vertices, l)
    boundary = resample_boundary(poly, l)
    pts, l = boundary.points, poly.local_length(l)  # both in the polygon's local frame
    steps = np.linalg.norm(np.roll(pts, -1, axis=0) - pts, axis=1)
    assert steps.min() >= (1.0 - REL_TOL) * l
    assert steps.max() <= 2.0 * l * (1.0 + REL_TOL)
    assert pdist(pts).min() >= (1.0 - REL_TOL) * l
    assert np.array_equal(pts[boundary.is_vertex], poly.local)


@given(
    st.floats(0.5, 60.0, exclude_max=True),
    st.floats(1.0, 1.5),
    st.sampled_from([1.0, 1.5, 2.0]),
    st.sampled_from([1.0, 2.0**-5, 2.0**7]),
)
def test_staggered_step2_separates_the_sides_of_a_sharp_corner(angle, stretch, spacing, l):
    """docs/proofs.md, "Sharp corners": at any corner angle down to 0.5 degrees, with both sides at least
    ``stagger_reach + l`` long, the Step 2 points of the two sides are pairwise at least l apart, and every
    boundary part is in [l, 2l]."""
    side = max(stagger_reach(angle, 1.0) + 2.0, 1.2 / math.sin(math.radians(angle) / 2.0)) * stretch
    poly = as_polygon(sharp_wedge(angle, side, 2.0) * l, l)
    boundary = resample_boundary(poly, l, spacing)
    lp = poly.local_length(l)
    parts = np.linalg.norm(np.roll(boundary.points, -1, axis=0) - boundary.points, axis=1)
    assert parts.min() >= (1.0 - REL_TOL) * lp and parts.max() <= 2.0 * (1.0 + REL_TOL) * lp
    tip = np.flatnonzero(np.all(poly.local == poly.frame.to_local(np.zeros((1, 2))), axis=1))[0]
    sides = [boundary.points[boundary.edge == (tip - 1) % 5], boundary.points[boundary.edge == tip]]
    sides[0] = np.vstack([sides[0], boundary.points[boundary.edge == tip][:1]])  # the tip closes the arriving side
    gaps = np.linalg.norm(sides[0][:, None, :] - sides[1][None, :, :], axis=2)
    gaps[-1, 0] = np.inf  # the tip with itself
    assert gaps.min() >= (1.0 - REL_TOL) * lp


def test_resample_boundary_uses_the_spacing():
    """A square of side 4l: parts of at most 2l (default) give 8 boundary points, of at most 1.5 l give 12."""
    poly = as_polygon(rectangle(4.0, 4.0), 1.0)
    assert len(resample_boundary(poly, 1.0).points) == 8
    boundary = resample_boundary(poly, 1.0, 1.5)
    assert len(boundary.points) == 12 and boundary.is_vertex.sum() == 4
    assert boundary.edge.tolist() == [0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3]
