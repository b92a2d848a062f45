"""Flattening of the auxiliary triangulation to the plane (Section 4, step 2, eq. (1)).

The surface nodes X_i^s0 of the auxiliary triangulation are mapped to plane
points X_i^p0 minimising the distortion energy

    E = 1/2 sum_j ((L_j^p0 - L_j^s0) / L_j^s0)^2                       (1)

over all edges j, with :func:`scipy.optimize.least_squares` (trust region
reflective, LSMR sub-problem solver) and an analytic sparse Jacobian.  On fine
grids eq. (1) is as ill-conditioned as a graph Laplacian; the variables are
therefore right-preconditioned by the Cholesky factor of the Gauss-Newton
matrix at the start (see :class:`_Preconditioner`), which keeps a 100 x 100
grid to about a second.

Rigid motion.  E is invariant under translations and rotations of the plane
(3 degrees of freedom).  They are removed by fixing both coordinates of a
*gauge node* g0 at the origin and the y-coordinate of one of its neighbours g1
at 0, i.e. the edge g0 -> g1 points along the x-axis; the remaining ``2N - 3``
coordinates are the variables.  Reflections are discrete and are fixed by the
start, which preserves the orientation of the triangles.

Start.  The default start is the affine image ``X = R u`` of the parameter
coordinates, with ``R^T R = M`` the constant metric that best fits the squared
edge lengths (``du^T M du ~ (L^s0)^2`` in relative least squares over all
edges): it never folds (``det R > 0``), keeps the triangles counter-clockwise
and already has the right average stretch in every direction.

Fold-over.  E depends only on lengths, so its minimiser can flip triangles:
a strongly doubly curved patch (say a near-hemisphere) has more surface near
its rim than a plane disk, and eq. (1) alone then wrinkles it.  Two guards:

* a barrier (:class:`~equimesh.surface.optimize.jacobian.AreaBarrier`), zero while every
  triangle keeps at least ``area_floor`` (default 0.1) of its plane area at
  the start and heavy enough that ``trf`` can never accept a folded state;
  for the mild surfaces of the paper it never acts and E is minimised as
  written;
* a check of the result: every flattened triangle must have positive
  orientation.  A caller's start that fails is retried once from the default
  start; a failure from the default start raises
  :class:`~equimesh.errors.InvalidSurfaceError`.

Speed: docs/performance.md, "Flattening and the grid size".
"""

from dataclasses import dataclass

import numpy as np
import scipy.optimize
import scipy.sparse
import scipy.sparse.linalg

from ..errors import InvalidSurfaceError, at
from ..mesh import edge_lengths, triangle_orient, unique_edges
from .optimize.jacobian import AreaBarrier, ElementJacobian


@dataclass(frozen=True)
class Flattening:
    """Result of :func:`flatten`.

    Attributes
    ----------
    points : (N, 2) float array
        The plane coordinates X_i^p0; node ``gauge[0]`` at the origin, the edge
        ``gauge[0] -> gauge[1]`` along the positive x-axis.
    energy : float
        The energy E of eq. (1) at ``points``.
    surface_lengths, plane_lengths : (E,) float arrays
        L_j^s0 and L_j^p0 for the rows of ``edges``.
    edges : (E, 2) int array
        The edges the energy sums over.
    gauge : (2,) int array
        The nodes g0, g1 fixing the rigid motion.
    nfev : int
        Residual evaluations used by the solver (summed over a retry).
    start : str
        ``"given"``, ``"metric"`` or ``"plane"``: which start produced the
        result (see :func:`flatten`).
    """

    points: np.ndarray
    energy: float
    surface_lengths: np.ndarray
    plane_lengths: np.ndarray
    edges: np.ndarray
    gauge: np.ndarray
    nfev: int
    start: str

    @property
    def relative_errors(self):
        """(L^p0 - L^s0) / L^s0 per edge: the residuals of eq. (1)."""
        return (self.plane_lengths - self.surface_lengths) / self.surface_lengths


def flatten(
    points3d,
    triangles,
    *,
    uv=None,
    x0=None,
    edges=None,
    area_floor=0.1,
    ftol=1e-10,
    xtol=1e-10,
    gtol=1e-10,
    max_nfev=100,
):
    """Map a triangulated surface patch to the plane minimising E of eq. (1).

    Parameters
    ----------
    points3d : (N, 3) array_like
        The surface nodes X_i^s0 (step 2).
    triangles : (M, 3) int array_like
        The auxiliary triangles, counter-clockwise in the parameter plane.
    uv : (N, 2) array_like, optional
        Parameter coordinates u_i^0 of the nodes; needed for the default
        (metric) start.  Without ``uv`` and ``x0`` the start is the orthogonal
        projection onto the best-fit plane, oriented to keep the triangles
        counter-clockwise.
    x0 : (N, 2) array_like, optional
        A start of the caller's own (retried from the default start if the
        result folds).
    edges : (E, 2) int array_like, optional
        Edges of the energy; by default every edge of ``triangles``.
    area_floor : float
        Fold-over barrier threshold in [0, 1): the fraction of its start area
        below which a triangle is penalised; 0 disables the barrier.
    ftol, xtol, gtol, max_nfev
        Passed to :func:`scipy.optimize.least_squares`.

    Returns
    -------
    Flattening
    """
    x3 = np.asarray(points3d, dtype=float)
    tri = np.asarray(triangles, dtype=np.int64)
    e = unique_edges(tri) if edges is None else np.asarray(edges, dtype=np.int64)
    ls = edge_lengths(x3, e)
    if not np.all(ls > 0):
        a, b = e[int(np.flatnonzero(~(ls > 0))[0])]
        where = f"at {at(uv[a])} and {at(uv[b])}" if uv is not None else f"of auxiliary nodes {a} and {b}"
        raise InvalidSurfaceError(f"the surface points {where} coincide (a collapsed side or cell)")
    g0, g1 = int(e[0, 0]), int(e[0, 1])
    options = dict(ftol=ftol, xtol=xtol, gtol=gtol, max_nfev=max_nfev)
    floor = float(area_floor)
    default = _metric_start(uv, e, ls) if uv is not None else plane_start(x3, tri)

    nfev = 0
    for start, guess in (("given", x0), ("metric" if uv is not None else "plane", default)):
        if guess is None:
            continue
        try:
            points, n = _solve(np.asarray(guess, dtype=float), tri, e, ls, (g0, g1), floor, options)
        except RuntimeError:  # singular start (degenerate triangles): try the next start
            points = None
            continue
        nfev += n
        if np.all(triangle_orient(points, tri) > 0):
            lp = edge_lengths(points, e)
            energy = 0.5 * float(np.sum(((lp - ls) / ls) ** 2))
            return Flattening(points, energy, ls, lp, e, np.array([g0, g1]), nfev, start)
    if points is None:
        raise InvalidSurfaceError("flattening failed: the auxiliary triangulation is degenerate on the surface")
    bad = np.flatnonzero(triangle_orient(points, tri) <= 0)
    near = "" if uv is None else f", first near {at(np.asarray(uv, dtype=float)[tri[bad[0]]].mean(axis=0))}"
    raise InvalidSurfaceError(
        f"flattening folds {bad.size} of {len(tri)} auxiliary triangles over{near}; "
        "the surface is degenerate or too strongly curved for this grid"
    )


def _solve(guess, tri, e, ls, gauge, area_floor, options):
    """Minimise eq. (1) (plus the fold-over barrier) from ``guess`` with the gauge g0 = origin, y(g1) = 0."""
    g0, g1 = gauge
    start = _gauge(guess, g0, g1)
    n = len(start)
    free = np.ones(2 * n, dtype=bool)
    free[[2 * g0, 2 * g0 + 1, 2 * g1 + 1]] = False
    residuals, jacobian = energy_terms(e, ls, n, free)
    if area_floor > 0:
        r0 = residuals(start)
        # weight^2 / 2 > E(start): a folded triangle alone costs more than the start
        barrier = AreaBarrier(tri, start, area_floor, 1.0 + 2.0 * np.sqrt(0.5 * r0 @ r0), free)

        def stacked_residuals(x):
            return np.concatenate([residuals(x), barrier.residuals(x)])

        def stacked_jacobian(x):
            return scipy.sparse.vstack([jacobian(x), barrier.jacobian(x)], format="csr")

    else:
        stacked_residuals, stacked_jacobian = residuals, jacobian
    full = start.ravel().copy()
    z0 = full[free].copy()
    precond = _Preconditioner(jacobian(start))

    def unpack(y):
        full[free] = z0 + precond.apply(y)
        return full.reshape(n, 2)

    def jac(y):
        j = stacked_jacobian(unpack(y))
        return scipy.sparse.linalg.LinearOperator(
            j.shape,
            matvec=lambda w: j @ precond.apply(np.ravel(w)),
            rmatvec=lambda q: precond.apply_transpose(j.T @ np.ravel(q)),
            dtype=float,
        )

    result = scipy.optimize.least_squares(
        lambda y: stacked_residuals(unpack(y)),
        np.zeros(len(z0)),
        jac=jac,
        method="trf",
        tr_solver="lsmr",
        x_scale=1.0,
        tr_options={"atol": 1e-10, "btol": 1e-10},
        **options,
    )
    return unpack(result.x).copy(), int(result.nfev)


class _Preconditioner:
    """Right preconditioner ``T = R^{-1}`` with ``R^T R = J0^T J0`` (J0: Jacobian at the start).

    Eq. (1) on a fine grid is as ill-conditioned as a graph Laplacian, which
    makes the LSMR sub-problems of ``trf`` slow.  Optimising over ``y`` with
    ``z = z0 + T y`` gives the Jacobian ``J T``, equal to an orthonormal matrix
    at the start, so LSMR converges in a few iterations.  ``J0^T J0`` is
    positive definite once the rigid motion is removed (a triangulated disk is
    infinitesimally rigid); its Cholesky factor comes from SuperLU with
    symmetric ordering and diagonal pivots: ``Pc^T A Pc = L U``, ``U = D L^T``,
    hence ``R = D^{-1/2} U Pc^T``.
    """

    def __init__(self, j0):
        a = (j0.T @ j0).tocsc()
        lu = scipy.sparse.linalg.splu(
            a, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True}
        )
        if not np.array_equal(lu.perm_r, lu.perm_c):  # pragma: no cover - SuperLU kept the diagonal
            raise RuntimeError("symmetric factorisation of the flattening preconditioner failed")
        u = lu.U.tocsc()
        self._perm = lu.perm_c
        self._sqrt_d = np.sqrt(u.diagonal())
        self._u = scipy.sparse.linalg.splu(u, permc_spec="NATURAL", diag_pivot_thresh=0.0)

    def apply(self, y):
        """``T y = Pc U^{-1} D^{1/2} y``."""
        return self._u.solve(self._sqrt_d * y)[self._perm]

    def apply_transpose(self, q):
        """``T^T q = D^{1/2} U^{-T} Pc^T q``."""
        s = np.empty_like(q)
        s[self._perm] = q
        return self._sqrt_d * self._u.solve(s, trans="T")


def energy_terms(edges, surface_lengths, n_nodes, free=None):
    """Residual and sparse Jacobian functions of eq. (1).

    Residual ``r_j = (|X_b - X_a| - L_j^s0) / L_j^s0`` for edge ``j = (a, b)``,
    so that ``E = 1/2 |r|^2``.  Its gradient with respect to ``X_b`` is
    ``(X_b - X_a) / (|X_b - X_a| L_j^s0)`` and the negative of that with
    respect to ``X_a``.

    Parameters
    ----------
    edges : (E, 2) int array
    surface_lengths : (E,) float array
        L_j^s0.
    n_nodes : int
    free : (2 n_nodes,) bool array, optional
        Which entries of the flattened coordinates ``X.ravel()`` are
        variables (Jacobian columns); all by default.

    Returns
    -------
    residuals : callable ``X (N, 2) -> (E,)``
    jacobian : callable ``X (N, 2) -> csr_matrix (E, free.sum())``
    """
    e = np.asarray(edges, dtype=np.int64)
    ls = np.asarray(surface_lengths, dtype=float)
    assemble = ElementJacobian(e, n_nodes, 2, free)

    def residuals(x):
        return (edge_lengths(x, e) - ls) / ls

    def jacobian(x):
        d = x[e[:, 1]] - x[e[:, 0]]
        lp = np.maximum(np.linalg.norm(d, axis=1), np.finfo(float).tiny)
        g = d / (lp * ls)[:, None]
        return assemble(-g, g)

    return residuals, jacobian


def _gauge(x, g0, g1):
    """Move and rotate ``x`` so that node g0 is at the origin and g0 -> g1 points along +x."""
    y = x - x[g0]
    c, s = y[g1] / np.linalg.norm(y[g1])
    y = y @ np.array([[c, -s], [s, c]])
    y[g0] = 0.0
    y[g1, 1] = 0.0  # exactly, not up to the rounding of the rotation
    return y


def _metric_start(uv, edges, ls):
    """Affine start ``X = R u`` with ``R^T R = M`` the best constant metric for the edges.

    ``M`` (symmetric 2 x 2) minimises ``sum_j ((du_j^T M du_j - L_j^2) / L_j^2)^2``,
    a linear least-squares problem in (M11, M12, M22).  ``R`` is the upper
    Cholesky factor, whose positive diagonal keeps orientations.  If the fit is
    not positive definite (never for a regular surface), the isotropic metric
    of the median stretch ``L_j / |du_j|`` is used instead.
    """
    uv = np.asarray(uv, dtype=float)
    du = uv[edges[:, 1]] - uv[edges[:, 0]]
    a = np.column_stack([du[:, 0] ** 2, 2.0 * du[:, 0] * du[:, 1], du[:, 1] ** 2]) / (ls**2)[:, None]
    m11, m12, m22 = np.linalg.lstsq(a, np.ones(len(ls)), rcond=None)[0]
    metric = np.array([[m11, m12], [m12, m22]])
    try:
        r = np.linalg.cholesky(metric).T
    except np.linalg.LinAlgError:
        r = np.median(ls / np.linalg.norm(du, axis=1)) * np.eye(2)
    return uv @ r.T


def plane_start(x3, tri):
    """Orthogonal projection on the best-fit plane, axes chosen to keep triangles counter-clockwise."""
    c = x3 - x3.mean(axis=0)
    axes = np.linalg.svd(c, full_matrices=False)[2][:2]
    x = c @ axes.T
    if np.sum(triangle_orient(x, tri)) < 0:
        x[:, 1] = -x[:, 1]
    return x
