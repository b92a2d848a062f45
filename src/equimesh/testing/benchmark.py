"""The benchmark set: five surfaces, each with its target length l, on which any surface mesher can be compared.

Every surface is an 80 x 80 bicubic :class:`~equimesh.BezierSurface` (a chart:
``domain``, ``evaluate(u, v)``, ``derivatives(u, v)``), meshed at l = 5 =
span / 16 (:data:`BENCHMARK`).  A *method* is a function
``method(surface, l) -> (points, triangles)``: ``points`` (N, 3) finite floats,
``triangles`` (M, 3) whole numbers indexing them, at least one triangle
(:func:`triangle_mesh` checks a method's answer).  Every method's mesh is
measured by the one function :func:`equimesh.metrics.comparison_figures`;
``experiments/compare_peers.py`` runs the methods of its table, and
``--method package.module:function`` (or an ``equimesh.methods`` entry point)
adds one.  The protocol: docs/benchmark.md.
"""

import importlib
from dataclasses import dataclass
from importlib import metadata

import numpy as np

from ..errors import InvalidMethodError
from ..surface.charts.bezier import BezierSurface

#: Side of every benchmark surface's square plan.
SPAN = 80.0
#: The target length of every benchmark surface: span / 16.
LENGTH = SPAN / 16
#: The entry-point group through which an installed package adds its methods (name = the method's name).
ENTRY_POINTS = "equimesh.methods"


@dataclass(frozen=True)
class BenchmarkSurface:
    """One surface of the benchmark set: its name, its chart, its target length l and what it tests."""

    name: str
    surface: BezierSurface
    length: float
    about: str


def _net(z):
    """A bicubic Bezier net over [0, SPAN]^2 with the (4, 4) heights ``z`` (first axis along u = x)."""
    t = np.linspace(0.0, SPAN, 4)
    x, y = np.meshgrid(t, t, indexing="ij")
    return BezierSurface(np.stack([x, y, np.asarray(z, dtype=float)], axis=-1))


def _reference_dome():
    """``experiments/surfaces/reference_dome.json``'s net, its numbers as written there (thirds to 10 decimals)."""
    t = np.array([0.0, 26.6666666667, 53.3333333333, 80.0])
    x, y = np.meshgrid(t, t, indexing="ij")
    z = np.zeros((4, 4))
    z[1:3, 1:3] = 46.6666666667
    return BezierSurface(np.stack([x, y, z], axis=-1))


def _benchmark():
    rise = np.zeros((4, 4))
    rise[1:3, 1:3] = 1.0
    w = np.array([0.0, 1.0, -1.0, 0.0])
    t = np.linspace(-1.0, 1.0, 4)
    surfaces = [
        ("reference dome", _reference_dome(), "the surface of Table 1: a dome of rise 35 on a plane boundary"),
        ("steep dome", _net(80.0 * rise), "a dome of rise 60: steep sides, members stretched most"),
        (
            "hyperbolic paraboloid",
            _net(20.0 * np.outer(t, t)),
            "z = 20 (2x/80 - 1)(2y/80 - 1), corners at +-20: negative curvature",
        ),
        ("wave", _net(15.0 * w[:, None] + 6.0 * w[None, :]), "a wave along x and along y: curvature of both signs"),
        ("barrel", _net(np.tile([0.0, 26.0, 26.0, 0.0], (4, 1))), "a cylinder over x: developable"),
    ]
    return {name: BenchmarkSurface(name, surface, LENGTH, about) for name, surface, about in surfaces}


#: The benchmark set by name, in table order.
BENCHMARK = _benchmark()


def parameter_grid(surface, l, samples=64):
    """A method by the protocol alone, the example of docs/benchmark.md: the parameter rectangle in cells.

    The chart's ``domain`` is cut into ``n_u x n_v`` cells, each split into two
    triangles, ``n_u`` the length of the surface's middle curve along u over l,
    rounded (measured on ``samples`` chords), and ``n_v`` likewise.  Not one of
    the compared methods: ``--method equimesh.testing.benchmark:parameter_grid``
    adds it.
    """
    domain = surface.domain
    t = np.linspace(0.0, 1.0, samples + 1)
    us, vs = domain.u[0] + t * (domain.u[1] - domain.u[0]), domain.v[0] + t * (domain.v[1] - domain.v[0])

    def cells(u, v):
        chords = np.diff(surface.evaluate(u, v), axis=0)
        return max(1, round(float(np.linalg.norm(chords, axis=1).sum()) / l))

    n_u, n_v = cells(us, np.full_like(us, np.mean(domain.v))), cells(np.full_like(vs, np.mean(domain.u)), vs)
    u, v = np.meshgrid(np.linspace(*domain.u, n_u + 1), np.linspace(*domain.v, n_v + 1), indexing="ij")
    k = np.arange((n_u + 1) * (n_v + 1)).reshape(n_u + 1, n_v + 1)[:-1, :-1].ravel()
    lower, upper = np.stack([k, k + n_v + 1, k + 1], axis=1), np.stack([k + 1, k + n_v + 1, k + n_v + 2], axis=1)
    return surface.evaluate(u.ravel(), v.ravel()), np.concatenate([lower, upper])


def triangle_mesh(result, method):
    """``(points, triangles)`` of a method's answer as arrays, or :class:`InvalidMethodError` saying what is wrong.

    ``result`` must be a pair: points (N, 3) of finite numbers and triangles
    (M >= 1, 3) of whole numbers in ``[0, N)``; ``method`` names the method in
    the message.
    """
    if not (isinstance(result, (tuple, list)) and len(result) == 2):
        raise InvalidMethodError(
            f"method {method} returned {type(result).__name__}, not a triangle mesh (points, triangles)"
        )
    try:
        points = np.asarray(result[0], dtype=float)
        triangles = np.asarray(result[1])
    except (TypeError, ValueError):
        raise InvalidMethodError(
            f"method {method} returned points or triangles that are not arrays of numbers"
        ) from None
    if points.ndim != 2 or points.shape[1] != 3 or not np.isfinite(points).all():
        raise InvalidMethodError(f"method {method} returned points of shape {points.shape}, not (N, 3) finite numbers")
    if triangles.ndim != 2 or triangles.shape[1] != 3 or len(triangles) == 0:
        raise InvalidMethodError(f"method {method} returned triangles of shape {triangles.shape}, not (M, 3), M >= 1")
    whole = np.issubdtype(triangles.dtype, np.integer) or (
        np.issubdtype(triangles.dtype, np.floating) and np.array_equal(triangles, np.round(triangles))
    )
    if not whole:
        raise InvalidMethodError(f"method {method} returned triangles that are not whole numbers")
    triangles = triangles.astype(np.int64)
    if triangles.min() < 0 or triangles.max() >= len(points):
        raise InvalidMethodError(f"method {method} returned triangles with node indices outside 0..{len(points) - 1}")
    return points, triangles


def load_method(spec):
    """The function ``package.module:function`` names (``function`` may be dotted: ``module:Class.method``).

    Raises
    ------
    InvalidMethodError
        ``spec`` is not of that form, the module cannot be imported, or it has no such callable.
    """
    module_name, _, attribute = str(spec).partition(":")
    if not module_name or not attribute:
        raise InvalidMethodError(f"method {spec!r}: expected package.module:function")
    try:
        found = importlib.import_module(module_name)
    except Exception as exc:  # any failure of the researcher's module: ImportError, or an error while importing
        raise InvalidMethodError(f"method {spec}: cannot import {module_name} ({type(exc).__name__}: {exc})") from None
    for part in attribute.split("."):
        found = getattr(found, part, None)
        if found is None:
            raise InvalidMethodError(f"method {spec}: {module_name} has no {attribute}")
    if not callable(found):
        raise InvalidMethodError(f"method {spec}: {attribute} is a {type(found).__name__}, not a function")
    return found


def entry_point_methods():
    """``{name: function}`` of every installed :data:`ENTRY_POINTS` entry point, by name."""
    found = {}
    for point in sorted(metadata.entry_points(group=ENTRY_POINTS), key=lambda p: p.name):
        found[point.name] = load_method(point.value)
    return found
