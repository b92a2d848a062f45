"""The sparse bounded Levenberg-Marquardt solver of the final optimisation (surface/_solver.py)."""

import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest
import scipy.optimize
import scipy.sparse
from blas_threads import outputs_with_one_and_two_threads
from hypothesis import given, settings
from hypothesis import strategies as st

from equimesh.errors import EquimeshError
from equimesh.surface.optimize import solver as _solver
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
    non-finite step is a rejected step: ``lambda`` rises and the solve goes on to the same minimum."""
    calls = []

    class FailingOnce(FACTORISATIONS["superlu"]):
        def factorise(self, values):
            calls.append(values)
            if len(calls) > 1:
                return super().factorise(values)
            if failure == "raises":
                raise _solver._FactorisationError("zero pivot")
            return lambda b: np.full_like(b, np.nan)

    monkeypatch.setitem(FACTORISATIONS, "failing", FailingOnce)
    a, b = scipy.sparse.csr_matrix(np.array([[2.0, 0.0], [1.0, 1.0], [0.0, 3.0]])), np.array([1.0, 2.0, 3.0])
    solution = least_squares(
        lambda x: a @ x - b,
        lambda x: a,
        np.zeros(2),
        np.full(2, -10.0),
        np.full(2, 10.0),
        ftol=1e-15,
        normal_equations=NormalEquations("failing"),
    )
    assert solution.converged and len(calls) > solution.iterations, solution.message
    np.testing.assert_allclose(solution.x, np.linalg.lstsq(a.toarray(), b, rcond=None)[0], atol=1e-8)


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


#: A solve of 60,000 residuals (long enough for OpenBLAS to split a dot product between threads) printing its x's hash.
_CHAIN_SOLVE = textwrap.dedent("""
    import hashlib, numpy as np, scipy.sparse
    from equimesh.surface.optimize.solver import least_squares
    n = 30000
    c, i = np.random.default_rng(0).uniform(0.5, 2.0, n), np.arange(n)
    def residuals(x):
        return np.concatenate([x**2 + 0.3 * np.roll(x, 1) - c, 0.1 * (x - np.roll(x, -1))])
    def jacobian(x):
        rows, ones = np.concatenate([i, i]), np.ones(n)
        top = scipy.sparse.csr_matrix((np.concatenate([2 * x, 0.3 * ones]), (rows, np.concatenate([i, (i - 1) % n]))),
        (n, n))
        bottom = scipy.sparse.csr_matrix((np.concatenate([0.1 * ones, -0.1 * ones]), (rows, np.concatenate([i, (i + 1) %
        n]))), (n, n))
        return scipy.sparse.vstack([top, bottom], format="csr")
    solution = least_squares(residuals, jacobian, np.ones(n), np.full(n, -10.0), np.full(n, 10.0), ftol=1e-15,
    gtol=1e-14)
    print(solution.iterations, hashlib.sha256(solution.x.tobytes()).hexdigest())
""")


@pytest.mark.skipif(
    (os.cpu_count() or 1) < 2, reason=f"{os.cpu_count()} core: OpenBLAS runs one thread either way, nothing to compare"
)
@pytest.mark.parametrize("factorisation", BOTH)
def test_the_same_bits_whatever_the_blas_thread_count(factorisation):
    """The solver's inner products do not go through the BLAS (``_solver.inner``): with ``a @ b`` OpenBLAS summed a
    long vector in parts, one per thread, and the same solve ended at other bits with 2 threads than with 1; and every
    factorisation runs in one thread."""
    outputs = outputs_with_one_and_two_threads(_CHAIN_SOLVE, factorisation)
    assert outputs[0] == outputs[1] and outputs[0].split()[0] != "0"


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


def test_a_factorisation_not_installed_or_unknown_is_refused_by_name(monkeypatch):
    """``NormalEquations`` names a factorisation whose library is missing, or one that does not exist, and lists the
    installed ones; the environment variable chooses the default."""
    monkeypatch.setattr(_solver, "INSTALLED", ("superlu",))
    with pytest.raises(EquimeshError, match="factorisation 'cholmod' is not installed; installed: superlu"):
        NormalEquations("cholmod")
    with pytest.raises(EquimeshError, match="unknown factorisation 'lu'; choose from superlu"):
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
