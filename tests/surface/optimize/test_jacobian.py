"""Sparse Jacobians of per-element residuals and the fold-over barrier (``surface/optimize/jacobian.py``)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from equimesh.surface.optimize.jacobian import AreaBarrier, ElementJacobian, signed_areas


def dense_jacobian(elements, n_nodes, dim, free, grads):
    """``d r_j / d x`` written out: the corner ``c`` of element ``j`` adds ``grads[j, c dim + d]`` to the column of
    its node's coordinate ``d``, the fixed columns dropped."""
    dense = np.zeros((len(elements), dim * n_nodes))
    for j, element in enumerate(elements):
        for c, node in enumerate(element):
            dense[j, dim * node : dim * node + dim] += grads[j, dim * c : dim * c + dim]
    return dense[:, free]


@settings(max_examples=30, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n_nodes=st.integers(1, 8),
    n_elements=st.integers(1, 12),
    k=st.integers(2, 3),
    dim=st.integers(1, 3),
    all_free=st.booleans(),
)
def test_element_jacobian_is_the_derivative_over_the_free_entries(seed, n_nodes, n_elements, k, dim, all_free):
    """Each corner's gradient lands in its node's columns, in the order of the free entries (a node may be a corner
    twice: summed); the gradients side by side or one array per corner give the same matrix."""
    rng = np.random.default_rng(seed)
    elements = rng.integers(0, n_nodes, (n_elements, k))
    free = np.ones(dim * n_nodes, dtype=bool) if all_free else rng.random(dim * n_nodes) < 0.6
    grads = rng.standard_normal((n_elements, k * dim))
    assemble = ElementJacobian(elements.tolist(), n_nodes, dim, None if all_free else free)
    expected = dense_jacobian(elements, n_nodes, dim, free, grads)
    jac = assemble(grads)
    assert jac.format == "csr" and jac.shape == expected.shape == (n_elements, int(free.sum()))
    np.testing.assert_array_equal(jac.toarray(), expected)
    corners = [grads[:, dim * c : dim * c + dim] for c in range(k)]
    np.testing.assert_array_equal(assemble(*corners).toarray(), expected)


def test_element_jacobian_keeps_its_structure_and_the_first_column():
    """The structure is the elements' whatever the values (zeros are stored), and node 0's first coordinate is
    the first column."""
    assemble = ElementJacobian([[0, 1], [1, 2]], 3, 2, [True, False, True, True, False, True])
    jac = assemble(np.zeros((2, 4)))
    assert jac.shape == (2, 4) and jac.nnz == 6
    np.testing.assert_array_equal(jac.indptr, [0, 3, 6])
    np.testing.assert_array_equal(jac.indices, [0, 1, 2, 1, 2, 3])
    values = assemble(np.array([[1.0, 2.0, 3.0, 4.0], [5.0, 6.0, 7.0, 8.0]])).toarray()
    np.testing.assert_array_equal(values, [[1.0, 3.0, 4.0, 0.0], [0.0, 5.0, 6.0, 8.0]])


def test_signed_areas_are_positive_counter_clockwise():
    points = np.array([[0.0, 0.0], [2.0, 0.0], [0.0, 3.0], [5.0, 5.0]])
    np.testing.assert_array_equal(signed_areas(points, [[0, 1, 2], [0, 2, 1], [1, 3, 2]]), [3.0, -3.0, 9.5])


#: Two counter-clockwise triangles of area 2, a degenerate one, a clockwise one and a counter-clockwise one of area 1,
#: over five points.
START = np.array([[0.0, 0.0], [2.0, 0.0], [0.0, 2.0], [2.0, 2.0], [1.0, 1.0]])
TRIANGLES = [[0, 1, 2], [1, 3, 2], [0, 4, 3], [0, 2, 1], [0, 1, 4]]


def finite_difference(fun, x, h=1e-7):
    columns = []
    for k in range(x.size):
        d = np.zeros(x.size)
        d[k] = h
        columns.append((fun(x + d.reshape(x.shape)) - fun(x - d.reshape(x.shape))) / (2 * h))
    return np.column_stack(columns)


def test_barrier_ignores_triangles_without_area_at_the_start():
    """Degenerate and clockwise triangles are dropped; by default the residuals are linear in the depth (``p = 1``)."""
    barrier = AreaBarrier(TRIANGLES, START.astype(int).tolist(), 0.5, 3.0)
    np.testing.assert_array_equal(barrier.triangles, [[0, 1, 2], [1, 3, 2], [0, 1, 4]])
    np.testing.assert_array_equal(barrier.residuals(START), [0.0, 0.0, 0.0])
    np.testing.assert_array_equal(barrier.residuals(0.25 * START), [3.0 * 0.875] * 3)  # 1/16 of the area, floor 1/2


@pytest.mark.parametrize("power", [1, 2])
def test_barrier_residuals_grow_below_the_floor(power):
    """``w max(0, 1 - A / (tau A0))^p``: zero down to ``tau`` of the start area (at it too), then growing; a folded
    triangle costs at least ``w^2 / 2``."""
    barrier = AreaBarrier(np.ravel(TRIANGLES[:2]), START, 0.25, 3.0, power=power)
    np.testing.assert_array_equal(barrier.residuals(0.5 * START), [0.0, 0.0])  # exactly a quarter of the area
    squeezed = 0.25 * START  # a sixteenth: 1 - 1/4 below the floor
    np.testing.assert_array_equal(barrier.residuals(squeezed), [3.0 * 0.75**power] * 2)
    folded = START * [1.0, -1.0]
    np.testing.assert_array_equal(barrier.residuals(folded), [3.0 * 5.0**power] * 2)
    assert 0.5 * np.sum(barrier.residuals(folded) ** 2) >= 0.5 * 3.0**2


@pytest.mark.parametrize("power", [1, 2])
def test_barrier_jacobian_matches_finite_differences(power):
    """Over the free coordinates only; zero where the barrier is inactive, including at the floor itself."""
    free = np.array([True, True, False, True, True, True, True, False, True, True])
    barrier = AreaBarrier(TRIANGLES, START, 0.5, 2.5, free, power=power)
    x = START.copy()
    x[3] = [1.2, 1.5]  # the second triangle below its floor, the first above
    jac = barrier.jacobian(x.tolist())
    assert jac.shape == (3, free.sum())
    assert np.all(jac.toarray()[[0, 2]] == 0.0) and np.any(jac.toarray()[1] != 0.0)
    np.testing.assert_allclose(jac.toarray(), finite_difference(barrier.residuals, x)[:, free], atol=1e-6)
    at_floor = AreaBarrier(TRIANGLES, START, 0.25, 2.5, free, power=power).jacobian(0.5 * START)
    assert at_floor.shape == (3, free.sum()) and at_floor.nnz == 14 and np.all(at_floor.toarray() == 0.0)


def test_barrier_jacobian_of_every_corner():
    """``dA / dp_k = perp(p_{k+2} - p_{k+1}) / 2``, scaled by ``-w p depth^(p-1) / (tau A0)``: the unit right
    triangle at half its floor."""
    start = np.array([[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]])
    barrier = AreaBarrier([[0, 1, 2]], start, 1.0, 4.0, power=2)
    x = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])  # area 1/2 of a floor of 2: depth 3/4
    scale = -4.0 * 2 * 0.75 / 2.0
    expected = scale * 0.5 * np.array([[-1.0, -1.0, 1.0, 0.0, 0.0, 1.0]])
    np.testing.assert_array_equal(barrier.jacobian(x).toarray(), expected)


def test_weighted_barrier_shares_all_but_the_weight():
    barrier = AreaBarrier(TRIANGLES, START, 0.5, 2.0, power=2)
    heavier = barrier.weighted(6)
    squeezed = 0.5 * START
    np.testing.assert_array_equal(heavier.residuals(squeezed), 3.0 * barrier.residuals(squeezed))
    np.testing.assert_array_equal(heavier.jacobian(squeezed).toarray(), 3.0 * barrier.jacobian(squeezed).toarray())
    assert barrier.residuals(squeezed)[0] == 2.0 * 0.5**2  # the original keeps its weight
    assert heavier.triangles is barrier.triangles
