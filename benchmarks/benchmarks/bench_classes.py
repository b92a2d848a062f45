"""Fabrication figures of the surface mesh per optimisation objective: not times, values over commits.

Uses only equimesh's public API (``equimesh.mesh_surface``, ``equimesh.length_classes``).
Input: the reference surface ``experiments/surfaces/reference_dome.json``, l = 5,
a 15 x 15 auxiliary grid (about 1000 members).  An objective this equimesh
does not have is skipped (asv's ``NotImplementedError``).
"""

import numpy as np

import equimesh

from .common import SURFACE_GRID, SURFACE_LENGTH, reference_surface_json

#: Objectives tracked; the first is the one every equimesh has (the smoke test runs it).
OBJECTIVES = ["paper", "bounded", "classes"]

#: The fabrication tolerance of the comparison: +-0.5 % of l.
TOLERANCE = 0.005


class FabricationFigures:
    """Share of members within 0.5 % of l, length classes at +-0.5 % of l, the share in the ten largest classes and
    the smallest triangle angle, after each objective.

    ``setup_cache`` meshes the reference surface once per objective (the
    ``paper`` optimisation is the slow part) and keeps the member lengths and
    the triangles' smallest angles.
    """

    params = OBJECTIVES
    param_names = ["objective"]
    timeout = 600.0

    def setup_cache(self):
        surface = equimesh.surface_from_dict(reference_surface_json())
        lengths = {}
        for objective in OBJECTIVES:
            try:
                mesh = equimesh.mesh_surface(surface, SURFACE_LENGTH, grid=SURFACE_GRID, optimize=objective)
            except equimesh.EquimeshError:  # no such objective in this equimesh
                continue
            lengths[objective] = mesh.edge_lengths()
            lengths[objective, "angle"] = _smallest_angle(mesh.points, mesh.triangles)
        return lengths

    def setup(self, lengths, objective):
        if objective not in lengths:
            raise NotImplementedError(f"this equimesh has no objective {objective!r}")

    def track_share_within_half_percent(self, lengths, objective):
        """Share of all members whose length is within 0.5 % of l."""
        return float(np.mean(np.abs(lengths[objective] - SURFACE_LENGTH) <= TOLERANCE * SURFACE_LENGTH))

    track_share_within_half_percent.unit = "share"

    def track_length_classes(self, lengths, objective):
        """Fewest length classes at +-0.5 % of l (equimesh.length_classes)."""
        return len(equimesh.length_classes(lengths[objective], SURFACE_LENGTH, TOLERANCE))

    track_length_classes.unit = "classes"

    def track_top10_share(self, lengths, objective):
        """Share of all members in the ten largest length classes at +-0.5 % of l."""
        count = equimesh.length_classes(lengths[objective], SURFACE_LENGTH, TOLERANCE).count
        return float(np.sort(count)[::-1][:10].sum() / count.sum())

    track_top10_share.unit = "share"

    def track_smallest_angle(self, lengths, objective):
        """The smallest triangle angle of the mesh, in degrees (sound joints: at least 30 but under paper)."""
        return lengths[objective, "angle"]

    track_smallest_angle.unit = "degrees"


def _smallest_angle(points, triangles):
    p = np.asarray(points)[np.asarray(triangles)]
    smallest = 180.0
    for k in range(3):
        u, v = p[:, (k + 1) % 3] - p[:, k], p[:, (k + 2) % 3] - p[:, k]
        angle = np.degrees(np.arctan2(np.linalg.norm(np.cross(u, v), axis=1), np.sum(u * v, axis=1)))
        smallest = min(smallest, float(angle.min()))
    return smallest
