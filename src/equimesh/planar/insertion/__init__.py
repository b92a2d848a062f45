"""Farthest-point (Voronoi) insertion under visibility distance.

One engine serves both problems of the paper:

* Problem 1 (Algorithm INCREMENT, Steps 3-5): the region is the convex polygon
  P, its resampled boundary the only constraint; every point sees every other,
  and the constrained Delaunay triangulation is the Delaunay triangulation.
* Problem 2 (Section 3): the region is the boundary strip R = P minus the kept
  lattice triangles; the constraints are the boundary of P and of the lattice
  part, and a point hidden behind a constraint is infinitely far (the paper's
  visibility distance ``d~``).

Engines are chosen by name from :data:`ENGINES`; every engine has the
signature ``engine(region, l) -> Insertion``.
"""

from ...errors import EquimeshError
from .fast import run as _fast
from .reference import run as _reference
from .region import Insertion, Region

#: Available insertion engines, by name.
ENGINES = {"reference": _reference, "fast": _fast}

#: The engine every verb uses unless told otherwise (the fast engine,
#: tested against the reference, which stays as the oracle).
DEFAULT_ENGINE = "fast"


def check_engine(engine):
    """``engine`` if it names an engine of :data:`ENGINES`, else a clear error listing them."""
    if not (isinstance(engine, str) and engine in ENGINES):
        raise EquimeshError(f"unknown insertion engine {engine!r}; choose from {sorted(ENGINES)}")
    return engine


def insert(region, l, engine=DEFAULT_ENGINE):
    """Run farthest-point insertion in ``region`` with minimum distance ``l``."""
    return ENGINES[check_engine(engine)](region, l)


__all__ = ["DEFAULT_ENGINE", "ENGINES", "Insertion", "Region", "check_engine", "insert"]
