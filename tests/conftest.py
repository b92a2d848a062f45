"""Hypothesis profiles, the experiment loader, and a note on conditional properties never exercised.

Profiles, chosen by the environment variable EQUIMESH_HYPOTHESIS_PROFILE:

* ``ci`` (default): 25 examples per property, derandomized so that every run
  of the suite checks the same examples; quick enough for ``make test``.
* ``thorough``: 500 examples per property, random; run it before a release:
  ``EQUIMESH_HYPOTHESIS_PROFILE=thorough python -m pytest -n 2 tests``.

No deadline in either: the reference engine re-triangulates after every
inserted point, so the time of one example grows with the polygon's area.

Replaying a failure.  Both profiles print the ``@reproduce_failure(...)``
blob of a failing example (``print_blob``).  A random profile also runs with
a seed that is printed in the header and again after failures
("hypothesis seed: N"): ``--hypothesis-seed=N`` with the same profile runs
the same examples again (one is drawn when none is given; under
pytest-xdist the controller draws it and the workers inherit it).

Fixture ``load_experiment``: import ``experiments/<name>.py`` for a smoke test.
Fixture ``saddle_mesh``: one mesh of a real surface, made once, for the writers of ``equimesh.io``.

Conditional properties.  A property that only says something when a
condition holds (``assume(c)``, or ``if c: check(...)``) passes vacuously if
the generated inputs never satisfy ``c``.  Such a test wraps the condition in
:func:`exercised`::

    from conftest import exercised

    assume(exercised("strip vertices globally separated (hypothesis H)", separated))

and the end of the run lists every condition that was reached but never held
("conditional properties never exercised: ..."), also under ``pytest -n 2``.
"""

import collections
import importlib
import os
import random
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, currently_in_test_context, event, settings

settings.register_profile(
    "ci",
    max_examples=25,
    deadline=None,
    derandomize=True,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile(
    "thorough",
    max_examples=500,
    deadline=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile(os.environ.get("EQUIMESH_HYPOTHESIS_PROFILE", "ci"))


EXPERIMENTS = Path(__file__).resolve().parent.parent / "experiments"


# --------------------------------------------------------------------------- a printed seed for random profiles


_SEED_KEY = "equimesh_hypothesis_seed"


@pytest.hookimpl(tryfirst=True)
def pytest_configure(config):
    """A random profile without ``--hypothesis-seed``: draw one, before hypothesis's plugin reads the option.

    A pytest-xdist worker takes the controller's (:func:`pytest_configure_node`).
    """
    if settings.default.derandomize or config.getoption("hypothesis_seed") is not None:
        return
    worker = getattr(config, "workerinput", None)
    config.option.hypothesis_seed = worker[_SEED_KEY] if worker else str(random.SystemRandom().randrange(2**32))


@pytest.hookimpl(optionalhook=True)
def pytest_configure_node(node):
    """Controller side of :func:`pytest_configure`: hand the seed to a starting worker."""
    node.workerinput[_SEED_KEY] = node.config.getoption("hypothesis_seed")


def replay_line(config):
    """How to run the same examples again, or None for a derandomized profile."""
    seed = config.getoption("hypothesis_seed")
    if settings.default.derandomize or seed is None:
        return None
    profile = settings.get_current_profile_name()
    return (
        f"hypothesis seed: {seed} (replay: EQUIMESH_HYPOTHESIS_PROFILE={profile} pytest --hypothesis-seed={seed} ...)"
    )


def pytest_report_header(config):
    return replay_line(config)


@pytest.fixture(scope="session")
def load_experiment():
    """``load_experiment(name)`` imports ``experiments/<name>.py`` as the module ``name``.

    The folder goes on ``sys.path`` (not just a module spec) so that worker
    processes started by the experiment can import it by name too, and so
    that the scripts find ``experiments/_common.py``.
    """
    folder = str(EXPERIMENTS)
    sys.path.insert(0, folder)
    yield importlib.import_module
    sys.path.remove(folder)


@pytest.fixture(scope="session")
def saddle_mesh():
    """The saddle of experiments/surfaces at l = 6 on an 8 x 8 grid, optimised ("bounded"): about a hundred nodes."""
    from equimesh import load_surface, mesh_surface

    return mesh_surface(load_surface(EXPERIMENTS / "surfaces" / "saddle.json"), 6.0, grid=(8, 8))


# --------------------------------------------------------------------------- conditional properties

#: Condition name -> [times reached, times held], in this process.
_CONDITIONS = collections.defaultdict(lambda: [0, 0])
_WORKER_KEY = "equimesh_exercised"


def exercised(name, held):
    """Record that the condition ``name`` was evaluated and whether it ``held``; returns ``held``.

    Also a hypothesis ``event`` inside a property test (``--hypothesis-show-statistics``).
    """
    held = bool(held)
    counts = _CONDITIONS[name]
    counts[0] += 1
    counts[1] += held
    if currently_in_test_context():
        event(f"{name}: {'held' if held else 'did not hold'}")
    return held


def never_exercised(conditions):
    """Lines naming each condition of ``{name: (reached, held)}`` that was reached but never held."""
    return [
        f"{name}: never held in {reached} evaluation(s)"
        for name, (reached, held) in sorted(conditions.items())
        if not held
    ]


def pytest_sessionfinish(session):
    """Under pytest-xdist a worker hands its counts to the controller."""
    output = getattr(session.config, "workeroutput", None)
    if output is not None:
        output[_WORKER_KEY] = {name: tuple(counts) for name, counts in _CONDITIONS.items()}


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    """Controller side of :func:`pytest_sessionfinish`: add a finished worker's counts."""
    for name, (reached, held) in getattr(node, "workeroutput", {}).get(_WORKER_KEY, {}).items():
        _CONDITIONS[name][0] += reached
        _CONDITIONS[name][1] += held


def pytest_terminal_summary(terminalreporter, exitstatus):
    replay = replay_line(terminalreporter.config)
    if replay and exitstatus != 0:
        terminalreporter.section("replaying the failures", red=True)
        terminalreporter.write_line(replay)
    lines = never_exercised(_CONDITIONS)
    if lines:
        terminalreporter.section("conditional properties never exercised", yellow=True)
        for line in lines:
            terminalreporter.write_line(line)
