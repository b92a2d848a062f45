"""Hypothesis profiles, the experiment loader, and conditional properties that must be exercised.

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
Fixture ``tent_mesh``: seven nodes by hand (a hexagon around a raised apex), three length classes, for the
writers' direct tests, which mutation testing runs once per mutant.

Conditional properties (:mod:`conditions`): the hook that counts, per test, the conditions it evaluates
and fails it when one never held or held less often than its ``exercised`` marker says.
"""

import collections
import importlib
import os
import random
import sys
from pathlib import Path

import numpy as np
import pytest
from conditions import RUNNING, unexercised
from hypothesis import HealthCheck, settings

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

    A pytest-xdist worker takes the controller's (:func:`pytest_configure_node`).  Also registers the marker of
    conditional properties (:func:`pytest_runtest_call`).
    """
    config.addinivalue_line("markers", "exercised(name, share): the condition name holds in share or more of the test")
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


class TentMesh:
    """A hexagon of radius 1 (its nodes at heights 0 and 0.2 in turn) around an apex at height 0.5, l = 1.

    The six sides are 1.0198 long, the spokes 1.1180 (to a low node) and 1.0440 (to a high one): three
    length classes of 6, 3 and 3 members at a tolerance of 1 %; the spokes are G1, the sides not; the first six
    nodes are the boundary.  It has what the writers, the report and the plot read of a mesh.
    """

    def __init__(self):
        from equimesh.mesh import G1, OTHER, unique_edges

        angles = np.arange(6) * np.pi / 3
        ring = np.column_stack([np.cos(angles), np.sin(angles), np.tile([0.0, 0.2], 3)])
        self.points = np.vstack([ring, [0.0, 0.0, 0.5]])
        self.triangles = np.array([[i, (i + 1) % 6, 6] for i in range(6)])
        self.edges = unique_edges(self.triangles)
        self.edge_groups = np.where(self.edges[:, 1] == 6, G1, OTHER).astype(np.int8)
        self.length = 1.0
        self.n_boundary = 6
        self.info = {"boundary_rings": [6]}  # one boundary ring, as a PlanarMesh says

    def edge_lengths(self):
        from equimesh.mesh import edge_lengths

        return edge_lengths(self.points, self.edges)


@pytest.fixture(scope="session")
def tent_mesh():
    """:class:`TentMesh`."""
    return TentMesh()


# --------------------------------------------------------------------------- conditional properties


@pytest.hookimpl(wrapper=True)
def pytest_runtest_call(item):
    """Count the conditions a test evaluates; fail it if one never held or held less often than its marker says."""
    counts = collections.defaultdict(lambda: [0, 0])
    RUNNING.append(counts)
    try:
        result = yield
    finally:
        RUNNING.pop()
    shares = {mark.args[0]: mark.kwargs["share"] for mark in item.iter_markers("exercised")}
    problems = unexercised(counts, shares)
    if problems:
        pytest.fail("\n".join(problems), pytrace=False)
    return result


def pytest_terminal_summary(terminalreporter, exitstatus):
    replay = replay_line(terminalreporter.config)
    if replay and exitstatus != 0:
        terminalreporter.section("replaying the failures", red=True)
        terminalreporter.write_line(replay)
