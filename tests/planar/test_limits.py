"""The size guard of Problems 1 and 2 (``planar/limits.py``): no run without a bound on its size.

What must hold: a request whose estimate exceeds ``max_nodes`` (each engine's default, or the caller's) is
refused before any work, with the estimate, the limit and what to change; ``max_nodes`` is a positive integer
or None (no limit).
"""

import numpy as np
import pytest

import equimesh
from equimesh import EquimeshError, MeshTooLargeError

SQUARE10 = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])


REFERENCE = {"engine": "reference"}


@pytest.mark.parametrize(
    "verb, l, kwargs, what, limit",
    [
        (equimesh.increment, 0.1, REFERENCE, "the polygon", 2500),
        (equimesh.uniform_triangulation, 1e-3, REFERENCE, "the boundary strip", 2500),
        (equimesh.increment, 1e-2, {}, "the polygon", 1000000),
        (equimesh.uniform_triangulation, 1e-2, {}, "the polygon", 1000000),
        (equimesh.best_lattice_placement, 1e-2, {}, "the polygon", 1000000),
    ],
)
def test_size_guard_refuses_before_any_work(verb, l, kwargs, what, limit):
    """Runs that would be unbounded are refused with the estimate, the engine's limit and what to change."""
    with pytest.raises(
        MeshTooLargeError, match=rf"would need about .* nodes in {what}, more than max_nodes = {limit}; use a larger l"
    ):
        verb(SQUARE10, l, **kwargs)


@pytest.mark.parametrize("bad", [0, -1, 2.5, True, float("nan"), "10"])
def test_max_nodes_must_be_a_positive_integer_or_none(bad):
    for verb in (equimesh.increment, equimesh.uniform_triangulation):
        with pytest.raises(EquimeshError, match=r"max_nodes .* must be an integer of at least 1"):
            verb(SQUARE10, 1.0, max_nodes=bad)


def test_max_nodes_none_and_small_limits():
    """None means no limit; a limit below the estimate refuses the same input."""
    assert equimesh.increment(SQUARE10 / 2, 1.0, max_nodes=None).n_nodes > 0
    with pytest.raises(MeshTooLargeError):
        equimesh.increment(SQUARE10 / 2, 1.0, max_nodes=10)
    with pytest.raises(MeshTooLargeError):
        equimesh.uniform_triangulation(SQUARE10, 1.0, max_nodes=10)
