"""The checks :func:`~equimesh.surface.pipeline.mesh_surface` runs on every mesh it returns, and on the options that
shape them.

The outputs: every triangle counter-clockwise in (u, v) (:func:`check_orientation`),
every member in [l, 2l] under an objective that bounds them (:func:`check_members`),
every node within the surface tolerance of the surface (:func:`check_deviation`)
and every triangle angle at least its bound under an objective with sound
joints (:func:`check_joints`, :mod:`~equimesh.surface.optimize.joints`); a mesh
that breaks one is an :class:`~equimesh.errors.InternalError`, never returned.
The options (:func:`check_fabrication_options`): a surface tolerance in [0, l) and
a catalogue that can hold every side of the outline (:func:`check_catalogue_holds`).
"""

import math

import numpy as np

from ..classes import check_catalogue, holds
from ..errors import EquimeshError, InternalError, InvalidCatalogueError, InvalidToleranceError, number
from ..mesh import edge_lengths
from ..tolerance import REL_TOL, at_least, at_most
from .optimize import OBJECTIVES
from .optimize.jacobian import signed_areas
from .optimize.joints import surface_angles


def check_fabrication_options(optimize, lengths, surface_tolerance, l):
    """``(catalogue, surface_tolerance)`` of a run with the objective ``optimize`` (a key of
    :data:`~equimesh.surface.optimize.OBJECTIVES` or "none"): a catalogue only under "classes", a surface tolerance
    above 0 only under an objective whose boundary nodes slide."""
    catalogue = None if lengths is None else check_catalogue(lengths, l)
    surface_tolerance = check_surface_tolerance(surface_tolerance, l)
    if catalogue is not None and optimize != "classes":
        raise EquimeshError(f"lengths= is a catalogue for optimize='classes', got optimize={optimize!r}")
    if surface_tolerance > 0 and not (optimize in OBJECTIVES and OBJECTIVES[optimize].slides):
        raise EquimeshError(
            f"surface_tolerance= lets the optimisation move nodes off the surface: use optimize='bounded' or "
            f"'classes', got optimize={optimize!r}"
        )
    return catalogue, surface_tolerance


def check_surface_tolerance(value, l):
    """``surface_tolerance`` as a float in [0, l): how far a node may leave the surface."""
    try:
        d = float(value)
    except (TypeError, ValueError, OverflowError):
        raise InvalidToleranceError(f"surface_tolerance must be a number, got {value!r}") from None
    if not (math.isfinite(d) and 0.0 <= d < l):
        raise InvalidToleranceError(f"surface_tolerance must be at least 0 and below l = {number(l)}, got {number(d)}")
    return d


def check_catalogue_holds(catalogue, points, plane, corners, l, tolerance):
    """Refuse a catalogue from which no members can run along a side of the outline.

    A side is a run of boundary members between two boundary nodes that stay
    put (the corners; a ring without one is one side); its length is the sum
    of its members on the surface after remapping, which the sliding nodes
    keep nearly so.  The members along it must be stock lengths within the
    tolerance: some count of them must add up to it (:func:`equimesh.classes.holds`).
    """
    fixed = np.zeros(plane.n_boundary, dtype=bool)
    fixed[np.asarray(corners, dtype=np.int64)] = True
    start = 0
    for ring, size in enumerate(plane.info["boundary_rings"]):
        nodes = np.arange(start, start + size)
        start += size
        chords = np.linalg.norm(points[np.roll(nodes, -1)] - points[nodes], axis=1)
        ends = np.flatnonzero(fixed[nodes])
        cuts = np.split(np.roll(chords, -ends[0]), (ends - ends[0])[1:]) if len(ends) else [chords]
        for side, part in enumerate(cuts):
            if not holds(float(part.sum()), catalogue, l, tolerance):
                where = "the outer boundary" if ring == 0 else f"opening {ring - 1}"
                raise InvalidCatalogueError(
                    f"lengths: no count of the stock lengths {', '.join(number(c) for c in catalogue)} within "
                    f"{tolerance:.3g} l of each adds up to side {side} of {where}, {number(part.sum())} long on the "
                    "surface; add a length or choose another l"
                )


def check_deviation(points, on_surface, surface_tolerance):
    """Every node within ``surface_tolerance`` of the surface (exactly on it at 0), or the optimisation broke it."""
    distance = np.linalg.norm(points - on_surface, axis=1)
    allowed = surface_tolerance * (1.0 + REL_TOL)
    if not np.all(distance <= allowed):
        raise InternalError(
            f"the optimisation put {int(np.count_nonzero(distance > allowed))} nodes farther than the surface "
            f"tolerance {number(surface_tolerance)} from the surface (up to {number(distance.max(), 10)}); "
            "please report this surface"
        )


def check_joints(points, triangles, bounds):
    """Every triangle angle on the surface at least its bound (:mod:`~equimesh.surface.optimize.joints`), or the
    optimisation broke its guarantee."""
    angles = surface_angles(points, triangles)
    low = np.any(angles < bounds, axis=1)
    if np.any(low):
        raise InternalError(
            f"the optimisation returned {int(np.count_nonzero(low))} of {len(triangles)} triangles with an angle "
            f"below its bound (smallest {np.degrees(angles.min()):.10g} degrees); please report this surface"
        )


def check_members(points, edges, l):
    """Every member of the surface mesh in [l, 2l] (up to REL_TOL), or the bounded optimisation broke its guarantee."""
    ratio = edge_lengths(points, edges) / l
    bad = np.flatnonzero(~(at_least(ratio, 1.0) & at_most(ratio, 2.0)))
    if bad.size:
        raise InternalError(
            f"the bounded optimisation returned {bad.size} of {len(edges)} members outside [l, 2l] "
            f"(lengths from {number(ratio.min(), 10)} l to {number(ratio.max(), 10)} l); please report this surface"
        )


def check_orientation(uv, triangles, stage):
    """Every triangle counter-clockwise with positive area in (u, v), or our ``stage`` broke it."""
    bad = np.flatnonzero(~(signed_areas(uv, triangles) > 0))
    if bad.size:
        k = int(bad[0])
        raise InternalError(
            f"{stage} inverted {bad.size} of {len(triangles)} triangles in (u, v) "
            f"(first: {triangles[k].tolist()}); please report this surface"
        )
