"""Remapping plane nodes to (u, v) and to the surface, eqs. (2)-(3) (Section 4, step 4)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from section4_standin import parabolic_vault
from surface_cases import Wrapped, plane_patch

import equimesh
from equimesh.errors import InternalError, InvalidSurfaceError
from equimesh.mesh import PlanarMesh
from equimesh.surface.auxiliary import auxiliary_grid
from equimesh.surface.charts.chart import Domain
from equimesh.surface.flatten import flatten
from equimesh.surface.plane_length import PlaneLength
from equimesh.surface.remap import Loop, barycentric, check_remapped, locate, remap, to_plane
from equimesh.testing.surfaces import dome


def test_nan_at_remapped_parameters_is_refused():
    """A NaN between the grid samples, met only by remapping (step 4): an error, never a NaN node."""
    surface = plane_patch()
    grid = auxiliary_grid(4, 4)
    flat = equimesh.flatten(surface.evaluate(grid.uv[:, 0], grid.uv[:, 1]), grid.triangles, uv=grid.uv).points
    holed = Wrapped(surface, lambda u, v: np.hypot(u - 0.5, v - 0.5) < 0.01)
    centre = flat[grid.boundary][grid.boundary_corner].mean(axis=0, keepdims=True)  # (u, v) = (0.5, 0.5)
    with pytest.raises(InvalidSurfaceError, match=r"not finite at \(u, v\) = \(0\.5, 0\.5\)"):
        equimesh.remap(holed, centre, flat, grid)


def test_bad_arguments_are_refused_by_name():
    """Step 4's arguments are checked before any work: each fault is an error of equimesh's naming it."""
    surface, grid = plane_patch(), auxiliary_grid(4, 4)
    flat = equimesh.flatten(surface.evaluate(grid.uv[:, 0], grid.uv[:, 1]), grid.triangles, uv=grid.uv).points
    middle = np.array([[0.5, 0.5]])
    with pytest.raises(InvalidSurfaceError, match=r"^plane_points must be an \(N, 2\) array, got shape \(3, 3\)"):
        equimesh.remap(surface, np.zeros((3, 3)), flat, grid)
    with pytest.raises(InvalidSurfaceError, match=r"^plane point 0 is not finite: \[nan, 0\.5\]"):
        equimesh.remap(surface, [[np.nan, 0.5]], flat, grid)
    grid_is = (
        r"^grid must be the auxiliary triangulation of step 1 \(with uv, triangles, boundary, boundary_sides, domain\)"
    )
    with pytest.raises(InvalidSurfaceError, match=grid_is + ", got int$"):
        equimesh.remap(surface, middle, flat, 5)
    with pytest.raises(InvalidSurfaceError, match=r"^flat_points must be an \(N, 2\) array, got shape \(25,\)$"):
        equimesh.remap(surface, middle, flat[:, 0], grid)
    with pytest.raises(InvalidSurfaceError, match=r"^flattened node 3 is not finite: \[nan, nan\]$"):
        equimesh.remap(surface, middle, np.where(np.arange(25)[:, None] == 3, np.nan, flat), grid)
    with pytest.raises(
        InvalidSurfaceError, match=r"^flat_points must have one row per node of the grid \(25\), got 24"
    ):
        equimesh.remap(surface, middle, flat[:-1], grid)


seeds = st.integers(min_value=0, max_value=2**32 - 1)


def flattened(surface=None, n_u=8, n_v=11):
    surface = surface or dome()
    g = auxiliary_grid(n_u, n_v)
    x = surface.evaluate(g.uv[:, 0], g.uv[:, 1])
    return surface, g, flatten(x, g.triangles, uv=g.uv).points


def forward(g, flat, uv):
    """The plane point of parameters ``uv``: eq. (3) inverted on the grid cell containing it."""
    i = np.minimum((uv[:, 0] * g.n_u).astype(int), g.n_u - 1)
    j = np.minimum((uv[:, 1] * g.n_v).astype(int), g.n_v - 1)
    s, t = uv[:, 0] * g.n_u - i, uv[:, 1] * g.n_v - j
    lower = s >= t  # triangle (i,j) (i+1,j) (i+1,j+1), else (i,j) (i+1,j+1) (i,j+1)
    a = g.node(i, j)
    c = g.node(i + 1, j + 1)
    b = np.where(lower, g.node(i + 1, j), c)
    d = np.where(lower, c, g.node(i, j + 1))
    alpha = np.where(lower, s - t, s)
    beta = np.where(lower, t, t - s)
    return flat[a] + alpha[:, None] * (flat[b] - flat[a]) + beta[:, None] * (flat[d] - flat[a])


@settings(max_examples=15, deadline=None)
@given(seed=seeds)
def test_round_trip_interior(seed):
    """A plane point of known (u, v) maps back to that (u, v)."""
    surface, g, flat = flattened()
    uv = np.random.default_rng(seed).uniform(0.01, 0.99, size=(200, 2))
    r = remap(surface, forward(g, flat, uv), flat, g)
    np.testing.assert_allclose(r.uv, uv, atol=1e-12)
    assert not r.on_boundary.any()
    assert np.all(r.triangle >= 0) and r.triangle.dtype == np.int64
    assert np.all((r.alpha >= 0) & (r.beta >= 0) & (r.alpha + r.beta <= 1))
    assert np.all(r.segment == -1) and np.all(np.isnan(r.t))
    np.testing.assert_allclose(r.points, surface.evaluate(uv[:, 0], uv[:, 1]), atol=1e-9)


def test_auxiliary_nodes_map_to_their_own_parameters():
    surface, g, flat = flattened()
    r = locate(flat, flat, g)
    np.testing.assert_allclose(r.uv, g.uv, atol=1e-12)
    # the boundary ones exactly, through the boundary path
    assert np.array_equal(r.uv[g.boundary], g.uv[g.boundary])
    assert r.on_boundary[g.boundary].all()


@settings(max_examples=15, deadline=None)
@given(seed=seeds)
def test_boundary_nodes_land_exactly_on_the_boundary(seed):
    surface, g, flat = flattened()
    rng = np.random.default_rng(seed)
    seg = rng.integers(0, len(g.boundary), size=50)
    t = rng.uniform(0, 1, size=50)
    a, b = flat[g.boundary[seg]], flat[np.roll(g.boundary, -1)[seg]]
    x = a + t[:, None] * (b - a)
    r = remap(surface, x, flat, g, on_boundary=np.arange(50))
    side = g.boundary_segment_side[seg]
    assert np.array_equal(r.uv[np.arange(50), side // 2], (side % 2).astype(float))
    ua, ub = g.uv[g.boundary[seg]], g.uv[np.roll(g.boundary, -1)[seg]]
    np.testing.assert_allclose(r.uv, ua + t[:, None] * (ub - ua), atol=1e-12)
    assert np.all(r.triangle == -1) and np.all(np.isnan(r.alpha)) and np.all(np.isnan(r.beta))
    assert np.all((r.segment >= 0) & (r.segment < len(g.boundary))) and np.all((r.t >= 0) & (r.t <= 1))


def outward_points(g, flat, offset, rng, k=40):
    seg = rng.integers(0, len(g.boundary), size=k)
    t = rng.uniform(0.05, 0.95, size=k)
    a, b = flat[g.boundary[seg]], flat[np.roll(g.boundary, -1)[seg]]
    d = b - a
    normal = np.column_stack([d[:, 1], -d[:, 0]]) / np.linalg.norm(d, axis=1)[:, None]  # outward for a CCW loop
    return a + t[:, None] * d + offset * normal


@pytest.mark.parametrize("offset", [1e-12, 1e-7, 1e-3, 5.0])
def test_points_outside_never_fail_and_land_on_the_boundary(offset):
    surface, g, flat = flattened()
    x = outward_points(g, flat, offset, np.random.default_rng(3))
    r = remap(surface, x, flat, g)
    assert r.on_boundary.all()
    on_side = np.any((r.uv == 0.0) | (r.uv == 1.0), axis=1)
    assert on_side.all()
    assert np.all((r.uv >= 0) & (r.uv <= 1))
    assert np.all(np.isfinite(r.points))


def test_points_just_inside_are_snapped():
    surface, g, flat = flattened()
    rng = np.random.default_rng(4)
    x = outward_points(g, flat, -1e-12, rng)
    r = locate(x, flat, g)
    assert r.on_boundary.all()
    r2 = locate(x, flat, g, snap_tol=0.0)
    assert not r2.on_boundary.any()  # found inside, no snapping
    np.testing.assert_allclose(r.uv, r2.uv, atol=1e-9)


def test_boundary_mask_accepts_bool():
    surface, g, flat = flattened()
    x = flat[g.boundary]
    mask = np.ones(len(x), dtype=bool)
    assert np.array_equal(locate(x, flat, g, on_boundary=mask).uv, g.uv[g.boundary])


@pytest.mark.parametrize("named", [np.array([1, 3]), np.array([False, True, False, True])], ids=["indices", "mask"])
def test_nodes_named_on_the_boundary_take_the_boundary_path_wherever_they_are(named):
    """Nodes 1 and 3, well inside, named as boundary nodes (by index or by mask): projected onto the boundary."""
    surface, g, flat = flattened()
    x = forward(g, flat, np.array([[0.5, 0.5], [0.5, 0.1], [0.4, 0.6], [0.9, 0.5]]))
    r = locate(x, flat, g, on_boundary=named)
    assert r.on_boundary.tolist() == [False, True, False, True]
    assert r.triangle[0] >= 0 and r.triangle[2] >= 0 and np.all(r.triangle[[1, 3]] == -1)
    assert r.uv[1, 1] == 0.0 and r.uv[3, 0] == 1.0  # the nearest sides, v = 0 and u = 1


def test_single_precision_points_are_located_as_their_double_precision_values():
    """Eqs. (2)-(3) are evaluated in double precision whatever the caller's arrays hold."""
    surface, g, flat = flattened()
    flat32 = flat.astype(np.float32)
    x = forward(g, flat32.astype(float), np.random.default_rng(8).uniform(0.01, 0.99, size=(50, 2))).astype(np.float32)
    single, double = locate(x, flat32, g), locate(x.astype(float), flat32.astype(float), g)
    assert np.array_equal(single.uv, double.uv) and np.array_equal(single.triangle, double.triangle)


def _gauge_edge_point(offset):
    """The flattened dome and the point at ``offset`` (>= 0: inside) from the middle of its boundary segment 0 -> 1.

    That segment is the gauge edge (docs: :func:`equimesh.flatten`), along the x-axis exactly, the interior below it.
    """
    surface, g, flat = flattened()
    assert g.boundary[-1] == 1 and g.boundary[0] == 0 and flat[1, 1] == 0.0 and flat[0, 1] == 0.0
    return g, flat, np.array([[flat[1, 0] / 2, -offset]])


def test_a_node_on_the_boundary_is_snapped_only_with_a_positive_tolerance():
    g, flat, x = _gauge_edge_point(0.0)
    r = locate(x, flat, g, snap_tol=0.0)
    assert r.triangle[0] >= 0 and not r.on_boundary[0]
    assert remap(dome(), x, flat, g, snap_tol=0.0).triangle[0] == r.triangle[0]
    assert remap(dome(), x, flat, g).on_boundary[0]


def test_a_node_at_the_snap_tolerance_is_snapped():
    g, flat, x = _gauge_edge_point(2.0**-30)
    assert locate(x, flat, g, snap_tol=2.0**-30).on_boundary[0]
    assert not locate(x, flat, g, snap_tol=2.0**-31).on_boundary[0]


@pytest.mark.parametrize("shift", [(0.0, 0.0), (1000.0, -3000.0)])
def test_the_default_snap_tolerance_is_1e_9_of_the_flattened_diameter(shift):
    """Wherever the plane puts the flattening: a node 0.5e-9 diameters inside is snapped, one 2e-9 inside is not."""
    g, flat, x = _gauge_edge_point(0.0)
    diameter = np.linalg.norm(np.ptp(flat, axis=0))
    inside = x + [[0.0, -0.5e-9 * diameter], [0.0, -2e-9 * diameter]]
    assert locate(inside + shift, flat + shift, g).on_boundary.tolist() == [True, False]


def test_developable_remap_length_error_is_first_order():
    """On a developable surface, eqs. (2)-(3) keep short plane distances up to an O(h) error.

    The piecewise-linear interpolation of (u, v) has an O(h) error in its
    derivative, so the relative error of a short remapped segment falls
    linearly with the auxiliary grid spacing h = 1/n: the fitted rate is ~1.
    """
    rng = np.random.default_rng(5)
    uv = rng.uniform(0.1, 0.9, size=(300, 2))
    angle = rng.uniform(0, 2 * np.pi, size=300)
    step = 0.5 * np.column_stack([np.cos(angle), np.sin(angle)])
    ns, errors = [8, 16, 32], []
    for n in ns:
        surface, g, flat = flattened(parabolic_vault(), n, n)
        p = forward(g, flat, uv)
        a, b = remap(surface, p, flat, g).points, remap(surface, p + step, flat, g).points
        errors.append(np.mean(np.abs(np.linalg.norm(b - a, axis=1) / 0.5 - 1.0)))
    rate = -np.polyfit(np.log(ns), np.log(errors), 1)[0]
    assert 0.8 < rate < 1.6
    assert errors[-1] < 5e-3


def test_barycentric_scales_a_point_beyond_the_far_side_back_onto_it():
    """Coefficients summing to more than 1 are divided by their sum: the point moves towards corner q onto side r-s."""
    corners = np.array([[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]] * 3)
    a, b = barycentric(np.array([[0.6, 0.6], [0.9, 0.3], [0.5, 0.5]]), corners)
    np.testing.assert_allclose(a, [0.5, 0.75, 0.5])
    np.testing.assert_allclose(b, [0.5, 0.25, 0.5])


def test_barycentric_clamps_rounding():
    corners = np.array([[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]] * 3)
    x = np.array([[0.25, 0.5], [-1e-17, 0.5], [0.5 + 1e-16, 0.5]])
    a, b = barycentric(x, corners)
    np.testing.assert_allclose([a[0], b[0]], [0.25, 0.5])
    assert np.all(a >= 0) and np.all(b >= 0) and np.all(a + b <= 1.0)


def test_mesh_surface_remaps_through_the_public_remap():
    """One remapping path: mesh_surface's step 4 is equimesh.remap with the outline, bit for bit.

    Boundary nodes on an outline vertex take its exact (u, v); every boundary node lies on a side of the square.
    """
    import equimesh

    surface = dome()
    mesh = equimesh.mesh_surface(surface, 6.0, grid=(8, 8), optimize="none")
    st_ = mesh.stages
    nb = st_.plane.n_boundary
    r = remap(
        surface, st_.plane.points, st_.flattening.points, st_.grid, on_boundary=np.arange(nb), outline=st_.outline
    )
    assert np.array_equal(r.uv, st_.remapped_uv) and np.array_equal(r.points, st_.remapped_points)
    ring = st_.plane.points[:nb]
    for vertex, uv in zip(st_.outline.vertices, st_.outline.uv):
        hit = np.flatnonzero(np.all(ring == vertex, axis=1))
        assert len(hit) == 1 and np.array_equal(r.uv[hit[0]], uv)
    assert np.all(np.any((r.uv[:nb] == 0.0) | (r.uv[:nb] == 1.0), axis=1))


def _fan():
    """A unit square of four boundary nodes around one inner node (index 4), in four counter-clockwise triangles."""
    points = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]]
    return PlanarMesh.build(points, [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]], 1.0, 4)


def test_check_remapped_passes_an_unfolded_mesh():
    plane = _fan()
    assert check_remapped(plane.points, plane, PlaneLength(1.0)) is None


@pytest.mark.parametrize(
    "inner, message",
    [
        # moved across two sides of the square: triangles 0 and 1 turn clockwise in (u, v)
        (
            [2.0, -1.0],
            r"^mapping the plane mesh back .* folds 2 of 4 triangles, first near \(u, v\) = \(1, -0\.333333\): ",
        ),
        # on side 0-1: triangle 0 is flat, neither counter-clockwise nor of boundary nodes alone
        ([0.5, 0.0], r"^mapping the plane mesh back .* folds 1 of 4 triangles, first near \(u, v\) = \(0\.5, 0\): "),
    ],
)
def test_check_remapped_refuses_folded_or_flat_triangles_naming_the_first(inner, message):
    plane = _fan()
    uv = plane.points.copy()
    uv[4] = inner
    with pytest.raises(
        InvalidSurfaceError, match=message + r".*length at l = 1; use a smaller l or a finer auxiliary grid$"
    ):
        check_remapped(uv, plane, PlaneLength(1.0))


def test_check_remapped_names_the_spacing_meshed_for_sound_joints():
    plane = _fan()
    uv = plane.points.copy()
    uv[4] = [2.0, -1.0]
    with pytest.raises(
        InvalidSurfaceError, match=r"at the spacing 1\.25 l = 1\.25 meshed for sound joints \(l = 1\); use a smaller l"
    ):
        check_remapped(uv, plane, PlaneLength(1.0, 1.25))


#: Meshes with ears: plane points, triangles, boundary nodes, (u, v) of the nodes, the ears' count and first centre.
EARS = {
    # two triangles of boundary nodes alone, both flat where the boundary is straight in (u, v)
    "two ears": ([[0, 0], [1, 0], [1, 1], [0, 1]], [[0, 1, 2], [0, 2, 3]], 4, [[0, 0], [1, 0], [2, 0], [3, 0]], 2),
    # a square fanned around inner node 5, and an ear of boundary nodes 0, 4, 1 below it, flat in (u, v)
    "an ear beside inner triangles": (
        [[0, 0], [2, 0], [2, 2], [0, 2], [1, -0.5], [1, 1]],
        [[0, 4, 1], [0, 1, 5], [1, 2, 5], [2, 3, 5], [3, 0, 5]],
        5,
        [[0, 0], [2, 0], [2, 2], [0, 2], [1, 0], [1, 1]],
        1,
    ),
}


@pytest.mark.parametrize("case", EARS.values(), ids=EARS.keys())
def test_check_remapped_refuses_flat_ears_of_boundary_nodes(case):
    """Both name the first ear, centred at (u, v) = (1, 0), and the count of ears."""
    points, triangles, n_boundary, uv, count = case
    plane = PlanarMesh.build(np.array(points, dtype=float), triangles, 1.0, n_boundary)
    with pytest.raises(
        InvalidSurfaceError,
        match=r"^the flattened boundary bends so sharply near \(u, v\) = \(1, 0\) that Problem 2 joins three boundary "
        rf"nodes there in a triangle \({count} such in all\), flat in \(u, v\), .*straight, at l = 1; .*another l$",
    ):
        check_remapped(np.array(uv, dtype=float), plane, PlaneLength(1.0))


def test_to_plane_maps_the_auxiliary_nodes_to_their_flattened_points_and_back():
    """Eqs. (2)-(3) forward: a node's (u, v) goes to its flattened point, any (u, v) to a point locate maps back."""
    surface, g, flat = flattened()
    np.testing.assert_allclose(to_plane(g.uv, flat, g), flat, atol=1e-12)
    uv = np.random.default_rng(6).uniform(0.01, 0.99, size=(100, 2))
    np.testing.assert_allclose(to_plane(uv, flat, g), forward(g, flat, uv), atol=1e-12)


def test_to_plane_refuses_a_point_outside_the_domain():
    surface, g, flat = flattened()
    with pytest.raises(InternalError, match=r"^\(u, v\) = \(1\.5, 0\.5\) is in no auxiliary triangle$"):
        to_plane([[0.05, 0.01], [0.5, 0.5], [1.5, 0.5], [2.0, 2.0]], flat, g)  # the first in auxiliary triangle 0


def test_loop_projects_onto_the_ring_of_each_segment():
    """An outer square on the sides of [0, 1]^2 and a clockwise hole inside: a point near the hole's closing edge is
    projected onto that edge (vertex 7 to its successor 4), and its (u, v) is interpolated there, on no side."""
    xy = np.array([[0, 0], [4, 0], [4, 4], [0, 4], [1, 1], [1, 3], [3, 3], [3, 1]], dtype=float)
    uv = np.vstack([[[0, 0], [1, 0], [1, 1], [0, 1]], xy[4:] / 4])
    loop = Loop(xy, uv, np.array([2, 1, 3, 0, -1, -1, -1, -1]), Domain(), np.array([1, 2, 3, 0, 5, 6, 7, 4]))
    segment, t, mapped = loop.project(np.array([[2.0, 1.2], [2.0, -1.0], [4.5, 1.0], [-1.0, 1.0], [2.0, 5.0]]))
    assert segment.tolist() == [7, 0, 1, 3, 2]
    np.testing.assert_allclose(t, [0.5, 0.5, 0.25, 0.75, 0.5])
    np.testing.assert_allclose(mapped, [[0.5, 0.25], [0.5, 0.0], [1.0, 0.25], [0.0, 0.25], [0.5, 1.0]])


def test_loop_puts_a_node_projected_onto_a_side_exactly_on_the_bound():
    """On [1/3, 1.7] x [0.45, 0.85], where interpolating a side's constant coordinate rounds at some of these points
    on every side: the bound, bit for bit."""
    domain = Domain((1 / 3, 1.7), (0.45, 0.85))
    loop = Loop(np.array([[0, 0], [4, 0], [4, 4], [0, 4]], dtype=float), domain.corners, np.array([2, 1, 3, 0]), domain)
    along = np.random.default_rng(7).uniform(0.0, 4.0, size=25)
    out = np.full(25, -1.0)
    points = np.vstack([np.column_stack(p) for p in [(along, out), (4 - out, along), (along, 4 - out), (out, along)]])
    segment, _, uv = loop.project(points)
    assert segment.tolist() == np.repeat([0, 1, 2, 3], 25).tolist()
    assert np.all(uv[:25, 1] == 0.45) and np.all(uv[25:50, 0] == 1.7)
    assert np.all(uv[50:75, 1] == 0.85) and np.all(uv[75:, 0] == 1 / 3)
