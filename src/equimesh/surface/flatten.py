"""Flattening of the auxiliary triangulation to the plane (Section 4, step 2, eq. (1)).

The surface nodes X_i^s0 of the auxiliary triangulation are mapped to plane
points X_i^p0 minimising the distortion energy

    E = 1/2 sum_j ((L_j^p0 - L_j^s0) / L_j^s0)^2                       (1)

over all edges j, with an analytic sparse Jacobian, by the sparse
Levenberg-Marquardt solver of the final optimisation
(:func:`equimesh.surface.optimize.solver.least_squares`): one sparse
factorisation of the damped normal equations per iteration, Marquardt's
scaling (eq. (1) on a fine grid is as ill-conditioned as a graph Laplacian,
and its rows scale with ``1 / L_j^s0``), a damping that takes a singular
Gauss-Newton matrix in its stride, and inner products that do not depend on
the BLAS's thread count, so that the flattening, and every mesh built on it,
is the same bits on any number of cores (docs/decisions.md, "Step 2 by the
solver of the final optimisation").

Lengths.  Each residual is relative to its edge, so an edge ``ratio`` times
shorter than another weighs ``ratio^2`` times more in the normal equations;
past :data:`~equimesh.tolerance.MAX_EDGE_RATIO` the longer edges are below the
rounding of the shorter ones and eq. (1) cannot be solved in floating point.
Such a surface is refused before any work (:func:`check_edge_lengths`), naming
its shortest and longest auxiliary edges.

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

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse

from .._checks import finite_rows, index_rows
from .._geometry import power_of_two_scale
from ..errors import InvalidSurfaceError, at, coordinates, number
from ..mesh import edge_lengths, triangle_orient, unique_edges
from ..tolerance import MAX_EDGE_RATIO
from .optimize.jacobian import AreaBarrier, ElementJacobian
from .optimize.solver import inner, least_squares

#: Iterations of the flattening's solve before it stops unconverged: a bound
#: on the work (one sparse factorisation each), not a tolerance.  Eq. (1) on
#: the reference dome converges well within it on every grid up to
#: :data:`~equimesh.surface.pipeline.MAX_GRID_CELLS` (docs/performance.md,
#: "Flattening and the grid size"); a surface pressing against the fold-over
#: barrier (a near-hemisphere) stops here, flattened as far as it got
#: (docs/decisions.md, "Step 2 by the solver of the final optimisation").
FLATTEN_ITERATIONS = 100


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
    ftol=1e-15,
    xtol=1e-15,
    gtol=1e-14,
    max_iterations=FLATTEN_ITERATIONS,
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
    ftol, xtol, gtol, max_iterations
        Passed to :func:`~equimesh.surface.optimize.solver.least_squares`
        (``gtol`` bounds the gradient in units where the median edge is
        about 1, :func:`_solve`); ``max_iterations`` (one sparse
        factorisation each) bounds the work.

    Returns
    -------
    Flattening

    Raises
    ------
    InvalidSurfaceError
        An argument is malformed (points not finite (N, 3) rows, no
        triangles, an index that is no point, ``uv`` or ``x0`` not one finite
        row per point), two auxiliary nodes coincide on the surface, the auxiliary edges'
        lengths are too far apart for eq. (1) (:func:`check_edge_lengths`),
        or the result folds over.
    """
    x3 = finite_rows(points3d, 3, "points3d", "surface point {}", InvalidSurfaceError)
    if np.asarray(triangles).size == 0:
        raise InvalidSurfaceError("no triangles to flatten")
    n = len(x3)
    tri = index_rows(triangles, 3, n, "triangles", "triangle {}", "point", InvalidSurfaceError)
    per = (n, "surface point")
    uv = None if uv is None else finite_rows(uv, 2, "uv", "the (u, v) of point {}", InvalidSurfaceError, per)
    x0 = None if x0 is None else finite_rows(x0, 2, "x0", "the start of point {}", InvalidSurfaceError, per)
    e = (
        unique_edges(tri)
        if edges is None
        else index_rows(edges, 2, n, "edges", "edge {}", "point", InvalidSurfaceError)
    )
    ls = edge_lengths(x3, e)
    if not np.all(ls > 0):
        a, b = e[int(np.flatnonzero(~(ls > 0))[0])]
        where = f"at {at(uv[a])} and {at(uv[b])}" if uv is not None else f"of auxiliary nodes {a} and {b}"
        raise InvalidSurfaceError(f"the surface points {where} coincide (a collapsed side or cell)")
    check_edge_lengths(ls, e, x3, uv)
    g0, g1 = int(e[0, 0]), int(e[0, 1])
    options = dict(ftol=ftol, xtol=xtol, gtol=gtol, max_iterations=max_iterations)
    floor = float(area_floor)
    default = _metric_start(uv, e, ls) if uv is not None else plane_start(x3, tri)

    nfev = 0
    for start, guess in (("given", x0), ("metric" if uv is not None else "plane", default)):
        if guess is None:
            continue
        points, n = _solve(np.asarray(guess, dtype=float), tri, e, ls, (g0, g1), floor, options)
        nfev += n
        if np.all(triangle_orient(points, tri) > 0):
            lp = edge_lengths(points, e)
            energy = 0.5 * inner((lp - ls) / ls, (lp - ls) / ls)
            return Flattening(points, energy, ls, lp, e, np.array([g0, g1]), nfev, start)
    bad = np.flatnonzero(~(triangle_orient(points, tri) > 0))
    near = "" if uv is None else f", first near {at(uv[tri[bad[0]]].mean(axis=0))}"
    raise InvalidSurfaceError(
        f"flattening folds {bad.size} of {len(tri)} auxiliary triangles over{near}; "
        "the surface is degenerate or too strongly curved for this grid"
    )


def _solve(guess, tri, e, ls, gauge, area_floor, options):
    """Minimise eq. (1) (plus the fold-over barrier) from ``guess`` with the gauge g0 = origin, y(g1) = 0.

    The solve runs in units scaled by the power of two that brings the median
    edge into [1, 2): the residuals are the same numbers, and the solver's
    gradient test (absolute) means the same in every unit of length.
    Returns the points and the residual evaluations.
    """
    g0, g1 = gauge
    scale = power_of_two_scale(float(np.median(ls)))
    start = _gauge(guess * scale, g0, g1)
    n = len(start)
    free = np.ones(2 * n, dtype=bool)
    free[[2 * g0, 2 * g0 + 1, 2 * g1 + 1]] = False
    residuals, jacobian = energy_terms(e, ls * scale, n, free)
    terms = [(residuals, jacobian)]
    if area_floor > 0:
        r0 = residuals(start)
        # weight^2 / 2 > E(start): a folded triangle alone costs more than the start
        barrier = AreaBarrier(tri, start, area_floor, 1.0 + 2.0 * math.sqrt(0.5 * inner(r0, r0)), free)
        terms.append((barrier.residuals, barrier.jacobian))
    full = start.ravel().copy()

    def unpack(z):
        full[free] = z
        return full.reshape(n, 2)

    def stacked_residuals(z):
        x = unpack(z)
        return np.concatenate([r(x) for r, _ in terms])

    def stacked_jacobian(z):
        x = unpack(z)
        return scipy.sparse.vstack([j(x) for _, j in terms], format="csr")

    z0 = full[free].copy()
    unbounded = np.full(len(z0), np.inf)
    solution = least_squares(stacked_residuals, stacked_jacobian, z0, -unbounded, unbounded, **options)
    return unpack(solution.x) / scale, solution.evaluations


def check_edge_lengths(surface_lengths, edges, points3d, uv=None):
    """Refuse auxiliary edges whose lengths on the surface span more than :data:`~equimesh.tolerance.MAX_EDGE_RATIO`.

    Each residual of eq. (1) is relative to its edge, so its Jacobian row
    scales with ``1 / L_j^s0``: an edge ``ratio`` times shorter than another
    weighs ``ratio^2`` times more in the normal equations, and past
    ``MAX_EDGE_RATIO = 2^26`` (``ratio^2`` beyond ``1 / eps``) the longer
    edges vanish in the rounding of the shorter ones.  The auxiliary grid
    then samples the surface far too unevenly to flatten (a parametrisation
    that is nearly stationary somewhere, such as a NURBS whose weights differ
    by orders of magnitude); the message names both edges.
    """
    shortest, longest = int(np.argmin(surface_lengths)), int(np.argmax(surface_lengths))
    ratio = surface_lengths[longest] / surface_lengths[shortest]
    if ratio > MAX_EDGE_RATIO:
        raise InvalidSurfaceError(
            f"the auxiliary triangulation samples the surface too unevenly to flatten by eq. (1): its edge "
            f"{_edge(uv, points3d, *edges[shortest])} is {number(surface_lengths[shortest])} long on the surface, "
            f"{number(ratio, 2)} times shorter than the one {_edge(uv, points3d, *edges[longest])} "
            f"({number(surface_lengths[longest])}), beyond the {number(MAX_EDGE_RATIO, 2)} that floating point "
            "resolves; the parametrisation is nearly stationary there (reparametrise the surface, or give a mesh "
            "of it)"
        )


def _edge(uv, points3d, a, b):
    """Where the auxiliary edge from node ``a`` to node ``b`` runs: by (u, v), or without ``uv`` by node and point."""
    if uv is not None:
        return f"from {at(uv[a])} to {at(uv[b])}"
    return f"from node {a} at {coordinates(points3d[a])} to node {b} at {coordinates(points3d[b])}"


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
    y = _rows_times(y, np.array([[c, s], [-s, c]]))
    y[g0] = 0.0
    y[g1, 1] = 0.0  # exactly, not up to the rounding of the rotation
    return y


def _metric_start(uv, edges, ls):
    """Affine start ``X = R u`` with ``R^T R = M`` the best constant metric for the edges (``uv`` a float array).

    ``M`` (symmetric 2 x 2) minimises ``sum_j ((du_j^T M du_j - L_j^2) / L_j^2)^2``,
    a linear least-squares problem in (M11, M12, M22).  ``R`` is the upper
    Cholesky factor, whose positive diagonal keeps orientations.  If the fit is
    not positive definite (never for a regular surface), the isotropic metric
    of the median stretch ``L_j / |du_j|`` is used instead.
    """
    du = uv[edges[:, 1]] - uv[edges[:, 0]]
    a = np.column_stack([du[:, 0] ** 2, 2.0 * du[:, 0] * du[:, 1], du[:, 1] ** 2]) / (ls**2)[:, None]
    # The normal equations, summed in one order (docs/decisions.md, "Step 2 by the solver of the final
    # optimisation"), of the rows scaled by a power of two c into [1, 2) at most: M = M(a / c) / c.
    c = power_of_two_scale(float(np.max(np.abs(a))))
    a = a * c
    try:
        m11, m12, m22 = np.linalg.solve(np.sum(a[:, :, None] * a[:, None, :], axis=0), np.sum(a, axis=0)) * c
        r = np.linalg.cholesky(np.array([[m11, m12], [m12, m22]])).T
        if not np.all(np.isfinite(r)):
            raise np.linalg.LinAlgError("metric out of range")
    except np.linalg.LinAlgError:
        r = np.median(ls / np.linalg.norm(du, axis=1)) * np.eye(2)
    return _rows_times(uv, r)


def plane_start(x3, tri):
    """Orthogonal projection on the best-fit plane, axes chosen to keep triangles counter-clockwise."""
    c = x3 - x3.mean(axis=0)
    axes = np.linalg.eigh(np.sum(c[:, :, None] * c[:, None, :], axis=0))[1][:, :0:-1].T  # the two largest
    x = _rows_times(c, axes)
    if np.sum(triangle_orient(x, tri)) < 0:
        x[:, 1] = -x[:, 1]
    return x


def _rows_times(x, m):
    """``x @ m.T`` summed in one order, not by the BLAS, whose blocking depends on its thread count."""
    return sum(x[:, k, None] * m[:, k] for k in range(x.shape[1]))
