"""Bounds on node counts for Problem 1 (used to check Theorem 2).

``node_lower_bound`` is a proven lower bound on the optimal node count n* of
Problem 1; ``packing_upper_bound`` a proven upper bound on the size of any
point set in P whose points are pairwise at least l apart (every output of
Algorithm INCREMENT is one).
"""

import math

from .increment import validate_problem1
from .limits import node_estimate


def node_lower_bound(vertices, l):
    """A lower bound on the optimal node count n* of Problem 1.

    Derivation.  Let T be any triangulation of P with every edge in [l, 2l],
    with n vertices of which h lie on the boundary of P.

    * A triangle with all edges at most ``2l`` has area at most that of the
      equilateral triangle of side ``2l``, ``sqrt(3) l^2`` (among triangles
      with edges bounded by ``s`` the equilateral one of side ``s`` has the
      largest area).  So T has at least ``ceil(A / (sqrt(3) l^2))`` triangles.
    * Euler's formula for a triangulated polygon: T has ``2n - h - 2``
      triangles.
    * Every vertex of P is a vertex of T, so ``h >= |V|``; the boundary is
      covered by edges of length at most ``2l``, so ``h >= ceil(perimeter / 2l)``.

    Hence ``2n - h - 2 >= ceil(A / (sqrt(3) l^2))`` and, as ``n`` grows with
    ``h``, ``n >= ceil((ceil(A / (sqrt(3) l^2)) + h_min + 2) / 2)``.

    Computed in the polygon's local frame (l in [1, 2)), so that neither a
    tiny l nor large coordinates overflow.
    """
    poly, l = validate_problem1(vertices, l)
    lp = poly.local_length(l)
    triangles = math.ceil(poly.local_area / (math.sqrt(3.0) * lp * lp) - 1e-12)
    h_min = max(len(poly.vertices), math.ceil(poly.local_perimeter / (2.0 * lp) - 1e-12))
    return math.ceil((triangles + h_min + 2) / 2)


def packing_upper_bound(vertices, l):
    """Upper bound on the number of points in P pairwise at least ``l`` apart.

    Oler's inequality (N. Oler, "An inequality in the geometry of numbers",
    Acta Math. 105, 1961; for every compact convex set by Folkman and Graham,
    1969): at most ``2 / sqrt(3) * A / l^2 + perimeter / (2 l) + 1`` points of
    a convex set of area A are pairwise at least l apart.
    """
    poly, l = validate_problem1(vertices, l)
    return math.floor(node_estimate(poly.local_area, poly.local_perimeter, poly.local_length(l)))
