"""The Problem 1 checks of ``invariants.py`` have teeth: each one catches a mesh broken in its way.

The base case is the square of side 2l with one interior point, a valid output
of Algorithm INCREMENT's Step 5 in shape (Delaunay, boundary covered by
edges); every test passes the intact mesh first, so that the failure on the
broken one is due to the break, and matches the check's own message.
"""

import dataclasses

import numpy as np
import pytest
from invariants import (
    assert_problem1_invariants,
    check_covering,
    check_edge_lengths,
    check_node_bounds,
    check_separation,
    check_triangulation,
)

import equimesh
from equimesh import REL_TOL, PlanarMesh
from equimesh.testing.generators import rectangle

SQUARE = rectangle(2.0, 2.0)


#: The four triangles around the interior point 4, counter-clockwise.
FAN = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]


def square_mesh(centre=(1.0, 1.0), triangles=FAN, l=1.0, n_boundary=4):
    """The square of side 2 with the interior point ``centre``, triangulated by ``triangles``."""
    return PlanarMesh.build(np.vstack([SQUARE, centre]), triangles, l, n_boundary)


def test_the_intact_mesh_passes_every_check():
    """The square 2l with its centre: edges 2l and sqrt(2) l, covering radius 1 l, Delaunay, 5 nodes."""
    assert assert_problem1_invariants(square_mesh(), SQUARE, 1.0) == 1.0  # n' = LB = 5


def test_edge_lengths_catch_an_edge_below_l():
    """An edge of sqrt(2) l checked against an l a hair above sqrt(2): Theorem 1's lower end fails."""
    mesh = square_mesh()
    check_edge_lengths(mesh, np.sqrt(2.0) * (1.0 + 0.5 * REL_TOL))
    with pytest.raises(AssertionError, match="< l"):
        check_edge_lengths(mesh, np.sqrt(2.0) * (1.0 + 2.0 * REL_TOL))


def test_edge_lengths_catch_an_edge_above_2l():
    """The sides of 2l checked against an l a hair below 1: Theorem 1's upper end fails."""
    mesh = square_mesh()
    check_edge_lengths(mesh, 1.0 - 0.5 * REL_TOL)
    with pytest.raises(AssertionError, match="> 2l"):
        check_edge_lengths(mesh, 1.0 - 2.0 * REL_TOL)


def test_separation_catches_two_close_points():
    """The interior point moved to 0.9 l from a corner: the points are no longer l-separated."""
    check_separation(square_mesh(), 1.0)
    close = 0.9 / np.sqrt(2.0)
    with pytest.raises(AssertionError, match="apart"):
        check_separation(square_mesh(centre=(close, close)), 1.0)


def test_covering_catches_an_uncovered_point():
    """Without the interior point the centre of the square is sqrt(2) l from every node."""
    check_covering(square_mesh(), SQUARE, 1.0)
    bare = PlanarMesh.build(SQUARE, [[0, 1, 2], [0, 2, 3]], 1.0, 4)
    with pytest.raises(AssertionError, match=r"\[1.0, 1.0\] of P is 1.41"):
        check_covering(bare, SQUARE, 1.0)


def test_covering_catches_a_slightly_moved_point():
    """The interior point pushed up by 0.2 l: the Voronoi vertex below it is 1.017 l from every node."""
    mesh = square_mesh(centre=(1.0, 1.2))
    with pytest.raises(AssertionError, match=r"of P is 1.01666"):
        check_covering(mesh, SQUARE, 1.0)


BROKEN_TRIANGULATIONS = {
    # (mesh, message the check must give)
    "a triangle dropped": (lambda: square_mesh(triangles=FAN[1:]), "Euler"),
    # PlanarMesh.build orients every triangle; a clockwise one needs a mesh assembled without it.
    "a triangle clockwise": (
        lambda: dataclasses.replace(square_mesh(), triangles=np.array([[0, 4, 1], *FAN[1:]])),
        "not counter-clockwise",
    ),
    "a sliver next to the bottom side": (lambda: square_mesh(centre=(1.0, 1e-8)), "sliver"),
    # Diagonal 0-2 instead of the edge 3-4: the circumcircle of (0, 2, 3) holds point 4.
    "a non-Delaunay flip": (
        lambda: square_mesh(centre=(1.0, 0.5), triangles=[[0, 1, 4], [1, 2, 4], [4, 2, 0], [0, 2, 3]]),
        "inside its circumcircle",
    ),
    # Points relabelled so that the boundary ring starts at the polygon's vertex 1.
    "the ring starting at another vertex": (
        lambda: PlanarMesh.build(np.vstack([np.roll(SQUARE, -1, axis=0), [1.0, 1.0]]), FAN, 1.0, 4),
        "does not start at vertex 0",
    ),
}


@pytest.mark.parametrize("name", sorted(BROKEN_TRIANGULATIONS))
def test_triangulation_catches(name):
    """Step 5: each way of breaking the Delaunay triangulation of P is caught, with its message."""
    make, message = BROKEN_TRIANGULATIONS[name]
    check_triangulation(square_mesh(), SQUARE, 1.0)
    with pytest.raises(AssertionError, match=message):
        check_triangulation(make(), SQUARE, 1.0)


def test_triangulation_catches_a_mesh_of_another_polygon():
    """The mesh of the square checked against a taller rectangle: the areas do not add up."""
    with pytest.raises(AssertionError, match="triangles cover"):
        check_triangulation(square_mesh(), rectangle(2.0, 2.5), 1.0)


def test_triangulation_catches_an_interior_point_outside_p():
    """The mesh of a larger square whose 'interior' point lies outside the square it is checked against."""
    bigger = rectangle(4.0, 4.0)
    mesh = PlanarMesh.build(np.vstack([bigger, [3.0, 3.0]]), FAN, 1.0, 4)
    check_triangulation(mesh, bigger, 1.0)
    with pytest.raises(AssertionError):
        check_triangulation(mesh, SQUARE, 1.0)


def test_node_bounds_catch_too_many_nodes():
    """INCREMENT's mesh for l/2 judged against l: packing bound first (n' = 13 > 9), then Theorem 2 (at l/4)."""
    assert check_node_bounds(square_mesh(), SQUARE, 1.0) == 1.0
    denser = equimesh.increment(SQUARE, 0.5)
    assert equimesh.packing_upper_bound(SQUARE, 1.0 - REL_TOL) < denser.n_nodes <= 16 * 5 / 3
    with pytest.raises(AssertionError, match="packing upper bound"):
        check_node_bounds(denser, SQUARE, 1.0)
    with pytest.raises(AssertionError, match="16/3"):
        check_node_bounds(equimesh.increment(SQUARE, 0.25), SQUARE, 1.0)
