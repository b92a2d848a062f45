"""The row-by-row lattice clearance of Problem 2 (``planar/clearance.py``), tested directly.

What must hold (Lemma 3 (1)): ``clear_of_boundary`` keeps a lattice vertex
exactly when it lies inside P and ``at_least(d(x, boundary), distance)``, the
per-vertex test with shapely, on ANY window of the lattice: a window cut
through P (boundary crossings left and right of it, segments above and below
it), not only the grid over P's bounding box that ``lattice.kept_vertices``
passes, and on that grid for generated polygons; at distances a hair either
side of the threshold and of the band's reach; with horizontal and nearly
horizontal boundary segments, without a numpy warning (warnings are errors in
this file).  Each test runs in milliseconds, so that the mutants of
``clearance.py`` (``make mutation``) are cheap to kill.
"""

import numpy as np
import pytest
import shapely
import strategies_simple as ss
from hypothesis import given
from hypothesis import strategies as st

import equimesh
from equimesh.planar import lattice
from equimesh.planar.clearance import DOUBT, clear_of_boundary, expand
from equimesh.planar.lattice import kept_vertices
from equimesh.planar.polygon import as_polygon
from equimesh.testing.generators import rectangle, regular_polygon
from equimesh.tolerance import REL_TOL, at_least

pytestmark = pytest.mark.filterwarnings("error")

SQUARE = np.array([[0.0, 0.0], [6.0, 0.0], [6.0, 6.0], [0.0, 6.0]])


HOLE = np.array([[2.5, 2.5], [3.5, 2.5], [3.5, 3.5], [2.5, 3.5]])


#: Two rooms joined by a corridor 1.5 wide; a slanted triangle (no side along a lattice row at angle 0).
DUMBBELL = np.array(
    [[0, 0], [6, 0], [6, 2], [9, 2], [9, 0], [15, 0], [15, 6], [9, 6], [9, 3.5], [6, 3.5], [6, 6], [0, 6]], float
)


TRIANGLE = np.array([[0.0, 0.3], [9.0, 1.7], [2.2, 8.1]])


POLYGONS = {
    "square with a hole": (SQUARE * 2.0, [HOLE * 2.0]),
    "dumbbell": (DUMBBELL, None),
    "triangle": (TRIANGLE, None),
}


def per_vertex(shape, points, distance):
    """The oracle: inside ``shape`` and at least ``distance`` from its boundary, one vertex at a time with shapely."""
    inside = shapely.contains_xy(shape, points[:, 0], points[:, 1])
    return inside & at_least(shapely.distance(shapely.points(points), shape.boundary), distance)


def window(first, grid_shape, l, angle, offset):
    """Index grid ``first + (a, b)`` over ``grid_shape``, row major, and its lattice points."""
    ii, jj = np.meshgrid(np.arange(grid_shape[0]) + first[0], np.arange(grid_shape[1]) + first[1], indexing="ij")
    return lattice.lattice_points(np.column_stack([ii.ravel(), jj.ravel()]), l, angle, offset)


def check_window(shape, first, grid_shape, l, angle, offset, distance):
    """``clear_of_boundary`` on one window agrees with the oracle on every vertex of it."""
    points = window(first, grid_shape, l, angle, offset)
    basis = lattice.lattice_basis(l, angle)
    kept = clear_of_boundary(shape, points, first, grid_shape, np.asarray(offset, float), basis, distance)
    assert kept.shape == tuple(grid_shape)
    assert np.array_equal(kept.ravel(), per_vertex(shape, points, distance))


def test_expand_by_hand():
    """One row per integer of each range; an empty range (lo > hi) gives none."""
    owner, value = expand(np.array([0, 5, 3, 7]), np.array([2, 4, 3, 5]))
    assert owner.tolist() == [0, 0, 0, 2] and value.tolist() == [0, 1, 2, 3]


@pytest.mark.parametrize("name", sorted(POLYGONS))
@given(
    angle=st.floats(0.0, 60.0),
    frac=st.tuples(st.floats(0.0, 1.0), st.floats(0.0, 1.0)),
    clearance=st.sampled_from([0.3, 1.0, 2.0]),
    cut=st.tuples(*[st.floats(0.0, 1.0)] * 4),
)
def test_any_window_keeps_the_vertices_inside_at_clearance(name, angle, frac, clearance, cut):
    """A window of the grid over P (cut by fractions of its size; P's boundary crosses it on every side) is decided
    vertex by vertex as shapely decides, whatever lies outside the window; clearance 0.3 keeps vertices one lattice
    step from the boundary, where a crossing counted one column off would show."""
    vertices, holes = POLYGONS[name]
    poly = as_polygon(vertices, 1.0, holes)
    offset = lattice.local_offset(poly, 1.0, angle, np.asarray(frac) @ lattice.lattice_basis(1.0, angle))
    ii, jj, _, _ = lattice.kept_vertices(poly, 1.0, angle, offset, clearance)
    ni, nj = ii.shape
    a, b = int(cut[0] * (ni - 1)), int(cut[1] * (nj - 1))
    size = (1 + int(cut[2] * (ni - 1 - a)), 1 + int(cut[3] * (nj - 1 - b)))
    check_window(poly.region, (int(ii.min()) + a, int(jj.min()) + b), size, 1.0, angle, offset, clearance)


def test_windows_cut_through_the_middle():
    """Fixed windows of the square with a hole at angle 0 (whose sides lie on lattice rows): the middle rows,
    the middle columns, one vertex inside, a window above and one right of P, and the grid over P."""
    poly = as_polygon(SQUARE * 2.0, 1.0, [HOLE * 2.0])
    for first, size in [
        ((-4, 3), (20, 4)),
        ((4, -2), (3, 18)),
        ((3, 2), (1, 1)),
        ((-3, 16), (12, 3)),
        ((14, 0), (5, 10)),
        ((-8, -2), (24, 18)),
    ]:
        for clearance in (0.3, 1.0, 2.0):
            check_window(poly.region, first, size, 1.0, 0.0, (0.0, 0.0), clearance)


@pytest.mark.parametrize("side", ["below", "left"])
@pytest.mark.parametrize("excess", [-3e-7, -1.5e-7, -1e-7, -2e-9, -1e-9, 0.0, 1e-9, 1e-7, 1.5e-7, 3e-7])
def test_a_vertex_a_hair_either_side_of_the_threshold_and_the_reach(side, excess):
    """The vertex (0, 0) at (1 + excess) d from a side below it (a lattice row) or left of it (across the rows):
    kept exactly when at_least says so (threshold (1 - REL_TOL) d), also in the doubtful window (DOUBT = 1e-7) and
    just inside the band's reach (1 + 2 DOUBT) d, where a narrower band would miss the side."""
    d = 1.7
    gap = (1.0 + excess) * d
    far = 40.0
    if side == "below":
        shape = shapely.Polygon([(-32.0, -gap), (32.0, -gap), (32.0, far), (-32.0, far)])
    else:
        shape = shapely.Polygon([(-gap, -32.0), (far, -32.0), (far, 32.0), (-gap, 32.0)])
    assert shapely.distance(shapely.Point(0.0, 0.0), shape.boundary) == pytest.approx(gap, rel=1e-15)
    check_window(shape, (-3, -3), (7, 7), 1.0, 0.0, (0.0, 0.0), d)
    assert per_vertex(shape, np.zeros((1, 2)), d)[0] == (excess >= -REL_TOL)


def test_a_vertex_just_past_the_doubtful_window_is_kept():
    """At d = 0.9702748543934043 the distance near = (1 - REL_TOL) d (1 + DOUBT), rounded, lies outside the window
    |near - threshold| <= DOUBT threshold by one rounding; the band decides it, and it is kept as at_least keeps it
    (a band test 'near > threshold (1 + DOUBT)' dropped it)."""
    d = 0.9702748543934043
    threshold = (1.0 - REL_TOL) * d
    near = threshold * (1.0 + DOUBT)
    assert abs(near - threshold) > DOUBT * threshold and not near > threshold * (1.0 + DOUBT)
    shape = shapely.Polygon([(-32.0, -near), (32.0, -near), (32.0, 40.0), (-32.0, 40.0)])
    assert shapely.distance(shapely.Point(0.0, 0.0), shape.boundary) == near
    points = np.zeros((1, 2))
    assert clear_of_boundary(shape, points, (0, 0), (1, 1), np.zeros(2), lattice.lattice_basis(1.0, 0.0), d)[0, 0]


def test_a_nearly_horizontal_side_overflows_nothing():
    """A side rising by 1e-310 over 8 (dv subnormal in lattice rows): its band parameters overflow to +-inf and are
    clipped, silently (warnings are errors here), and the answer is the oracle's."""
    shape = shapely.Polygon([(0.0, 0.0), (8.0, 1e-310), (0.5, 7.0)])
    for clearance in (0.3, 1.0):
        check_window(shape, (-6, -2), (14, 12), 1.0, 0.0, (0.0, 0.0), clearance)


def test_the_doubtful_window_is_relative_to_the_threshold():
    """Far from l the band's distance and shapely's differ by ulps of the distance: at 2.2e5 (l = 1) the vertex
    (0, 0) is 220735.05718048825 from side ab by the band, 220735.05718048828 by shapely (one ulp more), and d is
    chosen so that the threshold (1 - REL_TOL) d is shapely's distance exactly: kept (at_least), decided by shapely
    inside the window DOUBT threshold = 0.02 (an absolute window DOUBT / threshold = 5e-13 would leave it to the
    band, which drops it)."""
    a, b = (-106903.9722203594, -212767.62667451415), (225329.6581733608, -239794.76031489891)
    shape = shapely.Polygon([a, b, (4e7, 4e7), (-4e7, 4e7)])
    d = 220735.05740122334
    s = shapely.distance(shapely.Point(0.0, 0.0), shape.boundary)
    assert (1.0 - REL_TOL) * d == s == 220735.05718048828
    check_window(shape, (0, 0), (1, 1), 1.0, 0.0, (0.0, 0.0), d)
    assert per_vertex(shape, np.zeros((1, 2)), d)[0]


def kept_by_every_vertex(poly, l, angle, offset, clearance):
    """The scorer before the row-by-row clearance (the oracle): every lattice vertex tested against the boundary with
    shapely."""
    ii, _, pts, kept = kept_vertices(poly, l, angle, offset, clearance)
    shape = poly.region
    inside = shapely.contains_xy(shape, pts[:, 0], pts[:, 1])
    far = np.zeros(len(pts), dtype=bool)
    far[inside] = at_least(
        shapely.distance(shapely.points(pts[inside]), shape.exterior), clearance * poly.local_length(l)
    )
    return far.reshape(ii.shape), kept


fractions = st.tuples(st.floats(0.0, 1.0), st.floats(0.0, 1.0))


@given(
    ss.cases(),
    st.one_of(st.sampled_from([0.0, 30.0]), st.floats(0.0, 60.0)),
    fractions,
    st.sampled_from([1.0, 1.5, 2.0]),
)
def test_band_scan_keeps_the_same_vertices_as_testing_every_vertex(case, angle, frac, clearance):
    """The placement's scorer (:mod:`equimesh.planar.clearance`) keeps exactly the vertices the per-vertex test
    keeps."""
    vertices, l = case
    poly = as_polygon(vertices, l)
    offset = np.asarray(frac) @ equimesh.planar.lattice.lattice_basis(l, angle)
    old, new = kept_by_every_vertex(poly, l, angle, offset, clearance)
    assert np.array_equal(old, new)


@pytest.mark.parametrize("clearance", [1.0, 2.0, 3.0])
@pytest.mark.parametrize(
    "vertices",
    [rectangle(10.0, 8.0 * np.sqrt(3.0) / 2.0), rectangle(12.0, 12.0), regular_polygon(6, 6.0)],
    ids=["lattice rectangle", "square", "hexagon"],
)
def test_band_scan_on_vertices_exactly_at_clearance(vertices, clearance):
    """Boundaries along lattice rows: many vertices exactly ``clearance * l`` away, decided as before."""
    poly = as_polygon(vertices, 1.0)
    for angle in (0.0, 60.0 * 0.25, 30.0):
        old, new = kept_by_every_vertex(poly, 1.0, angle, (0.0, 0.0), clearance)
        assert np.array_equal(old, new)
