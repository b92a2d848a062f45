"""The structural guarantee of Problems 1 and 2 (``planar/guarantees.py``): every mesh is checked before it is returned.

What must hold: ``verify_planar`` accepts a returned mesh and raises :class:`~equimesh.InternalError` naming what
broke on each corruption of one; an engine that breaks Theorem 1 makes the verb raise instead of returning.
"""

import numpy as np
import pytest

import equimesh
from equimesh import InternalError
from equimesh.mesh import PlanarMesh
from equimesh.planar import insertion
from equimesh.planar.guarantees import verify_planar

SQUARE10 = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])


def _mesh():
    return equimesh.increment(SQUARE10 / 2.0, 1.0)


def _with(mesh, **changes):
    fields = {k: getattr(mesh, k) for k in ("points", "triangles", "edges", "edge_groups", "length", "n_boundary")}
    fields.update(changes)
    fields.setdefault("local_points", mesh.local_points)
    return PlanarMesh(**fields, frame=mesh.frame)


def test_verify_planar_accepts_a_returned_mesh():
    assert verify_planar(_mesh()) is not None


@pytest.mark.parametrize(
    "corrupt, message",
    [
        (
            lambda m: {"local_points": m.local_points * np.array([1.0, 0.9])},
            r"edge \(\d+, \d+\) has length .* outside \[l, 2l\]",
        ),
        (lambda m: {"triangles": m.triangles[:, ::-1]}, r"not counter-clockwise"),
        (lambda m: {"triangles": m.triangles[1:]}, r"Euler"),
        (lambda m: {"triangles": np.where(m.triangles == 0, m.n_nodes, m.triangles)}, r"outside 0\.\.\d+"),
        (lambda m: {"n_boundary": m.n_boundary - 1}, r"Euler"),
    ],
    ids=["short edge", "clockwise triangles", "missing triangle", "index out of range", "boundary count"],
)
def test_verify_planar_fires_on_a_corrupted_mesh(corrupt, message):
    """The check can fail: each corruption of a valid mesh raises InternalError naming what broke."""
    mesh = _mesh()
    with pytest.raises(InternalError, match=message):
        verify_planar(_with(mesh, **corrupt(mesh)))


def test_verify_planar_fires_on_a_degenerate_triangle():
    """A counter-clockwise triangle of sides (l, l, 2l) up to 1e-9 l is below the quality floor: InternalError."""
    mesh = _mesh()
    points = mesh.local_points.copy()
    lp = mesh.length * mesh.frame.scale
    points[:3] = [[0.0, 0.0], [2.0 * lp, 0.0], [lp, 1e-9 * lp]]
    with pytest.raises(InternalError, match=r"triangle 0 \(0, 1, 2\) has area .* below the floor 1e-08 l\^2"):
        verify_planar(_with(mesh, local_points=points, triangles=np.array([[0, 1, 2]])))


@pytest.mark.parametrize("verb", [equimesh.increment, equimesh.uniform_triangulation])
def test_a_broken_engine_is_never_returned(verb, monkeypatch):
    """An engine that moves an inserted point makes the verb raise InternalError instead of returning."""
    real = insertion.ENGINES[insertion.DEFAULT_ENGINE]

    def broken(region, l):
        out = real(region, l)
        points = out.points.copy()
        points[-1] = points[out.n_initial - 1] + 0.3 * l  # closer than l to a boundary point
        return insertion.Insertion(points, out.triangles, out.segments, out.n_initial, out.values)

    monkeypatch.setitem(insertion.ENGINES, insertion.DEFAULT_ENGINE, broken)
    with pytest.raises(InternalError):
        verb(SQUARE10, 1.0)
