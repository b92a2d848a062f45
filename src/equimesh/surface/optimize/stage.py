"""One stage of an objective: the least-squares solve the driver runs, and the signal of the work bound.

An objective's stages (:mod:`~equimesh.surface.optimize.objectives`) yield :class:`Stage` records to
:func:`~equimesh.surface.optimize.driver.optimize_uv`, which solves each from where the last ended and sends back
the point reached; where the Jacobians would pass the objective's work bound it throws :class:`WorkSpent` in.  A
stage may carry stages the objective yields later that do not depend on the ones before (:attr:`Stage.beside`), so
that the driver solves them beside those.
"""

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ...tolerance import PAPER_FTOL


class WorkSpent(Exception):
    """Thrown into an objective's stages where the optimisation reaches its work bound
    (:attr:`Objective.max_jacobians`, :func:`~equimesh.surface.optimize.driver.optimize_uv`): stages that keep a
    point meeting the objective's constraints return it as their end ``(x, stage)``; the others let it pass, and the
    surface is refused."""


@dataclass(frozen=True)
class Stage:
    """One least-squares solve: residuals ``r(x)`` and their sparse Jacobian ``J(x)``; its cost is ``|r|^2 / 2``.

    Attributes
    ----------
    residuals, jacobian : callables of the variable vector
    description : str
    ftol : float
        The solver's relative-reduction tolerance.
    max_iterations : int
        The solver's iteration limit (a round of a series need not converge).
    start : array or None
        Restart the solve there with the initial damping, instead of going on
        from where the previous stage ended with its damping.
    hold : bool array or None
        Variables kept at their start value by this solve.
    limit : callable or None
        Applied to every step (a trust region, :meth:`~.problem.UVProblem.step_limit`).
    feasible : callable or None
        A hard constraint ``x -> bool``: once an iterate satisfies it every
        later one does, and a stage that ends outside it is solved on to
        ``PAPER_FTOL``; if the point the optimisation ends at is outside, the
        surface is refused with ``violation(x)``, a phrase naming what is violated.
    beside : tuple of Stage
        Stages the objective yields later, each a solve from its own start without a hard constraint: the driver
        solves them beside this stage and the ones in between, on a thread of their own (so on a second core), and
        answers each, when it is yielded, with the end that solving it then, in turn, gives (the same point, the same
        count of its Jacobians against the work bound), so the result does not depend on the order the solves ran in.
    """

    residuals: Callable[[np.ndarray], np.ndarray]
    jacobian: Callable[[np.ndarray], object]
    description: str = ""
    ftol: float = PAPER_FTOL
    max_iterations: int = 500
    start: np.ndarray = None
    hold: np.ndarray = None
    limit: Callable[[np.ndarray], np.ndarray] = None
    feasible: Callable[[np.ndarray], bool] = None
    violation: Callable[[np.ndarray], str] = None
    beside: tuple = ()
