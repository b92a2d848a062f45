"""Algorithm INCREMENT (Problem 1, Section 2 of the paper, ``planar/increment.py``): its theorems and its steps.

What must hold: the output satisfies Theorems 1-2 and every check of ``tests/invariants.py`` on generated inputs
(``tests/strategies.py``); the input of Problem 1 is a convex polygon with inner angles of at least 90 degrees
and edges of at least l (anything else is refused with one line naming the vertex or edge); its points are the
Step 2 boundary points first (counter-clockwise from the caller's vertex 0, the caller's vertices bit for bit)
and then the inserted points, whose number ``info`` reports; the size guard refuses, before any work, what the
engine's default cannot afford.  The cases by hand run in well under a second, so that the mutants of
``increment.py`` (``make mutation``) are cheap to kill.
"""

import math

import numpy as np
import pytest
import shapely
from hypothesis import assume, given
from hypothesis import strategies as st
from invariants import (
    assert_problem1_invariants,
    check_covering,
    check_edge_lengths,
    check_separation,
    check_triangulation,
)
from strategies import problems

import equimesh
from equimesh import EquimeshError, InvalidLengthError, InvalidPolygonError, MeshTooLargeError
from equimesh.planar.boundary.resample import resample_boundary
from equimesh.planar.increment import validate_problem1
from equimesh.planar.insertion import ENGINES
from equimesh.planar.limits import MAX_NODES
from equimesh.testing.generators import rectangle, regular_polygon

#: Every property runs against both engines; the reference engine is the oracle.
ENGINE_NAMES = sorted(ENGINES)


engines = pytest.mark.parametrize("engine", ENGINE_NAMES)


@engines
@given(problems)
def test_theorem1_every_edge_between_l_and_2l(engine, problem):
    """Theorem 1: every edge of the output triangulation has length in [l, 2l] (up to REL_TOL)."""
    vertices, l = problem
    check_edge_lengths(equimesh.increment(vertices, l, engine=engine), l)


@engines
@given(problems)
def test_points_are_l_separated_and_cover_the_polygon(engine, problem):
    """Steps 3-4: output points are pairwise >= l apart, and every point of P is within l of one.

    Separation holds because a point is inserted only at distance >= l from
    all others; covering because insertion stops only when the farthest
    point of P is nearer than l.  Covering is checked at the Voronoi vertices
    inside P and at the crossings of Voronoi edges with the boundary.
    """
    vertices, l = problem
    mesh = equimesh.increment(vertices, l, engine=engine)
    check_separation(mesh, l)
    check_covering(mesh, vertices, l)


@engines
@given(problems)
def test_output_is_a_delaunay_triangulation_of_the_polygon(engine, problem):
    """Step 5: the output is a valid Delaunay triangulation of P covering its boundary.

    Areas sum to area(P), no triangle inverted or degenerate, circumcircles
    empty, every boundary segment and every vertex of P present.
    """
    vertices, l = problem
    check_triangulation(equimesh.increment(vertices, l, engine=engine), vertices, l)


@engines
@given(problems)
def test_same_input_gives_bit_identical_output(engine, problem):
    """Determinism: two runs on the same input give bit-identical points and triangles."""
    vertices, l = problem
    first, second = (
        equimesh.increment(vertices, l, engine=engine),
        equimesh.increment(vertices.copy(), l, engine=engine),
    )
    assert first.points.tobytes() == second.points.tobytes()
    assert np.array_equal(first.triangles, second.triangles)


@engines
@given(problems, st.sampled_from([-3, -2, -1, 1, 2, 3]))
def test_power_of_two_scaling_scales_the_mesh_exactly(engine, problem, k):
    """Scale invariance: scaling P and l by 2**k scales the output points exactly, same triangles.

    Multiplying by a power of two is exact in IEEE arithmetic, so any
    absolute tolerance hidden in the code would show up as a difference.
    Exact only while no intermediate result underflows: a coordinate such as
    1e-281 next to coordinates near 1 makes the degree-4 products inside
    Triangle's exact incircle predicate underflow, and a cocircular square
    is then split along different diagonals at different scales.  Such
    inputs (nonzero coordinates below 2^-60 l) are excluded here only.
    """
    vertices, l = problem
    tiny = (vertices != 0) & (np.abs(vertices) < 2.0**-60 * l)
    assume(not tiny.any())
    base = equimesh.increment(vertices, l, engine=engine)
    scaled = equimesh.increment(vertices * 2.0**k, l * 2.0**k, engine=engine)
    assert np.array_equal(scaled.points, base.points * 2.0**k)
    assert np.array_equal(scaled.triangles, base.triangles)


def _as_sets(mesh):
    points = [tuple(p) for p in mesh.points.tolist()]
    triangles = {frozenset(points[i] for i in t) for t in mesh.triangles.tolist()}
    return set(points), triangles


@engines
@given(problems)
def test_clockwise_input_gives_the_same_mesh(engine, problem):
    """Orientation is normalised: the clockwise input gives the same points and triangles.

    Only the reversed list is promised to match: starting the ring at another
    vertex renumbers the points, the circumcentres of tied candidates (equal
    up to rounding) then differ in their last bits, and the tie-break may pick
    another, equally valid, mesh.
    """
    vertices, l = problem
    ccw = equimesh.increment(vertices, l, engine=engine)
    cw = equimesh.increment(vertices[::-1], l, engine=engine)
    assert _as_sets(cw) == _as_sets(ccw)


#: Hand-picked inputs in units of l, each a known degeneracy of the algorithm.
REGRESSION_CASES = {
    # The polygon itself is the mesh: no insertion, diagonals sqrt(2) l.
    "unit square": rectangle(1.0, 1.0),
    # Edges 4l are split into parts of exactly 2l: boundary midpoints at exactly l.
    "square 4l": rectangle(4.0, 4.0),
    "square 20l": rectangle(20.0, 20.0),
    "square 2l": rectangle(2.0, 2.0),
    "regular octagon, edge l": regular_polygon(8, 1.0),
    "regular 12-gon, edge l": regular_polygon(12, 1.0),
    "square 2l rotated by 45 degrees": regular_polygon(4, 2.0, rotation=math.pi / 4),
    "long thin rectangle l x 40l": rectangle(1.0, 40.0),
    "long thin rectangle 2l x 40l": rectangle(2.0, 40.0),
    # Cocircular lattices: the boundary points lie on the integer (or even) lattice.
    "lattice rectangle 8l x 4l": rectangle(8.0, 4.0),
    "lattice square 6l": rectangle(6.0, 6.0),
    "lattice square 10l": rectangle(10.0, 10.0),
    "lattice rectangle 16l x 2l": rectangle(16.0, 2.0),
    # Collinear vertices (180 degree angles) at every lattice point of the boundary.
    "square 3l, every boundary lattice point a vertex": np.array(
        [[0, 0], [1, 0], [2, 0], [3, 0], [3, 1], [3, 2], [3, 3], [2, 3], [1, 3], [0, 3], [0, 2], [0, 1]], float
    ),
    # Near-cocircular: a circumcentre ~1e-9 l inside a boundary part of exactly 2l
    # (it was inserted, leaving a sliver of altitude 4e-9 l, before SLIVER_GAP).
    "rectangle 4l x (4 - 2^-12) l": rectangle(4.0, 4.0 - 2.0**-12),
    "rectangle 6l x (2 + 2^-12) l": rectangle(6.0, 2.0 + 2.0**-12),
    # Almost straight angle: 179.9 degrees at the vertex pushed out of the bottom edge.
    "rectangle with a 179.9 degree vertex": np.array(
        [[0.0, 0.0], [2.0, -2.0 * math.tan(math.radians(0.05))], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]]
    ),
}


@engines
@pytest.mark.parametrize("l", [1.0, 0.3])
@pytest.mark.parametrize("name", sorted(REGRESSION_CASES))
def test_regression_cases_satisfy_every_invariant(name, l, engine):
    """Every guarantee of INCREMENT (Theorems 1-2, separation, covering, Delaunay) on known degeneracies."""
    vertices = REGRESSION_CASES[name] * l
    assert_problem1_invariants(equimesh.increment(vertices, l, engine=engine), vertices, l)


def test_unit_square_needs_no_insertion():
    """A square of side l is already a valid mesh: the four corners and two triangles."""
    mesh = equimesh.increment(rectangle(1.0, 1.0), 1.0)
    assert mesh.n_nodes == 4 and len(mesh.triangles) == 2


# Fingerprints: node count and sum of the sorted edge lengths for fixed inputs.
# These are NOT theorems; the values were obtained by running the reference
# engine and pin its deterministic output (tie-breaking included) across
# refactors.  If a deliberate change of the algorithm alters them, update them
# and say so in the commit message.
FINGERPRINTS = [
    (rectangle(7.0, 5.0), 1.0, 31, 106.41828785908042),
    # 16 nodes before the local frame (docs/decisions.md, "The local frame"): a tie broken differently in the
    # last bit.
    (regular_polygon(9, 1.5, center=(3.0, -2.0), rotation=0.3), 1.0, 15, 45.21493876380816),
    (np.array([[0.0, 0.0], [9.0, 1.0], [10.5, 6.0], [6.0, 11.0], [-1.0, 8.0]]), 1.25, 48, 212.15458515151278),
]


@engines
@pytest.mark.parametrize("vertices, l, n_nodes, length_sum", FINGERPRINTS)
def test_fingerprint(vertices, l, n_nodes, length_sum, engine):
    """Regression pin (not a theorem): node count and summed edge length of fixed inputs."""
    mesh = equimesh.increment(vertices, l, engine=engine)
    assert mesh.n_nodes == n_nodes
    assert float(np.sum(np.sort(mesh.edge_lengths()))) == pytest.approx(length_sum, rel=1e-12)


#: Small polygons in units of l: a square whose sides split into parts of 2l, a rectangle, a convex pentagon.
CASES = {
    "square 4l": rectangle(4.0, 4.0),
    "rectangle 5l x 3l": rectangle(5.0, 3.0),
    "pentagon": np.array([[0.0, 0.0], [4.0, 0.0], [5.0, 2.5], [2.0, 4.5], [-1.0, 2.5]]),
}


@pytest.mark.parametrize("engine", sorted(ENGINES))
@pytest.mark.parametrize("name", sorted(CASES))
def test_every_invariant_and_the_point_order(name, engine):
    """Theorems 1-2 and the checks of tests/invariants.py; boundary points first, from vertex 0, counter-clockwise."""
    vertices = CASES[name] * 3.0
    mesh = equimesh.increment(vertices, 3.0, engine=engine)
    assert_problem1_invariants(mesh, vertices, 3.0)
    ring = mesh.points[: mesh.n_boundary]
    np.testing.assert_array_equal(ring[0], vertices[0])
    assert shapely.LinearRing(ring).is_ccw
    poly, l = validate_problem1(vertices, 3.0)
    assert mesh.info["n_inserted"] == mesh.n_nodes - len(resample_boundary(poly, l).points) > 0
    assert mesh.frame is not None and mesh.frame.scale == 0.5  # l = 3 scaled into [1, 2) by a power of two
    np.testing.assert_allclose(mesh.frame.to_caller(mesh.local_points), mesh.points, rtol=0, atol=1e-12)


def test_clockwise_input_is_reversed():
    """A clockwise polygon is reversed: the ring runs counter-clockwise from the caller's last vertex."""
    vertices = CASES["pentagon"][::-1]
    mesh = equimesh.increment(vertices, 1.0)
    np.testing.assert_array_equal(mesh.points[0], vertices[-1])
    assert shapely.LinearRing(mesh.points[: mesh.n_boundary]).is_ccw


def test_far_from_the_origin_the_vertices_are_the_callers_bits():
    """The local frame would round the vertices on the way back; they are pinned to the caller's coordinates."""
    vertices = CASES["pentagon"] * 1.1 + np.array([0.1, 0.7])
    poly, _ = validate_problem1(vertices, 1.0)
    assert not np.array_equal(poly.frame.to_caller(poly.local), vertices)  # the round trip alone would not do
    mesh = equimesh.increment(vertices, 1.0)
    found = {tuple(p) for p in mesh.points}
    assert all(tuple(v) in found for v in vertices)


@pytest.mark.parametrize(
    "vertices, l, error, message",
    [
        (
            np.array([[0, 0], [4, 0], [2, 1], [4, 4], [0, 4]], float),
            1.0,
            InvalidPolygonError,
            "polygon is not convex: reflex angle at vertex 2 at (2, 1)",
        ),
        (
            np.array([[0, 0], [4, 0], [0, 4]], float),
            1.0,
            InvalidPolygonError,
            "inner angle 45 degrees at vertex 1 at (4, 0) is below 90 degrees",
        ),
        (
            rectangle(4.0, 0.5),
            1.0,
            InvalidPolygonError,
            (
                "no mesh with every edge in [l, 2l] exists (both ends of a side are nodes, so some mesh edge on it is "
                "no "
                "longer than the side): edge (1, 2) has length 0.5, shorter than l = 1.0"
            ),
        ),
        (rectangle(4.0, 4.0), -1.0, InvalidLengthError, "target length l must be positive and finite, got -1.0"),
    ],
)
def test_input_outside_problem1_is_refused(vertices, l, error, message):
    """Problem 1 needs a convex polygon, inner angles >= 90 degrees, edges >= l, and a positive l."""
    with pytest.raises(error) as err:
        equimesh.increment(vertices, l)
    assert str(err.value) == message


@pytest.mark.parametrize("engine", sorted(ENGINES))
def test_default_size_guard_is_the_engines(engine, monkeypatch):
    """The default max_nodes is the engine's (MAX_NODES, made small here, so that a broken guard costs a small run):
    Oler's estimate of a square of side 6 l, 2/sqrt(3) 36 + 12 + 1 = 54.6 nodes, is over 50 and under 100."""
    monkeypatch.setitem(MAX_NODES, "reference", 50)
    monkeypatch.setitem(MAX_NODES, "fast", 100)
    vertices = rectangle(6.0, 6.0)
    if engine == "reference":
        with pytest.raises(MeshTooLargeError) as err:
            equimesh.increment(vertices, 1.0, engine=engine)
        assert str(err.value).startswith(
            "l = 1.0 would need about 54.6 nodes in the polygon, more than max_nodes = 50;"
        )
    else:
        assert equimesh.increment(vertices, 1.0, engine=engine).n_nodes > 0
        with pytest.raises(MeshTooLargeError, match="more than max_nodes = 10;"):
            equimesh.increment(vertices, 1.0, engine=engine, max_nodes=10)


def test_unknown_engine_is_refused_before_anything_else():
    with pytest.raises(EquimeshError, match="unknown insertion engine 'slow'"):
        equimesh.increment(np.zeros((1, 2)), -1.0, engine="slow")


def test_max_nodes_none_is_no_limit():
    """A square 2l with max_nodes=None: the four corners, then the centre (value sqrt(2) l), then the four
    side midpoints (value l), the boundary ones placed back on the ring."""
    mesh = equimesh.increment(rectangle(2.0, 2.0), 1.0, max_nodes=None)
    assert mesh.n_nodes == 9 and mesh.info["n_inserted"] == 5 and mesh.n_boundary == 8
    np.testing.assert_allclose(mesh.points[-1], [1.0, 1.0], atol=1e-12)


def test_the_engine_argument_chooses_the_engine(monkeypatch):
    """engine="reference" runs the reference engine (seen through a spy in ENGINES), once, at the local l."""
    calls = []
    reference = ENGINES["reference"]
    monkeypatch.setitem(ENGINES, "reference", lambda region, l: calls.append(l) or reference(region, l))
    mesh = equimesh.increment(CASES["square 4l"] * 3.0, 3.0, engine="reference")
    assert calls == [1.5] and mesh.n_nodes == 25
