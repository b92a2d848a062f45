"""Bezier patches for Section 4, shared by the tests and ``experiments/bounded_sweep.py``."""

import numpy as np

from ..surface.charts.bezier import BezierSurface


def dome(size=60.0, rise=12.0, seed=None, jitter=0.0):
    """A doubly curved bicubic patch over a ``size x size`` square (mild curvature).

    The control heights are ``0.9 rise (16 / 9) 4 i (1 - i) 4 j (1 - j)`` at
    ``(i, j)`` in ``{0, 1/3, 2/3, 1}^2`` (rise 0 is a flat square); with a
    ``seed``, ``jitter`` times standard normal draws of
    ``numpy.random.default_rng(seed)`` are added to the 16 heights.
    """
    i, j = np.meshgrid(np.arange(4) / 3, np.arange(4) / 3, indexing="ij")
    z = rise * 16 / 9 * (4 * i * (1 - i)) * (4 * j * (1 - j)) * 0.9
    net = np.stack([size * i, size * j, z], axis=-1)
    if seed is not None:
        rng = np.random.default_rng(seed)
        net[..., 2] += jitter * rng.standard_normal(z.shape)
    return BezierSurface(net)
