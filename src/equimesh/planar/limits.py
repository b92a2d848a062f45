"""Beyond the paper: the size guard shared by the planar algorithms and the surface pipeline.

The reference insertion engine re-triangulates after every inserted point and
tests every candidate against every constraint, so a run costs far more than
linear time in its node count (docs/decisions.md, "Hardening of the planar
core", has the measured times).  ``max_nodes`` bounds, before any heavy work,
the estimated number of nodes the farthest-point insertion has to place:

* Problem 1: every node (Oler's bound on an l-separated set, :func:`node_estimate`);
* Problem 2: the nodes of the boundary strip R, which lies within
  ``(clearance + 1) l`` of the boundary (:mod:`equimesh.planar.lattice`).  The
  lattice part is cheap (vectorised) and needs no limit of its own: by the
  isoperimetric inequality its bounding-box grid has at most about
  ``0.3 (perimeter / l)^2`` vertices, so bounding the strip bounds it too.
"""

import math
import numbers

from ..errors import EquimeshError, MeshTooLargeError

#: Default of ``max_nodes``: a run at this estimate takes about a minute on a
#: 2-core machine (docs/decisions.md).  ``None`` means no limit.
MAX_NODES = 2500


def check_count(value, name, least=1):
    """``value`` as an int, refusing anything but an integer of at least ``least`` (bool, 2.5, nan included)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < least:
        raise EquimeshError(f"{name} must be an integer of at least {least}, got {value!r}")
    return int(value)


def check_max_nodes(value):
    """``max_nodes`` as an int, or None for no limit."""
    return None if value is None else check_count(value, "max_nodes (None for no limit)")


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
