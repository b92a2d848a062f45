"""The sparse bounded Levenberg-Marquardt solver of the final optimisation (surface/_solver.py)."""

import numpy as np
import scipy.optimize
import scipy.sparse
from hypothesis import given, settings
from hypothesis import strategies as st

from equimesh.surface._solver import least_squares


@settings(max_examples=15, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(5, 40), st.floats(0.05, 1.0))
def test_linear_box_problem_matches_lsq_linear(seed, n, box):
    """On ``min |A x - b|^2 / 2`` over a box, the solver ends at scipy's lsq_linear optimum."""
    rng = np.random.default_rng(seed)
    a = scipy.sparse.random(2 * n, n, density=0.2, random_state=rng) + scipy.sparse.eye(2 * n, n)
    a = a.tocsr()
    b = 3.0 * rng.standard_normal(2 * n)
    lower, upper = np.full(n, -box), np.full(n, box)
    solution = least_squares(lambda x: a @ x - b, lambda x: a, np.zeros(n), lower, upper, ftol=1e-15)
    assert solution.converged, solution.message
    best = scipy.optimize.lsq_linear(a.toarray(), b, bounds=(lower, upper), tol=1e-14)
    assert solution.cost <= best.cost + 1e-9 * (1.0 + best.cost)
    assert np.all((solution.x >= lower) & (solution.x <= upper))


def test_rejected_steps_and_bounds_on_rosenbrock():
    """A nonlinear problem that needs rejected steps (retries) ends at its known minimum (1, 1), bit-identically twice."""

    def residuals(x):
        return np.array([10.0 * (x[1] - x[0] ** 2), 1.0 - x[0]])

    def jacobian(x):
        return scipy.sparse.csr_matrix(np.array([[-20.0 * x[0], 10.0], [-1.0, 0.0]]))

    runs = [least_squares(residuals, jacobian, np.array([-1.2, 1.0]), np.full(2, -2.0), np.full(2, 2.0)) for _ in range(2)]
    assert runs[0].converged and runs[0].evaluations > runs[0].iterations + 1  # some steps were rejected
    np.testing.assert_allclose(runs[0].x, [1.0, 1.0], atol=1e-6)
    assert np.array_equal(runs[0].x, runs[1].x)
