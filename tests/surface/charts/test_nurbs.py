"""NURBS surfaces: evaluation and exact rational derivatives against an independent evaluator, validation, meshing."""

import numpy as np
import pytest
from chart_checks import assert_derivatives_consistent
from geomdl import NURBS  # noqa: E402
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from repository import SURFACES
from strategies_nurbs import cylinder, nurbs
from surface_invariants import assert_valid_surface_mesh

import equimesh
from equimesh import BezierSurface, NurbsSurface

geomdl = pytest.importorskip("geomdl", reason="geomdl (the independent NURBS evaluator) is a test dependency")


def geomdl_surface(s):
    g = NURBS.Surface(normalize_kv=False)
    g.degree_u, g.degree_v = s.degree
    g.ctrlpts_size_u, g.ctrlpts_size_v = s.weights.shape
    g.ctrlpts = s.control_points.reshape(-1, 3).tolist()
    g.weights = s.weights.ravel().tolist()
    g.knotvector_u, g.knotvector_v = s.knots_u.tolist(), s.knots_v.tolist()
    return g


@settings(max_examples=30, deadline=None)
@given(s=nurbs(), fractions=st.lists(st.tuples(st.floats(0, 1), st.floats(0, 1)), min_size=1, max_size=4))
def test_matches_geomdl_with_first_and_second_derivatives(s, fractions):
    """X^s, (X_u, X_v) and (X_uu, X_uv, X_vv) equal geomdl's rational derivatives, domain ends and knots included."""
    g = geomdl_surface(s)
    uv = s.domain.at_fractions(*np.array(fractions).T)
    mine = [
        s.evaluate(uv[:, 0], uv[:, 1]),
        *s.derivatives(uv[:, 0], uv[:, 1]),
        *s.second_derivatives(uv[:, 0], uv[:, 1]),
    ]
    for k, (u, v) in enumerate(uv):
        d = np.array(g.derivatives(float(u), float(v), order=2))
        want = [d[0, 0], d[1, 0], d[0, 1], d[2, 0], d[1, 1], d[0, 2]]
        scale = np.abs(want).max() + np.abs(s.control_points).max()
        for order, (got, ref) in enumerate(zip(mine, want)):
            np.testing.assert_allclose(
                got[k], ref, rtol=0, atol=1e-11 * scale, err_msg=f"derivative {order} at {u}, {v}"
            )


@settings(max_examples=20, deadline=None)
@given(s=nurbs())
def test_derivatives_match_finite_differences(s):
    """The exact derivatives against differences, inside knot spans (where X^s is smooth)."""
    f = np.array([0.13, 0.37, 0.61, 0.83])
    uv = s.domain.at_fractions(*np.meshgrid(f, f)).reshape(-1, 2)
    off = [np.min(np.abs(uv[:, k, None] - knots), axis=1) > 1e-3 for k, knots in enumerate((s.knots_u, s.knots_v))]
    uv = uv[off[0] & off[1]]
    scale = (np.abs(s.control_points).max() + 1.0) * (s.weights.max() / s.weights.min()) ** 3 * 100
    assert_derivatives_consistent(s, uv[:, 0], uv[:, 1], atol=1e-5 * scale)


@settings(max_examples=20, deadline=None)
@given(m=st.integers(1, 5), n=st.integers(1, 5), data=st.data())
def test_bezier_knots_give_the_bezier_surface(m, n, data):
    """Knots [0]*(p+1) + [1]*(p+1) and unit weights: the NURBS is the Bezier surface of the same net."""
    net = data.draw(arrays(float, (m + 1, n + 1, 3), elements=st.floats(-10, 10)))
    s = NurbsSurface((m, n), [0.0] * (m + 1) + [1.0] * (m + 1), [0.0] * (n + 1) + [1.0] * (n + 1), net)
    b = BezierSurface(net)
    assert s.domain == b.domain
    uv = np.random.default_rng(m * 10 + n).uniform(0, 1, (9, 2))
    uv[:4] = [[0, 0], [1, 0], [0, 1], [1, 1]]
    for got, want in zip(
        [s.evaluate(*uv.T), *s.derivatives(*uv.T), *s.second_derivatives(*uv.T)],
        [b.evaluate(*uv.T), *b.derivatives(*uv.T), *b.second_derivatives(*uv.T)],
    ):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * 10 * 25 * 2**10)


def test_rational_quadratic_cylinder_is_an_exact_circle():
    u = np.linspace(0, 1, 101)
    p = cylinder().evaluate(u, 0.0 * u)
    np.testing.assert_allclose(np.hypot(p[:, 0], p[:, 2]), 10.0, rtol=0, atol=1e-13)


def test_cylinder_lattice_members_are_l_before_optimisation():
    """A developable surface: the G1 members come out l, up to chords for arcs and the grid's interpolation.

    Along the generators (straight lines of the surface) a member is exactly l.  A member whose
    developed length l crosses the curvature becomes a chord: it is at least ``2 R sin(l / 2R)``
    (the chord of an arc of length l, ``l (1 - l^2 / 24 R^2)``), and the remapping by the auxiliary
    grid adds an interpolation error that shrinks with the grid (measured: 4e-3 l with cells of
    12 degrees, 7e-4 l with cells of 3 degrees).
    """
    r, l = 10.0, 2.0
    surface = cylinder(r)
    mesh = equimesh.mesh_surface(surface, l, grid=(60, 2), optimize="none", placement="default")
    assert_valid_surface_mesh(mesh, surface)
    assert mesh.stages.flattening.energy < 1e-20  # the auxiliary cells are planar rectangles: eq. (1) is exact
    e = mesh.edges[mesh.g1_mask]
    d = mesh.points[e[:, 1]] - mesh.points[e[:, 0]]
    length = np.linalg.norm(d, axis=1)
    along = np.abs(d[:, 1]) > 0.99 * length
    assert 50 < along.sum() < len(e) / 2
    np.testing.assert_allclose(length[along], l, rtol=1e-12)
    chord = 2 * r * np.sin(l / (2 * r))
    assert np.all(length >= chord - 1e-3 * l) and np.all(length <= l + 1e-3 * l)


def test_doubly_curved_example_meshes(tmp_path):
    """The NURBS example of experiments/surfaces (non-uniform knots and weights) through load_surface."""

    path = SURFACES / "nurbs_roof.json"
    surface = equimesh.load_surface(path)
    assert isinstance(surface, NurbsSurface)
    mesh = equimesh.mesh_surface(surface, 4.0, grid=(10, 10), optimize="none")
    assert_valid_surface_mesh(mesh, surface)
    planar = mesh.stages.plane.edge_lengths()
    assert planar.min() >= (1 - 1e-9) * 4.0 and planar.max() <= 2 * (1 + 1e-9) * 4.0
