"""Stages solved beside the others: :class:`Beside`, what the driver does with :attr:`~.stage.Stage.beside`.

A stage that starts from a point of its own and has no hard constraint depends on nothing the stages before it
compute (bounded's second start, :func:`~equimesh.surface.optimize.objectives.bounded_stages`), so it can be solved
on a thread of its own while they run: the factorisations release the interpreter's lock, so on a second core.  Its
end must be the one that solving it in turn gives, bit for bit, work bound included (docs/decisions.md, "Bounded's
second start on a second core").
"""

import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace

from ...errors import InternalError
from .cores import CORES


class Beside:
    """The stages solved beside the others: each on a thread of its own (``concurrent``) or, if not, in turn when it
    is taken; both give the same end, bit for bit.

    ``solve(stage, work=None)`` solves a stage from its start (:attr:`~.stage.Stage.start`) with normal equations of
    its own, counted in ``work`` (by default its own iterations bound it alone).  :meth:`take` counts a solution's
    Jacobians against the optimisation's work bound as the solve in turn would have, solving it again in turn where
    that bound would have cut it short.  :meth:`close` stops a solve no stage took (the objective ended without it) at
    its next evaluation of the residuals, and waits for it.
    """

    def __init__(self, solve, concurrent):
        self._solve, self._concurrent, self._stop = solve, concurrent, threading.Event()
        self._pool = ThreadPoolExecutor(max_workers=1) if concurrent else None
        self._pending = {}  # id(stage) -> (stage, its future, or None where it is solved when taken)

    def start(self, stage):
        """Begin solving ``stage`` (on the thread, if ``concurrent``); refused unless it has its own start and no
        hard constraint, which solving it beside the stages before would change."""
        if stage.start is None or stage.feasible is not None:
            raise InternalError("a stage solved beside the others needs its own start and no hard constraint")
        future = self._pool.submit(self._on_one_core, self._stoppable(stage)) if self._concurrent else None
        self._pending[id(stage)] = (stage, future)

    def holds(self, stage):
        """Whether ``stage`` itself was started here and not yet taken (kept in :attr:`_pending` until then, so no
        other object can have its id)."""
        return id(stage) in self._pending

    def take(self, stage, work):
        """``stage``'s solution, its Jacobians counted in ``work`` (``work.cap`` and ``work.spend`` raise where the
        bound ends the optimisation, as in turn)."""
        _, future = self._pending.pop(id(stage))
        if future is None:  # not concurrent: solved now, in turn
            return self._solve(stage, work)
        cap = work.cap(stage.max_iterations, stage.start)
        solution = future.result()
        if solution.iterations > cap:  # in turn, the bound would have stopped it earlier: so solve it in turn
            return self._solve(stage, work)
        work.spend(solution, cap < stage.max_iterations)
        return solution

    def close(self):
        """Stop every solve not taken and wait for the thread to end."""
        self._stop.set()
        if self._pool is not None:
            for _, future in self._pending.values():
                if future is not None:
                    future.cancel()
            self._pool.shutdown(wait=True)

    def _on_one_core(self, stage):
        """``stage`` solved on this thread, beside the others (:meth:`~.cores.Cores.beside`): while it runs, each
        factorises on one thread."""
        with CORES.beside():
            return self._solve(stage)

    def _stoppable(self, stage):
        """``stage`` with residuals that raise :class:`Stopped` once :meth:`close` was called."""
        residuals = stage.residuals

        def stoppable(x):
            if self._stop.is_set():
                raise Stopped
            return residuals(x)

        return replace(stage, residuals=stoppable)


class Stopped(Exception):
    """Raised inside a solve beside the others once :meth:`Beside.close` asked it to stop."""
