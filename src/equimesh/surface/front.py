"""Section 4, steps 1-4 of :func:`~equimesh.surface.pipeline.mesh_surface`: the front, made once, and the plane at
a spacing.

Steps 1-2 do not depend on l: the auxiliary triangulation (a chart's grid,
:mod:`equimesh.surface.auxiliary`, checked by :mod:`equimesh.surface.regularity`;
a triangle mesh is its own) and its flattening by eq. (1)
(:mod:`equimesh.surface.flatten`, :mod:`equimesh.surface.charts.mesh_chart`),
with the size guard at l before and after it (:mod:`equimesh.surface.size`).
A :class:`Front` holds them.  Steps 3-4 depend on the spacing, a
:class:`~equimesh.surface.plane_length.PlaneLength`: the outline resampled
at it (:mod:`equimesh.surface.outline`, :mod:`equimesh.surface.mesh_outline`),
Problem 2's plane mesh of it and the remap by eqs. (2)-(3)
(:mod:`equimesh.surface.remap`), Problem 2's refusals restated in the
surface's terms (:mod:`equimesh.surface.messages`).  They run at l, and once
more at ``(1 + D) l`` on the same front when sound joints need the larger
spacing (:func:`~equimesh.surface.optimize.joints.joint_spacing`;
docs/decisions.md, "Sound joints").
"""

from dataclasses import dataclass
from functools import partial
from typing import Callable

import numpy as np

from ..errors import InvalidPolygonError, InvalidSurfaceError
from ..planar.placement import best_lattice_placement, fewest_classes_placement
from ..planar.strip import uniform_triangulation
from .auxiliary import auxiliary_grid
from .charts.chart import domain_of
from .charts.mesh_chart import MeshChart, flatten_mesh
from .charts.openings import holes_of
from .flatten import flatten
from .mesh_outline import boundary_uv, check_open, mesh_outline, restate_mesh_error
from .messages import restate_polygon_error
from .outline import resample_outline
from .regularity import check_regular, evaluate
from .remap import check_remapped, remap
from .size import check_plane_size, check_surface_size


@dataclass(frozen=True)
class Front:
    """Steps 1-2, which do not depend on l, and ``outlined``, step 3 at a spacing.

    ``chart`` is what the optimisation moves the nodes on; ``grid``,
    ``points`` (X_i^s0) and ``flattening`` are the auxiliary triangulation
    (step 1) and its flattening by eq. (1) (step 2);
    ``outlined(length, boundary_spacing, limit)`` is step 3 at the
    :class:`~equimesh.surface.plane_length.PlaneLength` ``length``, an
    :class:`Outlined` whose size is checked against ``limit``.
    """

    chart: object
    grid: object
    points: np.ndarray
    flattening: object
    outlined: Callable

    def remapped(self, length, limit, boundary_spacing, boundary, placement, tolerance, engine, clock):
        """Steps 3 and 4 at ``length``: the outline, Problem 2's plane mesh of it (its Step 2 points by ``boundary``,
        in the lattice ``placement`` chosen, :data:`~equimesh.surface.pipeline.PLACEMENTS`) and the remap;
        ``(outlined, placement, plane, mapped_uv, mapped_points)``."""
        outlined = self.outlined(length, boundary_spacing, limit)
        l = length.value
        try:
            # The size guard (surface/size.py: before and after the flattening) bounds the planar stage too.
            holes, vertices = outlined.holes, outlined.outline.vertices
            options = dict(holes=holes, boundary_spacing=boundary_spacing, boundary=boundary, engine=engine)
            chosen = (
                None if placement == "default" else best_lattice_placement(vertices, l, holes=holes, max_nodes=None)
            )
            if placement == "classes":
                chosen = fewest_classes_placement(vertices, l, start=chosen, tolerance=tolerance, **options)
            angle, offset = (chosen.angle, chosen.offset) if chosen else (0.0, (0.0, 0.0))
            plane = uniform_triangulation(vertices, l, angle=angle, offset=offset, max_nodes=None, **options)
        except InvalidPolygonError as exc:
            raise outlined.restate(exc) from None
        clock("planar triangulation (Problem 2)")

        mapped_uv, mapped_points = outlined.place(plane)
        check_remapped(mapped_uv, plane, length)
        clock("remapping (eqs. 2-3)")
        return outlined, chosen, plane, mapped_uv, mapped_points


@dataclass(frozen=True)
class Outlined:
    """Step 3 at one spacing, and how to do step 4 (:meth:`Front.remapped`).

    ``outline`` is the polygon handed to Problem 2, ``holes`` the rings of
    its openings (``holes=`` of Problem 2); ``place(plane)`` gives the
    remapped ``(uv, points)`` of a plane mesh (step 4); ``restate(exc)``
    turns Problem 2's refusal of the outline into the surface's terms;
    ``outline.slides(plane, uv)`` says how the boundary nodes slide under an
    objective whose boundary slides.
    """

    outline: object
    holes: list | None
    place: Callable
    restate: Callable


def chart_front(surface, n_u, n_v, l, limit, clock):
    """Steps 1-2 for a chart: the ``n_u`` x ``n_v`` auxiliary grid of its domain, checked regular, its size
    estimated at ``l`` (:func:`~equimesh.surface.size.check_surface_size`), and eq. (1); step 3 by
    :func:`_chart_outline`."""
    if not (hasattr(surface, "evaluate") and hasattr(surface, "derivatives")):
        raise InvalidSurfaceError(
            "surface must provide evaluate(u, v) and derivatives(u, v), or be a TriangulatedSurface"
        )
    aux = auxiliary_grid(n_u, n_v, domain_of(surface))
    x_s0 = evaluate(surface, aux.uv)
    check_regular(surface, aux)
    check_surface_size(x_s0, aux.triangles, l, limit)
    clock("auxiliary triangulation")

    flat = flatten(x_s0, aux.triangles, uv=aux.uv)
    clock("flattening (eq. 1)")
    return Front(surface, aux, x_s0, flat, partial(_chart_outline, surface, aux, x_s0, flat))


def _chart_outline(surface, aux, x_s0, flat, length, boundary_spacing, limit):
    """Step 3 for a chart at ``length``: the outline of the flattened rectangle and openings (its size estimated
    again, :func:`~equimesh.surface.size.check_plane_size`), and how to do step 4 (eqs. (2)-(3))."""
    outline = resample_outline(flat.points, aux, length, boundary_spacing, holes_of(surface))
    check_plane_size(x_s0, aux.triangles, outline, length.value, limit)

    def place(plane):
        mapped = remap(
            surface, plane.points, flat.points, aux, on_boundary=np.arange(plane.n_boundary), outline=outline
        )
        return mapped.uv, mapped.points

    def restate(exc):
        return restate_polygon_error(exc, surface, flat.points, aux, outline, length)

    return Outlined(outline, [hole.points for hole in outline.holes], place, restate)


def mesh_front(surface, l, limit, clock, feature_angle):
    """Steps 1-2 for a triangle mesh (:mod:`equimesh.surface.charts.triangulated`): it is the auxiliary triangulation.

    ``feature_angle`` decides the loops' corners.  The flattening starts from
    the projection onto the best-fit plane, or a conformal map or Tutte's
    embedding if that folds, with the openings capped
    (:func:`~equimesh.surface.charts.mesh_chart.flatten_mesh`; the size is
    estimated at ``l`` before and again on the flattened triangles,
    :func:`~equimesh.surface.size.check_surface_size`); the flattened mesh is
    the chart (:class:`~equimesh.surface.charts.mesh_chart.MeshChart`) and its
    loops the outline, step 3 by :func:`_mesh_outline`.
    """
    check_surface_size(surface.vertices, surface.triangles, l, limit)
    clock("auxiliary triangulation")

    flat = flatten_mesh(surface)
    check_open(surface, flat.points)
    check_surface_size(surface.vertices, surface.triangles, l, limit, flattened=flat.points)
    chart = MeshChart(surface, flat.points)
    clock("flattening (eq. 1)")
    return Front(chart, surface, surface.vertices, flat, partial(_mesh_outline, chart, feature_angle))


def _mesh_outline(chart, feature_angle, length, boundary_spacing, limit):
    """Step 3 for a triangle mesh at ``length``: its flattened loops as rings (:mod:`equimesh.surface.mesh_outline`),
    and how to do step 4 (the boundary nodes onto the loops).  ``limit`` is not used: the flattened triangles' size
    was checked at l (:func:`mesh_front`), the most nodes any spacing of at least l needs."""
    outline = mesh_outline(chart, length, boundary_spacing, feature_angle)

    def place(plane):
        uv = plane.points.copy()
        uv[: plane.n_boundary] = boundary_uv(outline, plane)
        return uv, evaluate(chart, uv)

    def restate(exc):
        return restate_mesh_error(exc, chart, outline, length)

    return Outlined(outline, outline.holes, place, restate)
