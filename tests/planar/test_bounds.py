"""Theorem 2 of the paper and the node-count bounds it is checked with.

Theorem 2: INCREMENT uses at most 16/3 times the optimal number of nodes n*.
n* is unknown, so we check the stronger ``n' <= 16/3 * node_lower_bound``
(``node_lower_bound <= n*`` is proven in its docstring), and the packing
bound ``n' <= packing_upper_bound`` (output points are l-separated).
"""

import math

import numpy as np
import pytest
from hypothesis import event, given, target
from invariants import check_edge_lengths, check_node_bounds
from strategies import problems

import equimesh
from equimesh import REL_TOL
from equimesh.testing.generators import rectangle, regular_polygon


@given(problems)
def test_theorem2_node_count_within_16_3_of_the_lower_bound(problem):
    """Theorem 2 (strengthened): n' <= 16/3 * node_lower_bound(P, l), and n' <= packing bound.

    The observed ratio n'/LB is recorded (``hypothesis.target`` steers the
    search towards large ratios; ``event`` buckets it in the statistics shown
    by ``pytest --hypothesis-show-statistics``).
    """
    vertices, l = problem
    ratio = check_node_bounds(equimesh.increment(vertices, l), vertices, l)
    target(ratio, label="n'/LB")
    event(f"n'/LB in [{math.floor(2 * ratio) / 2:.1f}, {math.floor(2 * ratio) / 2 + 0.5:.1f})")


@given(problems)
def test_lower_bound_below_packing_bound(problem):
    """Consistency of the bounds: LB <= packing bound (an optimal mesh is itself l-separated)."""
    vertices, l = problem
    assert equimesh.node_lower_bound(vertices, l) <= equimesh.packing_upper_bound(vertices, (1.0 - REL_TOL) * l)


@given(problems)
def test_bounds_are_scale_invariant(problem):
    """Both bounds depend on P / l only: scaling P and l by a power of two changes nothing."""
    vertices, l = problem
    for k in (-2, 3):
        s = 2.0**k
        assert equimesh.node_lower_bound(vertices * s, l * s) == equimesh.node_lower_bound(vertices, l)
        assert equimesh.packing_upper_bound(vertices * s, l * s) == equimesh.packing_upper_bound(vertices, l)


# Small polygons with a known feasible mesh of n nodes (edges in [l, 2l]); LB must not exceed n.
KNOWN_MESHES = {
    # The square itself: diagonals sqrt(2) l.
    "unit square": (rectangle(1.0, 1.0), np.empty((0, 2)), [[0, 1, 2], [0, 2, 3]]),
    # Corners and centre: sides 2l, spokes sqrt(2) l.
    "square 2l": (rectangle(2.0, 2.0), np.array([[1.0, 1.0]]), [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]),
    # Regular hexagon-like octagon: fan from vertex 0 is too long, use the centre.
    "regular octagon, edge l": (
        regular_polygon(8, 1.0),
        np.array([[0.0, 0.0]]),
        [[i, (i + 1) % 8, 8] for i in range(8)],
    ),
}


@pytest.mark.parametrize("name", sorted(KNOWN_MESHES))
def test_lower_bound_does_not_exceed_a_feasible_mesh(name):
    """node_lower_bound <= n for an explicit triangulation of P with every edge in [l, 2l]."""
    vertices, extra, triangles = KNOWN_MESHES[name]
    mesh = equimesh.PlanarMesh.build(np.vstack([vertices, extra]), triangles, 1.0, len(vertices))
    check_edge_lengths(mesh, 1.0)
    assert equimesh.node_lower_bound(vertices, 1.0) <= mesh.n_nodes


def test_lower_bound_is_tight_on_small_squares():
    """On the unit square and the square 2l the bound equals the optimum (4 and 5 nodes)."""
    assert equimesh.node_lower_bound(rectangle(1.0, 1.0), 1.0) == 4
    assert equimesh.node_lower_bound(rectangle(2.0, 2.0), 1.0) == 5


# Exact values of the lower bound where a term of its formula is an integer up to rounding:
# (polygon, l, LB, derivation).  ceil(x - 1e-12) must round such a term down to the integer.
EXACT_LOWER_BOUNDS = {
    # Area 4 sqrt(3) l^2: exactly 4 triangles; perimeter (4 + 4 sqrt(3)) l = 5.46 * 2l, so h >= 6.
    "rectangle 2 sqrt(3) l x 2l": (rectangle(2.0 * math.sqrt(3.0), 2.0), 1.0, 6),
    # Area 6 sqrt(3) (2l)^2 / 4 = 6 sqrt(3) l^2: 6 triangles; perimeter 12 l = 6 * 2l, h >= 6.
    "regular hexagon, edge 2l": (regular_polygon(6, 2.0), 1.0, 7),
    # Area 16 l^2: ceil(9.24) = 10 triangles; perimeter 16 l = 8 * 2l, so h >= 8 > |V|.
    "square 4l": (rectangle(4.0, 4.0), 1.0, 10),
    # Area 25 l^2: ceil(14.43) = 15 triangles; perimeter 20 l = 10 * 2l, h >= 10; 15 + 10 odd.
    "square 5l": (rectangle(5.0, 5.0), 1.0, 14),
    # The same at l = 2^-3: the bound depends on P / l only.
    "square 4l, l = 1/8": (rectangle(0.5, 0.5), 0.125, 10),
}


@pytest.mark.parametrize("name", sorted(EXACT_LOWER_BOUNDS))
def test_lower_bound_exact_values(name):
    """node_lower_bound = ceil((ceil(A / (sqrt(3) l^2)) + max(|V|, ceil(perimeter / 2l)) + 2) / 2), by hand."""
    vertices, l, expected = EXACT_LOWER_BOUNDS[name]
    assert equimesh.node_lower_bound(vertices, l) == expected
