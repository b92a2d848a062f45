"""The members of a final optimisation (``surface/optimize/members.py``): lengths, the band [l, 2l], residuals.

What must hold: the lengths are the members' lengths on the surface (or off it, with offsets) at the variables
asked for, however the caller reuses its arrays, and their Jacobian is their derivative (a member of length zero
has none); the band [l, 2l] holds up to ``REL_TOL`` and no further (the check fires just outside it, naming the
members out); members outside ``[target, high]`` are pulled to the nearer end; the weighted residuals and their
Jacobian are ``weight (L / l - goal)`` and its derivative, with extra terms after them.  On the tiny grids of
``optimize_cases``.
"""

from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse
from optimize_cases import RIM, finite_difference, moved, problem

from equimesh.mesh import edge_lengths
from equimesh.surface.optimize.members import Members, cauchy, edge_length_terms, out_of_reach, scale_rows, short_share
from equimesh.tolerance import BOUNDED_OFFSET, BOUNDED_PENALTY, BOUNDED_PULL, REL_TOL


def test_lengths_on_the_flat_grid_by_hand():
    """The flat grid's members are 10 (grid edges) and 10 sqrt(2) (diagonals) long."""
    p, _ = problem(rise=0.0)
    lengths, jacobian = edge_length_terms(p, p.edges)
    expected = np.where(p.edge_groups == 1, 10.0, 10.0 * np.sqrt(2.0))
    np.testing.assert_allclose(lengths(p.x0), expected, rtol=1e-14)
    got, jac = jacobian(p.x0)
    assert np.array_equal(got, lengths(p.x0)) and jac.shape == (len(p.edges), len(p.x0))


@pytest.mark.parametrize(
    "slides, tolerance, offset",
    [(False, 0.0, 0.0), (True, 0.0, 0.0), (True, 0.8, 0.6)],
    ids=["inner", "sliding", "off"],
)
def test_the_length_jacobian_is_its_derivative(slides, tolerance, offset):
    """Inner nodes free; the rim sliding along the square; every moving node off the surface (with the normal's
    own derivative)."""
    p, _ = problem(seed=2, slides=slides, surface_tolerance=tolerance)
    x = moved(p, 5, offset=offset)
    lengths, jacobian = edge_length_terms(p, p.edges)
    got, jac = jacobian(x)
    np.testing.assert_array_equal(got, edge_lengths(p.points_of(x), p.edges))
    np.testing.assert_allclose(jac.toarray(), finite_difference(lengths, x), atol=1e-6 * got.max())


def test_lengths_follow_the_variables_however_they_are_passed():
    """The lengths at one point then another, the Jacobian's at a third, and the first array changed in place:
    always the lengths at the values passed."""
    p, _ = problem(seed=4, surface_tolerance=0.5)
    lengths, jacobian = edge_length_terms(p, p.edges)

    def exact(x):
        return edge_lengths(p.points_of(x), p.edges)

    x, y, z = moved(p, 1, offset=0.3), moved(p, 2, offset=0.3), moved(p, 3, offset=0.3)
    for point in (x, y, x):
        np.testing.assert_array_equal(lengths(point), exact(point))
    np.testing.assert_array_equal(jacobian(z)[0], exact(z))
    np.testing.assert_allclose(jacobian(z)[1].toarray(), finite_difference(exact, z), atol=1e-5)
    w = z.copy()
    lengths(w)
    w[:2] += 0.01
    np.testing.assert_array_equal(lengths(w), exact(w))


def test_the_points_at_the_last_variables_are_computed_once():
    """The solver evaluates the Jacobian where it last evaluated the residuals, and a stage measures the lengths
    where its solve ended: the same point again takes the points and lengths kept, a new one computes them."""
    p, _ = problem(seed=4)
    calls = []

    class Counting(type(p)):
        def points_of(self, x):
            calls.append(np.array(x))
            return super().points_of(x)

    counting = Counting(**{f: getattr(p, f) for f in p.__dataclass_fields__})
    lengths, jacobian = edge_length_terms(counting, counting.edges)
    x, y = moved(p, 1), moved(p, 2)
    first = lengths(x)
    assert lengths(x) is first and jacobian(x)[0] is first and lengths(x.copy()) is first
    assert len(calls) == 1
    lengths(y)
    assert len(calls) == 2 and not np.array_equal(lengths(x), lengths(y)) and len(calls) == 4


def test_a_member_of_length_zero_has_no_gradient():
    """Two free nodes at one point: their member is 0 long, its Jacobian row zero (not NaN), on and off the
    surface."""
    for tolerance in (0.0, 0.5):
        p, _ = problem(surface_tolerance=tolerance)
        uv = p.uv.copy()
        uv[RIM + 1] = uv[RIM]
        edges = np.array([[RIM, RIM + 1], [RIM, RIM + 2]])
        p = type(p)(p.surface, uv, edges, np.ones(2, dtype=np.int8), p.length, p.free, surface_tolerance=tolerance)
        lengths, jac = edge_length_terms(p, edges)[1](p.x0)
        assert lengths[0] == 0.0 and lengths[1] > 0
        jac = jac.toarray()
        assert np.all(np.isfinite(jac)) and not np.any(jac[0]) and np.any(jac[1])


def test_the_band_holds_up_to_rel_tol_and_fires_beyond():
    """The check fires: a member a few REL_TOL below l or above 2l is outside; at the ends, or within REL_TOL
    of them, inside."""
    assert Members.inside(np.array([1.0, 1.5, 2.0]))
    assert Members.inside(np.array([1.0 - 0.5 * REL_TOL, 2.0 + 0.5 * REL_TOL]))
    assert not Members.inside(np.array([1.0 - 3 * REL_TOL, 1.5]))
    assert not Members.inside(np.array([1.5, 2.0 + 3 * REL_TOL]))


def test_feasible_and_the_violation_on_the_flat_grid():
    """With l = 8 the members are 1.25 l and 1.768 l long; with l = 6, 1.667 l and 2.357 l: the 9 diagonals
    are outside."""
    p, _ = problem(rise=0.0, length=8.0)
    members = Members(p)
    np.testing.assert_allclose(members.ratio(p.x0), members.lengths(p.x0) / 8.0)
    assert members.l == 8.0 and members.feasible(p.x0)
    assert members.violation(p.x0) == "0 of 33 members outside [l, 2l] (lengths from 1.25 l to 1.76777 l)"
    p, _ = problem(rise=0.0, length=6.0)
    members = Members(p)
    assert not members.feasible(p.x0)
    assert members.violation(p.x0) == "9 of 33 members outside [l, 2l] (lengths from 1.66667 l to 2.35702 l)"


def test_members_outside_the_targets_are_pulled_to_the_nearer_end():
    assert Members.target == 1.0 + BOUNDED_OFFSET and Members.high == 2.0 - BOUNDED_OFFSET
    ratio = np.array([0.9, 1.0 + BOUNDED_OFFSET, 1.5, 2.0 - BOUNDED_OFFSET, 1.9995, 2.2])
    weight, goal = Members(problem()[0]).pulled(ratio, np.array([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]), 1.25)
    np.testing.assert_array_equal(weight, [BOUNDED_PULL, 2.0, 3.0, 4.0, BOUNDED_PULL, BOUNDED_PULL])
    high = 2.0 - BOUNDED_OFFSET
    np.testing.assert_array_equal(goal, [1.0 + BOUNDED_OFFSET, 1.25, 1.25, 1.25, high, high])


@pytest.mark.parametrize("extra", [False, True], ids=["plain", "with extra terms"])
def test_weighted_residuals_and_their_jacobian(extra):
    """``weight (L / l - goal)`` per member, then the extra terms of ``L / l``; the Jacobian their derivative."""
    p, _ = problem(seed=6, slides=True)
    members = Members(p)
    x = moved(p, 8)
    rng = np.random.default_rng(9)
    weight, goal = rng.uniform(0.5, 2.0, len(p.edges)), rng.uniform(1.2, 1.8, len(p.edges))

    def cube(ratio):
        return ratio**3, 3 * ratio**2

    residuals, jacobian = members.weighted(weight, goal, cube if extra else None)
    ratio = edge_lengths(p.points_of(x), p.edges) / p.length
    expected = weight * (ratio - goal)
    np.testing.assert_allclose(residuals(x), np.concatenate([expected, ratio**3]) if extra else expected, rtol=1e-12)
    jac = jacobian(x)
    assert scipy.sparse.issparse(jac) and jac.format == "csr"
    np.testing.assert_allclose(jac.toarray(), finite_difference(residuals, x), atol=1e-6)


def test_the_weighted_jacobian_has_a_column_per_variable_of_a_node_no_member_touches_too():
    """The last free node's members dropped: its two variables move nothing, and the Jacobian still has their two
    (empty) columns, the shape the solver's normal equations are built for."""
    p, _ = problem(seed=6)
    last = len(p.uv) - 1
    p = replace(
        p, edges=p.edges[~np.any(p.edges == last, axis=1)], edge_groups=p.edge_groups[~np.any(p.edges == last, axis=1)]
    )
    members = Members(p)
    _, jacobian = members.weighted(np.ones(len(p.edges)), np.full(len(p.edges), 1.25))
    jac = jacobian(moved(p, 8))
    assert jac.shape == (len(p.edges), len(p.x0)) and jac[:, -2:].nnz == 0


def test_cauchy_weights_by_hand():
    np.testing.assert_allclose(cauchy(np.array([0.0, 3.0, -3.0, 1.0]), 4.0), [1.0, 0.8, 0.8, 1 / np.sqrt(1.0625)])


def test_scale_rows_keeps_the_structure():
    """``diag(scale) @ jac``, the entries of a row scaled by 0 kept (as zeros)."""
    jac = scipy.sparse.csr_matrix(np.array([[1.0, 0.0, 2.0, 0.0], [0.0, 3.0, 0.0, 0.0], [4.0, 5.0, 6.0, 0.0]]))
    scaled = scale_rows(np.array([2.0, 0.0, -1.0]), jac)  # the last column has no entries
    expected = [[2.0, 0.0, 4.0, 0.0], [0.0, 0.0, 0.0, 0.0], [-4.0, -5.0, -6.0, 0.0]]
    np.testing.assert_array_equal(scaled.toarray(), expected)
    assert scaled.nnz == jac.nnz and np.array_equal(scaled.indices, jac.indices) and scaled.shape == jac.shape


def test_a_start_is_out_of_reach_when_more_than_half_its_members_are_shorter_than_half_l():
    """Shorter than REACH_LENGTH = 0.5 l strictly, and more than REACH_SHARE = 0.5 of them strictly."""
    assert short_share(np.array([])) == 0.0
    assert short_share(np.array([0.4, 0.5, 0.6, 1.0])) == 0.25
    assert out_of_reach(np.array([0.4, 0.4, 0.6]))
    assert not out_of_reach(np.array([0.4, 0.6]))
    assert not out_of_reach(np.array([0.5, 0.5, 0.4]))


def test_the_reach_on_the_flat_grid():
    """With l = 21 the 24 sides (0.476 l) are shorter than l/2, the 9 diagonals (0.673 l) not; with l = 20 the sides
    are exactly l/2 and count as within reach."""
    p, _ = problem(rise=0.0, length=21.0)
    members = Members(p)
    assert out_of_reach(members.ratio(p.x0))
    assert members.reach(p.x0) == (
        "72.7273 % of its 33 members shorter than 0.5 l on the surface (the flattening stretched it), lengths from "
        "0.47619 l to 0.673435 l"
    )
    p, _ = problem(rise=0.0, length=20.0)
    assert short_share(Members(p).ratio(p.x0)) == 0.0


def test_the_band_penalty_by_hand():
    """The smoothed hinge: zero in [1 + BOUNDED_OFFSET / 2, high]; quadratic over the first BOUNDED_OFFSET / 4 of
    depth, linear of slope BOUNDED_PENALTY beyond; the slope signed towards the band, and the derivative of the
    value."""
    p, _ = problem(rise=0.0, length=8.0)
    members = Members(p)
    low, high, smooth = 1.0 + 0.5 * BOUNDED_OFFSET, members.high, 0.25 * BOUNDED_OFFSET
    ratio = np.array([low - 0.1, low - 0.5 * smooth, low, 1.5, high, high + 0.5 * smooth, high + 0.1])
    value, slope = members.band_penalty()(ratio)
    depth = np.array([0.1, 0.5 * smooth, 0.0, 0.0, 0.0, 0.5 * smooth, 0.1])
    psi = np.where(depth < smooth, depth**2 / (2 * smooth), depth - smooth / 2)
    np.testing.assert_allclose(value, BOUNDED_PENALTY * psi, rtol=1e-9, atol=1e-15)
    side = np.array([-1, -1, -1, -1, -1, 1, 1])
    np.testing.assert_allclose(slope, BOUNDED_PENALTY * np.minimum(depth / smooth, 1.0) * side, rtol=1e-9, atol=1e-12)
    h = 1e-9
    numeric = (members.band_penalty()(ratio + h)[0] - members.band_penalty()(ratio - h)[0]) / (2 * h)
    np.testing.assert_allclose(slope[[0, 1, 5, 6]], numeric[[0, 1, 5, 6]], rtol=1e-5)
