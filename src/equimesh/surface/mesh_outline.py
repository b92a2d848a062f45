"""Section 4, steps 3 and 4 for a triangle mesh: its flattened boundary loops as a polygon with openings, and back.

Step 3.  Each boundary loop of the flattened mesh is a closed polyline; the
outer boundary is the loop whose polygon contains all the others, every other
loop is an opening.  A loop is drawn at the mesh's resolution, with edges far
shorter than l and, where an opening was cut out of a fine mesh, a staircase
of mesh edges; its *corners* are decided at the scale of l: the vertices
where it turns by more than the feature angle over a stretch of about l
(:func:`scale_turns`, :func:`loop_corners`; :data:`DEFAULT_FEATURE_ANGLE`),
at most one within l / 2 and of two closer than l the sharper.  A loop
without such a vertex is one closed chain from its sharpest turn.  Each loop
is resampled into a ring of parts between l and 2l through its corners by
:func:`~equimesh.surface.ring.resample_ring` (Step 2, sharp corners
staggered), the rest as a curve whose ring vertices lie on the loop; a loop
narrower than l at a sharp turn, or too small for a ring, is refused
(:func:`loop_ring`).  Problem 2 then runs on the outer ring with the openings
as holes (:func:`equimesh.uniform_triangulation`, ``holes=``).

Step 4.  The parameter plane is the flattening itself
(:class:`~equimesh.surface.charts.mesh_chart.MeshChart`), so eq. (3) leaves every
inner node where it is.  A boundary node of the plane mesh lies on an edge of
its ring, a chord of the loop between two ring vertices at arc positions
``s_a`` and ``s_b``; at the fraction ``t`` of that chord it goes to the point of
the loop at arc position ``(1 - t) s_a + t s_b`` (exact at both ends), on the
boundary of the flattened mesh, hence on a boundary edge of the input mesh.
"""

import math
from dataclasses import dataclass

import numpy as np
import shapely

from .._checks import real_number
from .._geometry import Polyline, between
from ..errors import EquimeshError, InvalidSurfaceError, coordinates, number
from ..tolerance import REL_TOL
from .optimize.slide import between_corners
from .plane_length import PlaneLength, round_down
from .ring import reach, resample_ring

#: The feature angle of a triangle mesh's loops when none is given
#: (``mesh_surface(feature_angle=...)``, ``equimesh mesh --feature-angle``):
#: a loop vertex is a corner when the loop turns there by more than this many
#: degrees at the scale of l (:func:`scale_turns`).  The corners of a roof's
#: outline (about 90 degrees) and of polygonal openings (45 degrees and more)
#: are kept, while a round opening's staircase of mesh edges is resampled as
#: a curve (docs/decisions.md, "Corners of a mesh's loops", measured by
#: ``python experiments/feature_angle.py``).
DEFAULT_FEATURE_ANGLE = 40.0

#: A loop vertex turning by ``FIRM_TURN`` degrees or more at the scale of l
#: must lie within ``CORNER_DETAIL l`` of the loop's ring: a corner that the
#: ring cuts off farther than that (where the loop is narrower than l, two
#: corners closer than l cannot both be ring vertices) is refused with a
#: suggested l.  ``(l / 2) tan(30 deg) = 0.289 l`` is how far the chords of the
#: smallest ring a round opening can have (three parts of l, an equilateral
#: triangle) stand off their circle, and the staircase of a round opening at
#: least 1.5 l across turns by less than 60 degrees at the scale of l
#: (``python experiments/feature_angle.py``), so its detail is not checked.
#: Tests: tests/surface/test_mesh_outline.py (``test_narrow_ends_are_refused_and_details_dropped``).
FIRM_TURN = 60.0
CORNER_DETAIL = 0.5 * math.tan(math.radians(30.0))


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


def mesh_outline(chart, l, spacing, feature_angle=DEFAULT_FEATURE_ANGLE):
    """Step 3: the flattened loops of ``chart`` (a :class:`~equimesh.surface.charts.mesh_chart.MeshChart`) as rings.

    ``feature_angle`` (degrees) decides the corners of the loops (:func:`loop_corners`); ``l`` is the caller's l, or
    the :class:`~equimesh.surface.plane_length.PlaneLength` the refusals name.

    Raises
    ------
    InvalidSurfaceError
        A loop is too small for l, narrower than l at a corner, or a part
        of it between two corners is shorter than l (:func:`loop_ring`).
    """
    length = PlaneLength.of(l)
    l = length.value
    order = [chart.outer] + [k for k in range(len(chart.surface.loops)) if k != chart.outer]
    loops = [Polyline(chart.plane[chart.surface.loops[k]]) for k in order]
    rings, arcs, corner_arcs = [], [], []
    points = [loop.points for loop in loops]
    for k, loop in enumerate(loops):
        xy, arc = loop.points, loop.arc
        name = ring_name(chart, order, k)
        refuse = _refusals(chart, xy, points, name, length, spacing, feature_angle)
        corners, ring = loop_ring(xy, l, spacing, feature_angle, refuse)
        at = loop.project(ring)[2]
        at[1:] += arc[-1] * np.cumsum(np.diff(at) < 0)  # the ring starts at a corner: unwrap past the loop's start
        rings.append(ring)
        arcs.append(np.append(at, at[0] + arc[-1]))
        corner_arcs.append(arc[np.sort(corners)])
    return MeshOutline(tuple(loops), tuple(rings), tuple(arcs), tuple(order), tuple(corner_arcs))


def check_feature_angle(angle, meshed=True):
    """``angle`` (degrees) as a float, refusing anything but a real number in [0, 180); None: the default.

    Only a triangle mesh (``meshed``) takes a feature angle: a chart's
    corners are its rectangle's and its holes' vertices.
    """
    if not meshed:
        if angle is not None:
            raise EquimeshError(
                "a feature angle finds the corners of a triangle mesh's boundary loops; a parametric surface's "
                "corners are those of its parameter rectangle and the vertices of its holes"
            )
        return None
    if angle is None:
        return DEFAULT_FEATURE_ANGLE
    value = real_number(angle, "feature_angle", EquimeshError)
    if not 0.0 <= value < 180.0:
        raise EquimeshError(f"feature_angle must be at least 0 and below 180 degrees, got {number(value)}")
    return value


def check_open(surface, plane):
    """Refuse a triangle mesh whose flattening ``plane`` (step 2) closes an opening: its rim encloses no area there.

    Eq. (1) keeps the mesh's edge lengths; an opening whose rim is as long as
    the outer boundary, as at the end of a tube, cannot keep its length
    inside a plane region, and eq. (1) may squeeze it shut: a slit whose area
    is zero up to rounding (``REL_TOL`` times the squared rim length), on
    which no chart and no ring can be built.  The outer boundary is the loop
    enclosing the largest area.
    """
    vertices, loops = surface.vertices, surface.loops
    flat = [Polyline(plane[loop]) for loop in loops]
    area = [shapely.Polygon(loop.points).area for loop in flat]
    outer = int(np.argmax(area))
    rim = [float(np.linalg.norm(vertices[np.roll(loop, -1)] - vertices[loop], axis=1).sum()) for loop in loops]
    for k, loop in enumerate(loops):
        if k != outer and area[k] <= REL_TOL * flat[k].length ** 2:
            raise InvalidSurfaceError(
                f"the opening through {coordinates(vertices[loop[0]])} closes up when the surface is flattened "
                f"(eq. 1): its rim, {number(rim[k])} long on the surface (the outer boundary {number(rim[outer])}), "
                "encloses no area on the flattened surface, as when the surface wraps around the opening like a "
                "tube; cut the surface open: remove a strip of triangles from this opening to the outer boundary"
            )


def scale_turns(xy, l):
    """The turn (degrees, in [-180, 180], positive to the left) of the closed loop ``xy`` at each vertex, at the scale
    of l.

    At a scale ``s`` the loop leaves vertex ``x`` along a stretch that ends
    where it first lies ``s`` away from ``x`` (:func:`~equimesh.surface.ring.reach`),
    and arrives along the stretch that begins where, followed backwards, it
    does; the turn is the angle between the headings of the two stretches
    (:func:`_headings`), 180 where the loop never gets ``s`` away.  The turn
    at the scale of l is the smaller of those at ``s = l`` and ``s = l / 2``:
    a corner between sides at least l long turns by its angle at both scales,
    a curve or a staircase of mesh edges turns little over a stretch of l,
    and a point of a side shorter than 2l, whose stretches of l reach around
    the corners at its ends, turns by nothing at l / 2.  With the region on
    the loop's left, ``180 - turn`` is the inner angle at the scale of l.
    """
    forward, backward = Polyline(xy), Polyline(xy[::-1])
    starts = np.arange(len(xy))
    turns = []
    for s in (l, 0.5 * l):
        ahead, behind = reach(forward, s, starts), reach(backward, s, starts)
        a = -_headings(backward, behind)[::-1]
        b = _headings(forward, ahead)
        angle = np.degrees(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.sum(a * b, axis=1)))
        turns.append(np.where(np.isnan(ahead) | np.isnan(behind[::-1]), 180.0, angle))
    return np.where(np.abs(turns[0]) <= np.abs(turns[1]), turns[0], turns[1])


def _headings(loop, ends):
    """Per vertex of the closed ``loop``: its heading over the stretch from the vertex to the arc position ``ends``.

    The integral of ``(2u - S) p(u) du`` over the stretch, ``u`` the arc
    from the vertex and ``S`` the stretch's length: a weighted difference of
    the stretch's far and near halves, exactly the direction of a straight
    stretch, in which the teeth of a staircase of mesh edges average out
    where they would set the direction of a chord to the stretch's end.
    ``nan`` ends give zero headings.  From prefix sums of ``int p`` and
    ``int sigma p`` along the loop traversed twice (``sigma`` its arc), the
    points taken from its first vertex.
    """
    n, length = len(loop.points), loop.length
    pts = loop.points - loop.points[0]
    a, b = np.vstack([pts, pts]), np.vstack([pts[1:], pts, pts[:1]])  # segments of the loop traversed twice
    arc = np.concatenate([loop.arc[:-1], loop.arc[:-1] + length, [2.0 * length]])
    span = np.diff(arc)[:, None]
    first = span * (a + b) / 2.0
    second = arc[:-1, None] * first + span**2 * (a / 6.0 + b / 3.0)
    sums = [np.vstack([np.zeros((1, 2)), np.cumsum(term, axis=0)]) for term in (first, second)]

    def integrals(sigma):
        k = np.clip(np.searchsorted(arc, sigma, side="right") - 1, 0, 2 * n - 1)
        tau = (sigma - arc[k])[:, None]
        end = a[k] + tau / span[k] * (b[k] - a[k])
        part = tau * (a[k] + end) / 2.0
        return sums[0][k] + part, sums[1][k] + arc[k, None] * part + tau**2 * (a[k] / 6.0 + end / 3.0)

    start = loop.arc[:-1]
    stretch = np.nan_to_num(ends - start)
    (near, near_moment), (far, far_moment) = integrals(start), integrals(start + stretch)
    return 2.0 * (far_moment - near_moment) - (2.0 * start + stretch)[:, None] * (far - near)


def loop_corners(xy, l, feature_angle, turn=None):
    """Indices of the corners of a closed loop: its turns above ``feature_angle`` degrees at the scale of l.

    A vertex is a candidate when its turn at the scale of l (the size of
    ``turn``, by default :func:`scale_turns`) exceeds ``feature_angle`` and no vertex of
    the loop within l / 2 of it, before or after, turns more (the points of a
    side next to a corner turn by part of its angle).  Candidates are kept
    from the sharpest (the first on a tie), except one within l of a corner
    already kept, the loop between them within l of either: no side of at
    least l fits between them, and it is dropped; :func:`loop_ring` then
    checks what the ring cuts off.  Returns at least one index, the sharpest
    turn when no vertex is kept.
    """
    turn = np.abs(scale_turns(xy, l) if turn is None else turn)
    candidates = np.flatnonzero((turn > feature_angle) & _peaks(xy, turn, 0.5 * l))
    kept = []
    for c in sorted(candidates.tolist(), key=lambda i: (-turn[i], i)):
        if not any(_clash(xy, k, step, c, l) for k, step in _neighbours(kept, c)):
            kept.insert(int(np.searchsorted(kept, c)), c)
    return np.array(kept or [int(np.argmax(turn))], dtype=np.int64)


def _peaks(xy, turn, reach):
    """Whether each vertex turns at least as much as every vertex of the loop before and after it within ``reach``."""
    n = len(xy)
    index, peak = np.arange(n), np.ones(n, dtype=bool)
    for step in (1, -1):
        near = np.ones(n, dtype=bool)
        for m in range(1, n):
            other = (index + step * m) % n
            near &= np.linalg.norm(xy[other] - xy, axis=1) < reach
            if not near.any():
                break
            peak &= ~(near & (turn[other] > turn))
    return peak


def _neighbours(kept, c):
    """The corners kept before and after vertex ``c`` around the loop, each with the step (+1, -1) from it to ``c``."""
    if not kept:
        return []
    at = int(np.searchsorted(kept, c))
    return [(kept[at - 1], 1), (kept[at % len(kept)], -1)]


def _clash(xy, k, step, c, l):
    """Whether the loop from vertex ``k`` to vertex ``c`` (``step`` +1 forward, -1 backward) lies within l of either."""
    n = len(xy)
    path = (k + step * np.arange(1, (step * (c - k)) % n + 1)) % n  # the vertices after k, up to c
    return bool(
        np.all(np.linalg.norm(xy[path] - xy[k], axis=1) < l)
        or np.all(np.linalg.norm(xy[np.r_[k, path[:-1]]] - xy[c], axis=1) < l)
    )


def ring_name(chart, order, k):
    """``the outer boundary``, or ``hole k - 1 (the opening through (x, y, z))``: Problem 2's hole numbers, located in
    space."""
    if k == 0:
        return "the outer boundary"
    return f"hole {k - 1} (the opening through {coordinates(chart.surface.vertices[chart.surface.loops[order[k]][0]])})"


def loop_ring(xy, l, spacing, feature_angle, refuse):
    """Step 3 on one loop: its corners (:func:`loop_corners`) and the ring through them (:func:`resample_ring`).

    Corners turning by less than :data:`FIRM_TURN` are kept where they fit:
    if no ring runs through every corner, the ring runs through the firm ones
    only (the sharpest corner if none is firm), as on a small round opening,
    whose staircase turns by more than the feature angle all round.  Every
    vertex turning by :data:`FIRM_TURN` or more must then lie within
    :data:`CORNER_DETAIL` l of the ring.  A refusal is ``refuse(kind,
    *details)``, raised: ``("cut", i, gap)``, vertex ``i`` that far from the
    ring; ``("short", side, arc, chord, n_corners)``, a side no split leaves
    with chords of at least l; ``("small",)``, a ring of fewer than 3 parts.
    """
    turn = scale_turns(xy, l)
    size = np.abs(turn)
    corners = loop_corners(xy, l, feature_angle, turn)
    ring, why = _ring(xy, corners, l, spacing, turn)
    firm = corners[size[corners] >= FIRM_TURN]
    if ring is None and len(firm) < len(corners):
        corners = firm if len(firm) else corners[[np.argmax(size[corners])]]
        ring, why = _ring(xy, corners, l, spacing, turn)
    if ring is None:
        raise refuse(*why)
    firm = np.flatnonzero(size >= FIRM_TURN)
    gap = shapely.distance(shapely.LinearRing(ring), shapely.points(xy[firm]))
    if firm.size and gap.max() > CORNER_DETAIL * l:
        raise refuse("cut", int(firm[np.argmax(gap)]), float(gap.max()))
    return corners, ring


class _Refusal(Exception):
    """A ring that cannot be made, with the details :func:`loop_ring` refuses it with."""


def _ring(xy, corners, l, spacing, turn):
    """The ring through ``corners`` and None, or None and why there is none.

    :func:`resample_ring` with each corner's inner angle at the scale of l
    (``180 - turn``, :func:`scale_turns`): a staircase's own angle at a
    vertex says nothing of the corner there.
    """
    if np.any(np.abs(turn[corners]) >= 180.0):  # a corner the loop never gets l away from, or a slit's end
        return None, ("small",)
    try:
        ring = resample_ring(
            xy,
            xy,
            corners,
            l,
            spacing,
            too_short=lambda *side: _Refusal("short", *side, len(corners)),
            angles=180.0 - turn[corners],
        ).points
    except _Refusal as exc:
        return None, exc.args
    return (ring, None) if len(ring) >= 3 else (None, ("small",))


#: Bisection steps of :func:`largest_fitting_length`: 2^-20 of l, below the
#: four digits a suggested l is given with.
FIT_BISECTIONS = 20


def largest_fitting_length(loops, l, spacing, feature_angle):
    """The largest length below ``l`` (to four digits, rounded down) at which :func:`loop_ring` accepts every loop of
    ``loops`` (their plane points), or None.

    Found by bisection on ``(0, l)`` and checked: a refusal of any loop
    suggests an l that all of them pass, so the advice is not refused by the
    next loop (Problem 2 is not tried).
    """

    def fits(length):
        try:
            for xy in loops:
                loop_ring(xy, length, spacing, feature_angle, _Refusal)
        except _Refusal:
            return False
        return True

    low, high = 0.0, l
    for _ in range(FIT_BISECTIONS):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if fits(middle) else (low, middle)
    while low > 0.0 and not fits(round_down(low)):
        low = 0.5 * low
    return round_down(low) if low > 0.0 else None


def _refusals(chart, xy, loops, name, length, spacing, feature_angle):
    """The refusals of :func:`loop_ring` on the loop ``xy`` called ``name``, one of the chart's ``loops``, in the
    surface's terms, at the :class:`~equimesh.surface.plane_length.PlaneLength` ``length``; each suggests the largest
    l every loop takes (:func:`largest_fitting_length`)."""
    l = length.value

    def use():
        fit = largest_fitting_length(loops, l, spacing, feature_angle)
        return f"l <= {number(length.suggest(fit))}" if fit else "a smaller l"

    def too_small():
        rim = Polyline(xy).length
        return InvalidSurfaceError(
            f"{name} of the mesh is too small for {length}: no ring of 3 or more parts of at least {length.symbol} "
            f"follows its rim, {number(rim)} long on the flattened surface; use {use()}"
        )

    def refuse(kind, *details):
        if kind == "small" or (kind == "short" and details[-1] == 1):
            return too_small()
        if kind == "short":
            _, arc, chord, _ = details
            return InvalidSurfaceError(
                f"{name} of the mesh has a part {number(arc)} long between two corners {number(chord)} apart on the "
                f"flattened surface, shorter than {length}; use {use()}"
            )
        i, gap = details
        turn = scale_turns(xy, l)
        if _ring(xy, loop_corners(xy, l, 180.0, turn), l, spacing, turn)[0] is None:  # no ring at all: say so
            return too_small()
        return InvalidSurfaceError(
            f"{name} of the mesh is narrower than {length} on the flattened surface at its corner "
            f"{coordinates(chart.evaluate(xy[i, 0], xy[i, 1]))}: a ring of parts of at least {length.symbol} passes "
            f"{number(gap)} from it; use {use()}"
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
    ``l`` is the caller's l, or the :class:`~equimesh.surface.plane_length.PlaneLength` Problem 2 meshed at.
    """
    l = PlaneLength.of(l)
    if not exc.points or len(exc.points) != 2:
        holes = "; ".join(ring_name(chart, outline.order, k) for k in range(1, len(outline.rings)))
        return InvalidSurfaceError(
            f"the triangle mesh cannot be meshed with {l}: {exc}" + (f" ({holes})" if "hole" in str(exc) else "")
        )
    xy = np.asarray(exc.points, dtype=float)
    where = " and ".join(coordinates(p) for p in chart.evaluate(xy[:, 0], xy[:, 1]))
    gap = float(np.linalg.norm(xy[1] - xy[0]))
    return InvalidSurfaceError(
        f"the triangle mesh cannot be meshed with {l}: its boundary points at {where} are {number(gap)} apart on the "
        f"flattened surface, closer than {l.symbol} (a neck, an opening near the boundary or another opening, or a "
        f"corner too sharp for its sides); try l <= {number(l.suggest(round_down(gap)))}"
    )
