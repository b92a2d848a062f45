"""Fuzzing the planar core with hostile simple polygons: stars, necks and spikes.

What must hold (the hardening contract): for every polygon and length, either
:func:`equimesh.uniform_triangulation` (Problem 2) refuses it with an error of
our own (an :class:`equimesh.EquimeshError`, one line), or it returns a mesh
that satisfies every guarantee of Problem 2 (``tests/invariants_uniform.py``:
Theorem 3, Lemma 3, covering, a valid constrained Delaunay triangulation of
P).  Nothing else: no wrong mesh, no exception from deep inside a library.
The same for :func:`equimesh.increment` (Problem 1) on convex inputs that may
break its preconditions.

The families are built from lists of numbers drawn by hypothesis (angles,
radii, widths), never from a drawn seed, so that a failure shrinks to a
smaller, simpler polygon.  They aim at the places where Lemma 3 (1) is hard to
check: narrow necks beside reflex corners, sharp tips, boundary points that
rounding puts a hair outside the polygon.  The number of examples follows the
hypothesis profile (``tests/conftest.py``): a few dozen per family in
``make test``, thousands in the thorough profile.  Placement (rotation,
translation, start vertex, scale by l) is the suite's one convention,
:func:`strategies.placed`.
"""

import math
import os

import invariants as inv1
import invariants_uniform as inv2
import numpy as np
import pytest
from conditions import exercised
from hypothesis import given, settings
from hypothesis import strategies as st
from invariants import check_edge_lengths
from strategies import placed

import equimesh
from equimesh import EquimeshError

#: Examples per family: quick in CI, thousands in the thorough profile.
EXAMPLES = {"thorough": 2000}.get(os.environ.get("EQUIMESH_HYPOTHESIS_PROFILE", "ci"), 30)

fuzz = settings(max_examples=EXAMPLES)

#: The conditions of the fuzz tests: a generated polygon is meshed (not refused).  The share of meshed inputs
#: each test asks for is a lower bound the code meets with room on both hypothesis profiles: refusing everything
#: fails.
PROBLEM2_MESHED = "Problem 2 meshed a hostile polygon"
PROBLEM1_MESHED = "Problem 1 meshed a convex hull"
STAR_MESHED = "Problem 2 meshed a reported star"


@st.composite
def stars(draw):
    """Star-shaped polygons: 3 to 8 vertices at increasing angles and radii 3 to 10 (units of l = 1)."""
    k = draw(st.integers(3, 8))
    gaps = np.array(draw(st.lists(st.floats(0.05, 1.0), min_size=k, max_size=k)))
    radii = np.array(draw(st.lists(st.floats(3.0, 10.0), min_size=k, max_size=k)))
    phase = draw(st.floats(0.0, 2.0 * math.pi))
    theta = phase + 2.0 * math.pi * np.cumsum(gaps) / gaps.sum()
    return radii[:, None] * np.column_stack([np.cos(theta), np.sin(theta)])


@st.composite
def necks(draw):
    """Two boxes joined by a corridor ``width`` wide (0.2 to 3) and ``length`` long, sheared by ``skew``."""
    a, b = draw(st.floats(2.0, 8.0)), draw(st.floats(2.0, 8.0))
    c, d = draw(st.floats(0.3, 6.0)), draw(st.floats(2.0, 8.0))
    e = draw(st.floats(2.0, 8.0))
    width = draw(st.floats(0.2, 3.0))
    room = min(b, e) - width
    if room <= 0.05:
        width = 0.5 * min(b, e)
        room = min(b, e) - width
    y0 = draw(st.floats(0.0, 1.0)) * room * 0.9 + 0.05 * room
    skew = draw(st.floats(-0.5, 0.5))
    ring = [
        (0.0, 0.0),
        (a, 0.0),
        (a, y0),
        (a + c, y0 + skew * c),
        (a + c, 0.0),
        (a + c + d, 0.0),
        (a + c + d, e),
        (a + c, e),
        (a + c, y0 + width + skew * c),
        (a, y0 + width),
        (a, b),
        (0.0, b),
    ]
    return np.array(ring)


@st.composite
def spikes(draw):
    """A box with one tip of angle 3 to 150 degrees and length 1 to 14 (the tip at the origin)."""
    tip = math.radians(draw(st.floats(3.0, 150.0)))
    r = draw(st.floats(1.0, 14.0))
    w, h = draw(st.floats(1.0, 10.0)), draw(st.floats(1.0, 10.0))
    h = max(h, r * math.sin(tip / 2) + 0.1)
    x = r * math.cos(tip / 2)
    return np.array([[0.0, 0.0], [x, -r * math.sin(tip / 2)], [x + w, -h], [x + w, h], [x, r * math.sin(tip / 2)]])


def _mesh_or_refusal(function, vertices, l):
    """Run ``function``; an error of ours is a fine answer (returns None), anything else propagates."""
    try:
        return function(vertices, l)
    except EquimeshError as exc:
        message = str(exc)
        assert message and "\n" not in message, f"error message is not one line: {message!r}"
        return None


@pytest.mark.parametrize(
    "family",
    [
        pytest.param(stars(), marks=pytest.mark.exercised(PROBLEM2_MESHED, share=0.5), id="stars"),
        pytest.param(necks(), marks=pytest.mark.exercised(PROBLEM2_MESHED, share=0.01), id="necks"),
        pytest.param(spikes(), marks=pytest.mark.exercised(PROBLEM2_MESHED, share=0.3), id="spikes"),
    ],
)
def test_problem2_accepts_only_what_it_can_mesh(family):
    """Every accepted hostile polygon gives a mesh with every Problem 2 guarantee; the rest are refused cleanly."""

    @fuzz
    @given(placed(family))
    def check(problem):
        vertices, l = problem
        mesh = _mesh_or_refusal(equimesh.uniform_triangulation, vertices, l)
        if exercised(PROBLEM2_MESHED, mesh is not None):
            inv2.assert_problem2_invariants(mesh, vertices, l)

    check()


@st.composite
def convex_hulls(draw):
    """Convex hulls of 4 to 10 points on a circle of radius 2 to 12: angles may be below 90, edges below l."""
    k = draw(st.integers(4, 10))
    gaps = np.array(draw(st.lists(st.floats(0.02, 1.0), min_size=k, max_size=k)))
    radius = draw(st.floats(2.0, 12.0))
    theta = 2.0 * math.pi * np.cumsum(gaps) / gaps.sum()
    return radius * np.column_stack([np.cos(theta), np.sin(theta)])


@pytest.mark.exercised(PROBLEM1_MESHED, share=0.05)
@fuzz
@given(placed(convex_hulls()))
def test_problem1_accepts_only_what_it_can_mesh(problem):
    """Problem 1 on convex polygons that may break its preconditions: a valid mesh or a clean refusal."""
    vertices, l = problem
    mesh = _mesh_or_refusal(equimesh.increment, vertices, l)
    if exercised(PROBLEM1_MESHED, mesh is not None):
        inv1.assert_problem1_invariants(mesh, vertices, l)


ISSUE_EXAMPLES = {
    "sliver triangle [[0, 0], [10, 0], [10, 2]]": [[0, 0], [10, 0], [10, 2]],
    "sliver triangle [[0, 0], [10, 0], [9, 1]]": [[0, 0], [10, 0], [9, 1]],
    "20-degree tip": (
        lambda h, r: [
            [0, 0],
            [r * math.cos(h), -r * math.sin(h)],
            [r + 6, -6],
            [r + 6, 6],
            [r * math.cos(h), r * math.sin(h)],
        ]
    )(math.radians(20) / 2, 12.0),
}


@pytest.mark.parametrize("vertices", list(ISSUE_EXAMPLES.values()), ids=list(ISSUE_EXAMPLES))
def test_reported_wrong_meshes_are_refused_or_valid(vertices):
    """The inputs that used to return edges of 0.2 l to 0.52 l: now a valid mesh or a clean refusal."""
    mesh = _mesh_or_refusal(equimesh.uniform_triangulation, np.array(vertices, dtype=float), 1.0)
    if mesh is not None:
        inv2.assert_problem2_invariants(mesh, np.array(vertices, dtype=float), 1.0)


@st.composite
def reported_stars(draw):
    """Star-shaped polygons: 3 to 8 vertices, radii 3 to 10, l = 1."""
    k = draw(st.integers(3, 8))
    gaps = np.array(draw(st.lists(st.floats(0.2, 1.0), min_size=k, max_size=k)))
    angles = 2.0 * np.pi * np.cumsum(gaps) / gaps.sum()
    radii = np.array(draw(st.lists(st.floats(3.0, 10.0), min_size=k, max_size=k)))
    return np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])


@pytest.mark.exercised(STAR_MESHED, share=0.5)
@given(reported_stars())
def test_random_stars_are_meshed_within_theorem3_or_refused(vertices):
    """Every accepted star polygon gives edges in [l, 2l]; every refused one a one-line error of ours."""
    mesh = _mesh_or_refusal(equimesh.uniform_triangulation, vertices, 1.0)
    if exercised(STAR_MESHED, mesh is not None):
        check_edge_lengths(mesh, 1.0)


#: Polygons with a corner that rounds to (nearly) 0 degrees, and the lattice placement they were meshed at.
NEAR_ZERO_CORNERS = {
    "corner rounding to exactly 0 degrees": (
        [
            [-4.752209060842619, -5.879333958263281],
            [-8.146644104301632, -11.758667916526562],
            [-6.109983078226224, -8.231067541568594],
            [-2.0366610260754086, -5.879333958263281],
        ],
        0.5,
        {},
    ),
    "corner of 2.5e-11 degrees": ([[-1.0, 3**0.5], [1e-12, 0.0], [0.5, 0.3], [1.0, -(3**0.5)]], 0.2, {}),
    "vertex within 2e-16 of the line of its neighbours": (
        [
            [-2.1341976277594195, 1.2321795748907614],
            [-2.220446049250313e-16, -2.4643591497815227],
            [0.7113992092531395, -2.0536326248179355],
            [2.134197627759419, -6.160897874453807],
        ],
        0.4742661395020932,
        {"angle": 0.0, "offset": (0.0, 0.0)},
    ),
}


@pytest.mark.parametrize("engine", ["fast", "reference"])
@pytest.mark.parametrize("case", list(NEAR_ZERO_CORNERS.values()), ids=list(NEAR_ZERO_CORNERS))
def test_corners_that_round_to_degenerate_are_refused(case, engine):
    """Each used to raise ZeroDivisionError, fail inside Triangle, or return triangles of sides (l, l, 2l)."""
    vertices, l, placement = case
    with pytest.raises(equimesh.InvalidPolygonError, match=r"^the corner at vertex \d .* sharper than [^\n]*$"):
        equimesh.uniform_triangulation(vertices, l, engine=engine, **placement)


@st.composite
def near_zero_corners(draw):
    """A triangle or a quadrilateral with a corner of 1e-17 to 1e-4 degrees at the origin, whole sides 3 to 12 (l = 1).

    The triangle's far side is 1 to 3 longer than its bottom side, the quadrilateral's tip 2 or more short of it:
    whole lengths, on which the staggering fits, so that Problem 2 meshes most corners of 1e-4 degrees.
    """
    angle = math.radians(10.0 ** -draw(st.sampled_from((4.0, 4.5, 5.0, 5.5, 6.5, 8.0, 10.0, 12.0, 14.0, 17.0))))
    far = draw(st.integers(5, 9))
    if draw(st.booleans()):
        side = far + draw(st.integers(1, 3))
        corners = [[0.0, 0.0], [far, 0.0]]
    else:
        side = draw(st.integers(3, far - 2))
        corners = [[0.0, 0.0], [far, 0.0], [far, draw(st.integers(2, 4))]]
    return np.array([*corners, [side * math.cos(angle), side * math.sin(angle)]], dtype=float)


@pytest.mark.exercised("fuzz: Problem 2 accepted a near-zero corner", share=0.2)
@fuzz
@given(near_zero_corners())
def test_near_zero_corners_are_refused_or_meshed_without_a_degenerate_triangle(vertices):
    """Refused in one line (always below MIN_CORNER_ANGLE), or a mesh with every guarantee and the quality floor."""
    mesh = _mesh_or_refusal(equimesh.uniform_triangulation, vertices, 1.0)
    if exercised("fuzz: Problem 2 accepted a near-zero corner", mesh is not None):
        inv2.assert_problem2_invariants(mesh, vertices, 1.0)


@pytest.mark.parametrize("degrees", [1e-4, 1e-5])
@pytest.mark.parametrize("shape", ["triangle", "quadrilateral"])
def test_a_corner_of_1e_5_degrees_is_meshed_without_a_degenerate_triangle(shape, degrees):
    """Above MIN_CORNER_ANGLE a near-zero corner is meshed, with every guarantee (verify_planar's floor included)."""
    a = math.radians(degrees)
    if shape == "triangle":
        vertices = np.array([[0.0, 0.0], [6.0, 0.0], [8.0 * math.cos(a), 8.0 * math.sin(a)]])
    else:
        vertices = np.array([[0.0, 0.0], [6.0, 0.0], [6.0, 3.0], [4.0 * math.cos(a), 4.0 * math.sin(a)]])
    inv2.assert_problem2_invariants(equimesh.uniform_triangulation(vertices, 1.0), vertices, 1.0)
