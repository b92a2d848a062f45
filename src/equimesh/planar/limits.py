"""Beyond the paper: the size guard shared by the planar algorithms and the surface pipeline.

``max_nodes`` bounds, before any heavy work, the estimated number of nodes a
run has to place; its default depends on the insertion engine
(:data:`MAX_NODES`; docs/decisions.md, "A size guard per engine"):

* the reference engine re-triangulates after every inserted point and tests
  every candidate against every constraint, far more than linear time in the
  nodes it inserts, so only those count: Problem 1 every node (Oler's bound
  on an l-separated set, :func:`node_estimate`), Problem 2 the nodes of the
  boundary strip R, which lies within ``(clearance + 1) l`` of the boundary
  (:mod:`equimesh.planar.lattice`; the lattice part is vectorised, and by the
  isoperimetric inequality its bounding-box grid has at most about
  ``0.3 (perimeter / l)^2`` vertices, so bounding the strip bounds it too);
* the fast engine runs in about O(n log n), and at its limit the lattice
  part and the memory of the whole mesh matter as much as the strip: every
  node of the polygon counts (Oler's bound on the whole polygon), for
  Problem 2 and the lattice placement search too.
"""

import math

from .._checks import check_count
from ..errors import MeshTooLargeError
from .insertion import check_engine

#: Default of ``max_nodes`` (``max_nodes="default"``) for each insertion engine,
#: in the nodes it counts (module docstring).  Reference: a run at 2500 takes
#: about a minute; fast: 10^6 nodes take about 20 s and stay under 1 GB (the
#: memory, not the time, sets it; docs/decisions.md, "A size guard per engine").
#: ``None`` means no limit.
MAX_NODES = {"reference": 2500, "fast": 1_000_000}


def check_max_nodes(value, default):
    """``max_nodes`` as an int, None for no limit, or ``"default"``: then ``default``, the caller's own limit."""
    if isinstance(value, str) and value == "default":
        return default
    return None if value is None else check_count(value, 'max_nodes (None for no limit, "default" for the default)')


def planar_estimate(poly, l, strip, engine):
    """The node count ``max_nodes`` bounds for ``engine``: ``(what, estimate)`` (module docstring).

    ``strip`` is the reference engine's count for Problem 2 (the boundary
    strip's estimate), None for Problem 1.
    """
    if strip is not None and check_engine(engine) == "reference":
        return "the boundary strip", strip
    return "the polygon", node_estimate(poly.local_area, poly.local_perimeter, poly.local_length(l))


def node_estimate(area, perimeter, l):
    """Oler's bound ``2 / sqrt(3) A / l^2 + perimeter / (2 l) + 1`` on points pairwise l apart (see bounds.py).

    Exact for convex sets; an estimate for others.  Plain floats, so a tiny
    ``l`` gives a huge number (or inf), never an exception.
    """
    return 2.0 / math.sqrt(3.0) * area / (l * l) + perimeter / (2.0 * l) + 1.0


def check_size(what, estimate, max_nodes, l):
    """Refuse a run whose ``estimate`` (nodes of ``what``) exceeds ``max_nodes`` (None: no limit)."""
    if max_nodes is not None and not estimate <= max_nodes:
        about = f"about {estimate:.3g}" if math.isfinite(estimate) else "more than 1e308"
        raise MeshTooLargeError(
            f"l = {l!r} would need {about} nodes in {what}, more than max_nodes = {max_nodes}; "
            "use a larger l or raise max_nodes (--max-nodes on the command line; None for no limit)"
        )
