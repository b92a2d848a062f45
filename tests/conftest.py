"""Hypothesis profiles, chosen by the environment variable EQUIMESH_HYPOTHESIS_PROFILE.

* ``ci`` (default): 25 examples per property, derandomized so that every run
  of the suite checks the same examples; quick enough for ``make test``.
* ``thorough``: 500 examples per property, random; run it before a release:
  ``EQUIMESH_HYPOTHESIS_PROFILE=thorough python -m pytest -n 2 tests``.

No deadline in either: the reference engine re-triangulates after every
inserted point, so the time of one example grows with the polygon's area.

Fixture ``load_experiment``: import ``experiments/<name>.py`` for a smoke test.
"""

import importlib
import os
from pathlib import Path

import pytest
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


@pytest.fixture
def load_experiment(monkeypatch):
    """``load_experiment(name)`` imports ``experiments/<name>.py``.

    The folder goes on ``sys.path`` (not just a module spec) so that worker
    processes started by the experiment can import it by name too.
    """
    monkeypatch.syspath_prepend(str(EXPERIMENTS))
    return importlib.import_module
