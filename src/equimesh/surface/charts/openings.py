"""Openings: a chart with holes cut out of its parameter rectangle (beyond the paper).

Section 4 meshes the whole parameter rectangle.  A surface with openings
(skylights, supports) is a chart plus holes: closed polylines in (u, v), each
strictly inside the rectangle and apart from the others.  :class:`Perforated`
carries them on the chart, so that the surface and its openings travel
together from a file (JSON ``"holes"``, :mod:`equimesh.io`) to
:func:`~equimesh.surface.pipeline.mesh_surface`, which maps each hole to the
flattened plane (the forward direction of eqs. (2)-(3)) and hands it to
Problem 2 as a hole (:func:`equimesh.uniform_triangulation`).

What does not depend on l is checked here, in (u, v), by the same validation
as Problem 2's holes (:func:`equimesh.planar.polygon.as_polygon` with the
rectangle as the polygon): each hole simple, with at least 3 distinct
vertices, inside the rectangle without touching its boundary, no two holes
overlapping.  What depends on l (a hole closer than l to the boundary or to
another hole on the flattened surface) is Problem 2's refusal, restated by
:mod:`equimesh.surface.messages`.
"""

import numpy as np

from ...errors import InvalidPolygonError, InvalidSurfaceError, number
from ...planar.polygon import as_polygon
from .chart import domain_of


class Perforated:
    """A chart with openings: ``evaluate`` and ``derivatives`` of ``chart``, and ``holes`` in its domain.

    Parameters
    ----------
    chart : Chart
        The surface (:class:`~equimesh.surface.charts.chart.Chart`).
    holes : sequence of (k, 2) array_like
        Closed polylines in (u, v) (a closing copy of the first vertex is
        dropped), either orientation.

    Attributes
    ----------
    chart, domain, holes : the chart, its domain and the holes as given
        (``(k, 2)`` float arrays, the caller's order and orientation).
    rings : the holes clockwise (the region on their left), each with the
        caller's vertex index of every vertex: ``(uv, input_index)`` pairs.

    Raises
    ------
    InvalidSurfaceError
        one line naming the hole and, where it applies, its vertex.
    """

    def __init__(self, chart, holes):
        if isinstance(chart, Perforated):
            raise InvalidSurfaceError("the surface has holes already; give all holes at once")
        self.chart = chart
        self.domain = domain_of(chart)
        lo, hi = self.domain.lower, self.domain.upper
        rectangle = [lo, (hi[0], lo[1]), hi, (lo[0], hi[1])]
        try:
            poly = as_polygon(rectangle, holes=holes)
        except InvalidPolygonError as exc:
            where = f"[{number(lo[0])}, {number(hi[0])}] x [{number(lo[1])}, {number(hi[1])}]"
            text = str(exc).replace("the polygon", f"the parameter domain {where}")
            raise InvalidSurfaceError(f"holes (in (u, v)): {text}") from None
        self.rings = tuple((ring.vertices, ring.input_index) for ring in poly.holes)
        self.holes = tuple(_as_given(ring) for ring in poly.holes)
        if hasattr(chart, "second_derivatives"):
            self.second_derivatives = chart.second_derivatives

    def evaluate(self, u, v):
        return self.chart.evaluate(u, v)

    def derivatives(self, u, v):
        return self.chart.derivatives(u, v)


def _as_given(ring):
    """A validated hole ring back in the caller's order (vertex 0 first, the caller's orientation)."""
    out = np.empty_like(ring.vertices)
    out[ring.input_index] = ring.vertices
    return out


def holes_of(surface):
    """The openings of ``surface``: its :attr:`Perforated.rings`, or none."""
    return surface.rings if isinstance(surface, Perforated) else ()
