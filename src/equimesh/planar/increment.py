"""Problem 1: Algorithm INCREMENT (Section 2 of the paper).

Step 1  S := {}.
Step 2  resample the boundary so consecutive points are between l and 2l apart
        (:func:`equimesh.planar.polygon.resample_boundary`).
Step 3  find the point p* of P farthest from the current points
        (:mod:`equimesh.planar.insertion`).
Step 4  insert p* while d(p*, S u V u V') >= l, up to REL_TOL.
Step 5  output the Delaunay triangulation of S u V' u V.

Theorem 1: every edge of the output lies in [l, 2l] (up to REL_TOL).
Theorem 2: the node count is at most 16/3 of the optimum (checked against
:func:`equimesh.planar.bounds.node_lower_bound`).
"""

import numpy as np

from .insertion import Region, insert
from ..mesh import PlanarMesh, boundary_first
from .polygon import (
    as_polygon,
    check_boundary_separation,
    check_convex_right_angles,
    check_edges_at_least,
    check_length,
    resample_boundary,
)


def validate_problem1(vertices, l):
    """Validate the input of Problem 1 and return ``(polygon, l)``.

    The polygon must be simple, convex, with every inner angle at least 90
    degrees and every edge at least ``l`` long; ``l`` positive and finite.
    """
    l = check_length(l)
    poly = as_polygon(vertices)
    check_convex_right_angles(poly)
    check_edges_at_least(poly, l)
    return poly, l


def increment(vertices, l, *, engine="reference"):
    """Triangulate a convex polygon with every edge in [l, 2l] (Algorithm INCREMENT).

    Parameters
    ----------
    vertices : (n, 2) array_like
        The polygon, either orientation; convex, inner angles >= 90 degrees,
        edges >= l.
    l : float
        The minimum edge length.
    engine : str
        Name of the insertion engine (see :data:`equimesh.planar.insertion.ENGINES`).

    Returns
    -------
    PlanarMesh
        Points (boundary points first, counter-clockwise from the polygon's
        first vertex, then inserted points in insertion order), the Delaunay
        triangulation and its edges.
    """
    poly, l = validate_problem1(vertices, l)
    boundary = resample_boundary(poly, l)
    check_boundary_separation(poly, boundary, l)
    region = Region(boundary.points, boundary.segments, np.empty((0, 2)))
    result = insert(region, l, engine=engine)
    order, inverse, n_ring = boundary_first(result.segments, len(result.points))
    return PlanarMesh.build(
        result.points[order],
        inverse[result.triangles],
        l,
        n_ring,
        info={"n_inserted": len(result.points) - result.n_initial},
    )
