"""Remapping plane nodes to (u, v) and to the surface, eqs. (2)-(3) (Section 4, step 4)."""

import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from section4_standin import parabolic_vault
from surface_cases import Wrapped, plane_patch

import equimesh
from equimesh.errors import InvalidSurfaceError
from equimesh.mesh import PlanarMesh
from equimesh.surface.auxiliary import auxiliary_grid
from equimesh.surface.flatten import flatten
from equimesh.surface.remap import barycentric, check_remapped, locate, remap
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
    assert np.all(r.triangle >= 0)
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
    assert np.all(r.triangle == -1) and np.all(np.isnan(r.alpha))


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


def test_remapped_triangles_counter_clockwise_in_uv_pass():
    plane = PlanarMesh.build([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], [[0, 1, 2], [0, 2, 3]], 1.0, 4)
    check_remapped(plane.points, plane)


def _remapped(moved):
    """A plane mesh of the square [0, 2]^2 (boundary nodes 0-3, one inner node 4) and its nodes remapped to (u, v)
    with the nodes ``moved`` put elsewhere."""
    points = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [1.0, 1.5]]
    plane = PlanarMesh.build(points, [[0, 1, 2], [0, 2, 4], [2, 3, 4], [3, 0, 4]], 1.0, 4)
    uv = plane.points.copy()
    for node, to in moved.items():
        uv[node] = to
    return uv, plane


def test_a_remapped_triangle_that_folds_is_refused():
    """The inner node remapped beyond the left side: the triangle on that side turns clockwise in (u, v)."""
    message = (
        "mapping the plane mesh back onto the surface (eqs. 2-3) folds 1 of 4 triangles, first near (u, v) = "
        "(-0.166667, 1): the flattening's distortion turns there within a member's length; use a smaller l or a "
        "finer auxiliary grid"
    )
    with pytest.raises(InvalidSurfaceError, match="^" + re.escape(message) + "$"):
        check_remapped(*_remapped({4: (-0.5, 1.0)}))


def test_a_remapped_triangle_of_boundary_nodes_flat_in_uv_is_refused():
    """Three boundary nodes remapped onto one straight line in (u, v), and a triangle with the inner node folded:
    the flat one of boundary nodes is named, as the boundary's bend."""
    message = (
        "the flattened boundary bends so sharply near (u, v) = (1, 1) that Problem 2 joins three boundary nodes "
        "there in a triangle (1 such in all), flat in (u, v), where the boundary is straight; use a finer auxiliary "
        "grid or another l"
    )
    with pytest.raises(InvalidSurfaceError, match="^" + re.escape(message) + "$"):
        check_remapped(*_remapped({1: (1.0, 1.0), 4: (-0.5, 1.0)}))
