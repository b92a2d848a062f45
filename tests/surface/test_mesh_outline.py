"""The outline of a triangle mesh (``surface/mesh_outline.py``): the corners of a boundary loop at the scale of l.

What must hold: the turn at the scale of l is a corner's angle between
straight sides and the chord angle of a circle; the corners kept are exactly
the turns above the feature angle, on loops drawn at any resolution; of two
corners closer than l one is dropped, and every turn of ``FIRM_TURN`` or more
lies within ``CORNER_DETAIL l`` of the ring, else the loop is refused as
narrower than l; an opening that the flattening closes is refused in the
surface's terms; a feature angle is degrees in [0, 180), for triangle meshes only.
"""

import math

import numpy as np
import pytest
import shapely
from conditions import exercised
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from refusals import assert_one_line
from repository import SURFACES
from triangle_meshes import tube

from equimesh import EquimeshError, InvalidSurfaceError, TriangulatedSurface, mesh_surface
from equimesh._geometry import inner_angle
from equimesh.io import load_surface
from equimesh.surface.mesh_outline import (
    CORNER_DETAIL,
    DEFAULT_FEATURE_ANGLE,
    FIRM_TURN,
    check_feature_angle,
    loop_corners,
    loop_ring,
    scale_turns,
)


class Refused(Exception):
    """What ``loop_ring`` raises here: its refusal's kind and details."""


def corners_of(xy, l, feature_angle=30.0):
    return loop_corners(np.asarray(xy, dtype=float), l, feature_angle)


def ring_of(xy, l, feature_angle=30.0):
    return loop_ring(np.asarray(xy, dtype=float), l, 1.5, feature_angle, Refused)


def densified(vertices, per_side, wiggle=0.0):
    """The closed polyline through ``vertices`` with ``per_side`` segments a side, its inner points moved by
    ``+-wiggle`` across the side in turn; the vertices' indices."""
    vertices = np.asarray(vertices, dtype=float)
    pieces = []
    for a, b in zip(vertices, np.roll(vertices, -1, axis=0)):
        t = np.arange(per_side)[:, None] / per_side
        normal = np.array([a[1] - b[1], b[0] - a[0]]) / np.linalg.norm(b - a)
        offset = wiggle * np.where(np.arange(per_side) % 2, 1.0, -1.0)
        offset[0] = 0.0
        pieces.append(a + t * (b - a) + offset[:, None] * normal)
    return np.vstack(pieces), np.arange(len(vertices)) * per_side


def test_turns_at_the_scale_of_l():
    """A square's corners turn by 90 (to the left counter-clockwise, to the right clockwise) and its sides' points
    by nothing; a fine circle of diameter D turns by 2 asin(l / 2D), its turn over stretches of l / 2; a loop that
    never gets l / 2 away turns by 180."""
    xy, corners = densified([(0, 0), (6, 0), (6, 6), (0, 6)], 24)
    turn = scale_turns(xy, 1.0)
    np.testing.assert_allclose(turn[corners], 90.0, atol=1e-9)
    np.testing.assert_allclose(scale_turns(xy[::-1], 1.0)[::-1][corners], -90.0, atol=1e-9)
    far = np.min(np.abs(np.arange(len(xy))[:, None] - np.r_[corners, len(xy)]), axis=1) >= 3  # 0.75 from a corner
    np.testing.assert_allclose(turn[far], 0.0, atol=1e-9)
    for diameter in (1.5, 3.0, 10.0):
        angle = 2.0 * np.pi * np.arange(2000) / 2000
        circle = 0.5 * diameter * np.column_stack([np.cos(angle), np.sin(angle)])
        expected = 2.0 * math.degrees(math.asin(0.5 / diameter))
        np.testing.assert_allclose(scale_turns(circle, 1.0), expected, rtol=1e-5)
    np.testing.assert_array_equal(scale_turns(circle * 0.01, 1.0), 180.0)


@pytest.mark.exercised("a polygon vertex turns by more than the feature angle", share=0.5)
@settings(max_examples=40, deadline=None)
@given(
    n=st.integers(3, 7),
    jitter=st.lists(st.floats(-0.2, 0.2), min_size=7, max_size=7),
    radii=st.lists(st.floats(4.0, 8.0), min_size=7, max_size=7),
    per_side=st.integers(1, 40),
    wiggle=st.floats(0.0, 0.005),
    feature_angle=st.floats(10.0, 170.0),
)
def test_corners_kept_are_exactly_the_turns_above_the_feature_angle(n, jitter, radii, per_side, wiggle, feature_angle):
    """A star-shaped polygon (sides over 2l) drawn with 1 to 40 segments a side, its sides' points moved across
    by up to 0.005 l: the corners are its vertices turning by more than the feature angle, or one vertex if none."""
    angle = 2.0 * np.pi * (np.arange(n) + np.array(jitter[:n])) / n
    polygon = np.array(radii[:n])[:, None] * np.column_stack([np.cos(angle), np.sin(angle)])
    turn = np.array([abs(180.0 - inner_angle(polygon, i)) for i in range(n)])
    assume(np.all(np.abs(turn - feature_angle) > 5.0))
    xy, vertex = densified(polygon, per_side, wiggle)
    corners = corners_of(xy, 1.0, feature_angle)
    sharp = vertex[turn > feature_angle]
    if exercised("a polygon vertex turns by more than the feature angle", len(sharp)):
        np.testing.assert_array_equal(corners, sharp)
    else:
        assert len(corners) == 1


def narrow_end(width, length=3.0):
    """The rim of a rectangular opening ``length`` by ``width`` (clockwise: the surface outside), 200 segments a side,
    the corners of its ends ``width`` apart."""
    return densified([(0, 0), (0, width), (length, width), (length, 0)], 200)[0]


def tongue(turn, end=0.8):
    """A 4 x 3.8 body with a tapered tongue 3 long whose tip, ``end`` wide, turns by ``turn`` degrees at its first
    corner (index 2) and by more at its second, 40 segments a side."""
    a = np.array([3.0, 0.0])
    heading = math.atan2(1.5, 3.0) + math.radians(turn)
    b = a + end * np.array([math.cos(heading), math.sin(heading)])
    return densified([(-4, -1.5), (0, -1.5), a, b, (0, b[1] + 1.5), (-4, b[1] + 1.5)], 40)


def assert_firm_turns_near_the_ring(xy, ring, l):
    firm = np.flatnonzero(np.abs(scale_turns(xy, l)) >= FIRM_TURN)
    assert np.all(shapely.distance(shapely.LinearRing(ring), shapely.points(xy[firm])) <= CORNER_DETAIL * l)


@pytest.mark.parametrize(
    "width, refused",
    # An end narrower than l / 2 turns most at its middle, one corner; from 0.71 l on at its two corners, of which
    # the ring keeps one.  The other corner, or both, lie 0.247 l from the ring at 0.5 and 0.294 l at 0.6.
    [(0.3, False), (0.5, False), (0.6, True), (0.8, True), (0.95, True), (0.99, True), (1.01, False)],
)
def test_narrow_ends_are_refused_and_details_dropped(width, refused):
    """The ends of a narrow rectangle: refused, naming a corner, when the ring of parts of at least l passes farther
    than CORNER_DETAIL l from one; else every turn of FIRM_TURN or more lies within it, one corner on each end."""
    xy = narrow_end(width)
    if refused:
        with pytest.raises(Refused) as info:
            ring_of(xy, 1.0)
        kind, i, gap = info.value.args
        assert kind == "cut" and gap > CORNER_DETAIL and i in (0, 200, 400, 600)
        return
    corners, ring = ring_of(xy, 1.0)
    assert_firm_turns_near_the_ring(xy, ring, 1.0)
    if width > 1:
        np.testing.assert_array_equal(corners, [0, 200, 400, 600])
    else:
        assert len(corners) == 2 and 0 <= corners[0] <= 200 and 400 <= corners[1] <= 600


@pytest.mark.parametrize("turn, refused", [(50.0, False), (59.0, False), (61.0, True), (70.0, False)])
def test_only_firm_turns_must_stay_near_the_ring(turn, refused):
    """A tongue's tip 0.8 l wide: the ring keeps its sharper corner; the other lies 0.28, 0.32, 0.33 l from the
    ring at 50, 59, 61 degrees, refused only from FIRM_TURN on; at 70 degrees it is the sharper one."""
    xy, vertex = tongue(turn)
    if refused:
        with pytest.raises(Refused) as info:
            ring_of(xy, 1.0)
        assert info.value.args[:2] == ("cut", vertex[2])
        return
    corners, ring = ring_of(xy, 1.0)
    assert sum(np.isin(vertex[2:4], corners)) == 1
    assert_firm_turns_near_the_ring(xy, ring, 1.0)


def test_a_chamfered_corner_is_one_corner():
    """Two 45-degree turns 0.1 l apart are one corner at the scale of l, between them (at the middle, where the
    loop turns by 90 degrees on both scales)."""
    xy, vertex = densified([(0, 0), (5, 0), (5.1, 0.1), (5.1, 5), (0, 5)], 50)
    corners = corners_of(xy, 1.0)
    assert len(corners) == 4 and np.count_nonzero((corners >= vertex[1]) & (corners <= vertex[2])) == 1


@pytest.mark.parametrize("bad", ["30", True, float("nan"), -1.0, 180.0, 1e9, 2 + 1j])
def test_feature_angle_is_degrees_in_0_180(bad):
    with pytest.raises(EquimeshError, match="feature_angle must be") as info:
        check_feature_angle(bad)
    assert_one_line(str(info.value))


def test_feature_angle_is_for_triangle_meshes():
    """A chart's corners are its rectangle's and its holes' vertices: a feature angle is refused, in one line."""
    with pytest.raises(EquimeshError, match="feature angle finds the corners of a triangle mesh") as info:
        mesh_surface(load_surface(SURFACES / "saddle.json"), 6.0, grid=(8, 8), optimize="none", feature_angle=30.0)
    assert_one_line(str(info.value))
    assert check_feature_angle(0) == 0.0 and check_feature_angle(np.float32(179.5)) == 179.5
    assert check_feature_angle(None) == DEFAULT_FEATURE_ANGLE and check_feature_angle(None, meshed=False) is None


def test_an_opening_the_flattening_closes_is_named_in_the_surfaces_terms():
    """An open cylinder (two rims of 62.8): eq. (1) squeezes one rim shut; the refusal names the opening in space,
    the rims' lengths on the surface and what to do, and with a strip of triangles cut out the tube meshes."""
    with pytest.raises(InvalidSurfaceError) as info:
        mesh_surface(TriangulatedSurface(*tube()), 2.0, optimize="none")
    message = str(info.value)
    assert_one_line(message)
    assert message.startswith("the opening through (10, 0, 10) closes up when the surface is flattened")
    assert "rim, 62.8031 long on the surface (the outer boundary 62.8031)" in message and "like a tube" in message
    assert "remove a strip of triangles from this opening to the outer boundary" in message
    mesh_surface(TriangulatedSurface(*tube(strip=1)), 2.0, optimize="none")
