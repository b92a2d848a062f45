"""Flattening the auxiliary triangulation, eq. (1) (Section 4, step 2)."""

import textwrap
import time

import numpy as np
import pytest
from blas_threads import outputs_with_one_and_two_threads
from hypothesis import given, settings
from hypothesis import strategies as st
from section4_standin import CircularVault, flat_patch, parabolic_vault

from equimesh import InvalidSurfaceError
from equimesh._geometry import orient
from equimesh.mesh import edge_lengths
from equimesh.surface import flatten as flatten_module
from equimesh.surface.auxiliary import auxiliary_grid
from equimesh.surface.charts.bezier import BezierSurface
from equimesh.surface.flatten import check_edge_lengths, energy_terms, flatten, plane_start
from equimesh.surface.optimize.jacobian import AreaBarrier
from equimesh.surface.optimize.solver import INSTALLED
from equimesh.testing.surfaces import dome


def run(surface, n_u=15, n_v=15, **kw):
    g = auxiliary_grid(n_u, n_v)
    x = surface.evaluate(g.uv[:, 0], g.uv[:, 1])
    return g, x, flatten(x, g.triangles, uv=g.uv, edges=g.edges, **kw)


def orientations(points, triangles):
    return orient(*(points[triangles[:, k]] for k in range(3)))


FLATTEN_FAULTS = {
    "no triangles": ({"triangles": np.zeros((0, 3), dtype=int)}, "^no triangles to flatten$"),
    "points in the plane": (
        {"points3d": np.zeros((9, 2))},
        r"^points3d must be an \(N, 3\) array, got shape \(9, 2\)$",
    ),
    "a point not finite": (
        {"points3d": np.where(np.arange(9)[:, None] == 4, np.nan, np.ones((9, 3)))},
        r"^surface point 4 is not finite",
    ),
    "a triangle to no point": (
        {"triangles": [[0, 1, 9]]},
        r"^triangle 0 refers to a point outside 0 \.\. 8: \[0, 1, 9\]$",
    ),
    "a triangle to point -1": ({"triangles": [[1, -1, 2]]}, r"^triangle 0 refers to a point outside 0 \.\. 8"),
    "a fractional index": ({"triangles": [[0, 1, 3.7]]}, r"^triangles must be an \(M, 3\) array of point indices"),
    "four corners": ({"triangles": [[0, 1, 4, 3]]}, r"^triangles must be an \(M, 3\) array of point indices"),
    "uv of three columns": ({"uv": np.zeros((9, 3))}, r"^uv must be an \(N, 2\) array, got shape \(9, 3\)$"),
    "uv of another mesh": ({"uv": np.zeros((4, 2))}, r"^uv must have one row per surface point \(9\), got 4$"),
    "a (u, v) not finite": (
        {"uv": np.where(np.arange(9)[:, None] == 4, np.nan, np.full((9, 2), 0.5))},
        r"^the \(u, v\) of point 4 is not",
    ),
    "a start of another mesh": ({"x0": np.zeros((4, 2))}, r"^x0 must have one row per surface point \(9\), got 4$"),
    "a start not finite": (
        {"x0": np.where(np.arange(9)[:, None] == 2, np.inf, np.full((9, 2), 0.5))},
        r"^the start of point 2 is not",
    ),
    "an edge to no point": ({"edges": [[0, 1], [0, 9]]}, r"^edge 1 refers to a point outside 0 \.\. 8: \[0, 9\]$"),
    "an edge of fractions": ({"edges": [[0.0, 1.0]]}, r"^edges must be an \(M, 2\) array of point indices"),
}


@pytest.mark.parametrize("case", FLATTEN_FAULTS)
def test_bad_arguments_are_refused_by_name(case):
    """Step 2's arguments are checked before any work: each fault is an error of equimesh's naming it (a point of
    nan was reported as two coinciding points, a negative index was read from the end)."""
    grid = auxiliary_grid(2, 2)
    points = dome().evaluate(grid.uv[:, 0], grid.uv[:, 1])
    args = {"points3d": points, "triangles": grid.triangles, "uv": grid.uv, "x0": None, "edges": None}
    given, message = FLATTEN_FAULTS[case]
    args.update(given)
    with pytest.raises(InvalidSurfaceError, match=message):
        flatten(args["points3d"], args["triangles"], uv=args["uv"], x0=args["x0"], edges=args["edges"])


@pytest.mark.parametrize("shear", [0.0, 25.0])
def test_flat_surface_is_flattened_exactly(shear):
    g, x, f = run(flat_patch(shear=shear), 9, 13)
    assert f.energy < 1e-24
    np.testing.assert_allclose(f.plane_lengths, f.surface_lengths, rtol=1e-12)
    # congruent to the input plane: same pairwise distances from node 0
    d3 = np.linalg.norm(x - x[0], axis=1)
    d2 = np.linalg.norm(f.points - f.points[0], axis=1)
    np.testing.assert_allclose(d2, d3, atol=1e-9)


def test_developable_vault_has_zero_energy():
    g, x, f = run(parabolic_vault(), 15, 15)
    assert f.energy < 1e-10
    assert np.all(orientations(f.points, g.triangles) > 0)
    # the developed vault is a rectangle: depth by the length of the arch's chord polygon
    chord = np.sum(np.linalg.norm(np.diff(x[g.node(np.arange(16), 0)], axis=0), axis=1))
    extent = sorted(np.ptp(f.points, axis=0))
    np.testing.assert_allclose(extent, sorted([50.0, chord]), rtol=1e-9)


def test_circular_vault_has_zero_energy():
    """An exact circular cylinder (a non-Bezier surface through the same interface) is developable too."""
    g, x, f = run(CircularVault(), 15, 15)
    assert f.energy < 1e-10


@settings(max_examples=8, deadline=None)
@given(
    rise=st.floats(min_value=1.0, max_value=30.0),
    width=st.floats(min_value=20.0, max_value=80.0),
    n_u=st.integers(min_value=3, max_value=20),
    n_v=st.integers(min_value=3, max_value=20),
)
def test_developable_vaults_property(rise, width, n_u, n_v):
    """Theorem of the test: a developable surface has a flattening with E = 0, and the solver finds it."""
    g, _, f = run(parabolic_vault(width=width, rise=rise), n_u, n_v)
    assert f.energy < 1e-10
    assert np.all(orientations(f.points, g.triangles) > 0)


def test_gauge_and_result_fields():
    g, x, f = run(dome(), 10, 12)
    a, b = f.gauge
    assert np.array_equal(f.points[a], [0.0, 0.0])
    assert f.points[b, 1] == 0.0 and f.points[b, 0] > 0
    assert f.energy == pytest.approx(0.5 * np.sum(f.relative_errors**2))
    np.testing.assert_allclose(f.plane_lengths, edge_lengths(f.points, g.edges))
    assert f.start == "metric"
    assert 0 < f.energy < 1.0  # doubly curved: not developable, but nearly isometric


def test_result_is_stationary():
    """A minimiser of eq. (1): the gradient J^T r vanishes."""
    g, x, f = run(dome(rise=20.0), 12, 12)
    n = len(x)
    residuals, jacobian = energy_terms(f.edges, f.surface_lengths, n)
    grad = jacobian(f.points).T @ residuals(f.points)
    assert np.abs(grad).max() < 1e-7


@settings(max_examples=10, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_analytic_jacobian_matches_finite_differences(seed):
    rng = np.random.default_rng(seed)
    g = auxiliary_grid(3, 4)
    x = np.column_stack([g.uv, 0.3 * rng.standard_normal(len(g.uv))]) * 10
    ls = edge_lengths(x, g.edges)
    free = rng.random(2 * len(x)) < 0.8
    residuals, jacobian = energy_terms(g.edges, ls, len(x), free)
    p = g.uv * 10 + 0.5 * rng.standard_normal(g.uv.shape)
    jac = jacobian(p).toarray()
    h = 1e-6
    fd = np.empty_like(jac)
    for col, k in enumerate(np.flatnonzero(free)):
        d = np.zeros(p.size)
        d[k] = h
        fd[:, col] = (residuals(p + d.reshape(p.shape)) - residuals(p - d.reshape(p.shape))) / (2 * h)
    np.testing.assert_allclose(jac, fd, atol=1e-8)


def test_folded_start_is_detected_and_recovered():
    """A mirrored start converges to a mirrored (folded) flattening: detected, retried from the default."""
    g, x, _ = run(dome(), 10, 10)
    mirrored = g.uv * [-60.0, 60.0]
    f = flatten(x, g.triangles, uv=g.uv, x0=mirrored)
    assert f.start == "metric"
    assert np.all(orientations(f.points, g.triangles) > 0)
    # without a fallback the mirrored start would have folded every triangle
    f2 = flatten(x, g.triangles, x0=g.uv * [60.0, 60.0])
    assert f2.start == "given"


def test_strongly_curved_patch_folds_without_barrier_and_not_with_it():
    """A near-hemisphere: eq. (1) alone wrinkles the rim (detected and refused); the barrier prevents it."""
    g = auxiliary_grid(15, 15)
    x = dome(rise=60.0).evaluate(g.uv[:, 0], g.uv[:, 1])
    with pytest.raises(InvalidSurfaceError, match=r"folds .* auxiliary triangles over, first near \(u, v\) = \("):
        flatten(x, g.triangles, uv=g.uv, area_floor=0.0)
    f = flatten(x, g.triangles, uv=g.uv)
    assert np.all(orientations(f.points, g.triangles) > 0)


def test_the_barrier_weighs_a_fold_above_the_starts_energy(monkeypatch):
    """A flat grid from a start 1.2 times too large (every relative error 0.2, E(start) 0.32): the barrier's weight
    w has w^2 / 2 above E(start), so a folded triangle alone costs more than the start and is never accepted."""
    made = []

    class Recorded(AreaBarrier):
        def __init__(self, triangles, start, fraction, weight, free=None, power=1):
            made.append(weight)
            super().__init__(triangles, start, fraction, weight, free, power)

    monkeypatch.setattr(flatten_module, "AreaBarrier", Recorded)
    g = auxiliary_grid(2, 2)
    x = flat_patch(40.0, 40.0).evaluate(g.uv[:, 0], g.uv[:, 1])
    edges = g.edges
    start = 1.2 * x[:, :2]
    energy = 0.5 * np.sum(((edge_lengths(start, edges) - edge_lengths(x, edges)) / edge_lengths(x, edges)) ** 2)
    flatten(x, g.triangles, x0=start)
    assert energy == pytest.approx(0.32) and len(made) == 1 and made[0] ** 2 / 2 > energy


def test_barrier_is_inactive_on_mild_surfaces():
    g, x, f = run(dome(), 12, 12)
    f0 = flatten(x, g.triangles, uv=g.uv, area_floor=0.0)
    np.testing.assert_allclose(f.points, f0.points, atol=1e-8)


@settings(max_examples=10, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_barrier_jacobian_matches_finite_differences(seed):
    rng = np.random.default_rng(seed)
    g = auxiliary_grid(3, 3)
    start = g.uv * 10
    free = rng.random(start.size) < 0.8
    barrier = AreaBarrier(g.triangles, start, 0.9, 2.5, free)
    p = start + 1.5 * rng.standard_normal(start.shape)  # some triangles squeezed, some folded
    assert np.any(barrier.residuals(p) > 0)
    jac = barrier.jacobian(p).toarray()
    h = 1e-7
    fd = np.empty_like(jac)
    for col, k in enumerate(np.flatnonzero(free)):
        d = np.zeros(p.size)
        d[k] = h
        fd[:, col] = (barrier.residuals(p + d.reshape(p.shape)) - barrier.residuals(p - d.reshape(p.shape))) / (2 * h)
    np.testing.assert_allclose(jac, fd, atol=1e-5)


def test_without_uv_projection_start():
    g, x, f0 = run(dome(), 10, 10)
    f = flatten(x, g.triangles)
    assert f.start == "plane"
    assert f.energy == pytest.approx(f0.energy, rel=1e-6)
    assert np.all(orientations(f.points, g.triangles) > 0)


def test_degenerate_surface_is_rejected():
    net = np.zeros((2, 2, 3))
    net[1, :, 0] = 1.0  # the v = 0 and v = 1 edges coincide: every v-edge has zero length
    g = auxiliary_grid(4, 4)
    x = BezierSurface(net).evaluate(g.uv[:, 0], g.uv[:, 1])
    with pytest.raises(
        InvalidSurfaceError, match=r"points at \(u, v\) = \(0, 0\) and \(u, v\) = \(0, 0\.25\) coincide"
    ):
        flatten(x, g.triangles, uv=g.uv)
    with pytest.raises(InvalidSurfaceError, match="points of auxiliary nodes 0 and 1 coincide"):
        flatten(x, g.triangles)


def test_fine_grid_100_by_100_completes():
    """A 100 x 100 auxiliary grid (10 201 nodes, 30 100 edges); the time is printed, not asserted."""
    g = auxiliary_grid(100, 100)
    x = dome().evaluate(g.uv[:, 0], g.uv[:, 1])
    start = time.perf_counter()
    f = flatten(x, g.triangles, uv=g.uv, edges=g.edges)
    elapsed = time.perf_counter() - start
    print(f"\n100 x 100 flattening: {elapsed:.2f} s, E = {f.energy:.4g}, nfev = {f.nfev}")
    assert np.isfinite(f.energy)
    assert np.all(orientations(f.points, g.triangles) > 0)


_FLATTENINGS = textwrap.dedent("""
    import hashlib
    from equimesh.surface.auxiliary import auxiliary_grid
    from equimesh.surface.flatten import flatten
    from equimesh.testing.surfaces import dome
    g = auxiliary_grid(50, 50)
    x = dome().evaluate(g.uv[:, 0], g.uv[:, 1])
    for f in (flatten(x, g.triangles, uv=g.uv, edges=g.edges), flatten(x, g.triangles)):
        print(f.nfev, hashlib.sha256(f.points.tobytes()).hexdigest())
""")


@pytest.mark.parametrize("factorisation", INSTALLED)
def test_the_same_bits_whatever_the_blas_thread_count(factorisation):
    """Eq. (1) on a 50 x 50 grid, from the metric start and from the plane projection, is the same bits with
    ``OPENBLAS_NUM_THREADS`` 1 and 2 (scipy's solver and the starts' least-squares fits by LAPACK differed by 2e-4)."""
    outputs = outputs_with_one_and_two_threads(_FLATTENINGS, factorisation)
    assert outputs[0] == outputs[1] and int(outputs[0].split()[0]) > 0


def _folded_fan():
    """A flat fan of four triangles around node 4, put beyond the corners 0, 1 and 2 of the square: triangles 0 and 1
    are clockwise.  Its own points are a flattening of zero energy, so every start ends folded."""
    uv = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [2.0, -1.0]])
    return np.column_stack([uv, np.zeros(5)]), np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]), uv


@pytest.mark.parametrize("area_floor", [0.1, 0.0])
def test_a_folded_flattening_is_refused_naming_the_first_folded_triangle(area_floor):
    x, triangles, uv = _folded_fan()
    with pytest.raises(
        InvalidSurfaceError,
        match=r"^flattening folds 2 of 4 auxiliary triangles over, first near \(u, v\) = \(1, -0\.333333\); the "
        r"surface is degenerate or too strongly curved for this grid$",
    ):
        flatten(x, triangles, uv=uv, area_floor=area_floor)
    with pytest.raises(InvalidSurfaceError, match=r"^flattening folds 2 of 4 auxiliary triangles over; the surface"):
        flatten(x, triangles, area_floor=area_floor)


def test_a_retry_counts_the_evaluations_of_both_starts():
    g, x, f = run(dome(), 6, 6)
    retried = flatten(x, g.triangles, uv=g.uv, edges=g.edges, x0=g.uv * [-60.0, 60.0])
    assert retried.start == "metric" and retried.nfev > f.nfev
    np.testing.assert_array_equal(retried.points, f.points)


def test_edge_lengths_2_to_the_26_apart_are_flattened_and_further_apart_refused_naming_both():
    edges = np.array([[0, 1], [1, 2], [2, 3]])
    points = np.arange(12.0).reshape(4, 3)
    uv = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    check_edge_lengths(np.array([2.0, 1.0, 2.0**26]), edges, points, uv)
    lengths = np.array([2.0, 1.0, 2.0**27])
    with pytest.raises(
        InvalidSurfaceError,
        match=r"^the auxiliary triangulation samples the surface too unevenly to flatten by eq\. \(1\): its edge "
        r"from \(u, v\) = \(1, 0\) to \(u, v\) = \(1, 1\) is 1 long on the surface, 1\.3e\+08 times shorter than the "
        r"one from \(u, v\) = \(1, 1\) to \(u, v\) = \(0, 1\) \(1\.34218e\+08\), beyond the 6\.7e\+07 that floating "
        r"point resolves; .*give a mesh of it\)$",
    ):
        check_edge_lengths(lengths, edges, points, uv)
    with pytest.raises(
        InvalidSurfaceError,
        match=r"its edge from node 1 at \(3, 4, 5\) to node 2 at \(6, 7, 8\) is 1 long .* than the one from node 2 at "
        r"\(6, 7, 8\) to node 3 at \(9, 10, 11\) \(1\.34218e\+08\)",
    ):
        check_edge_lengths(lengths, edges, points)


def test_flatten_refuses_edges_too_far_apart_before_solving():
    """A node of a 2 x 1 grid 1e-9 from its neighbour: refused by the check of the lengths, not by the solver."""
    g = auxiliary_grid(2, 1)
    x = np.column_stack([g.uv, np.zeros(len(g.uv))])
    x[g.node(1, 0)] = x[g.node(0, 0)] + [1e-9, 0.0, 0.0]
    with pytest.raises(
        InvalidSurfaceError, match=r"^the auxiliary triangulation .* its edge from \(u, v\) = \(0, 0\) to"
    ):
        flatten(x, g.triangles, uv=g.uv)
    with pytest.raises(
        InvalidSurfaceError, match=r"^the auxiliary triangulation .* its edge from node 0 at \(0, 0, 0\) to"
    ):
        flatten(x, g.triangles)


def test_the_gauge_is_the_first_edge_given_whichever_nodes_it_joins():
    """The edges in reverse order: the gauge is their first edge, g0 at the origin and g1 on the positive x-axis,
    and the flattening is the same up to that rigid motion."""
    g, x, f = run(dome(), 6, 7)
    edges = g.edges[::-1]
    r = flatten(x, g.triangles, uv=g.uv, edges=edges)
    a, b = r.gauge
    assert [a, b] == edges[0].tolist() and a > 0
    assert np.array_equal(r.points[a], [0.0, 0.0]) and r.points[b, 1] == 0.0 and r.points[b, 0] > 0
    np.testing.assert_allclose(r.energy, f.energy, rtol=1e-9)
    np.testing.assert_allclose(edge_lengths(r.points, g.edges), edge_lengths(f.points, g.edges), rtol=1e-9)


@pytest.mark.parametrize("mirrored", [False, True])
def test_plane_start_is_the_plane_itself_for_a_planar_patch_counter_clockwise(mirrored):
    """A sheared grid on a tilted plane far from the origin (and its mirror image): the projection is congruent to
    it, centred at its centroid, and every triangle is counter-clockwise."""
    g = auxiliary_grid(3, 4)
    frame = (
        np.array([[0.6, 0.0, 0.8], [0.3, 0.9, -0.3]]) if not mirrored else np.array([[0.3, 0.9, -0.3], [0.6, 0, 0.8]])
    )
    x = (g.uv @ [[0.2, 0.0], [0.07, 0.15]]) @ frame + [100.0, -50.0, 20.0]  # of area about 0.03
    p = plane_start(x, g.triangles)
    np.testing.assert_allclose(p.mean(axis=0), 0.0, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(p - p[0], axis=1), np.linalg.norm(x - x[0], axis=1), rtol=1e-12)
    assert np.all(orientations(p, g.triangles) > 0)


def test_the_metric_start_is_exact_on_an_affine_patch():
    """A sheared plane patch is an affine image of (u, v): the best constant metric is its own, and the start (no
    iteration) is already a flattening of zero energy."""
    g, x, f = run(flat_patch(shear=25.0), 4, 5, max_iterations=0)
    assert f.start == "metric" and f.energy < 1e-24


def _kite():
    """A 1 x 1 grid laid flat as a kite: edges 0-1 and 0-2 of length 1, the three others (0-3 the diagonal) of 4.

    The least-squares metric of its edges is indefinite (the diagonal is longer than the sum of the roots of the
    fitted metric along u and v), so the start is the isotropic one of the median stretch, 4 / sqrt(2)."""
    g = auxiliary_grid(1, 1)
    h = np.sqrt(63.0) / 8.0
    return g, np.array([[0.0, 0.0, 0.0], [1 / 8, h, 0.0], [1 / 8, -h, 0.0], [4.0, 0.0, 0.0]])


def test_without_a_constant_metric_the_start_is_the_median_stretch_and_flattens():
    g, x = _kite()
    start = flatten(x, g.triangles, uv=g.uv, max_iterations=0)
    side = 2.0 * np.sqrt(2.0)  # the square of side 2 sqrt(2), node 0 -> node 1 along +x
    np.testing.assert_allclose(start.points, [[0.0, 0.0], [side, 0.0], [0.0, -side], [side, -side]], atol=1e-12)
    f = flatten(x, g.triangles, uv=g.uv)
    assert f.start == "metric" and f.energy < 1e-24
    np.testing.assert_allclose(f.plane_lengths, [1.0, 1.0, 4.0, 4.0, 4.0], rtol=1e-12)


def test_single_precision_points_and_32_bit_indices_flatten_to_the_same_bytes():
    """Eq. (1) is solved in double precision on 64-bit indices whatever the caller's arrays hold: the same bytes
    from the plane projection start (no uv), from the metric start of single-precision (u, v) and from a
    single-precision start of the caller's, as from the double-precision, 64-bit copies of the same values."""
    g = auxiliary_grid(5, 6)
    x = dome().evaluate(g.uv[:, 0], g.uv[:, 1]).astype(np.float32)
    single = flatten(x, g.triangles.astype(np.int32), edges=g.edges.astype(np.int32))
    double = flatten(x.astype(float), g.triangles.astype(np.int64), edges=g.edges.astype(np.int64))
    assert single.points.tobytes() == double.points.tobytes() and single.edges.tobytes() == double.edges.tobytes()
    uv = g.uv.astype(np.float32)
    on_uv = flatten(x, g.triangles, uv=uv, max_iterations=0)  # the metric start
    assert on_uv.points.tobytes() == flatten(x, g.triangles, uv=uv.astype(float), max_iterations=0).points.tobytes()
    start = (g.uv * 40.0).astype(np.float32)
    given = flatten(x, g.triangles, x0=start)
    assert (
        given.start == "given"
        and given.points.tobytes() == flatten(x, g.triangles, x0=start.astype(float)).points.tobytes()
    )


def test_the_first_pair_of_coinciding_nodes_is_named():
    """A fan of short edges (all below 1) whose inner node 4 sits on corner 2: edge 2-4, not the first edge, named."""
    x = np.array([[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.1, 0.1, 0.0], [0.0, 0.1, 0.0], [0.1, 0.1, 0.0]])
    triangles = np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]])
    uv = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]])
    with pytest.raises(InvalidSurfaceError, match=r"^the surface points of auxiliary nodes 2 and 4 coincide"):
        flatten(x, triangles)
    with pytest.raises(InvalidSurfaceError, match=r"points at \(u, v\) = \(1, 1\) and \(u, v\) = \(0\.5, 0\.5\) coin"):
        flatten(x, triangles, uv=uv)


@pytest.mark.parametrize("tolerance", ["ftol", "xtol", "gtol"])
def test_a_loose_tolerance_reaches_the_solver_and_stops_it_earlier(tolerance):
    g, x, f = run(dome(), 6, 6)
    loose = flatten(x, g.triangles, uv=g.uv, edges=g.edges, **{tolerance: 1e-3})
    assert loose.nfev < f.nfev and loose.energy >= f.energy


def test_a_solve_without_iterations_evaluates_eq_1_once_at_the_start():
    g, x, f = run(dome(), 6, 6, max_iterations=0)
    assert f.nfev == 1 and f.energy > 0


@pytest.mark.parametrize("with_uv", [False, True])
def test_a_flat_triangle_in_the_flattening_is_refused_as_folded(with_uv):
    """The inner node of a planar fan on side 0-1: its own points are a flattening of zero energy, with triangle 0
    of zero area, which keeps no orientation; the three others are counter-clockwise."""
    x = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [0.5, 0.0, 0.0]])
    triangles = np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]])
    near = r", first near \(u, v\) = \(0\.5, 0\)" if with_uv else ""
    with pytest.raises(InvalidSurfaceError, match=rf"^flattening folds 1 of 4 auxiliary triangles over{near}; the"):
        flatten(x, triangles, uv=x[:, :2] if with_uv else None)
