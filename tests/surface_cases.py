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


def vault_nurbs(weight=1.0, u_range=1.0):
    """A biquadratic NURBS vault over 30 x 20 as JSON: weights alternating 1 and ``weight``, u in [0, u_range]."""
    i, j = np.meshgrid(np.arange(5), np.arange(4), indexing="ij")
    z = np.array([0.0, 6**0.5, 12**0.5, 6**0.5, 0.0])[:, None] * np.array([0.0, 1.0, 1.0, 0.0])[None, :]
    knots_u = np.array([0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0]) * u_range
    return {
        "type": "nurbs",
        "degree": [2, 2],
        "knots_u": knots_u.tolist(),
        "knots_v": [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        "control_points": np.stack([7.5 * i, 20.0 / 3.0 * j, z], axis=-1).tolist(),
        "weights": np.where((i + j) % 2, weight, 1.0).tolist(),
    }


def vault(weight=1.0, u_range=1.0):
    """:func:`vault_nurbs` as a surface."""
    d = vault_nurbs(weight, u_range)
    return equimesh.NurbsSurface(d["degree"], d["knots_u"], d["knots_v"], d["control_points"], d["weights"])


#: A random steep Bezier net whose flattened side u = 0 bends within a few l: three of its nodes made a flat triangle.
STEEP_NET = [
    [
        [-0.10361425912855037, -0.29108474260140316, -20.199796787933302],
        [0.29420289071182265, 7.971798070756263, -5.91854126458961],
        [-0.8896646445229691, 14.40269353532838, 7.7065778776816565],
        [1.2046540123352727, 23.373399835919724, 15.507187604353742],
        [1.0294276862060254, 32.41702547306417, -10.582913586170221],
    ],
    [
        [4.460680990324418, 0.2031072819810376, 15.319036976179692],
        [5.681434933037146, 7.458362668318485, 9.088883118296547],
        [5.772030488112681, 16.550441814022477, 12.282420029084872],
        [5.340729469605599, 23.759542558118664, -20.95002400765137],
        [5.088725075793696, 31.248375653457824, -19.56923598738408],
    ],
    [
        [11.280910674248059, 0.028256429163804157, 20.6297078977796],
        [10.08592836044392, 8.054284411979438, -21.89793256347727],
        [11.067784002217282, 14.871378435650259, 7.142457535991902],
        [12.21606992356526, 22.8648309371243, 9.919505052371871],
        [11.130495282031312, 32.18599380975528, 21.404107805111526],
    ],
    [
        [16.796253833400506, -1.0316197046261966, -23.049506240740875],
        [15.617039660327578, 7.008063570681662, -0.7321249534835417],
        [16.238579212737253, 14.764391073811133, -4.843324992489421],
        [16.90726351825199, 22.828575354695676, 7.61239063930606],
        [15.859571720679604, 30.578292586529138, -3.964728339066877],
    ],
    [
        [22.529575339647703, -0.5159702847435046, 24.025108179265356],
        [21.337394523938542, 9.345901306354527, -23.448679715525035],
        [22.876462656301175, 14.848667212164571, -14.966677031809938],
        [22.332590124563467, 22.745913433079426, 16.981484537315165],
        [21.715432491432328, 30.737753293100226, 4.630383118115315],
    ],
]
