"""PARDISO on two threads with the bits of one (docs/decisions.md, "PARDISO on two threads, the same bits as on one"):
its reproducible mode from ``PARDISO_THREADS_FROM`` variables on, and the cores shared with a solve beside the others
(``cores.CORES``)."""

import os
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse
from optimize_cases import problem

from equimesh.surface.optimize import cores, driver, solver
from equimesh.surface.optimize.beside import Beside
from equimesh.surface.optimize.objectives import paper_stage
from equimesh.surface.pipeline import mesh_surface
from equimesh.testing.surfaces import dome

pytestmark = pytest.mark.skipif("pardiso" not in solver.INSTALLED, reason="extra mkl: pypardiso not installed")
CORES = min(cores.PARDISO_THREADS, os.cpu_count() or 1)


def _spd(n, seed=0):
    """The upper triangle ``(rows, cols, values)`` of a sparse symmetric positive definite matrix, sorted by row then
    column, as the normal equations hand it over."""
    b = scipy.sparse.random(2 * n, n, density=8.0 / n, random_state=seed, format="csr")
    upper = scipy.sparse.triu(b.T @ b + scipy.sparse.identity(n), format="coo")
    order = np.lexsort((upper.col, upper.row))
    return upper.row[order], upper.col[order], upper.data[order]


def _calls(monkeypatch):
    """Every PARDISO call's (phase, threads), recorded."""
    calls, call = [], solver._Pardiso._call

    def recorded(self, phase, b):
        calls.append((phase, self._threads))
        return call(self, phase, b)

    monkeypatch.setattr(solver._Pardiso, "_call", recorded)
    return calls


def test_the_reproducible_mode_starts_at_its_threshold(monkeypatch):
    """Below ``PARDISO_THREADS_FROM`` variables the sequential mode on one thread (iparm 34 = 0), from it on the
    reproducible one for ``PARDISO_THREADS`` (on as many of them as the machine has)."""
    modes, set_iparm = [], solver.pypardiso.PyPardisoSolver.set_iparm

    def recorded(self, i, value):
        if i == 34:
            modes.append(value)
        return set_iparm(self, i, value)

    monkeypatch.setattr(solver.pypardiso.PyPardisoSolver, "set_iparm", recorded)
    n = solver.PARDISO_THREADS_FROM
    below, at = (solver.FACTORISATIONS["pardiso"](*_spd(m)[:2], m) for m in (n - 1, n))
    assert modes == [0, cores.PARDISO_THREADS]
    assert (below._threads, at._threads) == (1, CORES)


def test_two_threads_give_the_bits_of_one_and_a_new_count_is_analysed_again(monkeypatch):
    """In the reproducible mode the same solution, bit for bit, with the factorisation on two threads and, beside
    another solve, on one; the analysis is done again for the new count (a factorisation on fewer threads than its
    analysis failed), and only then."""
    rows, cols, values = _spd(3000, seed=1)
    factor = solver.FACTORISATIONS["pardiso"](rows, cols, 3000, reproducible=cores.PARDISO_THREADS)
    calls = _calls(monkeypatch)
    rhs = np.linspace(-1.0, 1.0, 3000)
    alone = factor.factorise(values)(rhs)
    with cores.CORES.beside():
        beside = factor.factorise(values)(rhs)
    again = factor.factorise(values)(rhs)
    assert alone.tobytes() == beside.tobytes() == again.tobytes()
    analysed = [] if CORES == 1 else [(11, 1), (11, CORES)]
    assert [c for c in calls if c[0] == 11] == analysed
    assert [c for c in calls if c[0] == 22] == [(22, CORES), (22, 1), (22, CORES)]


def test_while_a_solve_runs_beside_every_factorisation_takes_one_thread():
    """``Cores.beside()``: its thread and every other one factorise on one thread while it lasts (two such solves
    at once too), on all the reproducible mode takes before and after."""
    shared, inside, entered, done = cores.Cores(), [], threading.Event(), threading.Event()

    def beside():
        with shared.beside():
            entered.set()
            inside.append(shared.threads())
            done.wait()

    assert shared.threads() == CORES
    with ThreadPoolExecutor(max_workers=1) as pool:
        future = pool.submit(beside)
        entered.wait()
        others = shared.threads()
        with shared.beside():
            both = shared.threads()
        still = shared.threads()
        done.set()
        future.result()
    assert inside == [1] and others == both == still == 1 and shared.threads() == CORES


def test_a_machine_whose_cores_are_unknown_factorises_on_one_thread(monkeypatch):
    monkeypatch.setattr(cores.os, "cpu_count", lambda: None)
    assert cores.Cores().threads() == 1


def test_the_solve_beside_the_others_runs_as_one_beside_them():
    """:class:`Beside` solves its stage inside ``CORES.beside()`` on its thread."""
    p, _ = problem()
    beside = Beside(lambda stage, work=None: cores.CORES.threads(), concurrent=True)
    beside.start(replace(paper_stage(p), start=p.x0))
    ((_, future),) = beside._pending.values()
    assert future.result() == 1
    beside.close()
    assert cores.CORES.threads() == CORES


def test_a_mesh_has_the_same_bits_with_its_factorisations_on_one_thread_and_on_two(monkeypatch):
    """ "bounded" on a dome with every factorisation in the reproducible mode (the threshold lowered to 0): the same
    mesh and work, bit for bit, with the factorisations on the machine's two threads and all on one."""
    monkeypatch.setattr(solver, "PARDISO_THREADS_FROM", 0)
    surface = dome(rise=10.0, seed=3, jitter=1.0)
    runs = []
    for threads in (None, 1):
        with monkeypatch.context() as patched:
            calls = _calls(patched)
            if threads:
                patched.setattr(cores.Cores, "threads", lambda self: threads)
            mesh = mesh_surface(surface, 2.5, placement="default")
        runs.append((mesh.uv.tobytes(), mesh.points.tobytes(), mesh.stages.optimization.njev))
        assert {t for _, t in calls} == ({1, CORES} if threads is None else {1})
    assert runs[0] == runs[1]


def test_the_driver_solves_beside_on_one_thread(monkeypatch):
    """The driver's solve beside the others (bounded's second start) factorises on one thread, inside
    ``CORES.beside()``."""
    seen, solve = [], driver._solve

    def spied(problem, stage, *args, **kwargs):
        seen.append((threading.current_thread() is threading.main_thread(), cores.CORES.threads()))
        return solve(problem, stage, *args, **kwargs)

    monkeypatch.setattr(driver, "_solve", spied)
    mesh_surface(dome(rise=10.0, seed=3, jitter=1.0), 5.0, placement="default")
    assert (False, 1) in seen


def test_each_call_sets_its_threads_and_restores_the_callers(monkeypatch):
    """Every PARDISO phase runs with MKL's thread count of this thread set to the factorisation's (one sequentially,
    ``CORES.threads()`` reproducibly), and the caller's count is put back after it."""
    rows, cols, values = _spd(500, seed=2)
    for reproducible, expected in ((0, 1), (cores.PARDISO_THREADS, CORES)):
        factor = solver.FACTORISATIONS["pardiso"](rows, cols, 500, reproducible=reproducible)
        settings = []

        class Recorded:  # MKL's setter, recorded: it returns the count it replaced, the caller's
            def MKL_Set_Num_Threads_Local(self, count):
                settings.append(count)
                return "caller's"

        monkeypatch.setattr(factor._solver, "libmkl", Recorded())
        factor.factorise(values)(np.ones(500))
        assert settings == [expected, "caller's", expected, "caller's"]
