"""NURBS surfaces: evaluation and exact rational derivatives against an independent evaluator, validation, meshing."""

import json

import numpy as np
import pytest
from chart_checks import assert_derivatives_consistent
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from test_io import assert_one_line
from test_pipeline import assert_valid_surface_mesh

import equimesh
from equimesh import BezierSurface, InvalidSurfaceError, NurbsSurface
from equimesh.io import surface_from_dict, surface_to_dict

geomdl = pytest.importorskip("geomdl", reason="geomdl (the independent NURBS evaluator) is a test dependency")
from geomdl import NURBS  # noqa: E402


@st.composite
def nurbs(draw):
    """A NURBS surface of degrees 1..4 with distinct or repeated interior knots (at most p times), clamped or not."""
    parts = []
    for _ in range(2):
        p = draw(st.integers(1, 4))
        n = draw(st.integers(p + 1, p + 4))
        inner = sorted(draw(st.lists(st.integers(1, 9), min_size=n - p - 1, max_size=n - p - 1)))
        if any(inner.count(k) > p for k in inner):
            inner = sorted(set(inner)) + [10 + k for k in range(n - p - 1 - len(set(inner)))]
        clamped = draw(st.booleans())
        ends = ([0] * (p + 1), [20] * (p + 1)) if clamped else (list(range(-p, 1)), list(range(20, 21 + p)))
        parts.append((p, n, np.array(ends[0] + inner + ends[1], dtype=float) / 20.0))
    (p, nu, ku), (q, nv, kv) = parts
    net = draw(arrays(float, (nu, nv, 3), elements=st.floats(-10, 10)))
    weights = draw(arrays(float, (nu, nv), elements=st.floats(0.2, 5.0)))
    return NurbsSurface((p, q), ku, kv, net, weights)


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


def cylinder(radius=10.0, height=20.0):
    """Half a circular cylinder of the given radius: two rational quadratic quarter circles times a line."""
    r, w = radius, np.sqrt(0.5)
    arc = np.array([[r, 0], [r, r], [0, r], [-r, r], [-r, 0]], dtype=float)
    net = np.zeros((5, 2, 3))
    net[..., 0], net[..., 2] = arc[:, :1], arc[:, 1:]
    net[:, 1, 1] = height
    weights = np.repeat(np.array([1, w, 1, w, 1])[:, None], 2, axis=1)
    return NurbsSurface((2, 1), [0, 0, 0, 0.5, 0.5, 1, 1, 1], [0, 0, 1, 1], net, weights)


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
    from pathlib import Path

    path = Path(__file__).resolve().parent.parent / "experiments" / "surfaces" / "nurbs_roof.json"
    surface = equimesh.load_surface(path)
    assert isinstance(surface, NurbsSurface)
    mesh = equimesh.mesh_surface(surface, 4.0, grid=(10, 10), optimize="none")
    assert_valid_surface_mesh(mesh, surface)
    planar = mesh.stages.plane.edge_lengths()
    assert planar.min() >= (1 - 1e-9) * 4.0 and planar.max() <= 2 * (1 + 1e-9) * 4.0


def good():
    return {
        "type": "nurbs",
        "degree": [2, 1],
        "knots_u": [0, 0, 0, 0.5, 1, 1, 1],
        "knots_v": [0, 0, 1, 1],
        "control_points": [[[i, j, (i - 1.5) ** 2], [i, j + 5, 0]] for i, j in zip(range(4), range(4))],
        "weights": [[1, 1], [0.5, 2], [1, 1], [3, 1]],
    }


def test_json_round_trip():
    s = surface_from_dict(json.loads(json.dumps(good())))
    assert isinstance(s, NurbsSurface) and s.domain.u == (0.0, 1.0)
    again = surface_from_dict(json.loads(json.dumps(surface_to_dict(s))))
    uv = np.random.default_rng(0).uniform(0, 1, (5, 2))
    assert np.array_equal(again.evaluate(*uv.T), s.evaluate(*uv.T))


def _with(**fields):
    return lambda d: {**d, **fields}


@pytest.mark.parametrize(
    "mutate, fragment",
    [
        (_with(degree=[0, 1]), "degree[0] must be at least 1, got 0"),
        (_with(degree=[2, 1.5]), "degree[1] must be an integer, got number 1.5"),
        (_with(degree=[2]), '"degree" needs at least 2 integers [p, q], got 1'),
        (_with(degree=[2, 1, 1]), '"degree" must be a list of 2 integers [p, q], got 3 entries'),
        (
            _with(knots_u=[0, 0, 0, 0.5, 0.4, 1, 1]),
            "knots_u must be non-decreasing, but knots_u[4] = 0.4 < knots_u[3] = 0.5",
        ),
        (_with(knots_u=[0, 0, 0, 1, 1, 1]), "knots_u must hold 7 knots (4 control points + degree 2 + 1), got 6"),
        (_with(knots_v=[0, 0, 1, "x"]), "knots_v[3] must be a real number, got string"),
        (_with(knots_v=[0, 0, 0, 0]), "knots_v spans no domain: knots_v[1] = knots_v[2] = 0.0"),
        (
            _with(knots_u=[0, 0, 0.5, 0.5, 1, 1], degree=[1, 1]),
            "knots_u repeats 0.5 2 times inside the domain, more than the degree 1",
        ),
        (_with(weights=[[1, 1], [0.5, 0], [1, 1], [3, 1]]), "weights[1][1] must be positive, got 0.0"),
        (_with(weights=[[1, 1], [0.5, -2], [1, 1], [3, 1]]), "weights[1][1] must be positive, got -2.0"),
        (_with(weights=[[1, 1], [0.5, 2], [1, 1]]), "weights must have shape (4, 2) like the control net, got (3, 2)"),
        (_with(weights=[[1, 1], [0.5], [1, 1], [3, 1]]), "weights[1] has 1 weights, but weights[0] has 2"),
        (_with(weights=[[1, 1], [0.5, float("nan")], [1, 1], [3, 1]]), "weights[1][1] is not a finite number: nan"),
        (_with(degree=[4, 1]), "control_points must have shape (n_u, n_v, 3) with n_u >= p + 1 = 5"),
        (
            _with(control_points=[[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1]]]),
            "control_points[1][1] must be a list [x, y, z]",
        ),
        (lambda d: {k: v for k, v in d.items() if k != "weights"}, 'missing the field "weights"'),
    ],
)
def test_bad_nurbs_are_refused_in_one_line_naming_the_field(mutate, fragment):
    with pytest.raises(InvalidSurfaceError) as err:
        surface_from_dict(mutate(good()))
    assert fragment in str(err.value)
    assert_one_line(str(err.value))
