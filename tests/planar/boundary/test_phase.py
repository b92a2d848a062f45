"""Step 2 in phase with the lattice (``planar/boundary/phase.py``, beyond the paper): a strip that repeats.

What must hold: on a straight side along a lattice direction the points lie a lattice period apart, half a period from
the first row's, so every member from a point inside the side to the row has one length; across a lattice direction
(period sqrt(3) l) two; the end parts lie in [SHORTEST_END l, sqrt(3) l]; a side that is curved, oblique to the
lattice or next to a corner sharper than 60 degrees keeps the paper's points, as does a boundary that would fail
Lemma 3 (1); Problem 2's guarantees hold throughout (``verify_planar`` runs on every mesh).
"""

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from equimesh import uniform_triangulation
from equimesh.classes import length_classes
from equimesh.errors import EquimeshError, InvalidPolygonError
from equimesh.planar.boundary import phase
from equimesh.planar.boundary.phase import LONGEST_PART, SHORTEST_END, _end, in_phase
from equimesh.planar.boundary.resample import resample_boundary
from equimesh.planar.lattice import lattice_part
from equimesh.planar.polygon import as_polygon
from equimesh.planar.strip import BOUNDARY_SPACING

SQRT3 = math.sqrt(3.0)


def rectangle(width, height):
    return np.array([(0.0, 0.0), (width, 0.0), (width, height), (0.0, height)])


def side_points(mesh, axis, value):
    """Indices of the boundary points on the side where coordinate ``axis`` is ``value``, sorted along it."""
    pts = mesh.points[: mesh.n_boundary]
    on = np.flatnonzero(np.abs(pts[:, axis] - value) <= 1e-9)
    return on[np.argsort(pts[on, 1 - axis])]


def inner_member_lengths(mesh, side, period):
    """Lengths of the members to nodes off the boundary from the side's points whose both neighbours on it lie
    ``period`` away, at least 3 l from its ends (nearer, the strip meets the next side's)."""
    pts = mesh.points
    step = np.linalg.norm(np.diff(pts[side], axis=0), axis=1)
    ends = pts[side[[0, -1]]]
    regular = [
        side[k]
        for k in range(1, len(side) - 1)
        if all(abs(step[j] - period) <= 1e-9 for j in (k - 1, k))
        and np.linalg.norm(ends - pts[side[k]], axis=1).min() >= 3.0
    ]
    edges = mesh.edges
    lengths = []
    for p in regular:
        other = np.where(edges[:, 0] == p, edges[:, 1], np.where(edges[:, 1] == p, edges[:, 0], -1))
        other = other[other >= mesh.n_boundary]
        lengths += list(np.linalg.norm(pts[other] - pts[p], axis=1))
    return np.array(lengths)


def distinct(values, tol=1e-9):
    values = np.sort(values)
    return 0 if not len(values) else 1 + int(np.count_nonzero(np.diff(values) > tol))


@settings(max_examples=25, deadline=None)
@given(
    width=st.floats(6.0, 20.0),
    height=st.floats(6.0, 20.0),
    fi=st.floats(0.0, 1.0),
    fj=st.floats(0.0, 1.0),
    l=st.sampled_from([0.4, 1.0, 3.0]),
)
def test_sides_along_and_across_the_lattice_repeat(width, height, fi, fj, l):
    """Angle 0 on a rectangle (sides in units of l): the bottom and top sides run along the lattice (one member
    length from their inner points to the first row), the left and right across it (two); the end parts are in
    [SHORTEST_END, sqrt 3] l."""
    offset = l * (fi * np.array([1.0, 0.0]) + fj * np.array([0.5, SQRT3 / 2]))
    mesh = uniform_triangulation(l * rectangle(width, height), l, offset=offset, boundary="lattice")
    assert mesh.info["boundary"] == "lattice"
    mesh = replace(mesh, points=mesh.points / l)  # in units of l
    for axis, value, period, lengths in (
        (1, 0.0, 1.0, 1),
        (1, height, 1.0, 1),
        (0, 0.0, SQRT3, 2),
        (0, width, SQRT3, 2),
    ):
        side = side_points(mesh, axis, value)
        steps = np.diff(mesh.points[side][:, 1 - axis])
        inner = np.abs(steps - period) <= 1e-9
        assert np.all(inner | ((steps >= SHORTEST_END - 1e-9) & (steps <= LONGEST_PART + 1e-9)))
        members = inner_member_lengths(mesh, side, period)
        assert distinct(members) <= lengths
        assert members.size or (height if axis == 0 else width) < 10.0  # a long side has regular points


def phased_boundary(vertices, l, angle=0.0, offset=(0.0, 0.0)):
    """The paper's Step 2 points of ``vertices`` and the same in phase with the lattice (the polygon, both
    boundaries), as Problem 2 computes them."""
    poly = as_polygon(vertices, l, None)
    boundary = resample_boundary(poly, l, BOUNDARY_SPACING)
    lattice = lattice_part(poly, l, angle, offset, 1.0)
    return poly, boundary, in_phase(poly, boundary, lattice, angle, l)


def check_on_their_edges(poly, boundary):
    """Every point lies on the polygon edge ``edge`` names, and is a vertex exactly where ``is_vertex`` says."""
    v = poly.local
    a, b = v[boundary.edge], np.roll(v, -1, axis=0)[boundary.edge]
    t = np.sum((boundary.points - a) * (b - a), axis=1) / np.sum((b - a) ** 2, axis=1)
    assert np.all((t >= -1e-12) & (t <= 1.0 + 1e-12))  # a point on an inner vertex of its side, up to rounding
    np.testing.assert_allclose(a + t[:, None] * (b - a), boundary.points, atol=1e-9)
    np.testing.assert_array_equal(np.all(boundary.points == a, axis=1), boundary.is_vertex)


@pytest.mark.parametrize("l, angle", [(1.0, 0.0), (3.0, 0.0), (1.0, 30.0)])
def test_vertices_along_a_side_move_with_its_points(l, angle):
    """A rectangle whose sides carry vertices of their own (a resampled outline), turned with the lattice: the same
    points as the plain rectangle, each on the edge its ``edge`` names, a vertex only where it is one."""
    w, h = 16.0 * l, 13.0 * l
    plain = rectangle(w, h)
    subdivided = np.array(
        [(0, 0), (2.5 * l, 0), (7 * l, 0), (w, 0), (w, 4 * l), (w, h), (9 * l, h), (0, h), (0, 6.5 * l)],
        dtype=float,
    )
    turn = math.radians(angle)
    rotation = np.array([[math.cos(turn), math.sin(turn)], [-math.sin(turn), math.cos(turn)]])
    _, _, reference = phased_boundary(plain @ rotation, l, angle)
    poly, equal, phased = phased_boundary(subdivided @ rotation, l, angle)
    assert phased is not equal
    np.testing.assert_allclose(phased.points, reference.points, atol=1e-9 * l)
    check_on_their_edges(poly, phased)


def test_a_side_through_vertex_0_is_two_sides():
    """Vertex 0 inside a side ends a side: the rest of the ring is phased, the point at vertex 0 kept."""
    l = 1.0
    ring = np.array([(8.0, 0.0), (16.0, 0.0), (16.0, 13.0), (0.0, 13.0), (0.0, 0.0)])
    poly, _, phased = phased_boundary(ring, l)
    check_on_their_edges(poly, phased)
    assert phased.is_vertex[0] and np.array_equal(phased.points[0], poly.local[0])
    steps = np.linalg.norm(np.diff(np.vstack([phased.points, phased.points[:1]]), axis=0), axis=1)
    assert steps.min() >= 1.0 - 1e-9 and steps.max() <= 2.0


def middle_offset(poly, phased, lattice, edge, lp):
    """How far the boundary point nearest the middle of the side starting at polygon vertex ``edge`` lies from half
    a period (l) past the point of the side's own first row (the lattice points over it, nearest to it) nearest
    that middle."""
    v = poly.local
    a, b = v[edge], v[(edge + 1) % len(v)]
    length = float(np.linalg.norm(b - a))
    d = (b - a) / length
    normal = np.array([-d[1], d[0]])
    rows = lattice.points[lattice.boundary_vertices]
    s, h = (rows - a) @ d, (rows - a) @ normal
    over = (s > 0) & (s < length) & (h > 0)
    s, h = s[over], h[over]
    row = s[h <= h.min() + 0.25 * lp]
    reference = row[np.argmin(np.abs(row - length / 2))]
    along = (phased.points[phased.edge == edge] - a) @ d
    return float(np.min(np.abs(along - (reference + 0.5 * lp))))


@pytest.mark.parametrize("l", [1.0, 3.0])
@pytest.mark.parametrize("shift", [0.0, 0.25, 0.5])
def test_the_phase_is_taken_at_the_middle_of_a_side(l, shift):
    """A rectangle half a degree off the lattice still counts as along it: the boundary point nearest the middle of
    its bottom side lies half a period from the first row's point nearest that middle (not the next row's, half a
    period along, whichever lies nearer the middle)."""
    turn = math.radians(0.5)
    rotation = np.array([[math.cos(turn), math.sin(turn)], [-math.sin(turn), math.cos(turn)]])
    offset = (shift * l, 0.0)
    poly, _, phased = phased_boundary(l * rectangle(17.0, 12.0) @ rotation, l, offset=offset)
    lattice = lattice_part(poly, l, 0.0, offset, 1.0)
    assert middle_offset(poly, phased, lattice, 0, poly.local_length(l)) <= 1e-9


def test_a_side_whose_line_runs_on_inside_takes_its_own_rows_phase():
    """An L: the side from (20, 8) to (10, 8) ends at a reflex corner, beyond which its line runs on through the
    polygon, with lattice points just under it; its phase is that of the row over the side itself."""
    l = 1.0
    ell = np.array([(0.0, 0.0), (20.0, 0.0), (20.0, 8.0), (10.0, 8.0), (10.0, 16.0), (0.0, 16.0)])
    for shift in (0.0, 0.3, 0.6):
        poly, _, phased = phased_boundary(ell, l, offset=(0.0, shift))
        lattice = lattice_part(poly, l, 0.0, (0.0, shift), 1.0)
        assert middle_offset(poly, phased, lattice, 2, poly.local_length(l)) <= 1e-9


@pytest.mark.parametrize("lp", [1.0, 1.5])
def test_the_ends_of_a_side(lp):
    """``_end``: a target closer to the end than SHORTEST_END l goes, as does one leaving a part between sqrt(3) l
    and 2 SHORTEST_END l; a longer gap is split into equal parts of at most sqrt(3) l."""
    assert _end([0.5 * lp, 1.5 * lp, 2.5 * lp], lp) == ([1.5 * lp, 2.5 * lp], [])
    assert _end([1.8 * lp, 2.8 * lp], lp) == ([2.8 * lp], [1.4 * lp])
    assert _end([1.04 * lp, 2.04 * lp, 3.04 * lp], lp) == ([3.04 * lp], [1.52 * lp])  # 2.04 l < 2.1 l: one more
    targets, points = _end([3.6 * lp], lp)
    assert targets == [3.6 * lp] and np.allclose(points, [1.2 * lp, 2.4 * lp])
    assert _end([1.2 * lp], lp) == ([1.2 * lp], [])
    assert _end([], lp) == ([], [])
    assert _end([SHORTEST_END * lp], lp) == ([SHORTEST_END * lp], [])  # the bounds themselves are kept
    assert _end([LONGEST_PART * lp], lp) == ([LONGEST_PART * lp], [])
    assert _end([2.0 * SHORTEST_END * lp], lp) == ([2.0 * SHORTEST_END * lp], [SHORTEST_END * lp])


def test_a_rectangle_along_the_lattice_has_few_classes():
    """The strip repeating is what cuts the classes: 16 x 19.3 l at angle 0, the offsets of one cell in thirds."""
    cell = np.array([[1.0, 0.0], [0.5, SQRT3 / 2]])
    counts = {}
    for boundary in ("equal", "lattice"):
        counts[boundary] = min(
            len(length_classes(mesh.edge_lengths(), 1.0, 0.005))
            for fi in range(3)
            for fj in range(3)
            for mesh in [
                uniform_triangulation(
                    rectangle(16.0, 19.3), 1.0, offset=np.array([fi, fj]) / 3 @ cell, boundary=boundary
                )
            ]
        )
    assert counts["lattice"] <= counts["equal"] / 2


@pytest.mark.parametrize(
    "vertices",
    [
        rectangle(12.0, 9.0) @ np.array([[math.cos(0.3), math.sin(0.3)], [-math.sin(0.3), math.cos(0.3)]]),
        np.array([(0.0, 0.0), (14.0, 0.0), (7.0, 7.0 * math.tan(math.radians(50.0)))]),
    ],
    ids=["oblique to the lattice", "corners of 50 degrees"],
)
def test_sides_that_do_not_qualify_keep_the_papers_points(vertices):
    equal = uniform_triangulation(vertices, 1.0)
    phased = uniform_triangulation(vertices, 1.0, boundary="lattice")
    assert phased.info["boundary"] == "equal"
    np.testing.assert_array_equal(phased.points, equal.points)
    np.testing.assert_array_equal(phased.triangles, equal.triangles)


def test_a_bent_side_keeps_the_papers_points_and_the_straight_ones_move():
    vertices = np.array([(0.0, 0.0), (6.0, 0.5), (12.0, 0.0), (12.0, 9.0), (0.0, 9.0)])
    equal = uniform_triangulation(vertices, 1.0)
    phased = uniform_triangulation(vertices, 1.0, boundary="lattice")
    assert phased.info["boundary"] == "lattice"
    bottom = [m.points[: m.n_boundary][m.points[: m.n_boundary, 1] <= 0.5] for m in (equal, phased)]
    np.testing.assert_array_equal(*bottom)
    top = [m.points[: m.n_boundary][m.points[: m.n_boundary, 1] == 9.0] for m in (equal, phased)]
    assert not np.array_equal(*top)


def test_a_boundary_failing_lemma_3_gives_way_to_the_papers(monkeypatch):
    def refuse(poly, boundary, l):
        raise InvalidPolygonError("two boundary points closer than l")

    monkeypatch.setattr(phase, "check_boundary_separation", refuse)
    equal = uniform_triangulation(rectangle(12.0, 9.0), 1.0)
    phased = uniform_triangulation(rectangle(12.0, 9.0), 1.0, boundary="lattice")
    assert phased.info["boundary"] == "equal"
    np.testing.assert_array_equal(phased.points, equal.points)


def test_an_unknown_boundary_is_refused_by_name():
    with pytest.raises(EquimeshError, match="boundary must be one of"):
        uniform_triangulation(rectangle(12.0, 9.0), 1.0, boundary="periodic")


def test_the_phase_turns_with_the_lattice_by_its_symmetry():
    """The lattice at angle 0 through the origin is its own image turned by 120 degrees about the origin: the
    phased points of a rectangle so turned (sides at 120 and 210 degrees, along and across e2 - e1) are those of
    the rectangle, turned."""
    turn = math.radians(120.0)
    rotation = np.array([[math.cos(turn), math.sin(turn)], [-math.sin(turn), math.cos(turn)]])
    rect = rectangle(16.0, 11.0) + np.array([2.3, 1.7])
    plain_poly, _, plain = phased_boundary(rect, 1.0)
    turned_poly, equal, turned = phased_boundary(rect @ rotation, 1.0)
    assert turned is not equal
    expected = plain_poly.frame.to_caller(plain.points) @ rotation
    got = turned_poly.frame.to_caller(turned.points)
    np.testing.assert_allclose(np.sort(np.round(got, 9), axis=0), np.sort(np.round(expected, 9), axis=0), atol=1e-8)
