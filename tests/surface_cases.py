"""Surfaces that break the pipeline's assumptions, and :func:`refuse`, the check of a one-line refusal by
``mesh_surface``."""

import numpy as np
import pytest

import equimesh
from equimesh.surface.charts.bezier import BezierSurface


def plane_patch(corner_u=(30.0, 0.0), corner_v=(0.0, 30.0)):
    """The flat parallelogram spanned by two vectors (a bilinear net)."""
    net = np.zeros((2, 2, 3))
    net[1, :, :2] += corner_u
    net[:, 1, :2] += corner_v
    return BezierSurface(net)


def folding_net():
    """A 4 x 2 net whose x-row goes 0, 3, -1, 2: x_u changes sign twice, the patch folds over itself."""
    net = np.zeros((4, 2, 3))
    net[..., 0] = 10.0 * np.array([0.0, 3.0, -1.0, 2.0])[:, None]
    net[..., 1] = np.array([0.0, 10.0])[None, :]
    return BezierSurface(net)


def waist_net():
    """A flat patch 60 long, 20 wide at its ends and only 4 wide in the middle (v = 0 and v = 1 bulge in)."""
    net = np.zeros((3, 2, 3))
    net[..., 0] = np.array([0.0, 30.0, 60.0])[:, None]
    net[:, 0, 1] = [0.0, 16.0, 0.0]
    net[:, 1, 1] = [20.0, 4.0, 20.0]
    return BezierSurface(net)


class Wrapped:
    """A surface that returns NaN (points and derivatives) where ``bad(u, v)`` holds."""

    def __init__(self, surface, bad):
        self.surface, self.bad = surface, bad

    def evaluate(self, u, v):
        p = np.array(self.surface.evaluate(u, v), dtype=float)
        p[self.bad(np.asarray(u), np.asarray(v))] = np.nan
        return p

    def derivatives(self, u, v):
        return self.surface.derivatives(u, v)


class Line:
    """X(u, v) = f(u + v): X_u and X_v are parallel everywhere (a curve, not a surface)."""

    def evaluate(self, u, v):
        s = np.asarray(u, dtype=float) + np.asarray(v, dtype=float)
        return np.stack([30 * s, 10 * s**2, np.zeros_like(s)], axis=-1)

    def derivatives(self, u, v):
        s = np.asarray(u, dtype=float) + np.asarray(v, dtype=float)
        d = np.stack([np.full_like(s, 30.0), 20 * s, np.zeros_like(s)], axis=-1)
        return d, d


def refuse(error, surface, l, match, **kwargs):
    """mesh_surface refuses with ``error`` and a one-line message matching ``match``; returns the message."""
    with pytest.raises(error, match=match) as info:
        equimesh.mesh_surface(surface, l, **kwargs)
    message = str(info.value)
    assert "\n" not in message and "np.float" not in message
    return message
