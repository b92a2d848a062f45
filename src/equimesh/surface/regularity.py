"""The surface must be a regular, non-folding map of its parameter rectangle (checked after Section 4, step 1).

Section 4 assumes that X^s is an immersion: the normal ``n = X^s_u x X^s_v``
never vanishes.  Then every small auxiliary triangle has a well-shaped image
and the flattening of eq. (1) and the remapping of eqs. (2)-(3) are
one-to-one.  Where ``n`` vanishes the surface is *singular* (X_u and X_v
parallel, or one of them zero: a side or corner collapsed to a point); where
``n`` changes direction across such a curve the surface *folds over* (a
control net whose x-row goes 0, 3, -1, 2 has ``x_u`` changing sign twice), and
a mesh of it would overlap itself.

Both are detected on the auxiliary grid: ``n`` is evaluated at every node and
at every triangle centroid, and the surface is refused

* when ``|n| <= SINGULAR_SIN |X_u| |X_v|`` at a sample (singular; computed
  from X_u and X_v scaled to unit length, so the test does not depend on the
  surface's units), or
* when the normal at a triangle's centroid and at one of its corners are
  ``MAX_NORMAL_TURN`` degrees or more apart (folded, or curved so strongly
  that the auxiliary grid cannot follow it: a finer grid tells which).

Non-finite values of X^s or its derivatives are refused by :func:`evaluate`
and :func:`derivatives`, naming the (u, v) at fault; every stage of Section 4
reads the surface through them.

The mesh is remapped and optimised in (u, v), where not every tolerance is
relative to the parameter ranges, so each range is at least
:data:`~equimesh.tolerance.MIN_PARAMETER_RANGE` and at most
:data:`~equimesh.tolerance.MAX_PARAMETER_RANGE` wide, within which a chart
gives the same mesh as on [0, 1] (:func:`check_regular`).
"""

import numpy as np

from ..errors import InvalidSurfaceError, at, number
from ..tolerance import MAX_NORMAL_TURN, MAX_PARAMETER_RANGE, MIN_PARAMETER_RANGE, SINGULAR_SIN


def evaluate(surface, uv):
    """X^s at the rows of ``uv`` (K, 2) as a (K, 3) float array; non-finite values are refused."""
    uv = np.asarray(uv, dtype=float).reshape(-1, 2)
    points = np.asarray(surface.evaluate(uv[:, 0], uv[:, 1]), dtype=float)
    if points.shape != (len(uv), 3):
        raise InvalidSurfaceError(
            f"surface.evaluate returned shape {points.shape} for {len(uv)} parameter pairs, expected ({len(uv)}, 3)"
        )
    _check_finite(points, uv, "point")
    return points


def derivatives(surface, uv):
    """(X^s_u, X^s_v) at the rows of ``uv`` (K, 2), each (K, 3); non-finite values are refused."""
    uv = np.asarray(uv, dtype=float).reshape(-1, 2)
    su, sv = (np.asarray(d, dtype=float).reshape(-1, 3) for d in surface.derivatives(uv[:, 0], uv[:, 1]))
    _check_finite(su, uv, "derivative X_u")
    _check_finite(sv, uv, "derivative X_v")
    return su, sv


def check_regular(surface, grid):
    """Refuse a parameter range out of range, or a singular or folding surface (see the module docstring).

    Parameters
    ----------
    surface : Chart
    grid : AuxiliaryGrid
        The auxiliary triangulation of step 1; its nodes and triangle
        centroids are the samples.
    """
    for name, (lo, hi) in (("u", grid.domain.u), ("v", grid.domain.v)):
        with np.errstate(over="ignore"):
            width = hi - lo
        if not MIN_PARAMETER_RANGE <= width <= MAX_PARAMETER_RANGE:
            raise InvalidSurfaceError(
                f"the parameter range of {name}, [{number(lo)}, {number(hi)}], is {number(width)} wide, outside the "
                f"supported [{number(MIN_PARAMETER_RANGE)}, {number(MAX_PARAMETER_RANGE)}] within which the mesh, "
                "made in (u, v), does not depend on the parametrisation's scale; reparametrise the surface (scale "
                "its knots)"
            )
    centroids = grid.uv[grid.triangles].mean(axis=1)
    uv = np.vstack([grid.uv, centroids])
    su, sv = derivatives(surface, uv)
    normal = np.cross(_rescaled(su), _rescaled(sv))
    size = np.linalg.norm(normal, axis=1)
    singular = np.flatnonzero(~(size > SINGULAR_SIN))
    if singular.size:
        k = int(singular[0])
        what = (
            "X_u vanishes there"
            if not np.any(su[k])
            else "X_v vanishes there"
            if not np.any(sv[k])
            else "X_u and X_v are parallel there"
        )
        raise InvalidSurfaceError(
            f"the surface is singular at {at(uv[k], evaluate(surface, uv[k])[0])}: {what} "
            "(a collapsed side or corner, or a crease); a mesh of it would have degenerate triangles"
        )
    unit = normal / size[:, None]
    centre = unit[grid.n_nodes :]
    cos = np.einsum("tkc,tc->tk", unit[grid.triangles], centre).min(axis=1)
    turned = np.flatnonzero(cos <= np.cos(np.radians(MAX_NORMAL_TURN)))
    if turned.size:
        t = int(turned[0])
        c = centroids[t]
        angle = np.degrees(np.arccos(np.clip(cos[t], -1.0, 1.0)))
        raise InvalidSurfaceError(
            f"the surface folds over near {at(c, evaluate(surface, c)[0])}: its normal turns by {angle:.0f} degrees "
            f"within one auxiliary cell, so a mesh of it would overlap itself "
            f"(if it is only strongly curved there, use a finer grid than {grid.n_u} x {grid.n_v})"
        )


def _rescaled(d):
    """The rows of ``d`` as unit vectors (zero rows stay zero), computed without overflow or underflow.

    Each row is first divided by the power of two nearest its largest
    component, so that a surface given in units of 1e-100 or 1e100 is tested
    exactly like the same surface in units of 1.
    """
    big = np.max(np.abs(d), axis=1, keepdims=True)
    scaled = np.ldexp(d, -np.frexp(np.where(big > 0, big, 1.0))[1])
    norm = np.linalg.norm(scaled, axis=1, keepdims=True)
    return scaled / np.where(norm > 0, norm, 1.0)


def _check_finite(values, uv, what):
    bad = np.flatnonzero(~np.all(np.isfinite(values), axis=1))
    if bad.size:
        k = int(bad[0])
        raise InvalidSurfaceError(f"the surface {what} is not finite at {at(uv[k])}: {values[k].tolist()}")
