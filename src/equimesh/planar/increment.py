"""Problem 1: Algorithm INCREMENT (Section 2 of the paper).

Step 1  S := {}.
Step 2  resample the boundary so consecutive points are between l and 2l apart
        (:func:`equimesh.planar.boundary.resample.resample_boundary`).
Step 3  find the point p* of P farthest from the current points
        (:mod:`equimesh.planar.insertion`).
Step 4  insert p* while d(p*, S u V u V') >= l, up to REL_TOL.
Step 5  output the Delaunay triangulation of S u V' u V.

Theorem 1: every edge of the output lies in [l, 2l] (up to REL_TOL).
Theorem 2: the node count is at most 16/3 of the optimum (checked against
:func:`equimesh.planar.bounds.node_lower_bound`).
"""

import numpy as np

from .._checks import check_length
from ..mesh import PlanarMesh, boundary_first
from .boundary.resample import resample_boundary
from .boundary.separation import check_boundary_separation
from .guarantees import verify_planar
from .insertion import DEFAULT_ENGINE, Region, check_engine, insert
from .limits import MAX_NODES, check_max_nodes, check_size, planar_estimate
from .polygon import as_polygon, check_convex_right_angles, check_edges_at_least, pinned_vertices


def validate_problem1(vertices, l):
    """Validate the input of Problem 1 and return ``(polygon, l)``.

    The polygon must be simple, convex, with every inner angle at least 90
    degrees and every edge at least ``l`` long; ``l`` positive, finite and in
    the supported range.  The polygon's local frame scales ``l`` into [1, 2).
    """
    l = check_length(l)
    poly = as_polygon(vertices, l)
    check_convex_right_angles(poly)
    check_edges_at_least(poly, l)
    return poly, l


def increment(vertices, l, *, engine=DEFAULT_ENGINE, max_nodes="default"):
    """Triangulate a convex polygon with every edge in [l, 2l] (Algorithm INCREMENT).

    Parameters
    ----------
    vertices : (n, 2) array_like
        The polygon, either orientation; convex, inner angles >= 90 degrees,
        edges >= l.
    l : float
        The minimum edge length.
    engine : str
        Name of the insertion engine (see :data:`equimesh.planar.insertion.ENGINES`):
        "fast" (the default) or "reference" (the oracle, slow).
    max_nodes : int, None or "default"
        Refuse, before any heavy work, a polygon whose estimated node count
        (Oler's bound) exceeds this; "default" is the engine's limit
        (:data:`equimesh.planar.limits.MAX_NODES`), None no limit.

    Returns
    -------
    PlanarMesh
        Points (boundary points first, counter-clockwise from the polygon's
        first vertex, then inserted points in insertion order), the Delaunay
        triangulation and its edges.  Theorem 1 is checked on it before it is
        returned (:func:`equimesh.planar.guarantees.verify_planar`).
    """
    check_engine(engine)
    max_nodes = check_max_nodes(max_nodes, MAX_NODES[engine])
    poly, l = validate_problem1(vertices, l)
    lp = poly.local_length(l)
    check_size(*planar_estimate(poly, l, None, engine), max_nodes, l)
    boundary = resample_boundary(poly, l)
    check_boundary_separation(poly, boundary, l)
    region = Region(boundary.points, boundary.segments, np.zeros((0, 2)))  # convex: no hole
    result = insert(region, lp, engine=engine)
    order, inverse, n_ring = boundary_first(result.segments, len(result.points))
    mesh = PlanarMesh.build(
        result.points[order],
        inverse[result.triangles],
        l,
        n_ring,
        info={"n_inserted": len(result.points) - result.n_initial},
        frame=poly.frame,
        pinned=pinned_vertices(poly),
    )
    return verify_planar(mesh)
