"""The final optimisation of the nodes' (u, v) (Section 4, last paragraph, and beyond).

* :mod:`.problem`     :class:`~.problem.UVProblem`: the variables (free parameters, arc positions
                      of sliding nodes), their bounds and the trust region;
* :mod:`.objectives`  what is minimised, one record per objective in :data:`~.objectives.OBJECTIVES`;
* :mod:`.class_rounds` the classes objective's rounds: members to nominal lengths, merged, its key;
* :mod:`.stage`       :class:`~.stage.Stage`: one least-squares solve an objective yields, and the work bound's signal;
* :mod:`.driver`      :func:`~.driver.optimize_uv`: the stages of an objective solved in turn,
                      with the fold-over guards;
* :mod:`.beside`      :class:`~.beside.Beside`: the stages solved beside the others, on a second thread;
* :mod:`.solver`      the sparse bounded Levenberg-Marquardt and its factorisations;
* :mod:`.jacobian`    sparse Jacobians of per-element residuals, the area barrier;
* :mod:`.slide`       boundary nodes sliding along closed polylines by their arc position.
"""

from .driver import UVOptimization, optimize_uv
from .objectives import OBJECTIVES, Objective
from .problem import UVProblem
from .stage import Stage

__all__ = ["OBJECTIVES", "Objective", "Stage", "UVOptimization", "UVProblem", "optimize_uv"]
