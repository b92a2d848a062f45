"""The insertion engines (Steps 3-4 of Algorithm INCREMENT): the fast engine against the reference.

What must hold:

* on tie-free inputs (random polygons, generic rotation: no four cocircular
  points) both engines insert the same points in the same order, with the
  same values, bit for bit, and end with the same triangles;
* the inserted values never increase (the heap top is the farthest point);
* on degenerate inputs (squares, regular polygons, lattice strips, exact
  multiples of l) the fast engine satisfies every invariant of Problems 1
  and 2 and is deterministic;
* engine names: an unknown one is a clear error listing the engines, refused
  before any work, and validation does not depend on the engine.

The kernels are tested one by one in ``tests/planar/insertion/``.
"""

import invariants_uniform as inv
import numpy as np
import pytest
import strategies
import strategies_simple as ss
from hypothesis import given
from hypothesis import strategies as st
from insertion_cases import ENGINE_NAMES, assert_same_insertion, problem1_runs, problem2_runs, recorded
from invariants import assert_problem1_invariants, assert_values_non_increasing
from strategies import problems

import equimesh
import equimesh.planar.increment
import equimesh.planar.strip
from equimesh import EquimeshError
from equimesh.testing.generators import rectangle, regular_polygon, rotate

SQUARE10 = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])


@pytest.mark.parametrize("engine", ["nope", ["reference"], None, 1])
def test_unknown_engine_is_refused_before_any_work(engine):
    """Before: a list was a TypeError from the ENGINES lookup, after the lattice and boundary were built."""
    for verb in (equimesh.increment, equimesh.uniform_triangulation):
        with pytest.raises(EquimeshError, match=r"^unknown insertion engine .*; choose from \[.*'reference'"):
            verb(SQUARE10, 1e-3, engine=engine)  # checked before the size guard would refuse l = 1e-3


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
