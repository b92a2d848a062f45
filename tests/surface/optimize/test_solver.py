"""The sparse bounded Levenberg-Marquardt solver of the final optimisation (surface/_solver.py)."""

import os
import subprocess
import sys
import types
from pathlib import Path

import numpy as np
import pytest
import scipy.optimize
import scipy.sparse
import scipy.sparse.linalg
from hypothesis import given, settings
from hypothesis import strategies as st

from equimesh.errors import EquimeshError
from equimesh.surface.optimize import cores
from equimesh.surface.optimize import solver as _solver
from equimesh.surface.optimize.ordering import DISSECT_FROM, nested_dissection
from equimesh.surface.optimize.solver import FACTORISATIONS, INSTALLED, NormalEquations, least_squares

#: The optional extra that installs each factorisation's library.
EXTRAS = {"cholmod": "fast: cvxopt", "pardiso": "mkl: pypardiso"}


def _available(name):
    """``name`` as a pytest parameter, skipped where its optional dependency is not installed."""
    missing = name not in INSTALLED
    return pytest.param(name, marks=pytest.mark.skipif(missing, reason=f"extra {EXTRAS.get(name)} not installed"))


BOTH = [_available(name) for name in sorted(FACTORISATIONS)]


@pytest.mark.parametrize("factorisation", BOTH)
@settings(max_examples=15, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(5, 40), st.floats(0.05, 1.0))
def test_linear_box_problem_matches_lsq_linear(factorisation, seed, n, box):
    """On ``min |A x - b|^2 / 2`` over a box, the solver ends at scipy's lsq_linear optimum, with either
    factorisation."""
    rng = np.random.default_rng(seed)
    a = scipy.sparse.random(2 * n, n, density=0.2, random_state=rng) + scipy.sparse.eye(2 * n, n)
    a = a.tocsr()
    b = 3.0 * rng.standard_normal(2 * n)
    lower, upper = np.full(n, -box), np.full(n, box)
    solution = least_squares(
        lambda x: a @ x - b,
        lambda x: a,
        np.zeros(n),
        lower,
        upper,
        ftol=1e-15,
        normal_equations=NormalEquations(factorisation),
    )
    assert solution.converged, solution.message
    best = scipy.optimize.lsq_linear(a.toarray(), b, bounds=(lower, upper), tol=1e-14)
    assert solution.cost <= best.cost + 1e-9 * (1.0 + best.cost)
    assert np.all((solution.x >= lower) & (solution.x <= upper))


@pytest.mark.parametrize("factorisation", BOTH)
@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 30), st.integers(1, 60), st.floats(1e-6, 10.0))
def test_normal_equations_solve_the_damped_system(factorisation, seed, n, m, lam):
    """``solve`` solves ``(J^T J + lam D) s = b`` on the free variables (backward error) and gives 0 on the held ones.

    ``D`` is ``diag(J^T J)`` floored at ``LM_DIAGONAL_FLOOR`` of its largest
    entry; the rows of ``J`` have different numbers of entries and some are
    all zero (an inactive barrier row), as in the optimisation; some have a
    column twice (summed).
    """
    rng = np.random.default_rng(seed)
    dense = rng.standard_normal((m, n)) * (rng.random((m, n)) < 0.4)
    dense[rng.random(m) < 0.2] = 0.0
    jac = scipy.sparse.csr_matrix(dense)
    jac.data[rng.random(jac.nnz) < 0.1] = 0.0  # stored zeros keep the structure
    if seed % 2:  # some entries given as two halves (duplicates, summed)
        coo, split = jac.tocoo(), rng.random(jac.nnz) < 0.3
        rows = np.concatenate([coo.row, coo.row[split]])
        by_row = np.argsort(rows, kind="stable")
        data = np.concatenate([np.where(split, 0.5, 1.0) * coo.data, 0.5 * coo.data[split]])[by_row]
        cols = np.concatenate([coo.col, coo.col[split]])[by_row]
        indptr = np.concatenate([[0], np.cumsum(np.bincount(rows, minlength=m))])
        jac = scipy.sparse.csr_matrix((data, cols, indptr), shape=(m, n))
    held = rng.random(n) < 0.2
    rhs = rng.standard_normal(n)
    system = NormalEquations(factorisation)
    system.assemble(jac, held)
    step = system.solve(lam, np.where(held, 0.0, rhs))
    normal = jac.toarray().T @ jac.toarray()
    diagonal = np.maximum(np.diag(normal), _solver.LM_DIAGONAL_FLOOR * max(np.diag(normal).max(), 1.0))
    free = ~held
    matrix = (normal + lam * np.diag(diagonal))[np.ix_(free, free)]
    assert np.all(step[held] == 0.0)
    error = np.abs(matrix @ step[free] - rhs[free]).max(initial=0.0)
    assert error <= 1e-9 * (np.abs(matrix).sum(axis=1).max(initial=0.0) * np.abs(step).max() + np.abs(rhs).max())


def test_a_rejected_step_is_halved_with_the_same_factor(monkeypatch):
    """``r(x) = atan(x)`` from x = 1.5: the Gauss-Newton step overshoots to -1.68, and its half is taken.

    Lines search before damping (Nocedal and Wright 10.3): one factorisation
    per iteration, more evaluations than iterations, and a step halved far
    enough to satisfy ``accept`` (here ``x >= -0.05``) is taken too.
    """
    factorised = []

    class Counting(FACTORISATIONS["superlu"]):
        def factorise(self, values):
            factorised.append(values)
            return super().factorise(values)

    monkeypatch.setitem(FACTORISATIONS, "counting", Counting)

    def run(accept=None):
        factorised.clear()
        solution = least_squares(
            np.arctan,
            lambda x: scipy.sparse.csr_matrix(1.0 / (1.0 + x**2)),
            np.array([1.5]),
            np.array([-5.0]),
            np.array([5.0]),
            accept=accept,
            damping=1e-12,
            normal_equations=NormalEquations("counting"),
        )
        assert solution.converged and abs(solution.x[0]) < 1e-6, solution.message
        return solution

    solution = run()
    assert len(factorised) == solution.iterations and solution.evaluations > solution.iterations + 1
    accepted = []
    solution = run(lambda x: accepted.append(float(x[0])) or x[0] >= -0.05)
    assert len(factorised) == solution.iterations and accepted[0] < -0.05 <= accepted[-1]


@pytest.mark.parametrize("failure", ["raises", "not finite"])
def test_a_failed_factorisation_is_damped_more(monkeypatch, failure):
    """A factorisation that fails in rounding (SuperLU "singular", PARDISO's zero pivot) or gives a
    non-finite step is a rejected step: ``lambda`` rises by ``nu``, which doubles (1e-3, 2e-3, 8e-3 after two
    failures), and the solve goes on to the same minimum."""
    calls = []

    class FailingTwice(FACTORISATIONS["superlu"]):
        def factorise(self, values):
            calls.append(values.copy())
            if len(calls) > 2:
                return super().factorise(values)
            if failure == "raises":
                raise _solver._FactorisationError("zero pivot")
            return lambda b: np.full_like(b, np.nan)

    monkeypatch.setitem(FACTORISATIONS, "failing", FailingTwice)
    a, b = scipy.sparse.csr_matrix(np.array([[2.0, 0.0], [1.0, 1.0], [0.0, 3.0]])), np.array([1.0, 2.0, 3.0])
    seen = []
    solution = least_squares(
        lambda x: seen.append(x) or a @ x - b,
        lambda x: a,
        np.zeros(2),
        np.full(2, -10.0),
        np.full(2, 10.0),
        ftol=1e-15,
        normal_equations=NormalEquations("failing"),
    )
    assert solution.converged and len(calls) > solution.iterations, solution.message
    np.testing.assert_allclose(solution.x, np.linalg.lstsq(a.toarray(), b, rcond=None)[0], atol=1e-8)
    assert np.all(np.isfinite(seen))  # no step of a failed factorisation is tried
    damping = [values[0] / 5.0 - 1.0 for values in calls[:3]]  # (J^T J)_00 = D_00 = 5, first of the pattern
    np.testing.assert_allclose(damping, [1e-3, 2e-3, 8e-3], rtol=1e-9)


def test_normal_equations_no_damping_helps_end_the_solve():
    """Residuals that are not numbers (a length of nan): every factorisation fails, the damping doubles its factor
    until it is no number either, and the solve stops there, unconverged, instead of damping forever."""
    a = scipy.sparse.csr_matrix(np.array([[2.0, 0.0], [1.0, 1.0], [0.0, 3.0]]))
    system, solves = NormalEquations("superlu"), []
    real = system.solve

    def solve(lam, rhs):
        solves.append(lam)
        assert len(solves) < 10_000, "damped forever"
        return real(lam, rhs)

    system.solve = solve
    solution = least_squares(
        lambda x: a @ x - np.nan,
        lambda x: a * np.nan,
        np.zeros(2),
        np.full(2, -10.0),
        np.full(2, 10.0),
        normal_equations=system,
    )
    assert solution.converged is False and solution.message == "no damping made the normal equations factorisable"
    assert solution.iterations == 0 and solution.evaluations == 1 and np.isnan(solution.cost)
    np.testing.assert_array_equal(solution.x, np.zeros(2))
    lam, nu, tried = 1e-3, 2.0, [1e-3]  # the damping times nu, nu doubling, while the next damping is a number
    while np.isfinite(lam * nu):
        lam, nu = lam * nu, 2.0 * nu
        tried.append(lam)
    assert solves == tried and solution.damping == tried[-1]


def test_a_limit_bounds_every_step_and_the_solve_still_converges():
    """``limit`` (a trust region per variable group) is applied to every step tried: on a linear problem whose
    minimum is far away, each accepted step stays within the limit, and the solve still ends at the minimum."""
    a, b = scipy.sparse.csr_matrix(np.array([[2.0, 0.0], [1.0, 1.0], [0.0, 3.0]])), np.array([10.0, 20.0, 30.0])
    tried = [np.zeros(2)]
    solution = least_squares(
        lambda x: a @ x - b,
        lambda x: a,
        np.zeros(2),
        np.full(2, -100.0),
        np.full(2, 100.0),
        ftol=1e-15,
        accept=lambda x: tried.append(np.array(x)) or True,
        limit=lambda d: np.clip(d, -0.5, 0.5),
    )
    assert solution.converged, solution.message
    np.testing.assert_allclose(solution.x, np.linalg.lstsq(a.toarray(), b, rcond=None)[0], atol=1e-8)
    steps = np.abs(np.diff(np.array(tried), axis=0))
    assert steps.max() <= 0.5 and len(tried) > 10  # the minimum is about 10 away: many limited steps


def test_rejected_steps_and_bounds_on_rosenbrock():
    """A nonlinear problem that needs rejected steps (retries) ends at its known minimum (1, 1), bit-identically
    twice."""

    def residuals(x):
        return np.array([10.0 * (x[1] - x[0] ** 2), 1.0 - x[0]])

    def jacobian(x):
        return scipy.sparse.csr_matrix(np.array([[-20.0 * x[0], 10.0], [-1.0, 0.0]]))

    runs = [
        least_squares(residuals, jacobian, np.array([-1.2, 1.0]), np.full(2, -2.0), np.full(2, 2.0)) for _ in range(2)
    ]
    assert runs[0].converged and runs[0].evaluations > runs[0].iterations + 1  # some steps were rejected
    np.testing.assert_allclose(runs[0].x, [1.0, 1.0], atol=1e-6)
    assert np.array_equal(runs[0].x, runs[1].x)


@pytest.mark.skipif("pardiso" not in INSTALLED, reason="extra mkl: pypardiso not installed")
def test_pardiso_releases_mkl_memory_with_the_solver():
    """MKL keeps a factorisation in memory it owns until phase -1: dropping the solver releases it (it leaked
    before)."""
    factorisation = FACTORISATIONS["pardiso"](np.arange(3), np.arange(3), 3)
    solve = factorisation.factorise(np.array([1.0, 4.0, 16.0]))  # exact square roots
    np.testing.assert_array_equal(solve(np.array([1.0, 4.0, 16.0])), 1.0)
    release = factorisation.release
    assert release.alive
    del factorisation, solve
    assert not release.alive
    again = FACTORISATIONS["pardiso"](np.arange(3), np.arange(3), 3)
    again.factorise(np.array([1.0, 4.0, 16.0]))
    again.release()  # released on demand too
    assert not again.release.alive


def test_a_factorisation_not_installed_or_unknown_is_refused_by_name(monkeypatch):
    """``NormalEquations`` names a factorisation whose library is missing, or one that does not exist, and lists the
    installed ones; the environment variable chooses the default."""
    monkeypatch.setattr(_solver, "INSTALLED", ("superlu",))
    with pytest.raises(EquimeshError, match="factorisation 'cholmod' is not installed; installed: superlu"):
        NormalEquations("cholmod")
    with pytest.raises(EquimeshError, match="unknown factorisation 'lu'; choose from superlu"):
        NormalEquations("lu")
    monkeypatch.setattr(_solver, "INSTALLED", ("superlu", "cholmod"))
    with pytest.raises(EquimeshError, match="'pardiso' is not installed; installed: superlu, cholmod$"):
        NormalEquations("pardiso")
    with pytest.raises(EquimeshError, match="unknown factorisation 'lu'; choose from superlu, cholmod$"):
        NormalEquations("lu")
    chosen = subprocess.run(
        [sys.executable, "-c", "from equimesh.surface.optimize import solver; print(solver.DEFAULT_FACTORISATION)"],
        env={**os.environ, _solver.FACTORISATION_VARIABLE: "superlu"},
        capture_output=True,
        text=True,
        check=True,
    )
    assert chosen.stdout.split() == ["superlu"]


@pytest.mark.skipif("cholmod" not in INSTALLED, reason="extra fast: cvxopt not installed")
def test_cholmod_refuses_a_matrix_that_is_not_positive_definite():
    """CHOLMOD's failure on an indefinite matrix is the solver's failed factorisation (a rejected step), and the same
    pattern factorises again once the matrix is positive definite."""
    factorisation = FACTORISATIONS["cholmod"](np.array([0, 0, 1]), np.array([0, 1, 1]), 2)
    with pytest.raises(_solver._FactorisationError):
        factorisation.factorise(np.array([1.0, 2.0, 1.0]))
    np.testing.assert_allclose(factorisation.factorise(np.array([2.0, 1.0, 2.0]))(np.array([3.0, 3.0])), [1.0, 1.0])


def _linear(a, b):
    """The residuals and Jacobian of ``A x - b``."""
    a = scipy.sparse.csr_matrix(np.asarray(a, dtype=float))
    return (lambda x: a @ x - b), (lambda x: a)


def _unit_solve(x0=0.0, **kwargs):
    """``min (x - 1)^2 / 2`` over [-10, 10] from ``x0``."""
    residuals, jacobian = _linear([[1.0]], np.array([1.0]))
    return least_squares(residuals, jacobian, np.array([x0]), np.array([-10.0]), np.array([10.0]), **kwargs)


def test_at_a_minimum_the_solver_stops_at_once():
    """Started at the least-squares optimum of an inconsistent system (integer coordinates): no iteration, one
    evaluation, the cost ``|r|^2 / 2`` there, the damping as given and a float point."""
    residuals, jacobian = _linear([[1.0], [1.0]], np.array([0.0, 2.0]))
    solution = least_squares(residuals, jacobian, [1], np.array([-5.0]), np.array([5.0]), damping=0.25)
    assert solution.x.dtype == float and solution.x.tolist() == [1.0]
    assert (solution.cost, solution.iterations, solution.evaluations) == (1.0, 0, 1)
    assert solution.converged and solution.message == "projected gradient below gtol" and solution.damping == 0.25


def test_a_minimum_on_the_bounds_is_found_by_the_projected_gradient():
    """The unconstrained minimum (5, -5) lies outside the box [-1, 1]^2: the solve ends on the corner (1, -1), where the
    gradient points out of the box and the projected gradient is exactly 0 (so even with ``gtol = 0``)."""
    residuals, jacobian = _linear(np.eye(2), np.array([5.0, -5.0]))
    solution = least_squares(residuals, jacobian, np.zeros(2), np.full(2, -1.0), np.full(2, 1.0), gtol=0.0)
    assert solution.x.tolist() == [1.0, -1.0]
    assert solution.converged and solution.message == "projected gradient below gtol", solution.message
    assert solution.cost == 0.5 * (16.0 + 16.0)


def test_a_variable_on_its_bound_without_gradient_is_free():
    """At (1, 0), x_0 on its upper bound with ``g_0 = 0``: it is not held, and the first step moves it inward towards
    the minimum (-1, 2)."""
    residuals, jacobian = _linear([[1.0, 1.0], [0.0, 1.0]], np.array([1.0, 2.0]))
    tried = []
    solution = least_squares(
        residuals,
        jacobian,
        np.array([1.0, 0.0]),
        np.array([-5.0, -5.0]),
        np.array([1.0, 5.0]),
        damping=1e-12,
        accept=lambda x: tried.append(np.array(x)) or True,
    )
    assert tried[0][0] < 1.0 and solution.converged
    np.testing.assert_allclose(solution.x, [-1.0, 2.0], atol=1e-8)


def test_a_held_variable_has_no_direction_for_the_limit():
    """x_0 on its upper bound with the gradient pointing out is held: its direction is 0, so a limit on the length of
    the whole direction sees only x_1's (0.3, not limited) and the first step takes it."""
    residuals, jacobian = _linear(np.eye(2), np.array([5.0, 0.3]))

    def limit(d):
        norm = np.linalg.norm(d)
        return d if norm <= 0.5 else 0.5 * d / norm

    tried = []
    least_squares(
        residuals,
        jacobian,
        np.array([1.0, 0.0]),
        np.full(2, -1.0),
        np.full(2, 1.0),
        damping=1e-12,
        accept=lambda x: tried.append(np.array(x)) or True,
        limit=limit,
    )
    assert tried[0][0] == 1.0 and abs(tried[0][1] - 0.3) < 1e-9


def test_damping_rises_by_nu_after_a_rejected_step_and_falls_after_a_full_one(monkeypatch):
    """``r(x) = x - 1`` from 0, ``lambda`` 1, the first ``2 (LM_BACKTRACKS + 1)`` trials refused, one taken, the
    next ``LM_BACKTRACKS + 1`` refused: each failed series of halvings multiplies ``lambda`` by ``nu`` and doubles
    ``nu`` (1, 2, 8), a full step taken with gain ratio 1 divides it by 3 (Nielsen's rule) and resets ``nu`` to 2
    (8/3, then 16/3)."""
    damped = []

    class Recording(FACTORISATIONS["superlu"]):
        def factorise(self, values):
            damped.append(float(values[0]) - 1.0)  # J^T J = D = 1: the diagonal is 1 + lambda
            return super().factorise(values)

    monkeypatch.setitem(FACTORISATIONS, "recording", Recording)
    series = _solver.LM_BACKTRACKS + 1
    trials = []

    def accept(x):
        trials.append(float(x[0]))
        return len(trials) == 2 * series + 1 or len(trials) > 3 * series + 1

    solution = _unit_solve(
        damping=1.0,
        accept=accept,
        normal_equations=NormalEquations("recording"),
    )
    assert solution.converged and abs(solution.x[0] - 1.0) < 1e-8, solution.message
    assert damped[:3] == [1.0, 2.0, 8.0]
    np.testing.assert_allclose(damped[3:5], [8.0 / 3.0, 16.0 / 3.0], rtol=1e-12)
    assert trials[:series] == [0.5**h * 0.5 for h in range(series)]
    assert trials[2 * series] == 1.0 / 9.0


def test_nielsens_rule_follows_the_gain_ratio():
    """One full step of ``r(x) = exp(x) - 2`` from 3 (gain ratio about 0.88): ``lambda`` is multiplied by
    ``max(1/3, 1 - (2 rho - 1)^3)``, and the solve reports the iteration cap of 1."""

    def residuals(x):
        return np.exp(x) - 2.0

    def jacobian(x):
        return scipy.sparse.csr_matrix(np.exp(x)[:, None])

    x0 = np.array([3.0])
    solution = least_squares(
        residuals, jacobian, x0, np.array([-10.0]), np.array([10.0]), damping=1e-3, max_iterations=1
    )
    assert solution.converged is False and solution.message == "stopped after 1 iterations"
    s, g, j = solution.x - x0, np.exp(x0) * residuals(x0), np.exp(x0)
    rho = (0.5 * residuals(x0)[0] ** 2 - 0.5 * residuals(solution.x)[0] ** 2) / -(
        g[0] * s[0] + 0.5 * (j[0] * s[0]) ** 2
    )
    assert 0.85 < rho < 0.9
    np.testing.assert_allclose(solution.damping, 1e-3 * (1.0 - (2.0 * rho - 1.0) ** 3), rtol=1e-12)


def test_a_large_constant_residual_stops_on_the_relative_reduction():
    """Behind a residual of 10^10 no step can lower the cost by more than ``ftol`` of it: the first step, taken in full
    (gain ratio about 1, so lambda / 3), ends the solve; a step taken after a refused trial does not."""
    a = scipy.sparse.csr_matrix(np.array([[1e6], [0.0]]))

    def residuals(x):
        return np.array([1e6 * (x[0] - 1.0), 1e10])

    def solve(**kwargs):
        return least_squares(residuals, lambda x: a, np.array([1.001]), np.array([-10.0]), np.array([10.0]), **kwargs)

    trials = []
    after_refusal = solve(accept=lambda x: trials.append(x) or len(trials) > 1)
    assert after_refusal.message == "relative reduction below ftol" and after_refusal.iterations == 2
    solution = solve()
    assert solution.converged is True and solution.message == "relative reduction below ftol", solution.message
    assert (solution.iterations, solution.evaluations) == (1, 2)
    lam = _solver.LM_INITIAL_DAMPING  # the step is the Gauss-Newton one divided by 1 + lambda
    np.testing.assert_allclose(solution.x - 1.0, [1e-3 * lam / (1.0 + lam)], rtol=1e-6)
    assert solution.cost == 0.5 * float(np.sum(residuals(solution.x) ** 2))
    np.testing.assert_allclose(solution.damping, _solver.LM_INITIAL_DAMPING / 3.0, rtol=1e-12)


def test_a_step_below_xtol_ends_the_solve():
    """``xtol = 10^-3`` and the minimum 10^-4 away: the first step is taken and is below ``xtol (xtol + |x|)``."""
    solution = _unit_solve(1.0001, gtol=0.0, ftol=0.0, xtol=1e-3)
    assert solution.converged is True and solution.message == "step below xtol", solution.message
    assert (solution.iterations, solution.evaluations) == (1, 2)
    lam = _solver.LM_INITIAL_DAMPING  # the step is the Gauss-Newton one divided by 1 + lambda
    np.testing.assert_allclose(solution.x - 1.0, [1e-4 * lam / (1.0 + lam)], rtol=1e-6)
    assert solution.cost == 0.5 * (solution.x[0] - 1.0) ** 2
    np.testing.assert_allclose(solution.damping, _solver.LM_INITIAL_DAMPING / 3.0, rtol=1e-12)


@pytest.mark.parametrize("damping", [1e-3, 1.0 / _solver.LM_DIAGONAL_FLOOR])
def test_no_acceptable_step_ends_when_damping_is_at_its_limit(damping):
    """Every trial refused: the damping rises until a step is below ``xtol`` with ``lambda >= 1 / LM_DIAGONAL_FLOOR``,
    and the solve ends where it started, converged, after one iteration; started at that limit it ends at once."""
    trials = []
    solution = _unit_solve(
        0.5,
        xtol=1e-3,
        damping=damping,
        accept=lambda x: trials.append(x) and False,
    )
    assert solution.converged is True and solution.message == "no further reduction: step below xtol"
    assert solution.x.tolist() == [0.5] and solution.cost == 0.125
    assert solution.iterations == 1 and solution.evaluations == 1 + len(trials)
    assert solution.damping >= 1.0 / _solver.LM_DIAGONAL_FLOOR
    if damping > 1.0:
        assert solution.damping == damping and len(trials) == 1


def test_an_endless_descent_stops_at_max_iterations():
    """Steps limited to 1e-3 towards a minimum 10^6 away: no criterion is met, and the solve reports the cap (500 by
    default) it hit."""
    residuals, jacobian = _linear([[1.0]], np.array([1e6]))
    solution = least_squares(
        residuals, jacobian, np.zeros(1), np.array([-1e7]), np.array([1e7]), limit=lambda d: np.clip(d, -1e-3, 1e-3)
    )
    assert solution.converged is False and solution.message == "stopped after 500 iterations"
    assert solution.iterations == 500 and solution.evaluations == 501
    np.testing.assert_allclose(solution.x, [0.5], rtol=1e-9)
    assert solution.cost == 0.5 * (solution.x[0] - 1e6) ** 2 and isinstance(solution.damping, float)


@pytest.mark.parametrize("factorisation", BOTH)
def test_normal_equations_follow_a_new_structure(factorisation):
    """One ``NormalEquations`` for Jacobians of different structures (a column twice in a row, its entries summed;
    other columns in the same rows; other rows): each is analysed anew and solved as its own dense system."""
    system = NormalEquations(factorisation)
    held = np.zeros(3, dtype=bool)
    rhs = np.array([1.0, 2.0, 3.0])
    duplicates = scipy.sparse.csr_matrix((np.array([1.0, 2.0, 1.0, 3.0]), np.array([0, 0, 1, 2]), np.array([0, 2, 4])))
    for dense in (
        duplicates,
        [[2.0, 1.0, 0.0], [0.0, 1.0, 3.0]],
        [[2.0, 0.0, 1.0], [1.0, 3.0, 0.0]],
        [[1.0, 1.0, 1.0], [0.0, 2.0, 0.0], [4.0, 0.0, 0.0]],
    ):
        jac = dense if scipy.sparse.issparse(dense) else scipy.sparse.csr_matrix(np.array(dense))
        system.assemble(jac, held)
        normal = jac.toarray().T @ jac.toarray()
        expected = np.linalg.solve(normal + 0.5 * np.diag(np.diag(normal)), rhs)
        np.testing.assert_allclose(system.solve(0.5, rhs), expected, rtol=1e-10)


def test_a_variable_no_residual_sees_is_damped_by_the_floor():
    """Marquardt's diagonal of a column without entries is ``LM_DIAGONAL_FLOOR`` times the largest diagonal entry (9
    here), so its step is ``rhs / (lam 9 LM_DIAGONAL_FLOOR)``."""
    system = NormalEquations("superlu")
    system.assemble(scipy.sparse.csr_matrix(np.array([[3.0, 0.0]])), np.zeros(2, dtype=bool))
    step = system.solve(1.0, np.array([1.0, 1.0]))
    np.testing.assert_allclose(step, [1.0 / 18.0, 1.0 / (9.0 * _solver.LM_DIAGONAL_FLOOR)], rtol=1e-9)


@pytest.mark.parametrize("rejection", ["refused", "failed"])
def test_a_step_after_a_rejection_does_not_end_the_solve(monkeypatch, rejection):
    """A small step taken after a refused trial (``xtol = 0.85``: the full step 0.999 from 0 is not small, its half
    is) or after a failed factorisation (``xtol = 1``: every step is small) does not end the solve: the next, taken
    at once, does (2 iterations)."""

    class FailingFirst(FACTORISATIONS["superlu"]):
        calls = 0

        def factorise(self, values):
            FailingFirst.calls += 1
            if rejection == "failed" and FailingFirst.calls == 1:
                raise _solver._FactorisationError("zero pivot")
            return super().factorise(values)

    monkeypatch.setitem(FACTORISATIONS, "failing first", FailingFirst)
    trials = []
    solution = _unit_solve(
        gtol=0.0,
        ftol=0.0,
        xtol=0.85 if rejection == "refused" else 1.0,
        accept=lambda x: trials.append(x) or rejection != "refused" or len(trials) > 1,
        normal_equations=NormalEquations("failing first"),
    )
    assert solution.message == "step below xtol" and solution.iterations == 2, solution.message


def test_a_step_that_does_not_lower_the_cost_is_not_taken():
    """A Jacobian that promises a reduction the residuals never give (they are constant): every trial is refused, and
    the solve ends where it started."""
    solution = least_squares(
        lambda x: np.ones(1),
        lambda x: scipy.sparse.csr_matrix(np.ones((1, 1))),
        np.array([0.5]),
        np.array([-10.0]),
        np.array([10.0]),
        xtol=1e-3,
    )
    assert solution.x.tolist() == [0.5] and solution.message == "no further reduction: step below xtol"


def test_superlu_keeps_the_natural_order_and_the_diagonal_pivots():
    """A positive definite matrix whose column 0 has an entry below the diagonal larger than it (partial pivoting
    would swap rows 0 and 3) and whose order SuperLU's own orders change: both permutations stay the identity."""
    dense = 10.0 * np.eye(6)
    dense[0, 0] = 1.0
    for i, j, value in ((0, 3, 2.0), (1, 4, 1.0), (2, 5, 1.0), (3, 5, 1.0), (4, 5, 1.0)):
        dense[i, j] = dense[j, i] = value
    assert np.all(np.linalg.eigvalsh(dense) > 0)
    lu = _solver._factorise(scipy.sparse.csc_matrix(dense), "NATURAL")
    assert np.array_equal(lu.perm_r, np.arange(6)) and np.array_equal(lu.perm_c, np.arange(6))


def _path_pattern(n):
    """The upper-triangular pattern (diagonal included) of a tridiagonal matrix of ``n`` variables."""
    rows = np.concatenate([np.arange(n), np.arange(n - 1)])
    cols = np.concatenate([np.arange(n), np.arange(1, n)])
    key = np.lexsort((cols, rows))
    return rows[key], cols[key]


def test_superlu_orders_by_dissection_from_dissect_from_variables_on():
    """From DISSECT_FROM variables on the order is the nested dissection of the pattern; one variable fewer, SuperLU's
    MMD_AT_PLUS_A in symmetric mode (its order without it differs on this pattern); an order asked for is taken
    whatever the size."""
    for n in (DISSECT_FROM - 1, DISSECT_FROM):
        rows, cols = _path_pattern(n)
        full = scipy.sparse.csc_matrix((np.ones(2 * n - 1), (rows, cols)), shape=(n, n))
        full = full + full.T
        dissected = nested_dissection(full)
        options = {"SymmetricMode": True}
        diagonal = full + n * scipy.sparse.identity(n, format="csc")
        lu = scipy.sparse.linalg.splu(diagonal, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options=options)
        minimum_degree = np.argsort(lu.perm_c)
        assert not np.array_equal(dissected, minimum_degree)
        expected = dissected if n >= DISSECT_FROM else minimum_degree
        assert np.array_equal(FACTORISATIONS["superlu"](rows, cols, n)._order, expected)
        assert np.array_equal(FACTORISATIONS["superlu"](rows, cols, n, ordering="MMD_AT_PLUS_A")._order, minimum_degree)
        assert np.array_equal(FACTORISATIONS["superlu"](rows, cols, n, ordering="nested dissection")._order, dissected)


def test_the_openblas_bundled_beside_a_package_is_kept_to_one_thread(tmp_path, monkeypatch):
    """Each OpenBLAS in ``<package>.libs``, ``<package>/.libs`` and ``<package>/.dylibs`` is loaded and its setter,
    under either name it has, called with 1; other libraries and other folders are left alone."""
    files = {
        "pkg.libs/libopenblas64_p-r0.so": "openblas_set_num_threads",
        "pkg/.libs/libscipy_openblas64_.so": "scipy_openblas_set_num_threads64_",
        "pkg/.dylibs/libopenblas.0.dylib": "openblas_set_num_threads",
        "pkg/.libs/libgfortran.so": None,
        "pkg/lib/libopenblas.so": None,
    }
    for name in files:
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).touch()
    (tmp_path / "pkg/__init__.py").touch()
    calls = []

    def library(path):
        setter = files[str(Path(path).relative_to(tmp_path.resolve()))]
        return types.SimpleNamespace(**{setter: lambda threads: calls.append((Path(path).name, setter, threads))})

    monkeypatch.setattr(cores.ctypes, "CDLL", library)
    cores.one_blas_thread(types.SimpleNamespace(__file__=str(tmp_path / "pkg/__init__.py")))
    assert calls == [
        ("libopenblas64_p-r0.so", "openblas_set_num_threads", 1),
        ("libscipy_openblas64_.so", "scipy_openblas_set_num_threads64_", 1),
        ("libopenblas.0.dylib", "openblas_set_num_threads", 1),
    ]
