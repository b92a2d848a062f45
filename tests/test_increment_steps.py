"""Algorithm INCREMENT (Problem 1, ``planar/increment.py``): its steps and its input checks, on small polygons.

What must hold: the input of Problem 1 is a convex polygon with inner angles
of at least 90 degrees and edges of at least l (anything else is refused with
one line naming the vertex or edge); the output satisfies Theorems 1-2 and
every check of ``tests/invariants.py``; its points are the Step 2 boundary
points first (counter-clockwise from the caller's vertex 0, the caller's
vertices bit for bit) and then the inserted points, whose number ``info``
reports; the size guard refuses, before any work, what the engine's default
cannot afford.  Each case runs in well under a second, so that the mutants of
``increment.py`` (``make mutation``) are cheap to kill.
"""

import numpy as np
import pytest
import shapely
from invariants import assert_problem1_invariants

import equimesh
from equimesh import EquimeshError, InvalidLengthError, InvalidPolygonError, MeshTooLargeError
from equimesh.planar.boundary.resample import resample_boundary
from equimesh.planar.increment import validate_problem1
from equimesh.planar.insertion import ENGINES
from equimesh.planar.limits import MAX_NODES
from equimesh.testing.generators import rectangle

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
                "no mesh with every edge in [l, 2l] exists (both ends of a side are nodes, so some mesh edge on it is no "
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
