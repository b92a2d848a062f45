"""The insertion engines (Steps 3-4 of Algorithm INCREMENT): the fast engine against the reference.

What must hold:

* on tie-free inputs (random polygons, generic rotation: no four cocircular
  points) both engines insert the same points in the same order, with the
  same values, bit for bit, and end with the same triangles;
* the inserted values never increase (the heap top is the farthest point);
* on degenerate inputs (squares, regular polygons, lattice strips, exact
  multiples of l) the fast engine satisfies every invariant of Problems 1
  and 2 and is deterministic;
* engine names: an unknown one is a clear error listing the engines, and
  validation does not depend on the engine.

The predicates and the heap are tested in ``tests/test_fast_kernels.py``.
"""

from contextlib import contextmanager

import invariants_uniform as inv
import numpy as np
import pytest
import strategies
import strategies_simple as ss
from hypothesis import given
from hypothesis import strategies as st
from invariants import assert_problem1_invariants, assert_values_non_increasing
from strategies import problems

import equimesh
import equimesh.planar.increment
import equimesh.planar.strip
from equimesh import EquimeshError
from equimesh.planar.insertion import ENGINES, insert
from equimesh.planar.insertion.cdt import adjacency, cavity_boundary, locate
from equimesh.planar.insertion.region import constrained_delaunay
from equimesh.testing.generators import rectangle, regular_polygon, rotate

ENGINE_NAMES = sorted(ENGINES)

# --------------------------------------------------------------------------- recording the engine's output


@contextmanager
def recorded(module):
    """Record the :class:`Insertion` of every ``insert`` call made by ``module``."""
    runs = []

    def recording(region, l, engine):
        runs.append(insert(region, l, engine=engine))
        return runs[-1]

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(module, "insert", recording)
        yield runs


def problem1_runs(vertices, l):
    """``{engine: (mesh, insertion)}`` of Algorithm INCREMENT."""
    out = {}
    for name in ENGINE_NAMES:
        with recorded(equimesh.planar.increment) as runs:
            out[name] = equimesh.increment(vertices, l, engine=name), runs[0]
    return out


def problem2_runs(vertices, l, angle):
    """``{engine: (mesh, insertion)}`` of the Problem 2 pipeline."""
    out = {}
    for name in ENGINE_NAMES:
        with recorded(equimesh.planar.strip) as runs:
            out[name] = equimesh.uniform_triangulation(vertices, l, angle=angle, engine=name), runs[0]
    return out


def assert_same_insertion(runs):
    """Same points in the same order, same values, same constraints, same triangles (as sets), bit for bit."""
    (mesh_a, a), (mesh_b, b) = runs["reference"], runs["fast"]
    assert a.points.shape == b.points.shape, f"{len(a.points)} points against {len(b.points)}"
    assert a.points.tobytes() == b.points.tobytes(), "the engines inserted different points"
    assert a.values.tobytes() == b.values.tobytes(), "the engines report different values"
    assert a.segments.tolist() == b.segments.tolist()
    assert {tuple(sorted(t)) for t in a.triangles.tolist()} == {tuple(sorted(t)) for t in b.triangles.tolist()}
    assert mesh_a.points.tobytes() == mesh_b.points.tobytes()


# --------------------------------------------------------------------------- equivalence


@st.composite
def tie_free_convex(draw):
    """Random convex polygons (inner angles >= 90) at a generic rotation and l: no four cocircular points."""
    v = draw(strategies.random_polygons(max_area=150.0))
    l = draw(st.floats(0.3, 3.0))
    return rotate(v, draw(st.floats(0.01, 1.5))) * l + np.array(
        [draw(strategies.frame_coordinates), draw(strategies.frame_coordinates)]
    ), l


@given(tie_free_convex())
def test_problem1_engines_agree_bit_for_bit(problem):
    """Problem 1, tie-free input: the same points, order, values and triangles; values non-increasing."""
    runs = problem1_runs(*problem)
    assert_same_insertion(runs)
    for _, insertion in runs.values():
        assert_values_non_increasing(insertion)


@st.composite
def tie_free_simple(draw):
    """Simple polygons (:mod:`strategies_simple`) grown by 1% and every vertex moved by up to 1e-3 l.

    The families are built on grids and with symmetries (letters, stars,
    regular polygons), which put four boundary points exactly on a circle
    even after a rotation; the random moves break every such tie, and the
    1% growth keeps every edge and every gap above l.
    """
    vertices, l = draw(ss.cases(150.0))
    # A drawn seed, not drawn numbers, on purpose: the moves must stay generic, and
    # hypothesis would shrink drawn moves to zero, straight back to the ties.
    rng = np.random.default_rng(draw(strategies.seeds))
    return 1.01 * vertices + rng.uniform(-1e-3 * l, 1e-3 * l, vertices.shape), l


@given(tie_free_simple(), st.floats(1.0, 59.0))
def test_problem2_engines_agree_bit_for_bit(case, angle):
    """Problem 2, tie-free polygon, lattice at a generic angle: the same strip insertion; values non-increasing."""
    runs = problem2_runs(*case, angle)
    assert_same_insertion(runs)
    for _, insertion in runs.values():
        assert_values_non_increasing(insertion)


# --------------------------------------------------------------------------- degenerate inputs


@given(problems)
def test_problem1_fast_engine_invariants_and_determinism(problem):
    """Every Problem 1 invariant (squares, regular polygons, exact multiples of l included); deterministic."""
    vertices, l = problem
    with recorded(equimesh.planar.increment) as runs:
        mesh = equimesh.increment(vertices, l, engine="fast")
        again = equimesh.increment(vertices.copy(), l, engine="fast")
    assert_problem1_invariants(mesh, vertices, l)
    assert_values_non_increasing(runs[0])
    assert mesh.points.tobytes() == again.points.tobytes()
    assert np.array_equal(mesh.triangles, again.triangles)


@given(ss.cases(300.0), st.sampled_from([0.0, 30.0, 90.0]))
def test_problem2_fast_engine_invariants_and_determinism(case, angle):
    """Every Problem 2 invariant with the lattice aligned to the axes (cocircular everywhere); deterministic."""
    vertices, l = case
    with recorded(equimesh.planar.strip) as runs:
        mesh = equimesh.uniform_triangulation(vertices, l, angle=angle, engine="fast")
        again = equimesh.uniform_triangulation(vertices.copy(), l, angle=angle, engine="fast")
    inv.assert_problem2_invariants(mesh, vertices, l)
    assert_values_non_increasing(runs[0])
    assert mesh.points.tobytes() == again.points.tobytes()
    assert np.array_equal(mesh.triangles, again.triangles)


@pytest.mark.parametrize("engine", ENGINE_NAMES)
@pytest.mark.parametrize(
    "vertices",
    [rectangle(8.0, 8.0), rectangle(12.0, 2.0), rectangle(4.0, 4.0 - 2.0**-12), regular_polygon(12, 2.0)],
    ids=["square", "strip", "near-cocircular", "12-gon"],
)
def test_lattice_strips_and_regular_polygons(engine, vertices):
    """Exact multiples of l, axis-aligned lattice: both engines satisfy every invariant of both problems."""
    assert_problem1_invariants(equimesh.increment(vertices, 1.0, engine=engine), vertices, 1.0)
    big = vertices * 2.0
    inv.assert_problem2_invariants(equimesh.uniform_triangulation(big, 1.0, engine=engine), big, 1.0)


# --------------------------------------------------------------------------- names and bad input


def test_unknown_engine_is_a_clear_error():
    with pytest.raises(EquimeshError, match=r"unknown insertion engine 'quick'; choose from \['fast', 'reference'\]"):
        equimesh.increment(rectangle(3.0, 3.0), 1.0, engine="quick")


@pytest.mark.parametrize(
    "call",
    [
        lambda e: equimesh.increment([[0, 0], [3, 0], [0, 3]], 1.0, engine=e),
        lambda e: equimesh.increment(rectangle(3.0, 0.5), 1.0, engine=e),
        lambda e: equimesh.uniform_triangulation(rectangle(3.0, 3.0), -1.0, engine=e),
    ],
    ids=["acute", "short-edge", "negative-l"],
)
def test_validation_does_not_depend_on_the_engine(call):
    messages = set()
    for name in ENGINE_NAMES:
        with pytest.raises(EquimeshError) as info:
            call(name)
        messages.add((type(info.value), str(info.value)))
    assert len(messages) == 1, messages


def test_cavity_boundary_fills_its_buffer_exactly():
    """A cavity of k triangles has k + 2 boundary edges: a buffer of exactly that length suffices.

    Regression: an interior edge visited after the last boundary edge was
    refused as "buffer full", and a cavity of 64 triangles (the initial
    buffer) broke the run (random convex polygons of ~6,800 l^2).
    """
    V = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.int64)
    N = np.array([[-1, -1, 1], [0, -1, -1]], dtype=np.int64)
    S = np.full((2, 3), -1, dtype=np.int64)
    mark = np.ones(2, dtype=np.int64)
    edges = np.empty((4, 4), dtype=np.int64)
    # Triangle 1 first, so the last edge visited (2, 0) of triangle 0 is interior.
    assert cavity_boundary(V, N, S, np.array([1, 0]), 2, -1, mark, 1, edges) == 4
    assert {tuple(e[:2]) for e in edges.tolist()} == {(2, 3), (3, 0), (0, 1), (1, 2)}


@given(st.integers(3, 7), st.integers(3, 7), st.data())
def test_local_locate_gives_the_lowest_slot_like_the_scan(nx, ny, data):
    """The local walk of :func:`_cdt.locate` answers what scanning every slot answers.

    On a lattice (cocircular everywhere) and for query points at vertices,
    edge midpoints and inside triangles; ``max_steps=0`` forces the scan.
    """
    xy = np.array([[x, y] for y in range(ny) for x in range(nx)], dtype=float)
    ring = [i for i in range(nx)] + [i * nx + nx - 1 for i in range(1, ny)]
    ring += [(ny - 1) * nx + i for i in range(nx - 2, -1, -1)] + [i * nx for i in range(ny - 2, 0, -1)]
    segments = np.array([[ring[i], ring[(i + 1) % len(ring)]] for i in range(len(ring))], dtype=np.int64)
    V = constrained_delaunay(xy, segments, np.empty((0, 2)))
    N, _, _ = adjacency(V, segments[:, 0].copy(), segments[:, 1].copy(), len(xy))
    alive = np.ones(len(V), dtype=np.bool_)
    t = data.draw(st.integers(0, len(V) - 1))
    weights = np.array(data.draw(st.sampled_from([(1, 0, 0), (1, 1, 0), (0, 1, 1), (1, 1, 1), (2, 1, 1)])), dtype=float)
    x, y = (weights @ xy[V[data.draw(st.integers(0, len(V) - 1))]]) / weights.sum()
    scan = locate(xy, V, N, alive, len(V), t, x, y, 0)
    assert scan >= 0
    assert locate(xy, V, N, alive, len(V), t, x, y, len(V) + 1) == scan
