"""Section 4, step 3: the boundary of the flattened auxiliary triangulation, and the openings, as a polygon.

The boundary of the flattened auxiliary triangulation is a closed polyline
through the images of the boundary nodes of the parameter rectangle,
generally not convex (paper, Fig. 2).  It is resampled into the polygon of
Problem 2 (:func:`equimesh.uniform_triangulation`) by
:func:`~equimesh.surface.ring.resample_ring`, the corners being the images of
the four corners of the grid's domain; every polygon vertex carries its
(u, v), on the boundary of the parameter rectangle (paper, eq. (3) on a
boundary edge).  The openings of a chart (:mod:`equimesh.surface.charts.openings`)
are mapped to the plane exactly and resampled alike, their vertices as
corners (:func:`resample_holes`).
"""

from dataclasses import dataclass

import numpy as np

from .._geometry import cross
from ..errors import SurfaceTooSmallError, number
from ..tolerance import REL_TOL
from .charts.chart import Domain, corner_name, side_name
from .optimize.slide import along_polygon
from .plane_length import PlaneLength, round_down
from .remap import Loop, to_plane
from .ring import resample_ring


@dataclass(frozen=True)
class Outline:
    """The resampled boundary polygon and where its vertices sit in (u, v).

    Attributes
    ----------
    vertices : (n, 2) plane coordinates, counter-clockwise.
    uv : (n, 2) parameter coordinates, on the boundary of the domain.
    side : (n,) the side of the domain each polygon edge (i, i+1) runs along
        (index into :data:`~equimesh.surface.charts.chart.SIDES`).
    domain : Domain, the parameter rectangle.
    holes : tuple of :class:`~equimesh.surface.ring.Ring`, the openings (:func:`resample_holes`):
        clockwise on the plane, ``params`` their exact (u, v) on the hole's
        polyline, ``side`` the hole's edge (corner ``i`` of its clockwise ring).
    openings : tuple of (k, 2) arrays, the openings' polygons in (u, v), clockwise.
    """

    vertices: np.ndarray
    uv: np.ndarray
    side: np.ndarray
    domain: Domain
    holes: tuple = ()
    openings: tuple = ()

    @property
    def rings(self):
        """Plane vertices of every ring: the outer boundary, then each hole."""
        return (self.vertices, *(hole.points for hole in self.holes))

    def loop(self):
        """All rings as one :class:`~equimesh.surface.remap.Loop` (hole segments on no side of the domain)."""
        sizes = [len(ring) for ring in self.rings]
        start = np.repeat(np.cumsum(sizes) - sizes, sizes)
        succ = start + (np.arange(len(start)) - start + 1) % np.repeat(sizes, sizes)
        return Loop(
            np.vstack(self.rings),
            np.vstack([self.uv, *(hole.params for hole in self.holes)]),
            np.concatenate([self.side, *(np.full(len(hole.points), -1) for hole in self.holes)]),
            self.domain,
            succ,
        )

    def slides(self, plane, uv):
        """The boundary nodes of ``plane`` sliding in the final optimisation: the outer ring's along the parameter
        rectangle, each opening's along its (u, v) polygon.

        Both are closed polygons with every vertex a corner
        (:func:`~equimesh.surface.optimize.slide.along_polygon`): the
        rectangle's four corners and the openings' vertices stay fixed, so with
        the other nodes on the edges and no fold-over no node can enter an
        opening.  ``plane`` is Problem 2's mesh of this outline (its rings in
        the order of ``info["boundary_rings"]``), ``uv`` its nodes' remapped parameters.

        Returns
        -------
        slides : list of Slide, one per ring
        fixed : (c,) int array
            The boundary nodes at a corner.
        """
        ends = np.cumsum(plane.info["boundary_rings"])
        rings = [(self.domain.corners, np.arange(ends[0]))]
        rings += [(polygon, np.arange(a, b)) for polygon, a, b in zip(self.openings, ends[:-1], ends[1:])]
        pairs = [along_polygon(nodes, polygon, uv[nodes]) for polygon, nodes in rings]
        return [slide for slide, _ in pairs], np.concatenate([fixed for _, fixed in pairs])

    def ring_of(self, vertex):
        """Index into :attr:`rings` of the ring holding vertex ``vertex`` of :meth:`loop`."""
        return int(np.searchsorted(np.cumsum([len(ring) for ring in self.rings]), vertex, side="right"))


def resample_outline(plane, grid, l, spacing, holes=()):
    """Resample the flattened boundary ``plane[grid.boundary]`` into a polygon (:func:`resample_ring`).

    ``l`` is the caller's l, or a :class:`~equimesh.surface.plane_length.PlaneLength` (the spacing the refusals
    name).  ``plane`` holds the flattened nodes of the auxiliary grid ``grid`` (step
    2); the corners are the images of the corners of the grid's domain, in
    the counter-clockwise order of ``grid.boundary``.  ``holes`` are the
    openings' rings in (u, v) (:func:`resample_holes`).

    Raises
    ------
    SurfaceTooSmallError
        A side whose corners are closer than ``l`` on the plane, named by its
        side and corners of the parameter rectangle.
    """
    length = PlaneLength.of(l)
    l = length.value
    loop, uv, domain = grid.boundary, grid.uv[grid.boundary], grid.domain
    corners = np.flatnonzero(grid.boundary_corner)
    ends = [(uv[c0], uv[c1]) for c0, c1 in zip(corners, np.roll(corners, -1))]

    def too_short(side, arc, chord):
        a, b = ends[side]
        return SurfaceTooSmallError(
            f"{side_name(side_index(a, b, domain), domain)} of the surface, from {corner_name(a)} to {corner_name(b)}, "
            f"is {number(arc)} long on the flattened surface (its corners {number(chord)} apart), "
            f"shorter than {length}; use l <= {number(length.suggest(round_down(chord)))}"
        )

    ring = resample_ring(plane[loop], uv, corners, l, spacing, too_short)
    sides = np.array([side_index(a, b, domain) for a, b in ends])
    holes = tuple(holes)
    return Outline(
        ring.points,
        ring.params,
        sides[ring.side],
        domain,
        resample_holes(holes, plane, grid, length, spacing),
        tuple(polygon for polygon, _ in holes),
    )


def resample_holes(rings, plane, grid, l, spacing):
    """The openings on the plane: each hole's (u, v) polyline mapped and resampled (:func:`resample_ring`).

    ``l`` is as in :func:`resample_outline`.

    ``rings`` are the holes clockwise in (u, v) with the caller's vertex
    indices (:attr:`~equimesh.surface.charts.openings.Perforated.rings`).  A hole's
    polyline is first split wherever it crosses an auxiliary edge
    (:func:`densify`), so each piece lies in one auxiliary triangle, where
    eqs. (2)-(3) are linear: the image (:func:`~equimesh.surface.remap.to_plane`)
    of the densified polyline is exactly the image of the hole.  Its corners
    are the hole's vertices, so every hole vertex is a polygon vertex and
    every polygon vertex has its exact (u, v) on the hole's polyline.

    Raises
    ------
    SurfaceTooSmallError
        A hole's edge too short on the flattened surface for l, named by the
        hole, its vertices (the caller's indices) and their (u, v).
    """
    length = PlaneLength.of(l)
    l = length.value
    holes = []
    for k, (uv, index) in enumerate(rings):
        dense, corners = densify(uv, grid)

        def too_short(side, arc, chord, uv=uv, index=index, k=k):
            a, b = side, (side + 1) % len(uv)
            return SurfaceTooSmallError(
                f"edge ({index[a]}, {index[b]}) of hole {k}, from (u, v) = ({number(uv[a, 0])}, {number(uv[a, 1])}) "
                f"to ({number(uv[b, 0])}, {number(uv[b, 1])}), is {number(arc)} long on the flattened surface "
                f"(its ends {number(chord)} apart), too short for {length}; use l <= "
                f"{number(length.suggest(round_down(chord)))} "
                "or give the hole with fewer vertices"
            )

        holes.append(resample_ring(to_plane(dense, plane, grid), dense, corners, l, spacing, too_short))
    return tuple(holes)


def hole_image(uv, plane, grid):
    """The exact image on the flattened plane of a hole's closed (u, v) polyline (:func:`densify`, then eqs. (2)-(3)
    forward)."""
    return to_plane(densify(uv, grid)[0], plane, grid)


def densify(polyline, grid):
    """The closed (u, v) ``polyline`` split at every crossing with an edge of the auxiliary triangulation.

    Returns the points (the polyline's vertices and the crossings, in order)
    and the indices of the polyline's vertices among them.  A crossing of
    segment ``p + t (q - p)`` with auxiliary edge ``a + s (b - a)`` solves
    ``t d - s e = a - p`` by Cramer's rule.  Where the polyline passes
    through an auxiliary node several edges give crossings a rounding error
    apart: crossings closer than ``REL_TOL`` (as a fraction ``t`` of the
    segment) to each other or to the segment's ends are merged, so that no
    piece is a rounding error long (its direction would be noise, and the
    inner angle at a vertex with it); the image then strays from the exact
    one by at most ``REL_TOL`` of a segment.
    """
    a, b = grid.uv[grid.edges[:, 0]], grid.uv[grid.edges[:, 1]]
    e = b - a
    points, corners = [], []
    for p, q in zip(polyline, np.roll(polyline, -1, axis=0)):
        d, w = q - p, a - p
        den = cross(d, e)
        with np.errstate(divide="ignore", invalid="ignore"):
            t, s = cross(w, e) / den, cross(w, d) / den
        t = np.unique(t[(den != 0) & (t > REL_TOL) & (t < 1.0 - REL_TOL) & (s >= 0) & (s <= 1)])
        t = t[np.diff(t, prepend=0.0) > REL_TOL]
        points.append(np.vstack([p, p + t[:, None] * d]))
        corners.append(sum(len(x) for x in points[:-1]))
    return np.vstack(points), np.array(corners)


def side_index(uv_a, uv_b, domain):
    """Index into :data:`~equimesh.surface.charts.chart.SIDES` of the side of ``domain`` through two of its points."""
    axis = 0 if uv_a[0] == uv_b[0] else 1
    return 2 * axis + int(uv_a[axis] == domain.upper[axis])
