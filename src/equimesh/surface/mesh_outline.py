"""Section 4, steps 3 and 4 for a triangle mesh: its flattened boundary loops as a polygon with openings, and back.

Step 3.  Each boundary loop of the flattened mesh is a closed polyline; the
outer boundary is the loop whose polygon contains all the others, every other
loop is an opening.  Each loop is resampled into a ring of parts between l and
2l by :func:`~equimesh.surface.outline.resample_ring` (Step 2, sharp corners
staggered), keeping its *corners*: the loop vertices where the flattened
polyline turns by :data:`CORNER_TURN` degrees or more.  A loop without such
a vertex is one closed chain from its sharpest turn.  Two corners closer than
l (a side no part of at least l fits on) cannot both be kept; the one that
turns less is dropped, until no such side is left.  Problem 2 then runs on
the outer ring with the openings as holes
(:func:`equimesh.uniform_triangulation`, ``holes=``).

Step 4.  The parameter plane is the flattening itself
(:class:`~equimesh.surface.charts.mesh_chart.MeshChart`), so eq. (3) leaves every
inner node where it is.  A boundary node of the plane mesh lies on an edge of
its ring, a chord of the loop between two ring vertices at arc positions
``s_a`` and ``s_b``; at the fraction ``t`` of that chord it goes to the point of
the loop at arc position ``(1 - t) s_a + t s_b`` (exact at both ends), on the
boundary of the flattened mesh, hence on a boundary edge of the input mesh.
"""

from dataclasses import dataclass

import numpy as np

from .._geometry import Polyline, between, inner_angle
from ..errors import InvalidSurfaceError, coordinates, number
from ..tolerance import REL_TOL
from .optimize.slide import between_corners
from .outline import round_down
from .ring import resample_ring

#: A flattened boundary loop keeps a polygon vertex where it turns by at least
#: this many degrees (inner angle at most 150 or at least 210 degrees): the
#: corners of a roof's outline (about 90 degrees) and any sharp corner are
#: kept exactly, while a smoothly curved edge, tessellated with small turns,
#: is resampled as one curve.  Test: tests/surface/charts/test_triangulated.py
#: (``test_corners_of_the_outline_are_kept``).
CORNER_TURN = 30.0

#: A corner turning by this many degrees or more is never dropped: two such
#: corners closer than l are refused ("use l <= their distance").  Dropping a
#: corner replaces the loop near it by a chord; below 60 degrees of turn (a
#: coarsely tessellated curve: an octagon turns by 45) the chord stays within
#: ``(l / 2) tan(30 deg) < 0.29 l`` of the loop, beyond it a rectangular
#: opening whose sides are shorter than l would be cut across, its corners
#: meshed over.  Test: ``test_openings_and_boundaries_too_small_for_l``.
FIRM_TURN = 60.0


@dataclass(frozen=True)
class MeshOutline:
    """The flattened boundary loops resampled into rings (step 3).

    Attributes
    ----------
    loops : tuple of closed :class:`~equimesh._geometry.Polyline`
        The flattened loops (the surface on their left), the outer one first.
    rings : tuple of (n, 2) arrays
        The polygon of each loop, same order: the outer ring, then the holes.
    arcs : tuple of (n + 1,) arrays
        Arc position along its loop of each ring vertex, increasing (past the
        loop's length after its start), and the first one plus the length last.
    order : tuple of int
        The index in ``surface.loops`` of each loop.
    corners : tuple of (c,) arrays
        Arc position along its loop of each corner kept (:func:`loop_corners`), increasing.
    """

    loops: tuple
    rings: tuple
    arcs: tuple
    order: tuple
    corners: tuple

    @property
    def vertices(self):
        """The outer ring (the polygon of Problem 2)."""
        return self.rings[0]

    @property
    def holes(self):
        """The rings of the openings (``holes=`` of Problem 2)."""
        return list(self.rings[1:])

    def slides(self, plane, uv):
        """The boundary nodes of ``plane`` sliding along their loops in the final optimisation.

        Each node not at a corner of its loop slides between the corners before
        and after it (:func:`~equimesh.surface.optimize.slide.between_corners`).
        ``uv`` is not read: the nodes' arc positions follow from ``plane``
        (:func:`boundary_uv`, whose (u, v) they are).

        Returns
        -------
        slides : list of Slide, one per loop
        fixed : (c,) int array
            The boundary nodes at a corner.
        """
        pairs = [between_corners(*ring) for ring in _ring_arcs(self, plane)]
        return [slide for slide, _ in pairs], np.concatenate([fixed for _, fixed in pairs])


def mesh_outline(chart, l, spacing):
    """Step 3: the flattened loops of ``chart`` (a :class:`~equimesh.surface.charts.mesh_chart.MeshChart`) as rings.

    Raises
    ------
    InvalidSurfaceError
        A part of a loop between two corners is shorter than l.
    """
    order = [chart.outer] + [k for k in range(len(chart.surface.loops)) if k != chart.outer]
    loops = [Polyline(chart.plane[chart.surface.loops[k]]) for k in order]
    rings, arcs, corner_arcs = [], [], []
    for k, loop in enumerate(loops):
        xy, arc = loop.points, loop.arc
        name = ring_name(chart, order, k)
        corners = loop_corners(xy, l, _too_close(chart, xy, name, l))
        ring = resample_ring(xy, xy, corners, l, spacing, too_short=_too_short(name, l, len(corners))).points
        if len(ring) < 3:
            raise InvalidSurfaceError(
                f"{name} of the mesh is too small for l = {number(l)}: its rim, {number(arc[-1])} long on the "
                "flattened "
                "surface, gives fewer than 3 parts of at least l; use a smaller l"
            )
        at = loop.project(ring)[2]
        at[1:] += arc[-1] * np.cumsum(np.diff(at) < 0)  # the ring starts at a corner: unwrap past the loop's start
        rings.append(ring)
        arcs.append(np.append(at, at[0] + arc[-1]))
        corner_arcs.append(arc[np.sort(corners)])
    return MeshOutline(tuple(loops), tuple(rings), tuple(arcs), tuple(order), tuple(corner_arcs))


def loop_corners(xy, l, too_close):
    """Indices of the corners of a closed loop: turns of at least :data:`CORNER_TURN` degrees, none closer than l.

    Returns at least one index (the sharpest turn when no vertex turns that
    much).  Where two consecutive corners are closer than ``l``, the one
    that turns less (the later one on a tie) is dropped, one at a time,
    unless it turns by :data:`FIRM_TURN` degrees or more: then the loop
    cannot be followed with parts of at least l, and ``too_close(i, j)`` is
    raised for the closest two consecutive firm corners ``i`` and ``j``
    (any l up to their distance keeps every firm corner).
    """
    turn = np.array([abs(180.0 - inner_angle(xy, i)) for i in range(len(xy))])
    corners = list(np.flatnonzero(turn >= CORNER_TURN))
    while len(corners) > 1:
        ends = np.array(corners)
        gaps = np.linalg.norm(xy[np.roll(ends, -1)] - xy[ends], axis=1)
        short = np.flatnonzero(gaps < l)
        if not short.size:
            break
        pairs = [(k, (k + 1) % len(ends)) for k in short]
        drop = min((j for pair in pairs for j in pair), key=lambda j: (turn[ends[j]], -j))
        if turn[ends[drop]] >= FIRM_TURN:  # then its partner is firm too: name the closest firm neighbours
            firm = np.flatnonzero(turn >= FIRM_TURN)
            gaps = np.linalg.norm(xy[np.roll(firm, -1)] - xy[firm], axis=1)
            k = int(np.argmin(gaps))
            raise too_close(int(firm[k]), int(firm[(k + 1) % len(firm)]))
        corners.pop(drop)
    if not corners:
        corners = [int(np.argmax(turn))]
    return np.array(corners, dtype=np.int64)


def ring_name(chart, order, k):
    """``the outer boundary``, or ``hole k - 1 (the opening through (x, y, z))``: Problem 2's hole numbers, located in
    space."""
    if k == 0:
        return "the outer boundary"
    return f"hole {k - 1} (the opening through {coordinates(chart.surface.vertices[chart.surface.loops[order[k]][0]])})"


def _too_close(chart, xy, name, l):
    def refuse(i, j):
        gap = float(np.linalg.norm(xy[j] - xy[i]))
        where = " and ".join(coordinates(p) for p in chart.evaluate(xy[[i, j], 0], xy[[i, j], 1]))
        return InvalidSurfaceError(
            f"{name} of the mesh has corners at {where} only {number(gap)} apart on the flattened surface, closer than "
            f"l = {number(l)}; use l <= {number(round_down(gap))}"
        )

    return refuse


def _too_short(name, l, n_corners):
    def refuse(side, arc, chord):
        if n_corners == 1:
            return InvalidSurfaceError(
                f"{name} of the mesh is too small for l = {number(l)}: its rim is {number(arc)} long on the flattened "
                "surface, too short for parts of at least l; use a smaller l"
            )
        return InvalidSurfaceError(
            f"{name} of the mesh has a part {number(arc)} long between two corners {number(chord)} apart on the "
            f"flattened surface, shorter than l = {number(l)}; use l <= {number(round_down(chord))}"
        )

    return refuse


def boundary_uv(outline, plane):
    """Step 4 on the boundary: the (u, v) on the flattened loops of the ``n_boundary`` leading nodes of ``plane``.

    ``plane`` is the :class:`~equimesh.mesh.PlanarMesh` of Problem 2 on
    ``outline`` (the rings in the order of ``info["boundary_rings"]``).
    """
    return np.vstack([loop.at(s) for _, loop, s, _ in _ring_arcs(outline, plane)])


def _ring_arcs(outline, plane):
    """Per loop: the boundary nodes of ``plane`` on it, the loop, the nodes' arc positions, its corners'.

    A node at the fraction ``t`` of the ring edge between ring vertices at arc
    positions ``s_a``, ``s_b`` is at ``(1 - t) s_a + t s_b`` (step 4).  The
    ring starts at a corner, so its arc positions run from ``s_0`` to
    ``s_0 + length``; the corners are taken into that range.
    """
    start = 0
    for ring, arcs, loop, corner, count in zip(
        outline.rings, outline.arcs, outline.loops, outline.corners, plane.info["boundary_rings"]
    ):
        nodes = np.arange(start, start + count)
        start += count
        seg, t, _ = Polyline(ring).project(plane.points[nodes])
        s = between(arcs[seg], arcs[seg + 1], t)
        first = arcs[0] - REL_TOL * loop.length  # the ring's first vertex, a corner, up to rounding
        yield nodes, loop, s, np.sort(np.where(corner < first, corner + loop.length, corner))


def restate_mesh_error(exc, chart, outline, l):
    """Problem 2's refusal of the rings (:class:`~equimesh.errors.InvalidPolygonError`) in terms of the mesh.

    The two boundary points at fault (if named) are given in space; the gap
    between them on the flattened surface bounds the l that can pass there.
    Otherwise Problem 2's message is kept, with its holes located in space.
    """
    if not exc.points or len(exc.points) != 2:
        holes = "; ".join(ring_name(chart, outline.order, k) for k in range(1, len(outline.rings)))
        return InvalidSurfaceError(
            f"the triangle mesh cannot be meshed with l = {number(l)}: {exc}"
            + (f" ({holes})" if "hole" in str(exc) else "")
        )
    xy = np.asarray(exc.points, dtype=float)
    where = " and ".join(coordinates(p) for p in chart.evaluate(xy[:, 0], xy[:, 1]))
    gap = float(np.linalg.norm(xy[1] - xy[0]))
    return InvalidSurfaceError(
        f"the triangle mesh cannot be meshed with l = {number(l)}: its boundary points at {where} are {number(gap)} "
        "apart on the flattened surface, closer than l (a neck, an opening near the boundary or another opening, "
        f"or a corner too sharp for its sides); try l <= {number(round_down(gap))}"
    )
