"""The structural guarantee of Problems 1 and 2 (``planar/guarantees.py``): every mesh is checked before it is returned.

What must hold: ``verify_planar`` accepts a returned mesh and raises :class:`~equimesh.InternalError` naming what
broke on each corruption of one; an engine that breaks Theorem 1 makes the verb raise instead of returning; every
angle of Problem 2 is at least ``min(30, arccos(c / 2l))`` for the longest boundary part c.
"""

import numpy as np
import pytest
import strategies_simple as ss
from hypothesis import given, settings
from hypothesis import strategies as st

import equimesh
from equimesh import InternalError
from equimesh.mesh import PlanarMesh
from equimesh.planar import guarantees, insertion
from equimesh.planar.guarantees import ANGLE_ROUNDING, angle_bound, verify_planar

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


def _smallest_angle(mesh):
    p = mesh.points[mesh.triangles]
    angles = []
    for k in range(3):
        u, v = p[:, (k + 1) % 3] - p[:, k], p[:, (k + 2) % 3] - p[:, k]
        angles.append(np.degrees(np.arctan2(np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]), np.sum(u * v, axis=1))))
    return float(np.min(angles))


def _longest_boundary_part(mesh):
    sizes = mesh.info.get("boundary_rings", (mesh.n_boundary,))
    ends = np.cumsum(sizes)
    return max(
        float(np.max(np.linalg.norm(np.roll(mesh.points[e - s : e], -1, axis=0) - mesh.points[e - s : e], axis=1)))
        for e, s in zip(ends, sizes)
    )


@settings(max_examples=25, deadline=None)
@given(case=ss.cases(200.0), spacing=st.sampled_from([1.0, 1.2, 1.5, 1.7]))
def test_problem2_angles_are_at_least_30_degrees_when_no_part_exceeds_sqrt3_l(case, spacing):
    """Chew's bound: a triangle whose circumcentre its vertices see has circumradius below l and edges at least l,
    so its smallest angle is at least 30 degrees; one whose circumcentre a constraint of length c hides lies in the
    cap c cuts off, smallest angle at least arccos(c / 2l).  With parts up to sqrt(3) l both are 30 degrees, but at a
    sharp corner, where Step 2 staggers parts of 2l."""
    vertices, l = case
    mesh = equimesh.uniform_triangulation(vertices, l, boundary_spacing=spacing)
    bound = angle_bound(_longest_boundary_part(mesh) / l)
    assert _smallest_angle(mesh) >= bound - ANGLE_ROUNDING
    if _longest_boundary_part(mesh) <= np.sqrt(3.0) * l:
        assert _smallest_angle(mesh) >= 30.0 - ANGLE_ROUNDING


def test_angle_bound_by_hand():
    assert angle_bound(1.0) == 30.0 and angle_bound(np.sqrt(3.0)) == pytest.approx(30.0)
    assert angle_bound(1.8) == pytest.approx(np.degrees(np.arccos(0.9))) and angle_bound(2.0) == 0.0


def test_verify_planar_fires_on_an_angle_below_the_bound(monkeypatch):
    """The angle check can fail: with a bound no mesh meets (above 60 degrees) every mesh is refused."""
    monkeypatch.setattr(guarantees, "angle_bound", lambda longest: 61.0)
    with pytest.raises(InternalError, match=r"has an angle of .* below the 61"):
        verify_planar(_mesh())
