"""Problem 2 end to end (``planar/strip.py``): the assembly of the lattice part and the boundary strip, tested directly.

What must hold, on small polygons whose lattice part is known by hand
(``tests/test_lattice.py``): the output satisfies every guarantee of
``tests/invariants_uniform.py``; its G1 edges are exactly the lattice edges
(length l, between neighbouring lattice vertices); the points come boundary
first, counter-clockwise from the caller's vertex 0, each hole after the
outer ring; ``info`` reports the lattice part and the insertion as they are;
the parameter checks refuse what the paper excludes (clearance below 1,
spacing outside [1, 2]) with one line naming the parameter.  Each case runs
in well under a second, so that the mutants of ``strip.py`` (``make
mutation``) are cheap to kill.
"""

import math

import invariants_uniform as inv
import numpy as np
import pytest
import shapely

import equimesh
from equimesh import G1, EquimeshError
from equimesh.planar import lattice, strip
from equimesh.planar.insertion import ENGINES
from equimesh.planar.limits import MAX_NODES, node_estimate
from equimesh.planar.polygon import as_polygon

SQUARE = np.array([[0.0, 0.0], [6.0, 0.0], [6.0, 6.0], [0.0, 6.0]])
#: The offset of tests/test_lattice.py::test_square_lattice_part_by_hand: 22 vertices, 28 triangles, 49 edges.
OFFSET = (0.5, 1.0)
BIG = SQUARE * 2.0
HOLE = np.array([[5.0, 5.0], [7.0, 5.0], [7.0, 7.0], [5.0, 7.0]])


def lattice_edges(mesh, part):
    """Mesh edges joining two lattice-adjacent vertices of ``part`` (matched by position)."""
    local = mesh.local_points
    index = {tuple(p): k for k, p in enumerate(part.points)}
    which = np.array([index.get(tuple(p), -1) for p in local])
    e = mesh.edges
    both = (which[e[:, 0]] >= 0) & (which[e[:, 1]] >= 0)
    adjacent = np.zeros(len(e), dtype=bool)
    adjacent[both] = lattice.lattice_adjacent(part.ij[which[e[both, 0]]], part.ij[which[e[both, 1]]])
    return adjacent


@pytest.fixture
def square_mesh():
    """Function-scoped: mutmut maps a test to the functions it calls, and a module-scoped fixture calls once."""
    return equimesh.uniform_triangulation(SQUARE, 1.0, offset=OFFSET)


def test_square_satisfies_theorem3_and_every_invariant(square_mesh):
    """Theorem 3 and the conforming CDT, on the square whose lattice part is known."""
    inv.assert_problem2_invariants(square_mesh, SQUARE, 1.0)


def test_square_g1_edges_are_exactly_the_lattice_edges(square_mesh):
    """The 49 edges of K (3 * 28 triangles, 14 on its boundary: (84 + 14) / 2) are G1, and nothing else."""
    g1 = square_mesh.edge_groups == G1
    assert g1.sum() == 49
    part = lattice.lattice_part(as_polygon(SQUARE, 1.0), 1.0, 0.0, OFFSET)
    assert np.array_equal(g1, lattice_edges(square_mesh, part))
    p = square_mesh.points
    np.testing.assert_allclose(
        np.linalg.norm(p[square_mesh.edges[g1, 1]] - p[square_mesh.edges[g1, 0]], axis=1), 1.0, rtol=1e-12
    )


def test_square_info_and_point_order(square_mesh):
    """info holds the lattice part's sizes and the run's parameters; boundary first, then strip, then lattice interior."""
    m = square_mesh
    info = m.info
    assert (info["n_lattice_vertices"], info["n_lattice_triangles"]) == (22, 28)
    assert (info["angle"], info["offset"], info["clearance"]) == (0.0, (0.5, 1.0), 1.0)
    # Step 2 at spacing 1.5 splits each side of 6 into 4 parts: 16 boundary points, one ring.
    assert m.n_boundary == 16 and info["boundary_rings"] == (16,)
    assert len(m.points) == 16 + 22 + info["n_inserted"]
    assert info["n_inserted"] > 0
    np.testing.assert_array_equal(m.points[0], SQUARE[0])
    ring = m.points[:16]
    assert shapely.LinearRing(ring).is_ccw
    np.testing.assert_allclose(np.linalg.norm(np.roll(ring, -1, axis=0) - ring, axis=1), 1.5, rtol=1e-15)
    part = lattice.lattice_part(as_polygon(SQUARE, 1.0), 1.0, 0.0, OFFSET)
    interior = np.setdiff1d(np.arange(len(part.points)), part.boundary_vertices)
    np.testing.assert_array_equal(m.local_points[len(m.points) - len(interior) :], part.points[interior])
    assert len(m.triangles) >= 28


def test_start_vertex_and_orientation_of_the_input_are_kept():
    """Points start at the caller's vertex 0, counter-clockwise, whichever vertex or orientation is given."""
    rolled = np.roll(SQUARE, -2, axis=0)
    mesh = equimesh.uniform_triangulation(rolled, 1.0, offset=OFFSET)
    np.testing.assert_array_equal(mesh.points[0], rolled[0])
    cw = equimesh.uniform_triangulation(SQUARE[::-1], 1.0, offset=OFFSET)
    assert (cw.edge_groups == G1).sum() == 49
    inv.assert_problem2_invariants(cw, SQUARE[::-1], 1.0)


def test_square_with_a_hole():
    """The hole's ring follows the outer ring, clockwise; the lattice keeps 1.25 l from it; every invariant holds."""
    mesh = equimesh.uniform_triangulation(BIG, 1.0, holes=[HOLE], offset=OFFSET, clearance=1.25)
    inv.assert_problem2_invariants(mesh, BIG, 1.0, clearance=1.25, holes=[HOLE])
    outer, hole = mesh.info["boundary_rings"]
    assert (outer, hole) == (32, 8) and mesh.n_boundary == 40  # sides of 12 and 2 in parts of 1.5 and 1
    ring = mesh.points[outer : outer + hole]
    assert not shapely.LinearRing(ring).is_ccw
    assert {tuple(p) for p in HOLE} <= {tuple(p) for p in ring}
    part = lattice.lattice_part(as_polygon(BIG, 1.0, [HOLE]), 1.0, 0.0, OFFSET, 1.25)
    assert mesh.info["n_lattice_vertices"] == len(part.points)
    assert np.array_equal(mesh.edge_groups == G1, lattice_edges(mesh, part))
    assert len(mesh.points) == 40 + len(part.points) + mesh.info["n_inserted"]


def test_polygon_too_small_for_a_lattice_part():
    """A 2 x 2 square keeps no lattice vertex (none is 1 from all four sides): no G1 edge, the strip is all of P."""
    mesh = equimesh.uniform_triangulation(SQUARE / 3.0, 1.0)
    assert mesh.info["n_lattice_vertices"] == 0 and not np.any(mesh.edge_groups == G1)
    inv.assert_problem2_invariants(mesh, SQUARE / 3.0, 1.0)


def test_hole_seed_lies_inside_a_non_convex_hole():
    """The centroid of a U-shaped hole is outside it; the seed must be inside."""
    u = np.array([[0, 0], [5, 0], [5, 5], [4, 5], [4, 1], [1, 1], [1, 5], [0, 5]], float)
    poly = as_polygon(np.array([[-5, -5], [10, -5], [10, 10], [-5, 10]], float), 1.0, [u])
    seed = strip.hole_seed(poly.holes[0])
    assert seed.shape == (1, 2)
    assert shapely.Polygon(poly.holes[0].local).contains(shapely.Point(seed[0]))


@pytest.mark.parametrize(
    "side, clearance, l, area",
    [(6.0, 1.0, 1.0, 36.0), (100.0, 1.0, 1.5, 2 * 1.5 * 400.0), (100.0, 2.0, 1.0, 3 * 400.0)],
)
def test_strip_estimate_by_hand(side, clearance, l, area):
    """min(A, (clearance + 1) l perimeter) under Oler's bound, plus perimeter / l boundary vertices of K."""
    poly = as_polygon(SQUARE / 6.0 * side, l)
    expected = node_estimate(area, 4 * side, l) + 4 * side / l
    assert strip.strip_estimate(poly, l, clearance) == pytest.approx(expected, rel=1e-14)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (
            {"clearance": 0.999},
            "clearance must be at least 1 (Lemma 3 needs lattice vertices l from the boundary), got 0.999",
        ),
        ({"clearance": math.inf}, "clearance must be finite, got inf"),
        ({"boundary_spacing": 0.999}, "boundary_spacing must be between 1 and 2 (units of l, Step 2), got 0.999"),
        ({"boundary_spacing": 2.001}, "boundary_spacing must be between 1 and 2 (units of l, Step 2), got 2.001"),
        ({"angle": math.nan}, "angle must be finite, got nan"),
        ({"offset": (1.0, 2.0, 3.0)}, "offset must be a pair of finite numbers, got (1.0, 2.0, 3.0)"),
        ({"offset": (1.0, math.inf)}, "offset must be a pair of finite numbers, got (1.0, inf)"),
        ({"offset": "ab"}, "offset must be an array of numbers"),
        ({"boundary_spacing": math.nan}, "boundary_spacing must be finite, got nan"),
        ({"clearance": "a"}, "clearance must be a real number, got 'a'"),
    ],
)
def test_parameters_outside_the_paper_are_refused(kwargs, message):
    """One line, naming the parameter and the value."""
    with pytest.raises(EquimeshError) as err:
        equimesh.uniform_triangulation(SQUARE, 1.0, **kwargs)
    assert str(err.value) == message


@pytest.mark.parametrize(
    "check, value", [(strip.check_clearance, 1.0), (strip.check_spacing, 1.0), (strip.check_spacing, 2.0)]
)
def test_parameters_at_their_limits_are_accepted(check, value):
    """Clearance exactly 1, spacing exactly 1 or 2: allowed, returned as plain floats."""
    out = check(value)
    assert out == value and type(out) is float


def test_the_callers_vertices_are_kept_bit_for_bit():
    """The local frame rounds these vertices on the way back; the output pins them to the caller's coordinates."""
    vertices = np.array([[0.0, 0.0], [4.0, 0.0], [5.0, 2.5], [2.0, 4.5], [-1.0, 2.5]]) * 1.7 + np.array([0.1, 0.7])
    poly = as_polygon(vertices, 1.0)
    assert not np.array_equal(poly.frame.to_caller(poly.local), vertices)  # the round trip alone would not do
    mesh = equimesh.uniform_triangulation(vertices, 1.0)
    found = {tuple(p) for p in mesh.points}
    assert all(tuple(v) in found for v in vertices)
    np.testing.assert_allclose(mesh.frame.to_caller(mesh.local_points), mesh.points, rtol=0, atol=1e-12)


def test_size_guard_counts_what_the_engine_pays_for(monkeypatch):
    """The reference engine's default limit counts the boundary strip, the fast engine's the polygon (MAX_NODES, made
    small here, so that a broken guard costs a small run).

    The 6 l square: strip area min(36, 2 * 24) = 36 l^2, Oler's bound 41.57 + 12 + 1, plus 24 vertices on the
    boundary of K: 78.6 > 50; the whole polygon 54.6 < 100.
    """
    monkeypatch.setitem(MAX_NODES, "reference", 50)
    monkeypatch.setitem(MAX_NODES, "fast", 100)
    with pytest.raises(equimesh.MeshTooLargeError) as err:
        equimesh.uniform_triangulation(SQUARE, 1.0, engine="reference")
    assert str(err.value).startswith(
        "l = 1.0 would need about 78.6 nodes in the boundary strip, more than max_nodes = 50;"
    )
    assert equimesh.uniform_triangulation(SQUARE, 1.0, offset=OFFSET).info["n_lattice_vertices"] == 22
    with pytest.raises(equimesh.MeshTooLargeError, match=r"nodes in the polygon, more than max_nodes = 10;"):
        equimesh.uniform_triangulation(SQUARE, 1.0, max_nodes=10)
    assert (
        equimesh.uniform_triangulation(SQUARE, 1.0, max_nodes=None, engine="reference").info["n_lattice_vertices"] > 0
    )


def test_an_offset_given_as_a_row_is_a_pair():
    """Any array of two numbers is a pair: (2,), (1, 2) or (2, 1)."""
    for offset in ([[0.5, 1.0]], [[0.5], [1.0]]):
        assert equimesh.uniform_triangulation(SQUARE, 1.0, offset=offset).info["offset"] == (0.5, 1.0)


def test_the_engine_argument_chooses_the_engine(monkeypatch):
    """engine="reference" runs the reference engine on the boundary strip (seen through a spy in ENGINES)."""
    calls = []
    reference = ENGINES["reference"]
    monkeypatch.setitem(ENGINES, "reference", lambda region, l: calls.append(l) or reference(region, l))
    mesh = equimesh.uniform_triangulation(SQUARE, 1.0, offset=OFFSET, engine="reference")
    assert calls == [1.0] and (mesh.edge_groups == G1).sum() == 49


def test_info_reports_the_parameters_as_used():
    """angle (taken as given), offset and clearance, as floats, in info."""
    mesh = equimesh.uniform_triangulation(SQUARE, 1.0, angle=7.5, offset=(0.25, 0.5), clearance=1.25)
    assert (mesh.info["angle"], mesh.info["offset"], mesh.info["clearance"]) == (7.5, (0.25, 0.5), 1.25)
