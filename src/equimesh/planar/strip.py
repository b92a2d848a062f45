"""Problem 2 (Section 3 of the paper): a triangulation with most edges exactly l.

1. Step 2 of Algorithm INCREMENT on the boundary of P (any simple polygon).
2. The lattice part K (the paper's H', :mod:`equimesh.planar.lattice`).
3. The boundary strip R = P \\ K is filled by farthest-point insertion under
   the visibility distance ``d~`` (:mod:`equimesh.planar.insertion`), the
   constraints being the boundary of P and the boundary of K.
4. Output: the constrained Delaunay triangulation of R plus the lattice
   triangles of K, one conforming triangulation of P.

Theorem 3 (every edge in [l, 2l]).  Edges of K have length l.  In R every
edge joins two points that see each other, all of them pairwise at least
``(1 - REL_TOL) l`` apart (boundary points by the validation of Lemma 3 (1),
lattice vertices by the clearance, inserted points by Step 4).  A triangle of
R whose circumcentre is visible from it had that circumcentre as a candidate,
so its circumradius is below ``(1 - REL_TOL) l`` and its edges below ``2l``
(Lemma 4, the counterpart of Lemma 1).  A triangle whose circumcentre c is
hidden behind a constraint ``e = ab`` (the first one crossed from the
triangle towards c) has ``a`` and ``b`` outside its circumcircle (a constraint
endpoint inside the circle would give a vertex visible from the triangle
inside the circle, against the CDT property), so the circle meets the line of
``e`` in a chord contained in ``e``; the triangle lies in the cap cut off by
that chord on the side away from c, whose diameter is the chord: its edges
are at most ``|e| <= 2l`` (Lemma 5, the counterpart of Lemma 2).
"""

import numpy as np
import shapely

from .._checks import check_length, real_array, real_number
from ..errors import EquimeshError
from ..mesh import PlanarMesh, boundary_first, boundary_ring, unique_edges
from .boundary.phase import in_phase
from .boundary.resample import resample_boundary
from .boundary.separation import check_boundary_separation
from .guarantees import verify_planar
from .insertion import DEFAULT_ENGINE, Region, check_engine, insert
from .lattice import lattice_adjacent, lattice_part
from .limits import MAX_NODES, check_max_nodes, check_size, node_estimate, planar_estimate
from .polygon import as_polygon, check_edges_at_least, pinned_vertices

#: Default Step 2 spacing for Problem 2, in units of l.  Below 2 so that no
#: boundary part is 2l long: a part of exactly 2l leaves its midpoint at
#: distance exactly l and the farthest point then lands a hair inside the
#: boundary, a sliver.  With parts of at most 1.5 l a point inserted against a
#: boundary part is at least ``l sqrt(1 - 0.75^2) = 0.66 l`` inside it.  Among
#: the spacings 1.0, 1.2, 1.5, 1.8 and 2.0 compared by ``experiments/problem2.py``
#: (results/problem2.md), 1.8 gives a mean G1 share up to 0.9 points larger and
#: 1.5 the larger smallest angle; we take the angle (docs/decisions.md,
#: "Boundary parts of at most 1.5 l in Problem 2").
BOUNDARY_SPACING = 1.5
#: Step 2's points (``boundary=`` of :func:`uniform_triangulation`): the paper's equal parts, or in phase with the
#: lattice on straight sides along or across it (beyond the paper).
BOUNDARIES = ("equal", "lattice")


def uniform_triangulation(
    vertices,
    l,
    *,
    holes=None,
    angle=0.0,
    offset=(0.0, 0.0),
    clearance=1.0,
    boundary_spacing=BOUNDARY_SPACING,
    boundary="equal",
    engine=DEFAULT_ENGINE,
    max_nodes="default",
):
    """Triangulate a simple polygon with most edges exactly ``l`` and all in [l, 2l] (Problem 2).

    Parameters
    ----------
    vertices : (n, 2) array_like
        A simple polygon, convex or not, either orientation; every edge at
        least ``l`` long (longer than ``2l`` is resampled as in Step 2), and
        mutually visible boundary points at least ``l`` apart.
    l : float
        Lattice spacing and minimum edge length.
    holes : list of (k, 2) array_like, optional
        Openings: simple polygons, either orientation, strictly inside the
        polygon, each at least ``l`` from its boundary and from every other
        hole (Lemma 3 (1) across boundaries), every edge at least ``l`` long.
        The lattice is kept ``clearance * l`` from every boundary and the
        strip is filled between the outer boundary, the holes and the lattice.
    angle : float
        Direction of the first lattice vector, in degrees (taken modulo 60,
        the lattice's symmetry).
    offset : (2,) array_like
        Position of the lattice vertex (0, 0).
    clearance : float
        Lattice vertices closer than ``clearance * l`` to the boundary of P
        are removed; at least 1 (Lemma 3).
    boundary_spacing : float
        Target length, in units of l, of the parts long boundary edges are
        split into (Step 2); kept within [l, 2l].
    boundary : "equal" or "lattice"
        Step 2's points: the paper's equal parts, or (beyond the paper) on
        straight sides along or across a lattice direction the lattice's
        period, in phase with its first row, so the strip there repeats
        (:func:`~equimesh.planar.boundary.phase.in_phase`).
    engine : str
        Insertion engine for the boundary strip: "fast" (the default) or
        "reference" (the oracle, slow).
    max_nodes : int, None or "default"
        Refuse, before any heavy work, a polygon estimated to need more nodes
        than this (the boundary strip's for the reference engine, the whole
        polygon's for the fast one, :mod:`equimesh.planar.limits`); "default"
        is the engine's limit (:data:`equimesh.planar.limits.MAX_NODES`), None
        no limit.

    Returns
    -------
    PlanarMesh
        Points: the boundary of P (counter-clockwise from vertex 0, with any
        point inserted on it), then each hole's boundary (clockwise), then
        the rest; ``n_boundary`` counts all boundary points and
        ``info["boundary_rings"]`` the points of each ring (outer first);
        ``edge_groups`` marks the lattice edges (length exactly l) as G1.  Theorem 3 is checked on it
        before it is returned (:func:`equimesh.planar.guarantees.verify_planar`).
    """
    l = check_length(l)
    clearance = check_clearance(clearance)
    offset = _check_pair(offset, "offset")
    angle = _check_scalar(angle, "angle")
    spacing = check_spacing(boundary_spacing)
    if boundary not in BOUNDARIES:
        raise EquimeshError(f"boundary must be one of {BOUNDARIES}, got {boundary!r}")
    check_engine(engine)
    max_nodes = check_max_nodes(max_nodes, MAX_NODES[engine])
    poly = as_polygon(vertices, l, holes)
    check_edges_at_least(poly, l)
    check_size(*planar_estimate(poly, l, strip_estimate(poly, l, clearance), engine), max_nodes, l)
    equal = resample_boundary(poly, l, spacing)
    check_boundary_separation(poly, equal, l)
    lat = lattice_part(poly, l, angle, offset, clearance)
    sampled = in_phase(poly, equal, lat, angle, l) if boundary == "lattice" else equal

    nb = len(sampled.points)
    lat_boundary = lat.boundary_vertices
    lat_index = np.full(len(lat.points), -1, dtype=np.int64)
    lat_index[lat_boundary] = nb + np.arange(len(lat_boundary))
    region = Region(
        np.vstack([sampled.points, lat.points[lat_boundary]]),
        np.vstack([sampled.segments, lat_index[lat.boundary_edges]]).astype(np.int64),
        np.vstack([lat.holes, *(hole_seed(hole) for hole in poly.holes)]),
    )
    strip = insert(region, poly.local_length(l), engine=engine)

    interior = np.flatnonzero(lat_index < 0)
    lat_index[interior] = len(strip.points) + np.arange(len(interior))
    points = np.vstack([strip.points, lat.points[interior]])
    triangles = np.vstack([strip.triangles, lat_index[lat.triangles]])
    ij = np.full((len(points), 2), np.iinfo(np.int64).min, dtype=np.int64)
    ij[lat_index] = lat.ij
    is_lattice = np.zeros(len(points), dtype=bool)
    is_lattice[lat_index] = True

    starts = np.cumsum(sampled.ring_sizes) - sampled.ring_sizes
    rings = tuple(len(boundary_ring(strip.segments, start)) for start in starts)
    order, inverse, n_ring = boundary_first(strip.segments, len(points), starts)
    mesh_edges = unique_edges(triangles)
    both = is_lattice[mesh_edges[:, 0]] & is_lattice[mesh_edges[:, 1]]
    g1 = mesh_edges[both][lattice_adjacent(ij[mesh_edges[both, 0]], ij[mesh_edges[both, 1]])]
    mesh = PlanarMesh.build(
        points[order],
        inverse[triangles],
        l,
        n_ring,
        g1_edges=inverse[g1],
        info={
            "n_lattice_vertices": len(lat.points),
            "n_lattice_triangles": len(lat.triangles),
            "n_inserted": len(strip.points) - strip.n_initial,
            "angle": angle,
            "offset": tuple(offset),
            "clearance": clearance,
            "boundary_rings": rings,
            "boundary": "equal" if sampled is equal else "lattice",
        },
        frame=poly.frame,
        pinned=pinned_vertices(poly),
    )
    return verify_planar(mesh)


def hole_seed(hole):
    """A point strictly inside a hole's ring (local frame): the seed that tells the CDT to leave the hole empty."""
    point = shapely.Polygon(hole.local).representative_point()
    return np.array([[point.x, point.y]])


def strip_estimate(poly, l, clearance):
    """Estimated node count of the boundary strip R (what the insertion engine pays for).

    R lies within ``(clearance + 1) l`` of the boundary (:mod:`.lattice`), so
    its area is at most ``min(A, (clearance + 1) l perimeter)``; Oler's bound
    on that area, plus the lattice vertices on the boundary of K (about one
    per l of perimeter).
    """
    lp, perimeter = poly.local_length(l), poly.local_perimeter
    area = min(poly.local_area, (clearance + 1.0) * lp * perimeter)
    return node_estimate(area, perimeter, lp) + perimeter / lp


def _check_scalar(value, name):
    v = real_number(value, name, EquimeshError)
    if not np.isfinite(v):
        raise EquimeshError(f"{name} must be finite, got {v!r}")
    return v


def _check_pair(value, name):
    v = real_array(value, name, EquimeshError).reshape(-1)
    if v.shape != (2,) or not np.all(np.isfinite(v)):
        raise EquimeshError(f"{name} must be a pair of finite numbers, got {value!r}")
    return v


def check_clearance(value):
    """``clearance`` as a float, at least 1 (Lemma 3)."""
    c = _check_scalar(value, "clearance")
    if c < 1.0:
        raise EquimeshError(
            f"clearance must be at least 1 (Lemma 3 needs lattice vertices l from the boundary), got {c}"
        )
    return c


def check_spacing(value):
    """``boundary_spacing`` as a float in [1, 2] (units of l, Step 2)."""
    s = _check_scalar(value, "boundary_spacing")
    if not 1.0 <= s <= 2.0:
        raise EquimeshError(f"boundary_spacing must be between 1 and 2 (units of l, Step 2), got {s}")
    return s
