"""The solver's bits do not depend on the BLAS's thread count (docs/decisions.md, "A sparse Levenberg-Marquardt
solver"): a long solve run in fresh processes with one and with two threads."""

import os
import textwrap

import pytest
from blas_threads import outputs_with_one_and_two_threads

from equimesh.surface.optimize.solver import INSTALLED

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
@pytest.mark.parametrize("factorisation", INSTALLED)
def test_the_same_bits_whatever_the_blas_thread_count(factorisation):
    """The solver's inner products do not go through the BLAS (``_solver.inner``): with ``a @ b`` OpenBLAS summed a
    long vector in parts, one per thread, and the same solve ended at other bits with 2 threads than with 1; and every
    factorisation runs in one thread."""
    outputs = outputs_with_one_and_two_threads(_CHAIN_SOLVE, factorisation)
    assert outputs[0] == outputs[1] and outputs[0].split()[0] != "0"
