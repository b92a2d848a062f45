"""Charts: a parameter rectangle and a map X^s on it (Section 4, step 1).

Section 4 of the paper meshes a surface given as a map ``X^s(u, v)`` of a
parameter rectangle.  A *chart* is that pair, kept apart from every mesh built
on it (after scikit-fem's ``mapping/``): a :class:`Domain`, the rectangle
``[u0, u1] x [v0, v1]`` with its four sides labelled, and the vectorised map
with its derivatives (:class:`Chart`).  The auxiliary grid (step 1), the
outline (step 3), the remapping (step 4) and the bounds of the final
optimisation read the rectangle from the chart's ``domain``; nothing else in
Section 4 knows where the rectangle lies.

:class:`~equimesh.surface.charts.bezier.BezierSurface` (the paper's example, on
[0, 1]^2) and :class:`~equimesh.surface.charts.nurbs.NurbsSurface` (on the span of its
knot vectors) are charts.  An object with ``evaluate`` and ``derivatives`` but
no ``domain`` is taken on [0, 1]^2 (:func:`domain_of`).
"""

import math
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from ...errors import InvalidSurfaceError, number
from ...tolerance import REL_TOL

#: The sides of a domain, in the order used everywhere (columns of
#: :attr:`~equimesh.surface.auxiliary.AuxiliaryGrid.boundary_sides`, values of
#: ``Outline.side``): side ``k`` is where coordinate ``k // 2`` (0 for u, 1 for
#: v) takes its lower (``k % 2 == 0``) or upper (``k % 2 == 1``) bound.
SIDES = ("u=u0", "u=u1", "v=v0", "v=v1")


def _interval(name, bounds):
    try:
        lo, hi = (float(x) for x in bounds)
    except (TypeError, ValueError):
        raise InvalidSurfaceError(f"parameter range of {name} must be a pair of numbers, got {bounds!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise InvalidSurfaceError(f"parameter range of {name} must be finite, got [{lo!r}, {hi!r}]")
    if not hi - lo > REL_TOL * max(abs(lo), abs(hi)):
        raise InvalidSurfaceError(
            f"parameter range of {name}, [{lo!r}, {hi!r}], is empty or too narrow for its position "
            f"(width at most {REL_TOL:g} times its bounds)"
        )
    return lo, hi


@dataclass(frozen=True)
class Domain:
    """The parameter rectangle ``[u0, u1] x [v0, v1]`` of a chart.

    Parameters
    ----------
    u, v : (float, float)
        Lower and upper bound of each parameter, finite, lower < upper, and
        the width at least ``REL_TOL`` times the larger bound's magnitude (so
        that an auxiliary grid of the rectangle is not lost to rounding).

    Raises
    ------
    InvalidSurfaceError
        naming the parameter at fault.
    """

    u: tuple = (0.0, 1.0)
    v: tuple = (0.0, 1.0)

    def __post_init__(self):
        for name in ("u", "v"):
            lo, hi = _interval(name, getattr(self, name))
            object.__setattr__(self, name, (lo, hi))

    @property
    def lower(self):
        """(2,) array ``(u0, v0)``."""
        return np.array([self.u[0], self.v[0]])

    @property
    def upper(self):
        """(2,) array ``(u1, v1)``."""
        return np.array([self.u[1], self.v[1]])

    @property
    def side_values(self):
        """(4,) array: the constant coordinate of each side, in the order of :data:`SIDES`."""
        return np.array([*self.u, *self.v])

    @property
    def corners(self):
        """(4, 2) array: the rectangle's corners counter-clockwise from ``(u0, v0)``."""
        (u0, u1), (v0, v1) = self.u, self.v
        return np.array([[u0, v0], [u1, v0], [u1, v1], [u0, v1]])

    def at_fractions(self, s, t):
        """Points ``(1 - s) u0 + s u1, (1 - t) v0 + t v1`` for fractions ``s, t`` in [0, 1].

        Exact at both ends (``s = 0`` gives ``u0``, ``s = 1`` gives ``u1``
        bit for bit), and ``s`` itself on [0, 1]^2.
        """
        s, t = np.asarray(s, dtype=float), np.asarray(t, dtype=float)
        return np.stack([(1.0 - s) * self.u[0] + s * self.u[1], (1.0 - t) * self.v[0] + t * self.v[1]], axis=-1)

    def clip(self, uv):
        """``uv`` (..., 2) clipped into the rectangle."""
        return np.clip(uv, self.lower, self.upper)


#: The paper's parameter square [0, 1]^2.
UNIT = Domain()


@runtime_checkable
class Chart(Protocol):
    """A map X^s : domain -> R^3 with first derivatives (Section 4).

    The methods broadcast ``u`` and ``v`` against each other and return arrays
    of shape ``broadcast(u, v).shape + (3,)``.  A chart may also provide
    ``second_derivatives(u, v) -> (X_uu, X_uv, X_vv)``.
    """

    domain: Domain

    def evaluate(self, u, v) -> np.ndarray:
        """Points X^s(u, v)."""

    def derivatives(self, u, v) -> tuple[np.ndarray, np.ndarray]:
        """First partial derivatives (dX^s/du, dX^s/dv)."""


def domain_of(surface):
    """The parameter :class:`Domain` of ``surface``: its ``domain``, or [0, 1]^2 if it has none."""
    domain = getattr(surface, "domain", UNIT)
    if not isinstance(domain, Domain):
        raise InvalidSurfaceError(f"surface.domain must be an equimesh Domain, got {type(domain).__name__}")
    return domain


def side_name(side, domain):
    """``side v = 0`` for an index into :data:`~equimesh.surface.charts.chart.SIDES` of ``domain``."""
    return f"side {'uv'[side // 2]} = {number(domain.side_values[side])}"


def corner_name(uv):
    """``corner (u, v) = (1, 0)`` for a corner of the parameter rectangle."""
    return f"corner (u, v) = ({number(uv[0])}, {number(uv[1])})"
