"""Valid inputs of Problem 1 by construction: convex polygons with every inner angle >= 90 degrees.

Shared by the tests (``tests/strategies.py``, which feeds the constructive
steps below with values hypothesis draws) and ``experiments/ratio_sweep.py``.
The benchmarks deliberately do not use it: their inputs are frozen literals
(``benchmarks/benchmarks/common.py``), so that a change here cannot move
timings measured across commits.

Construction of :func:`random_convex_polygon`.  A convex polygon is fixed by
its edge directions and edge lengths.  Walking counter-clockwise, the edge
direction turns at each vertex by the *exterior* angle ``180 - inner``; the
turns are positive (convexity), at most 90 degrees (inner angle >= 90) and sum
to 360 degrees, so at least 4 vertices are needed.

1. Turns: draw ``v_i`` in (0, 1] and map them to ``t_i`` in (0, 1]
   with ``sum t_i = 4`` (turn ``90 t_i`` degrees): if ``sum v > 4`` scale
   ``v`` down, ``t = 4 v / sum v``; otherwise move every ``v_i`` towards 1,
   ``t_i = 1 - s (1 - v_i)`` with ``s = (k - 4) / sum(1 - v) in [0, 1]``.
   Both maps keep every ``t_i`` in (0, 1].
2. Lengths: draw positive lengths, then close the polygon.  The gap
   ``g = -sum L_i u_i`` lies in the cone of two consecutive directions
   ``u_j, u_{j+1}`` (they are at most 90 degrees apart and go all the way
   round), so ``g = a u_j + b u_{j+1}`` with ``a, b >= 0``; adding ``a`` to
   ``L_j`` and ``b`` to ``L_{j+1}`` closes the polygon and keeps every length
   positive.
3. Scale so that the shortest edge is at least ``min_edge`` and the area
   reaches the requested value, then rotate and translate.
"""

import math

import numpy as np

from .._geometry import cross, signed_area


def rectangle(width, height, origin=(0.0, 0.0)):
    """Axis-parallel rectangle, counter-clockwise from its lower-left corner."""
    x, y = float(origin[0]), float(origin[1])
    w, h = float(width), float(height)
    return np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]])


def regular_polygon(k, edge, center=(0.0, 0.0), rotation=0.0):
    """Regular ``k``-gon with edges of length ``edge``, counter-clockwise.

    Inner angles are ``180 (k - 2) / k`` degrees, at least 90 exactly when
    ``k >= 4``.
    """
    if k < 3:
        raise ValueError(f"a regular polygon needs k >= 3, got {k}")
    radius = edge / (2.0 * math.sin(math.pi / k))
    phi = rotation + 2.0 * math.pi * np.arange(k) / k
    return np.asarray(center, dtype=float) + radius * np.column_stack([np.cos(phi), np.sin(phi)])


def rotate(vertices, angle, center=(0.0, 0.0)):
    """Rotate ``vertices`` by ``angle`` radians about ``center``."""
    c, s = math.cos(angle), math.sin(angle)
    o = np.asarray(center, dtype=float)
    return (np.asarray(vertices, dtype=float) - o) @ np.array([[c, s], [-s, c]]) + o


def right_angle_turns(rng, k, min_turn=0.0):
    """:func:`turns_from_fractions` of ``k`` uniform draws in (0, 1] from ``rng``."""
    if k < 4:
        raise ValueError(f"a convex polygon with inner angles >= 90 degrees has >= 4 vertices, got {k}")
    return turns_from_fractions(1.0 - rng.random(k), min_turn)


def turns_from_fractions(fractions, min_turn=0.0):
    """Exterior turns (fractions of 90 degrees) in (0, 1], summing to 4 (step 1 of the module docstring).

    ``fractions`` are the raw values ``v_i`` in (0, 1], one per vertex (at
    least 4); all equal give the regular polygon's turns ``4 / k``.
    ``min_turn`` in [0, 1) mixes the result with uniform turns ``4 / k`` so
    that no turn is below ``min_turn * 4 / k``.
    """
    v = np.asarray(fractions, dtype=float)
    k = len(v)
    if k < 4:
        raise ValueError(f"a convex polygon with inner angles >= 90 degrees has >= 4 vertices, got {k}")
    total = v.sum()
    if total > 4.0:
        t = 4.0 * v / total
    else:
        deficit = np.sum(1.0 - v)
        s = (k - 4) / deficit if deficit > 0 else 0.0
        t = 1.0 - s * (1.0 - v)
    return (1.0 - min_turn) * t + min_turn * 4.0 / k


def close_polygon(directions, lengths):
    """Lengthen two consecutive edges so that edges ``lengths * u(directions)`` close (step 2).

    ``directions`` must increase and go once round with consecutive gaps of
    at most 90 degrees (pi / 2).
    """
    u = np.column_stack([np.cos(directions), np.sin(directions)])
    lengths = np.array(lengths, dtype=float)
    gap = -(lengths @ u)
    nxt = np.roll(u, -1, axis=0)
    det = cross(u, nxt)
    # Where det <= 0, or is tiny (two directions nearly alike, a cone too narrow to hold the gap: a and b huge and
    # of opposite signs), the quotients are discarded or never chosen.
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        a = np.where(det > 0, cross(gap, nxt) / det, -np.inf)
        b = np.where(det > 0, cross(u, gap) / det, -np.inf)
    # The cone containing the gap has a, b >= 0; rounding may leave -1e-17.
    j = int(np.argmax(np.minimum(a, b)))
    lengths[j] += max(a[j], 0.0)
    lengths[(j + 1) % len(lengths)] += max(b[j], 0.0)
    return lengths


def polygon_from_edges(directions, lengths):
    """Vertices of the polygon walking edges ``lengths[i] * u(directions[i])`` from the origin."""
    steps = np.asarray(lengths)[:, None] * np.column_stack([np.cos(directions), np.sin(directions)])
    return np.vstack([[0.0, 0.0], np.cumsum(steps[:-1], axis=0)])


def random_convex_polygon(
    rng,
    *,
    n_vertices=None,
    area=None,
    min_edge=1.0,
    elongation=1.0,
    length_spread=4.0,
    min_turn=0.0,
    max_area=None,
):
    """A random convex polygon with every inner angle >= 90 degrees and every edge >= ``min_edge``.

    Parameters
    ----------
    rng : numpy.random.Generator
        The only source of randomness.
    n_vertices : int, optional
        Number of vertices (>= 4); drawn from 4..12 when omitted.
    area : float, optional
        Target area.  The polygon is scaled up to it unless its shortest edge
        would drop below ``min_edge``, in which case the area is larger.
        When omitted the polygon is scaled so its shortest edge is
        ``min_edge``.
    min_edge : float
        Lower bound on every edge length (the ``l`` of Problem 1).
    elongation : float
        >= 1; edges roughly parallel to a random axis are drawn this many
        times longer, giving long thin polygons.
    length_spread : float
        >= 1; raw edge lengths are log-uniform in [1, length_spread].
    min_turn : float
        In [0, 1); see :func:`right_angle_turns`.  Values near 1 give nearly
        regular polygons, 0 allows nearly straight (180 degree) angles.
    max_area : float, optional
        Cap on the area, at least ``50 min_edge**2``.  A shape whose shortest
        edge forces a larger area has its edge lengths made more uniform
        (both the spread and the elongation are raised to the powers 1/2,
        1/4, ..., then 0) until it fits; with equal raw lengths the area at
        unit shortest edge is below ``(2 k)^2 / (4 pi) < 46`` for ``k <= 12``.
        ``area`` is clipped to ``max_area``.

    Returns
    -------
    (k, 2) float array, counter-clockwise.
    """
    k = int(rng.integers(4, 13)) if n_vertices is None else int(n_vertices)
    turns = right_angle_turns(rng, k, min_turn)
    start = rng.uniform(0.0, 2.0 * math.pi)
    log_lengths = rng.uniform(0.0, math.log(length_spread), k)
    axis = rng.uniform(0.0, math.pi)
    shift = rng.uniform(-100.0, 100.0, 2) * min_edge
    vertices = convex_polygon(
        turns,
        log_lengths,
        start=start,
        axis=axis,
        elongation=elongation,
        area=area,
        min_edge=min_edge,
        max_area=max_area,
    )
    return vertices + shift


def convex_polygon(turns, log_lengths, *, start=0.0, axis=0.0, elongation=1.0, area=None, min_edge=1.0, max_area=None):
    """Steps 2-3 of the module docstring: the convex polygon with exterior ``turns`` and raw edge lengths.

    ``turns`` (from :func:`turns_from_fractions`) are fractions of 90 degrees;
    the first edge points in direction ``start`` (radians).  Raw edge lengths
    are ``exp(log_lengths)``, those of edges nearly parallel to ``axis`` about
    ``elongation`` times longer.  ``area``, ``min_edge`` and ``max_area`` are
    as in :func:`random_convex_polygon`.  The first vertex is at the origin.
    """
    directions = start + 0.5 * math.pi * np.concatenate([[0.0], np.cumsum(turns[:-1])])
    stretch = np.log1p((elongation - 1.0) * np.abs(np.cos(directions - axis)) ** 4)
    if max_area is not None:
        area = None if area is None else min(area, max_area)
    for power in [0.5**i for i in range(30)] + [0.0]:
        lengths = close_polygon(directions, np.exp(power * (log_lengths + stretch)))
        vertices = polygon_from_edges(directions, lengths)
        vertices = fit_scale(vertices, area, min_edge)
        if max_area is None or signed_area(vertices) <= max_area:
            break
    return vertices


def fit_scale(vertices, area, min_edge):
    """Scale ``vertices`` about the origin to ``area`` but keep every edge >= ``min_edge``."""
    v = np.asarray(vertices, dtype=float)
    edges = np.linalg.norm(np.roll(v, -1, axis=0) - v, axis=1)
    factor = min_edge / edges.min()
    if area is not None:
        factor = max(factor, math.sqrt(area / signed_area(v)))
    # One ulp of slack: a scaled edge must not round to just below min_edge.
    return v * (factor * (1.0 + 4e-16))


__all__ = [
    "close_polygon",
    "convex_polygon",
    "fit_scale",
    "polygon_from_edges",
    "random_convex_polygon",
    "rectangle",
    "regular_polygon",
    "right_angle_turns",
    "rotate",
    "turns_from_fractions",
]
