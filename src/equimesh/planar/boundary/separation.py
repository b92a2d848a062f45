"""Lemma 3 (1) on the resampled boundary: mutually visible boundary points at least l apart (Section 3).

Problem 2's proof of Theorem 3 needs it; Step 2 guarantees it for Problem 1
and next to sharp corners whose sides are long enough, and
:func:`check_boundary_separation` checks it on every other ring.  A refusal
says what is proven: that no mesh with every edge in [l, 2l] exists, that no
Step 2 can meet Lemma 3 (1) at a corner or a run of corners (decided on a grid
of cells by :mod:`~equimesh.planar.boundary.corner` and
:mod:`~equimesh.planar.boundary.chain`), or that the polygon is too narrow for
this method there.
"""

import math

import numpy as np
import shapely
from scipy.spatial import cKDTree

from ...errors import InvalidPolygonError, number
from ...tolerance import REL_TOL
from . import chain as _chain
from . import corner as _corner
from .sides import SHARP_CORNER, sharp_run, stagger_count, stagger_reach

#: Positions the proofs of one refusal may reduce together (:class:`.chain.Work`): a bound on the time a refusal
#: takes to say what is proven, not a tolerance; past it the corners left are "not handled".
PROOF_WORK = 2_000_000


def check_boundary_separation(poly, boundary, l):
    """Lemma 3 (1): mutually visible boundary points are at least ``l`` apart.

    Only pairs closer than ``(1 - REL_TOL) l`` are examined.  Such a pair is
    accepted only when the segment joining them provably leaves the polygon:
    some point of it lies farther than ``REL_TOL l`` outside, i.e. the segment
    is not covered by the polygon grown by ``REL_TOL l``.  Resampled points lie
    on the boundary only up to rounding, so an exact visibility test would skip
    a pair whose segment runs a rounding error outside; a segment that grazes a
    reflex vertex ``r`` counts as visible too, which refuses nothing valid:
    then ``|pr| + |rq|`` is within rounding of ``|pq| < l``, so ``r`` is closer
    than ``l`` to ``p`` or ``q`` (``docs/proofs.md``, "Boundary separation
    (Problem 2)").  Holds automatically for Problem 1 (:func:`resample_boundary`);
    for a non-convex polygon it fails at necks narrower than ``l`` and at
    corners too sharp for the resampled points next to them.

    Raises :class:`InvalidPolygonError` for the closest offending pair, with
    ``points`` the two boundary points in the caller's coordinates.  The
    message says what is proven (docs/proofs.md, "Sharp corners"): that no
    mesh with every edge in ``[l, 2l]`` exists (:func:`unmeshable_corner`),
    that no Step 2 can meet Lemma 3 (1) at a corner (its first points,
    :func:`unseparable_corner`; or all its points, decided on a grid,
    :func:`unplaceable_corner` at the corners of the offending pairs, or
    :func:`unplaceable_chain` at two or more of them in a row), or neither (a
    corner or neck this method does not handle).
    """
    pts = boundary.points
    lp = poly.local_length(l)
    pairs = cKDTree(pts).query_pairs((1.0 - REL_TOL) * lp, output_type="ndarray")
    if not len(pairs):
        return
    grown = poly.region.buffer(REL_TOL * lp)
    shapely.prepare(grown)
    lines = shapely.linestrings(np.stack([pts[pairs[:, 0]], pts[pairs[:, 1]]], axis=1))
    visible = shapely.covers(grown, lines)
    if not np.any(visible):
        return
    pairs = pairs[visible]
    gap = np.linalg.norm(pts[pairs[:, 0]] - pts[pairs[:, 1]], axis=1)
    i, j = pairs[np.lexsort((pairs[:, 1], pairs[:, 0], gap))[0]]
    work = _chain.Work(PROOF_WORK)
    raise (
        unmeshable_corner(poly, l)
        or unseparable_corner(poly, l)
        or unplaceable_corner(poly, l, corners_of(poly, boundary, pairs), work)
        or unplaceable_chain(poly, l, corners_of(poly, boundary, pairs), work)
        or separation_error(poly, boundary, l, int(i), int(j))
    )


def corners(poly):
    """Every corner of every ring: ``(ring, i, theta, leaving, arriving)``, the angle in radians, side lengths local."""
    for ring in poly.rings:
        lengths = ring.local_edge_lengths
        for i in range(len(lengths)):
            yield ring, i, math.radians(ring.inner_angle(i)), lengths[i], lengths[i - 1]


def chord(a, b, theta):
    """The distance between points at distances ``a`` and ``b`` from a corner of angle ``theta``, on its two sides."""
    return math.sqrt(max(a * a + b * b - 2.0 * a * b * math.cos(theta), 0.0))


def first_node(length, lp):
    """Where the first node after a corner can lie on a side of ``length``: ``(lowest, highest)`` distance from it.

    The side is split into parts in ``[l, 2l]``: the first part ``f`` is at
    most ``2l`` and leaves 0 or at least ``l``, so ``f = length`` below
    ``2l`` and ``f`` in ``[l, min(2l, length - l)]`` past ``2l`` (``[l, 2l]``
    at ``2l``).  The range is widened by REL_TOL, the tolerance of the checks
    on parts and edges, so that it contains every placement they accept.
    """
    if length < 2.0 * lp * (1.0 - REL_TOL):
        return length, length
    high = 2.0 * lp if length <= 2.0 * lp * (1.0 + REL_TOL) else min(2.0 * lp, length - lp)
    return (1.0 - REL_TOL) * lp, high * (1.0 + REL_TOL)


def unmeshable_corner(poly, l):
    """The error for the first corner at which no mesh with every edge in ``[l, 2l]`` exists, or None.

    A side of length ``beta < 2l`` at a corner ``v`` of angle ``theta`` is a
    single mesh edge ``v b`` (:func:`first_node`).  The triangle on it has
    a third node ``q`` with ``|v q|`` in ``[l, 2l]`` and the segment ``v q``
    in P, so ``q`` lies in the sector of radii ``l`` to ``2l`` between the
    two sides; its farthest point from ``b`` is at radius ``l`` or ``2l`` on
    the other side (radii widened by REL_TOL, the tolerance of the edge
    checks).  When both are closer than ``l`` to ``b``, the edge
    ``q b`` is shorter than ``l`` in every mesh: that is
    ``beta < 2 l cos theta`` and ``beta^2 - 4 l beta cos theta + 3 l^2 < 0``
    (docs/proofs.md, "Sharp corners", the sector lemma).
    """
    lp = poly.local_length(l)
    for ring, i, theta, leaving, arriving in corners(poly):
        for side, beta in ((i, leaving), (i - 1, arriving)):
            far = max(chord(r, beta, theta) for r in ((1.0 - REL_TOL) * lp, 2.0 * lp * (1.0 + REL_TOL)))
            if beta < 2.0 * lp * (1.0 - REL_TOL) and far < (1.0 - REL_TOL) * lp:
                c = math.cos(theta)
                low, need = (2.0 * c - math.sqrt(4.0 * c * c - 3.0)) * l, 2.0 * c * l
                return InvalidPolygonError(
                    f"no mesh with every edge in [l, 2l] exists for l = {number(l, None)}: at the corner at "
                    f"{ring.vertex_name(i)} ({number(math.degrees(theta))} degrees) {ring.edge_name(side)} is "
                    f"{number(beta / poly.frame.scale, None)} long, a single mesh edge, and the third node of its "
                    "triangle "
                    f"would be closer than l to its other end, {ring.vertex_name(side if side < i else i + 1)} "
                    f"(docs/proofs.md, 'Sharp corners'); at this angle that side must be at least {number(need, 10)} "
                    "long "
                    f"(or at most {number(low, 10)})"
                )
    return None


def unseparable_corner(poly, l):
    """The error for the first corner at which no boundary resampling meets Lemma 3 (1), or None.

    Any Step 2 places on each side a first point within :func:`first_node`'s
    range.  :func:`chord` is convex in each distance, so if it is below ``l``
    at the four ends of the two ranges, the first points of the two sides are
    closer than ``l`` wherever they lie; when the triangle of the corner and
    the far ends of the ranges lies in P (grown by ``REL_TOL l``, as in
    :func:`check_boundary_separation`), they also see each other.  Then no
    boundary resampling meets Lemma 3 (1), which this method and the paper's
    need; it is not a proof that no mesh exists (docs/proofs.md, "Sharp
    corners").
    """
    lp = poly.local_length(l)
    grown = poly.region.buffer(REL_TOL * lp)
    for ring, i, theta, leaving, arriving in corners(poly):
        ends = [(a, b) for a in first_node(leaving, lp) for b in first_node(arriving, lp)]
        if theta < math.pi and max(chord(a, b, theta) for a, b in ends) < (1.0 - REL_TOL) * lp:
            if not sees_within(grown, ring, i, *ends[-1]):
                continue
            need = number((stagger_reach(math.degrees(theta), lp) + lp) / poly.frame.scale, None)
            return InvalidPolygonError(
                f"the corner at {ring.vertex_name(i)} ({number(math.degrees(theta))} degrees) cannot meet Lemma 3 (1) "
                f"for l = {number(l, None)}: with sides of {number(leaving / poly.frame.scale, None)} and "
                f"{number(arriving / poly.frame.scale, None)} the first boundary points of its two sides are closer "
                "than l "
                "wherever they lie, so no Step 2 separates them (a limit of the paper's method, not a proof that no "
                f"mesh exists; docs/proofs.md, 'Sharp corners'); sides of at least {need} are handled; "
                "use a smaller l, longer sides or a wider corner"
            )
    return None


def sees_within(grown, ring, i, leaving, arriving):
    """Whether the triangle of corner ``i`` and the points ``leaving`` and ``arriving`` along its sides lies in
    ``grown``.

    Then every two points of the two sides within those distances see each
    other (the segment joining them lies in the triangle).
    """
    v, n = ring.local[i], len(ring.local)
    lengths = ring.local_edge_lengths
    far = [v + (ring.local[j % n] - v) * r / lengths[k] for j, r, k in ((i + 1, leaving, i), (i - 1, arriving, i - 1))]
    return grown.covers(shapely.Polygon([v, *far]))


#: Bisection steps of :func:`visible_radii` between the last halving of the sides that is seen and the one
#: before: a bound on the work (the radii are then within ``2^-VISIBLE_BISECTIONS`` of the largest seen at that
#: ratio), not a tolerance.
VISIBLE_BISECTIONS = 20


def visible_radii(grown, ring, i, sides):
    """``sides`` scaled down until :func:`sees_within` holds for them, or ``(0, 0)`` (nothing seen).

    Halved first (at most 64 times), then bisected between the first
    halving seen and the one before (:data:`VISIBLE_BISECTIONS` steps): the
    triangles of the corner and ``t sides`` grow with ``t``, so every ``t``
    below one seen is seen too.  Never below the halving alone.
    """
    for k in range(64):
        if sees_within(grown, ring, i, *(x / 2.0**k for x in sides)):
            break
    else:
        return 0.0, 0.0
    low, high = 0.5**k, 2.0 * 0.5**k
    for _ in range(VISIBLE_BISECTIONS * bool(k)):
        middle = (low + high) / 2.0
        if sees_within(grown, ring, i, *(x * middle for x in sides)):
            low = middle
        else:
            high = middle
    return tuple(x * low for x in sides)


def corners_of(poly, boundary, pairs):
    """The corners ``(ring, i)`` at which a pair of ``pairs`` (boundary point indices) lies on the two sides.

    A vertex of P lies on the edge it starts and on the one it ends.
    """
    found = set()
    for i, j in pairs:
        r = int(boundary.ring[i])
        if r != int(boundary.ring[j]):
            continue
        n = len(poly.rings[r].local)
        edges = [{int(boundary.edge[k]), int(boundary.edge[k] - boundary.is_vertex[k]) % n} for k in (i, j)]
        found |= {(r, b) for a in edges[0] for b in edges[1] if (a + 1) % n == b}
        found |= {(r, a) for a in edges[0] for b in edges[1] if (b + 1) % n == a}
    return sorted(found)


def unplaceable_corner(poly, l, corners, work=None):
    """The error for the first of ``corners`` (``(ring, i)``) that no Step 2 can separate (Lemma 3 (1)), or None.

    Only corners sharper than :data:`SHARP_CORNER` are decided
    (:func:`.corner.corner_unplaceable`, then on finer cells
    :func:`.chain.chain_unplaceable` with no second corner): distances are
    checked within the largest of the sides' lengths halved until the triangle they span with
    the corner lies in P (grown by ``REL_TOL l``), where every two points of
    the two sides see each other (:func:`sees_within`).  When no split of
    the two sides into parts of ``[l, 2l]`` keeps them ``l`` apart there, no
    boundary resampling meets Lemma 3 (1), which this method and the
    paper's need; it is not a proof that no mesh exists (docs/proofs.md,
    "Sharp corners").
    """
    lp = poly.local_length(l)
    grown = poly.region.buffer(REL_TOL * lp)
    for r, i in corners:
        ring = poly.rings[r]
        angle, lengths = ring.inner_angle(i), ring.local_edge_lengths
        sides = (lengths[i], lengths[i - 1])
        if not angle < SHARP_CORNER:
            continue
        radii = visible_radii(grown, ring, i, sides)
        theta = math.radians(angle)
        if not _corner.corner_unplaceable(theta, sides, lp, radii) and not _chain.chain_unplaceable(
            (theta, None), (sides[1], sides[0], 0.0), lp, (radii[1], radii[0], 0.0, 0.0), work
        ):
            continue
        need = number((stagger_reach(angle, lp) + lp) / poly.frame.scale, None)
        return InvalidPolygonError(
            f"the corner at {ring.vertex_name(i)} ({number(angle)} degrees) cannot meet Lemma 3 (1) for l = "
            f"{number(l, None)}: "
            f"no split of its sides of {number(sides[0] / poly.frame.scale, None)} and "
            f"{number(sides[1] / poly.frame.scale, None)} "
            "into parts of [l, 2l] keeps every two points of different sides l apart (decided on a grid of cells), so "
            "no Step 2 separates them (a limit of the paper's method, not a proof that no mesh exists; docs/proofs.md, "
            f"'Sharp corners'); sides of at least {need} are handled; use a smaller l, longer sides or a wider corner"
        )
    return None


def unplaceable_chain(poly, l, corners, work=None):
    """The error for the first sharp corners in a row, one of ``corners``, that no Step 2 separates together, or None.

    First each two consecutive corners ``i``, ``i + 1`` both sharper than
    :data:`SHARP_CORNER` (either in ``corners``), then each run of three or
    more through one of ``corners`` (:func:`_run`), are decided by
    :func:`.chain.chain_unplaceable`, distances checked within each
    corner's :func:`visible_radii` as in :func:`unplaceable_corner`.  When
    no split of their sides into parts of ``[l, 2l]`` keeps every corner's
    two sides ``l`` apart there, no boundary resampling meets Lemma 3 (1);
    it is not a proof that no mesh exists (docs/proofs.md, "Sharp corners").
    """
    lp = poly.local_length(l)
    grown = poly.region.buffer(REL_TOL * lp)
    pairs = sorted({(r, (j - k) % len(poly.rings[r].local)) for r, j in corners for k in (0, 1)})
    runs = [(r, [i, (i + 1) % len(poly.rings[r].local)]) for r, i in pairs]
    for r, j in corners:
        ring = poly.rings[r]
        angles = [ring.inner_angle(i) for i in range(len(ring.local))]
        if stagger_count(angles[j]):
            run = sharp_run(ring.local_edge_lengths, angles, lp, j)
            if len(run) > 2 and (r, run) not in runs:
                runs.append((r, run))
    for r, run in runs:
        ring = poly.rings[r]
        n, lengths = len(ring.local), ring.local_edge_lengths
        angles = [ring.inner_angle(c) for c in run]
        if not max(angles) < SHARP_CORNER:
            continue
        edges = [lengths[(run[0] - 1 + k) % n] for k in range(len(run) + 1)]
        radii = sum((visible_radii(grown, ring, c, (edges[k + 1], edges[k]))[::-1] for k, c in enumerate(run)), ())
        if not _chain.chain_unplaceable(tuple(math.radians(a) for a in angles), tuple(edges), lp, radii, work):
            continue
        names = [f"{ring.vertex_name(c)} ({number(a)} degrees)" for c, a in zip(run, angles)]
        sides = ", ".join(number(x / poly.frame.scale, None) for x in edges)
        return InvalidPolygonError(
            f"the corners at {', '.join(names[:-1])} and {names[-1]} cannot meet Lemma 3 (1) together for l = "
            f"{number(l, None)}: "
            f"no split of their sides of {sides} (the middle {'ones' if len(run) > 2 else 'one'} shared) into parts of "
            "[l, 2l] keeps every two points of different sides l apart at "
            f"{'both corners' if len(run) == 2 else 'every corner'} "
            "(decided on a grid of cells), so "
            "no Step 2 separates them (a limit of the paper's method, not a proof that no mesh exists; docs/proofs.md, "
            "'Sharp corners'); use a smaller l, longer sides or wider corners"
        )
    return None


def separation_error(poly, boundary, l, i, j):
    """The error for boundary points ``i`` and ``j`` closer than ``l`` that see each other."""
    p, q = boundary.points[i], boundary.points[j]
    d = number(np.linalg.norm(q - p) / poly.frame.scale, None)
    ri, rj = (poly.rings[int(boundary.ring[k])] for k in (i, j))
    ei, ej = int(boundary.edge[i]), int(boundary.edge[j])
    where = f"boundary points on {ri.edge_name(ei)} and {rj.edge_name(ej)} are {d} apart"
    caller = poly.frame.to_caller(np.array([p, q]))
    n = len(ri.local)
    corner = None if ri is not rj else ej if (ei + 1) % n == ej else ei if (ej + 1) % n == ei else None
    if corner is not None:
        angle = ri.inner_angle(corner)
        need = number((stagger_reach(angle, poly.local_length(l)) / poly.frame.scale) + l, None)
        message = (
            f"the corner at {ri.vertex_name(corner)} ({number(angle)} degrees) is not handled for l = "
            f"{number(l, None)}: "
            f"{where}, closer than l (Lemma 3 (1)); the staggered Step 2 is proven at {number(angle)} degrees for "
            "sides "
            f"of at least {need}, longer if the next corner is sharp too; for these the searches found no placement "
            "and none is proven impossible, even for each corner alone (a limit of this method, not a proof that no "
            "mesh exists; docs/proofs.md, 'Sharp corners'); "
            "use a smaller l, longer sides or a wider corner"
        )
    else:
        message = (
            f"polygon is too narrow for l = {number(l, None)}: {where} and see each other across the polygon "
            f"(Lemma 3 (1), a limit of this method); use l <= {d} or widen the polygon there"
        )
    return InvalidPolygonError(message, points=caller)
