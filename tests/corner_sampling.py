"""Placements of the two sides of a corner enumerated on a grid, independently of planar/_corner.py.

A placement splits each side (lengths by distance from the corner) into parts of ``[l, 2l]`` and keeps every
two points of different sides at least ``l`` apart (the corner excluded).  :func:`sampled_placement` tries
every split whose parts, all but the last, are multiples of ``step l`` from ``l`` to ``2l``, checking every
pair directly, with the other side's points pruned as soon as one is too close.  Finding none confirms,
without proving, that a corner refused as impossible to separate has no placement.
"""

import math

import numpy as np


def _splits(length, l, step):
    """Every split of ``length`` into parts of [l, 2l], all but the last a multiple of ``step l``: its points."""
    out, stack = [], [(0.0, ())]
    while stack:
        at, points = stack.pop()
        if l <= length - at <= 2.0 * l:
            out.append(np.array(points + (length,)))
        for part in np.arange(l, 2.0 * l + 1e-9, step * l):
            if at + part <= length - l:
                stack.append((at + part, points + (at + part,)))
    return out


def _far_enough(theta, a, points, l):
    """Whether every point of ``points`` is at least l from every point at distance ``a`` on the other side."""
    return np.all(a * a + points * points - 2.0 * math.cos(theta) * a * points >= l * l)


def sampled_placement(theta, lengths, l, step=0.125):
    """``(xs, ys)`` for the corner of ``theta`` radians and sides ``lengths``, or None if no split on the grid works."""
    for xs in _splits(lengths[0], l, step):
        stack = [(0.0, ())]
        while stack:
            at, points = stack.pop()
            if l <= lengths[1] - at <= 2.0 * l and _far_enough(theta, lengths[1], xs, l):
                return xs, np.array(points + (lengths[1],))
            for part in np.arange(l, 2.0 * l + 1e-9, step * l):
                y = at + part
                if y <= lengths[1] - l and _far_enough(theta, y, xs, l):
                    stack.append((y, points + (y,)))
    return None


def corners(rings):
    """``(theta, leaving, arriving)`` of every corner of ``rings`` (the region on their left): radians, lengths."""
    for ring in rings:
        for prev, v, nxt in zip(np.roll(ring, 1, axis=0), ring, np.roll(ring, -1, axis=0)):
            u, w = nxt - v, prev - v
            theta = math.atan2(u[0] * w[1] - u[1] * w[0], float(np.dot(u, w))) % (2.0 * math.pi)
            yield theta, float(np.linalg.norm(u)), float(np.linalg.norm(w))
