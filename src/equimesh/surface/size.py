"""The size guard of :func:`~equimesh.surface.pipeline.mesh_surface`: the node count estimated before heavy work.

The estimate is Oler's bound at the lattice density (:func:`~equimesh.planar.limits.node_estimate`) on the
surface's area, before the flattening, and again after it (a chart's flattened outline, a triangle mesh's flattened
triangles) before Problem 2, because eq. (1) can stretch a surface many times (docs/decisions.md, "Size limits of
mesh_surface").  Areas are computed in units of the points' extent (scaled by a power of two, which is exact), so
that no unit overflows or underflows.
"""

import numpy as np

from .._geometry import power_of_two_scale, signed_area
from ..errors import number
from ..planar.limits import check_size, node_estimate


def check_surface_size(surface_points, triangles, l, max_nodes, flattened=None):
    """Estimate the node count (surface area at the lattice density) and refuse it above ``max_nodes``.

    The area is computed in units of the surface's extent (the points scaled
    by a power of two, which is exact), so neither a surface given in units of
    1e-100 nor one in units of 1e100 overflows or underflows; a tiny ``l``
    gives an estimate of ``inf`` rather than an overflow.  With ``flattened``
    (a triangle mesh's plane points after eq. (1)) it is the flattened
    triangles' area, overlaps counted (at least the area of the outline they
    tile), checked before the outline is made: a tube closed at one end
    flattens to several times its area, and would otherwise fail only after
    minutes of optimisation.  A chart's is checked on its outline
    (:func:`check_plane_size`).
    """
    if max_nodes is None:
        return
    area, scale = surface_area(surface_points, triangles)
    what = f"this surface (area {number(area / scale / scale)})"
    if flattened is not None:
        surface = area / scale / scale
        area, scale = surface_area(flattened, triangles)
        what = _stretched(area / scale / scale, surface)
    check_size(what, node_count_estimate(area, scale, l), max_nodes, l)


def check_plane_size(surface_points, triangles, outline, l, max_nodes):
    """:func:`check_surface_size` again on a chart's flattened ``outline`` (minus openings), which eq. (1) can make
    many times the area of the surface's ``triangles``; the refusal says how much."""
    if max_nodes is None:
        return
    rings = [np.asarray(ring, dtype=float) for ring in (outline.vertices, *(hole.points for hole in outline.holes))]
    scale = power_of_two_scale(float(np.max(np.ptp(rings[0], axis=0))))
    area = abs(signed_area(rings[0] * scale)) - sum(abs(signed_area(ring * scale)) for ring in rings[1:])
    estimate = node_count_estimate(area, scale, l)
    if not estimate <= max_nodes:
        surface, surface_scale = surface_area(surface_points, triangles)
        check_size(_stretched(area / scale / scale, surface / surface_scale / surface_scale), estimate, max_nodes, l)


def _stretched(plane, surface):
    """What a refusal on a flattened ``plane`` area of a ``surface`` area names."""
    return (
        f"the flattened surface (area {number(plane)}, {number(plane / surface, 3)} times the surface's "
        f"{number(surface)}: eq. (1) stretches it that much)"
    )


def triangle_areas(points, triangles):
    """The area of each triangle, ``|(b - a) x (c - a)| / 2``, of ``points`` (2-D or 3-D) indexed by ``triangles``."""
    p = points[triangles]
    if p.shape[-1] == 2:
        p = np.concatenate([p, np.zeros(p.shape[:-1] + (1,))], axis=-1)
    return 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)


def surface_area(points, triangles):
    """``(area, scale)``: the area of the triangles (2-D or 3-D points) in units of the points' extent, and that
    power of two."""
    scale = power_of_two_scale(float(np.max(np.ptp(points, axis=0))))
    return float(triangle_areas(points * scale, triangles).sum()), scale


def node_count_estimate(area, scale, l):
    """Oler's bound at the lattice density for an ``area`` in units scaled by ``scale``: a float, inf for a tiny l."""
    with np.errstate(over="ignore", under="ignore", divide="ignore"):
        return node_estimate(area, 0.0, np.float64(l * scale))
