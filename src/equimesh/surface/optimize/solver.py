"""A sparse, bounded Levenberg-Marquardt solver for the (u, v) optimisation of Section 4.

The paper's final step ("the deviation of the edge lengths ... is minimized by
considering (u_i, v_i) of inner nodes as variables") is a nonlinear least-squares
problem ``min |r(x)|^2 / 2`` whose Jacobian has a few entries per row (one
residual per member or triangle).  :func:`least_squares` solves it by
Levenberg-Marquardt with a sparse direct factorisation of the damped normal
equations, so that one iteration costs about as much as one sparse
factorisation of a mesh-Laplacian-like matrix (near-linear in the node count
on surface meshes) instead of an inner iterative solve:

* step: ``(J_F^T J_F + lambda D_F) s_F = -g_F`` over the free variables ``F``,
  ``D = diag(J^T J)`` (Marquardt's scaling, floored at :data:`~equimesh.tolerance.LM_DIAGONAL_FLOOR`
  of its largest entry so that a variable no residual sees stays regular).
  The normal matrix keeps one sparsity pattern for the whole solve
  (:class:`NormalEquations`: the Jacobian's structure is the mesh's at every
  iteration, and a held variable keeps its row and column, with an identity
  diagonal and a zero right-hand side), so the products ``J^T J`` are summed
  into it through an index map computed once, and the factorisation's
  symbolic analysis (the fill-reducing order) is done once
  (:data:`FACTORISATIONS`: MKL PARDISO's supernodal Cholesky when the optional
  ``pypardiso`` is installed, else CHOLMOD's, through the optional ``cvxopt``,
  else SuperLU in symmetric mode; :data:`INSTALLED`);
* a rejected step is first shortened along the same direction, halving it
  up to :data:`~equimesh.tolerance.LM_BACKTRACKS` times with the same factor
  (a line search, Nocedal and Wright 10.3), and only then retried with a
  larger ``lambda`` (a new factorisation), and so is a factorisation that
  fails in rounding (a zero pivot) or gives a step that is not finite;
* bounds by projection: a variable on a bound whose gradient points outwards is
  held there for the step (it leaves ``F``), and the step is clipped to the box;
* acceptance: the gain ratio ``rho = actual / predicted reduction`` of the
  projected step; ``rho > 0`` and ``accept(x_new)`` (a caller's predicate, e.g.
  "no triangle folds over", "every member stays in [l, 2l]") are required;
  ``lambda`` follows Nielsen's rule after a full step and stays after a
  shortened one (lowering it there made more steps fail, raising it made
  more iterations: docs/decisions.md, "Rejected steps are shortened first");
* convergence, not an evaluation cap: the infinity norm of the projected
  gradient below ``gtol``, or a step below ``xtol (xtol + |x|)``, or actual
  and predicted relative reductions below ``ftol``.  ``max_iterations`` is
  only a guard against a bug and is reported when it is hit.

Deterministic: no randomness, a fixed ordering, factorisations and inner
products (:func:`inner`) whose rounding does not depend on their threads
(:mod:`~equimesh.surface.optimize.cores`), so the same input gives the same
bits on one installation, whatever its cores (the factorisations round
differently, so a result's last bits depend on which one is used).
"""

import os
import weakref
from dataclasses import dataclass

import numpy as np
import scipy.sparse
import scipy.sparse.linalg

from ..._jit import compiled
from ...errors import EquimeshError
from ...tolerance import LM_BACKTRACKS, LM_DIAGONAL_FLOOR, LM_INITIAL_DAMPING
from .cores import CORES, PARDISO_THREADS, one_blas_thread
from .ordering import DISSECT_FROM, nested_dissection

try:
    from cvxopt import cholmod as _cvxopt_cholmod
    from cvxopt import matrix as _cvxopt_matrix
    from cvxopt import spmatrix as _cvxopt_spmatrix
except ImportError:  # the extra 'fast' is not installed
    _cvxopt_cholmod = None

try:
    import pypardiso
except ImportError:  # the extra 'mkl' is not installed, or its MKL library is not found
    pypardiso = None
else:
    # Every PyPardisoSolver() looks for MKL's library again, by a recursive glob of the
    # environment when ctypes does not find it (0.15 s on an idle machine, 0.75 s under load,
    # per solver): the one its import found is named once for all of them.
    os.environ.setdefault("PYPARDISO_MKL_RT", pypardiso.ps.libmkl._name)
    # MKL's OpenMP threads wait for work by spinning, 200 ms by default: "bounded" at 22,448 variables took 17.3 and
    # 19.0 CPU seconds with it, 13.2 and 16.2 without, in about the same wall time (KMP_BLOCKTIME=200 and unset,
    # `python experiments/optimisation_timing.py --length 0.88 --objective bounded`).
    os.environ.setdefault("KMP_BLOCKTIME", "0")

#: Below this many variables PARDISO factorises sequentially on one thread, from it on reproducibly on two
#: (:data:`~.cores.PARDISO_THREADS`): results/pardiso_threads.md (``python experiments/pardiso_threads.py``) timed a
#: factorisation and a solve so at 1.35 times the sequential one's time at 1,344 variables, 1.01 at 2,698, 0.75 to
#: 0.82 from 5,278 to 22,448 and 0.91 at 64,784 (the reproducible solve takes 1.5 to 2 times as long).
PARDISO_THREADS_FROM = 4_000


@dataclass(frozen=True)
class Solution:
    """Result of :func:`least_squares`: the point, its cost, why the solver stopped and its last damping ``lambda``."""

    x: np.ndarray
    cost: float
    iterations: int
    evaluations: int
    converged: bool
    message: str
    damping: float


def least_squares(
    residuals,
    jacobian,
    x0,
    lower,
    upper,
    *,
    accept=None,
    gtol=1e-10,
    xtol=1e-10,
    ftol=1e-12,
    max_iterations=500,
    damping=LM_INITIAL_DAMPING,
    normal_equations=None,
    limit=None,
):
    """Minimise ``|residuals(x)|^2 / 2`` over the box ``[lower, upper]`` (see the module docstring).

    ``x0`` must lie in the box and satisfy ``accept`` (if given); every
    iterate, and so the result, then does too.  ``damping`` is the initial
    ``lambda``; a continuation passes the previous solve's final
    :attr:`Solution.damping` so that it does not pay again for rejected steps.
    ``normal_equations`` (a :class:`NormalEquations`, a new one by default)
    keeps the index maps and the symbolic factorisation: a continuation
    passes the same one to every solve so that the analysis of the one
    pattern is done once.  ``limit`` (optional) maps each solved direction to
    the step tried along it: a trust region per group of variables (e.g.
    each node's move on the surface at most a fraction of l), applied
    before the line search; the gain ratio is that of the limited step.
    """
    x = np.clip(np.asarray(x0, dtype=float), lower, upper)
    r = residuals(x)
    cost = 0.5 * inner(r, r)
    evaluations, nu, lam = 1, 2.0, damping
    system = NormalEquations() if normal_equations is None else normal_equations
    for iteration in range(max_iterations):
        jac = jacobian(x)
        g = jac.T @ r
        projected = x - np.clip(x - g, lower, upper)
        if np.all(np.abs(projected) <= gtol):
            return Solution(x, cost, iteration, evaluations, True, "projected gradient below gtol", lam)
        held = ((x <= lower) & (g > 0)) | ((x >= upper) & (g < 0))
        system.assemble(jac, held)
        rhs = np.where(held, 0.0, -g)
        retried = False
        while True:
            direction = system.solve(lam, rhs)
            if direction is None:  # not numerically positive definite: damp more, while the damping is a number
                if not np.isfinite(lam * nu):  # no damping helps: the normal equations are not finite
                    message = "no damping made the normal equations factorisable"
                    return Solution(x, cost, iteration, evaluations, False, message, lam)
                lam, nu, retried = lam * nu, 2.0 * nu, True
                continue
            if limit is not None:
                direction = limit(direction)
            for halving in range(LM_BACKTRACKS + 1):
                x_new = np.clip(x + 0.5**halving * direction, lower, upper)
                s = x_new - x
                js = jac @ s
                predicted = -(inner(g, s) + 0.5 * inner(js, js))
                r_new = residuals(x_new)
                evaluations += 1
                cost_new = 0.5 * inner(r_new, r_new)
                actual = cost - cost_new
                small_step = np.sqrt(inner(s, s)) <= xtol * (xtol + np.sqrt(inner(x, x)))
                taken = predicted > 0 and actual > 0 and (accept is None or accept(x_new))
                if taken or small_step or predicted <= 0:
                    break
                retried = True
            if taken:
                if halving == 0:  # Nielsen's rule on a full step; a shortened one keeps lambda
                    lam *= max(1.0 / 3.0, 1.0 - (2.0 * actual / predicted - 1.0) ** 3)
                    nu = 2.0
                x, r, old, cost = x_new, r_new, cost, cost_new
                if small_step and not retried:
                    return Solution(x, cost, iteration + 1, evaluations, True, "step below xtol", lam)
                if actual <= ftol * old and predicted <= ftol * old and not retried:
                    return Solution(x, cost, iteration + 1, evaluations, True, "relative reduction below ftol", lam)
                break
            if small_step and lam >= 1.0 / LM_DIAGONAL_FLOOR:
                return Solution(x, cost, iteration + 1, evaluations, True, "no further reduction: step below xtol", lam)
            lam *= nu
            nu *= 2.0
            retried = True
    return Solution(x, cost, max_iterations, evaluations, False, f"stopped after {max_iterations} iterations", lam)


def inner(a, b):
    """``a . b`` of two vectors, the same bits whatever the BLAS library and its thread count.

    ``a @ b`` and ``np.linalg.norm`` call the BLAS ``ddot``, which OpenBLAS
    splits between its threads on long vectors, each thread summing a part:
    the rounding then depended on how many cores the machine had (measured:
    the same optimisation of the reference dome at 101,654 members took 366
    Jacobians with ``OPENBLAS_NUM_THREADS=1`` and 262 with 2).  NumPy's own
    pairwise sum of the products has one order.
    """
    return float(np.sum(a * b))


class NormalEquations:
    """The damped normal equations ``(J^T J + lambda D) s = b`` on one sparsity pattern for the whole solve.

    The Jacobian's structure is the mesh's at every iteration (residuals of
    members and triangles, inactive barrier rows stored as zeros), so the
    upper triangle of ``J^T J`` has one pattern: :meth:`assemble` sums the
    products ``J_ri J_rj`` of each row into it through an index map computed
    when the structure is first (or newly) seen, and the factorisation
    analyses the pattern (orders it) only then.  A held variable keeps its
    row and column, zeroed, with a unit diagonal (its step is 0), so that
    the pattern does not change with the set of free variables either.
    """

    def __init__(self, factorisation=None):
        """``factorisation``: one of :data:`INSTALLED`, :data:`DEFAULT_FACTORISATION` by default."""
        self._factorisation = FACTORISATIONS[factorisation_name(factorisation)]
        self._structure = None

    def assemble(self, jac, held):
        """The normal matrix of the CSR Jacobian ``jac`` with the variables ``held`` (bool) kept in place."""
        jac = jac.tocsr()
        if self._structure is None or not (
            np.array_equal(jac.indptr, self._structure[0]) and np.array_equal(jac.indices, self._structure[1])
        ):
            self._analyse(jac)
        values = np.zeros(len(self._rows))
        data = jac.data
        for starts, first, second, slot in self._groups:
            _sum_products(data, starts, first, second, slot, values)
        diagonal = values[self._diagonal]
        self._damping = np.maximum(diagonal, LM_DIAGONAL_FLOOR * max(float(diagonal.max(initial=0.0)), 1.0))
        if held.any():
            values[held[self._rows] | held[self._cols]] = 0.0
            self._damping[held] = 0.0
            values[self._diagonal[held]] = 1.0
        self._values = values

    def solve(self, lam, rhs):
        """The solution of ``(J^T J + lam D) s = rhs`` (a new factorisation per call), or None if it fails.

        The matrix is positive definite in exact arithmetic; a factorisation
        that meets a zero or negative pivot, or a solution that is not finite,
        says that ``lam`` is too small for the rounding, and the caller damps more.
        """
        values = self._values.copy()
        values[self._diagonal] += lam * self._damping
        try:
            step = self._factor.factorise(values)(rhs)
        except _FactorisationError:
            return None
        return step if np.all(np.isfinite(step)) else None

    def _analyse(self, jac):
        """Index maps from the products of each row's entries to the upper-triangular pattern, and its symbolic
        factorisation.

        Rows are grouped by their number ``k`` of entries; a group keeps, per
        row, the position in ``jac.data`` of its first entry, the offsets from
        there of the two factors of each of its ``k (k + 1) / 2`` products
        ``J_rp J_rq`` (positions ``p <= q``, the same for every row of the
        group), and the slot of the pattern each product is summed into.  The
        structure is taken as it comes (no sort per iteration: the Jacobians of
        :class:`~equimesh.surface.optimize.jacobian.ElementJacobian` list a row's
        columns by corner): a row's columns may be in any order, and a column
        may appear twice (entries to be summed): the product of its two
        entries then counts twice, ``(J_rp + J_rq)^2 = J_rp^2 + J_rq^2 + 2 J_rp J_rq``,
        so it forms one more group, of one product per pair (its first
        factor's position, and the offset of the second per pair).
        """
        n = jac.shape[1]
        counts = np.diff(jac.indptr)
        groups, keys = [], [np.arange(n, dtype=np.int64) * (n + 1)]  # the whole diagonal, even where no row reaches
        twice = ([], [], [])  # the positions and keys of the products of a column's two entries in a row
        for k in np.unique(counts[counts > 0]):
            starts = jac.indptr[:-1][counts == k].astype(np.int64)
            i, j = np.triu_indices(k)
            left, right = starts[:, None] + i, starts[:, None] + j
            a, b = jac.indices[left].astype(np.int64), jac.indices[right].astype(np.int64)
            keys.append((np.minimum(a, b) * n + np.maximum(a, b)).ravel())
            groups.append((starts, i[None, :], j[None, :], left.size))
            repeated = (a == b) & (left != right)
            for part, value in zip(twice, (left, right - left, a * (n + 1))):
                part.append(value[repeated])
        if sum(len(key) for key in twice[2]):
            keys.append(np.concatenate(twice[2]))
            pairs = np.concatenate(twice[0])
            groups.append((pairs, np.zeros((1, 1), dtype=np.int64), np.concatenate(twice[1])[:, None], pairs.size))
        unique, slots = np.unique(np.concatenate(keys), return_inverse=True)
        slots = slots.astype(np.int32 if len(unique) <= np.iinfo(np.int32).max else np.int64)
        offsets = np.cumsum([n] + [size for *_, size in groups])
        self._groups = [
            (starts, first, second, slots[offsets[g] - size : offsets[g]].reshape(len(starts), -1))
            for g, (starts, first, second, size) in enumerate(groups, start=1)
        ]
        self._rows, self._cols = unique // n, unique % n
        self._diagonal = np.flatnonzero(self._rows == self._cols)
        self._structure = (jac.indptr.copy(), jac.indices.copy())
        self._factor = self._factorisation(self._rows, self._cols, n)


class _SuperLU:
    """SuperLU in symmetric mode on the full symmetric matrix, in a fill-reducing order computed once.

    The order is taken at construction and the permuted matrix factorised in
    its natural order at every call (measured on the reference dome at
    101,654 members: SuperLU's ordering was about a third of each
    factorisation's time).  ``ordering``: ``"nested dissection"``
    (:func:`~equimesh.surface.optimize.ordering.nested_dissection`), or one
    of SuperLU's own (its ``permc_spec``); by default the first from
    :data:`~equimesh.surface.optimize.ordering.DISSECT_FROM` variables on,
    else ``MMD_AT_PLUS_A`` (docs/decisions.md, "SuperLU in a nested-dissection order").
    """

    def __init__(self, rows, cols, n, ordering=None):
        if ordering is None:
            ordering = "nested dissection" if n >= DISSECT_FROM else "MMD_AT_PLUS_A"
        off = rows != cols
        entry_rows, entry_cols = np.concatenate([rows, cols[off]]), np.concatenate([cols, rows[off]])
        pattern = scipy.sparse.csc_matrix((np.ones(len(entry_rows)), (entry_rows, entry_cols)), shape=(n, n))
        if ordering == "nested dissection":
            self._order = nested_dissection(pattern)
        else:
            self._order = np.argsort(_factorise(pattern + n * scipy.sparse.identity(n, format="csc"), ordering).perm_c)
        position = np.empty(n, dtype=np.int64)
        position[self._order] = np.arange(n)
        # Which upper entry each entry of the permuted full CSC matrix takes its value from.
        source = np.concatenate([np.arange(len(rows)), np.flatnonzero(off)])
        permuted = scipy.sparse.coo_matrix(
            (np.arange(1, len(source) + 1), (position[entry_rows], position[entry_cols])), shape=(n, n)
        ).tocsc()
        permuted.sort_indices()
        self._source = source[permuted.data - 1]
        self._indices, self._indptr, self._n = permuted.indices, permuted.indptr, n

    def factorise(self, values):
        """A function ``b -> A^-1 b`` for the matrix of the pattern's upper-triangular ``values``."""
        matrix = scipy.sparse.csc_matrix((values[self._source], self._indices, self._indptr), shape=(self._n, self._n))
        try:
            lu, order = _factorise(matrix, "NATURAL"), self._order
        except RuntimeError as error:  # SuperLU: "Factor is exactly singular"
            raise _FactorisationError(str(error)) from None

        def solve(b):
            out = np.empty_like(b)
            out[order] = lu.solve(b[order])
            return out

        return solve


class _Pardiso:
    """MKL PARDISO (``pypardiso``): a supernodal Cholesky of the upper triangle, its symbolic analysis (METIS order)
    done once; from :data:`PARDISO_THREADS_FROM` variables on reproducible on up to two threads, else on one."""

    def __init__(self, rows, cols, n, threads=None, reproducible=None):
        """``threads``: those it runs on (by default :meth:`~.cores.Cores.threads` at each factorisation if
        ``reproducible``, else 1); ``reproducible``: iparm 34 (by default as :data:`PARDISO_THREADS_FROM` says)."""
        if reproducible is None:
            reproducible = PARDISO_THREADS if n >= PARDISO_THREADS_FROM else 0
        self._fixed = threads or (None if reproducible else 1)
        self._threads = self._fixed or CORES.threads()
        self._solver = pypardiso.PyPardisoSolver(mtype=2)
        # Our own parameters (iparm 1 = 1): METIS order (2 = 2), no iterative refinement (8 = 0: it
        # took two of three triangular solves; the Cholesky solve alone is backward stable),
        # the default pivot perturbation 1e-8 (10 = 8), results reproducible on up to that many threads (34).
        for i, value in ((1, 1), (2, 2), (8, 0), (10, 8), (34, reproducible)):
            self._solver.set_iparm(i, value)
        self._pattern = scipy.sparse.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
        self._pattern.sort_indices()
        self._call(11, np.zeros(n))
        # MKL keeps the factorisation in its own memory until phase -1: released with the solver.
        self.release = weakref.finalize(self, self._solver.free_memory, everything=True)

    def _call(self, phase, b):
        """PARDISO's ``phase`` on the pattern's matrix, on its threads (two in the sequential mode would change the
        last bits)."""
        self._solver.set_phase(phase)
        threads = self._solver.libmkl.MKL_Set_Num_Threads_Local(self._threads)
        try:
            return self._solver._call_pardiso(self._pattern, b)
        except pypardiso.pardiso_wrapper.PyPardisoError as error:  # e.g. -4, a zero pivot
            raise _FactorisationError(str(error)) from None
        finally:
            self._solver.libmkl.MKL_Set_Num_Threads_Local(threads)

    def factorise(self, values):
        """A function ``b -> A^-1 b`` for the matrix of the pattern's upper-triangular ``values``."""
        threads = self._fixed or CORES.threads()
        if threads != self._threads:  # PARDISO's threads are fixed by its analysis (fewer after it failed)
            self._threads = threads
            self._call(11, np.zeros(self._pattern.shape[0]))
        self._pattern.data[:] = values
        self._call(22, np.zeros(self._pattern.shape[0]))
        return lambda b: self._call(33, np.asarray(b, dtype=float))


class _Cholmod:
    """CHOLMOD's supernodal Cholesky (SuiteSparse, through ``cvxopt``) of the lower triangle, its symbolic analysis
    (AMD order, supernodes) done once, the BLAS it calls kept to one thread."""

    def __init__(self, rows, cols, n):
        one_blas_thread(_cvxopt_cholmod)
        # The lower triangle is the upper one transposed: sorted by row then column, its entries are in the
        # column-major order that cvxopt keeps, so the values are handed over as they come.
        self._matrix = _cvxopt_spmatrix(
            _cvxopt_matrix(np.ones(len(rows))), _cvxopt_matrix(cols.tolist()), _cvxopt_matrix(rows.tolist()), (n, n)
        )
        options = {"supernodal": 2, "postorder": True}  # cvxopt's defaults, named here since they are global
        self._symbolic = _with_options(options, _cvxopt_cholmod.symbolic, self._matrix, uplo="L")

    def factorise(self, values):
        """A function ``b -> A^-1 b`` for the matrix of the pattern's upper-triangular ``values``."""
        self._matrix.V = _cvxopt_matrix(np.ascontiguousarray(values))
        try:
            _cvxopt_cholmod.numeric(self._matrix, self._symbolic)
        except ArithmeticError as error:  # CHOLMOD: "not positive definite"
            raise _FactorisationError(str(error)) from None
        symbolic = self._symbolic

        def solve(b):
            out = _cvxopt_matrix(np.array(b, dtype=float))
            _cvxopt_cholmod.solve(symbolic, out)
            return np.array(out).ravel()

        return solve


def _with_options(options, function, *args, **kwargs):
    """``function(*args, **kwargs)`` with cvxopt's CHOLMOD ``options`` set, the caller's restored after."""
    saved = dict(_cvxopt_cholmod.options)
    _cvxopt_cholmod.options.update(options)
    try:
        return function(*args, **kwargs)
    finally:
        _cvxopt_cholmod.options.clear()
        _cvxopt_cholmod.options.update(saved)


class _FactorisationError(ArithmeticError):
    """A factorisation of the damped normal matrix failed (a zero or negative pivot in rounding)."""


#: Factorisations of the damped normal matrix by name, each ``f(rows, cols, n)``
#: (the upper-triangular pattern, sorted by row then column) with ``factorise(values) -> solver``.
FACTORISATIONS = {"superlu": _SuperLU, "cholmod": _Cholmod, "pardiso": _Pardiso}
_LIBRARIES = {"pardiso": pypardiso, "cholmod": _cvxopt_cholmod, "superlu": scipy}
#: The factorisations whose library is installed, the fastest first (docs/performance.md, "The final
#: optimisation"): PARDISO (the extra ``mkl``: pypardiso, where MKL exists), CHOLMOD (the extra ``fast``: cvxopt,
#: wheels on every platform, about as fast), SuperLU (scipy, always; about three times slower).
INSTALLED = tuple(name for name, library in _LIBRARIES.items() if library is not None)
#: The environment variable that names the default factorisation (e.g. ``superlu``, to measure an installation
#: without the extras in the same checkout); by default the first of :data:`INSTALLED`.
FACTORISATION_VARIABLE = "EQUIMESH_FACTORISATION"
DEFAULT_FACTORISATION = os.environ.get(FACTORISATION_VARIABLE) or INSTALLED[0]


def factorisation_name(factorisation=None):
    """``factorisation`` (:data:`DEFAULT_FACTORISATION` when None), checked: one of :data:`INSTALLED`."""
    name = factorisation or DEFAULT_FACTORISATION
    if name in _LIBRARIES and name not in INSTALLED:
        raise EquimeshError(f"factorisation {name!r} is not installed; installed: {', '.join(INSTALLED)}")
    if name not in FACTORISATIONS:
        raise EquimeshError(f"unknown factorisation {name!r}; choose from {', '.join(INSTALLED)}")
    return name


def _sum_products(data, starts, first, second, slot, values):
    """``values[slot[r, p]] += data[starts[r] + first[r, p]] * data[starts[r] + second[r, p]]`` for every row ``r``
    and product ``p``, in order.

    The products ``J_ri J_rj`` of one group of rows summed into the normal
    matrix (:meth:`NormalEquations.assemble`), compiled: one pass without
    the temporary arrays of a vectorised ``np.bincount`` (which summed the
    same terms in the same order, so the bits are the same).  The offsets
    ``first`` and ``second`` of a row's two factors from its first entry
    broadcast over the rows: one row of them for the whole group (its rows
    have the same number of entries), or one per row (the products of a
    column's two entries).  A zero product is not added (the rows of
    inactive barrier terms are stored zeros): the sums start at +0, and
    adding a zero changes no sum but -0, which they never are.
    """
    for r in range(slot.shape[0]):
        base = starts[r]
        a, b = min(r, first.shape[0] - 1), min(r, second.shape[0] - 1)
        for p in range(slot.shape[1]):
            product = data[base + first[a, p]] * data[base + second[b, p]]
            if product != 0.0:
                values[slot[r, p]] += product


_sum_products = compiled(_sum_products)


def _factorise(matrix, ordering):
    """SuperLU of a symmetric positive definite CSC ``matrix`` in symmetric mode (diagonal pivots), ``ordering`` its
    ``permc_spec``."""
    return scipy.sparse.linalg.splu(matrix, permc_spec=ordering, diag_pivot_thresh=0.0, options={"SymmetricMode": True})
