"""Non-convex inputs of Problem 2: orthogonal, letter, star and flattened-square polygons.

Shared by the property tests (``tests/strategies_simple.py``) and
``experiments/problem2.py``; convex polygons come from
:mod:`equimesh.testing.generators`.  All constructors are deterministic and return
``(n, 2)`` float arrays, counter-clockwise.  Conditions under which each is a
valid input of :func:`equimesh.uniform_triangulation` for ``l = 1``:

* :func:`column_polygon` scaled by ``u >= 1`` (each axis): every two distinct
  x (and y) coordinates of vertices differ by at least ``u``, so two edges
  that do not touch are at least ``u`` apart and the corners are 90 or 270
  degrees: all Step 2 points that see each other are at least 1 apart.
* :func:`star_polygon` with ``inner sin(pi / k) >= half_width >= 1/2`` and
  ``outer - inner >= 1``: the arms narrow outwards to a tip ``2 half_width``
  wide, every tip angle is above 90 degrees, the valleys are reflex.
* :func:`flattened_square` with ``L = max(a ky, b kx) < 1`` and spacing
  ``n / parts >= 1.2 / (1 - L)``: ``F - id`` is ``L``-Lipschitz, so ``F`` is
  injective, edges are at least ``(1 - L) n / parts >= 1.2`` long and corner
  angles are within ``2 atan(L)`` of 90 degrees (keep ``L <= 0.25``).
"""

import math

import numpy as np

from .generators import rotate


def remove_collinear(vertices):
    """Drop vertices where the boundary goes straight on (exact for integer input)."""
    v = np.asarray(vertices, dtype=float)
    prev, nxt = np.roll(v, 1, axis=0), np.roll(v, -1, axis=0)
    turn = (v[:, 0] - prev[:, 0]) * (nxt[:, 1] - v[:, 1]) - (v[:, 1] - prev[:, 1]) * (nxt[:, 0] - v[:, 0])
    return v[turn != 0]


def column_polygon(intervals):
    """Orthogonal polygon, the union of unit columns ``[i, i+1] x [lo_i, hi_i]`` (integer grid).

    Consecutive intervals must overlap in at least one unit, so the union is a
    simple x-monotone polygon without holes.  Integer-valued vertices,
    collinear vertices removed.
    """
    iv = [(int(lo), int(hi)) for lo, hi in intervals]
    for (a0, a1), (b0, b1) in zip(iv, iv[1:]):
        if min(a1, b1) - max(a0, b0) < 1:
            raise ValueError(f"columns {(a0, a1)} and {(b0, b1)} do not overlap in a whole unit")
    lower = [p for i, (lo, _) in enumerate(iv) for p in ((i, lo), (i + 1, lo))]
    upper = [p for i in range(len(iv) - 1, -1, -1) for p in ((i + 1, iv[i][1]), (i, iv[i][1]))]
    ring = lower + upper
    return remove_collinear([p for k, p in enumerate(ring) if p != ring[k - 1]])


def letter_polygon(kind, arm, length):
    """``"L"``, ``"U"``, ``"T"`` or ``"plus"`` on the integer grid: arms ``arm`` wide and ``length`` long (units)."""
    w, a = int(arm), int(length)
    columns = {
        "L": [(0, w + a)] * w + [(0, w)] * a,
        "U": [(0, w + a)] * w + [(0, w)] * a + [(0, w + a)] * w,
        "T": [(a, a + w)] * a + [(0, a + w)] * w + [(a, a + w)] * a,
        "plus": [(a, a + w)] * a + [(0, 2 * a + w)] * w + [(a, a + w)] * a,
    }
    if kind not in columns:
        raise ValueError(f"unknown letter {kind!r}; choose from {sorted(columns)}")
    return column_polygon(columns[kind])


def dumbbell_polygon(left, right, corridor_length, shift=0):
    """Two square blobs ``left`` and ``right`` units wide joined by a corridor one unit wide (integer grid)."""
    lo = max(left, right) // 2 + shift
    lo = min(max(lo, 1), min(left, right) - 2)
    return column_polygon([(0, left)] * left + [(lo, lo + 1)] * corridor_length + [(0, right)] * right)


def star_polygon(k, half_width, inner, outer):
    """Star with ``k`` arms of half-width ``half_width`` ending at radius ``outer``; valleys at radius ``inner``."""
    out = []
    for i in range(k):
        phi = 2.0 * math.pi * i / k
        u = np.array([math.cos(phi), math.sin(phi)])
        n = np.array([-u[1], u[0]])
        psi = phi + math.pi / k
        out += [
            outer * u - half_width * n,
            outer * u + half_width * n,
            inner * np.array([math.cos(psi), math.sin(psi)]),
        ]
    return np.array(out)


def flattened_square(n, parts, a, b, ky, kx, p=0.0, q=0.0):
    """Boundary of ``[0, n]^2``, ``parts`` equal parts per side, mapped by ``F(x, y) = (x + a sin(ky y + p), y + b
    sin(kx x + q))``.

    A stand-in for the flattened boundary of a surface patch (paper, Fig. 3):
    smooth, wavy, generally not convex.
    """
    t = np.arange(parts) / parts * n
    z = np.zeros(parts)
    ring = np.vstack(
        [
            np.column_stack([t, z]),
            np.column_stack([z + n, t]),
            np.column_stack([n - t, z + n]),
            np.column_stack([z, n - t]),
        ]
    )
    x, y = ring[:, 0], ring[:, 1]
    return np.column_stack([x + a * np.sin(ky * y + p), y + b * np.sin(kx * x + q)])


def sharp_wedge(angle, side, depth):
    """A tip of ``angle`` degrees at the origin, sides ``side`` long, closed by a rectangle ``depth`` deep.

    Corners: the tip, ``180 - angle / 2`` twice and 90 twice; the rectangle is
    ``2 side sin(angle / 2)`` wide.  Valid for Problem 2 with ``l = 1`` when
    ``side >= stagger_reach(angle) + 1`` (the proven limit of the staggered
    Step 2, docs/proofs.md "Sharp corners") and ``side sin(angle / 2) >= 1.2``.
    """
    h = math.radians(angle) / 2.0
    a, b = side * np.array([math.cos(h), -math.sin(h)]), side * np.array([math.cos(h), math.sin(h)])
    return np.array([[0.0, 0.0], a, a + [depth, 0.0], b + [depth, 0.0], b])


def sharp_rhombus(angle, side):
    """A rhombus with two tips of ``angle`` degrees and sides ``side`` long (the other corners obtuse).

    Valid for Problem 2 with ``l = 1`` when ``side >= stagger_reach(angle) + 1``
    and ``side sin(angle) >= 1.2`` (the width between opposite sides).
    """
    t = math.radians(angle)
    return np.array(
        [
            [0.0, 0.0],
            [side, 0.0],
            [side * (1 + math.cos(t)), side * math.sin(t)],
            [side * math.cos(t), side * math.sin(t)],
        ]
    )


def sharp_dart(angle, barbs, side):
    """An arrowhead: a tip of ``angle`` degrees at the origin, sides ``side`` long, barbs of ``barbs`` degrees, a notch.

    Counter-clockwise: the tip, the lower barb, the notch, the upper barb.
    The notch is where the barbs' inner sides meet; it is reflex and lies
    inside the triangle of the tip and the barbs whenever ``angle`` and both
    ``barbs`` are below 60 (the triangle's base angles are then above 60).
    With all three sharp, the sides between them are shared by two sharp
    corners each: a run of three (docs/proofs.md, "Sharp corners").
    """
    h = math.radians(angle) / 2.0
    lower, upper = side * np.array([math.cos(h), -math.sin(h)]), side * np.array([math.cos(h), math.sin(h)])

    def inward(barb, towards, turn):  # the direction from a barb, turned from the side to the tip
        d = (towards - barb) / np.linalg.norm(towards - barb)
        c, s = math.cos(turn), math.sin(turn)
        return np.array([c * d[0] - s * d[1], s * d[0] + c * d[1]])

    d1, d2 = inward(lower, 0.0 * lower, -math.radians(barbs[0])), inward(upper, 0.0 * upper, math.radians(barbs[1]))
    t = np.linalg.solve(np.column_stack([d1, -d2]), upper - lower)[0]
    return np.array([[0.0, 0.0], lower, lower + t * d1, upper])


def sharp_corner_shape(kind, angle, reach, u, v, w):
    """``(outer, holes)``: a corner of ``angle`` degrees with sides between l and ``reach`` (``l = 1``).

    ``u, v, w`` in ``[0, 1]`` pick the sizes.  Kinds (``tests/strategies_sharp.py``):
    ``"thin triangle"`` (tip sides ``1 + u (reach - 1)`` and ``1 + v (reach - 1)``),
    ``"short wedge"`` (:func:`sharp_wedge`, base at least 1.2), ``"spike"`` (a
    rectangle with a spike on top, base at least 1.2, the rectangle at least
    1.2 beyond it) and ``"dart hole"`` (a rectangle with a dart-shaped hole
    whose notch is the sharp corner of the region, 1.2 to 3.2 from the
    rectangle).  Corners other than the sharp one are whatever the sizes
    make them; shapes may be beyond what Step 2 handles.
    """
    half = math.radians(angle) / 2.0
    wide = 0.6 / math.sin(half)
    side = max(wide, 1.0) + u * max(reach - max(wide, 1.0), 0.0)
    if kind == "thin triangle":
        a, b = 1.0 + u * (reach - 1.0), 1.0 + v * (reach - 1.0)
        return np.array([[0.0, 0.0], [a, 0.0], [b * math.cos(2.0 * half), b * math.sin(2.0 * half)]]), []
    if kind == "short wedge":
        return sharp_wedge(angle, side, 1.2 + 4.8 * w), []
    if kind == "spike":
        h, base = side * math.cos(half), 2.0 * side * math.sin(half)
        width, height = base + 2.4 + 6.0 * v, 2.4 + 4.0 * w
        x0 = (width - base) / 2.0
        outer = [
            [0, 0],
            [width, 0],
            [width, height],
            [x0 + base, height],
            [x0 + base / 2.0, height + h],
            [x0, height],
            [0, height],
        ]
        return np.array(outer, dtype=float), []
    if kind == "dart hole":
        d, h = side * math.cos(half), side * math.sin(half)
        tip, gap = d + 1.2 + 3.0 * v, 1.2 + 2.0 * w
        hole = np.array([[0.0, 0.0], [tip, h], [0.0, 2.0 * h], [d, h]])
        outer = np.array([[-gap, -gap], [tip + gap, -gap], [tip + gap, 2.0 * h + gap], [-gap, 2.0 * h + gap]])
        return outer, [hole]
    raise ValueError(f"unknown kind {kind!r}")


def perforated_rectangle(holes, gap):
    """A rectangle around ``holes`` set in a row: ``(outer, holes)``, counter-clockwise.

    Each hole is translated so that the bounding boxes are ``gap`` apart from
    each other and from the rectangle's sides.  Every hole is then at least
    ``gap`` from the outer boundary and from every other hole, and the
    rectangle's edges are at least ``2 gap`` long: with ``gap >= 1`` and hole
    edges at least 1 long, a valid input of Problem 2 with holes for
    ``l = 1`` as far as the holes go (Lemma 3 (1) across boundaries).
    """
    placed, x = [], gap
    rings = [np.asarray(h, dtype=float) for h in holes]
    height = max(float(np.ptp(h[:, 1])) for h in rings) + 2.0 * gap
    for h in rings:
        lo = h.min(axis=0)
        placed.append(h - lo + [x, (height - np.ptp(h[:, 1])) / 2.0])
        x += float(np.ptp(h[:, 0])) + gap
    outer = np.array([[0.0, 0.0], [x, 0.0], [x, height], [0.0, height]])
    return outer, placed


def place(vertices, angle, shift):
    """Rotate by ``angle`` radians about the mean of the vertices, which then moves to ``shift``."""
    v = np.asarray(vertices, dtype=float)
    return rotate(v - v.mean(axis=0), angle) + np.asarray(shift, dtype=float)


__all__ = [
    "column_polygon",
    "dumbbell_polygon",
    "flattened_square",
    "letter_polygon",
    "perforated_rectangle",
    "place",
    "remove_collinear",
    "sharp_rhombus",
    "sharp_wedge",
    "star_polygon",
]
