"""Beyond the paper: :func:`equimesh.best_lattice_placement` (docs/decisions.md, "The lattice placement search").

The search maximises the number of edges of the kept lattice part K over the
lattice angle and offset.  What must hold: it is deterministic, it never
returns a placement worse than the default (angle 0, offset (0, 0)) in its
objective, the objective is a lower bound on the G1 count of the mesh built
with the returned placement, and it is fast enough for the surface pipeline
(the time on a ~1,000-edge mesh is printed, not asserted).
"""

import time

import invariants_uniform as inv
import numpy as np
import pytest
import shapely
import strategies_simple as ss
from hypothesis import given
from hypothesis import strategies as st

import equimesh
from equimesh import G1
from equimesh.planar.lattice import kept_vertices
from equimesh.planar.placement import lattice_edge_count
from equimesh.planar.polygon import as_polygon
from equimesh.testing.generators import rectangle, regular_polygon
from equimesh.tolerance import at_least

#: Polygons of the property tests: the search costs ~250 lattice evaluations.
MAX_AREA = 400.0


def kept_by_every_vertex(poly, l, angle, offset, clearance):
    """The scorer before the row-by-row clearance (the oracle): every lattice vertex tested against the boundary with shapely."""
    ii, _, pts, kept = kept_vertices(poly, l, angle, offset, clearance)
    shape = poly.region
    inside = shapely.contains_xy(shape, pts[:, 0], pts[:, 1])
    far = np.zeros(len(pts), dtype=bool)
    far[inside] = at_least(
        shapely.distance(shapely.points(pts[inside]), shape.exterior), clearance * poly.local_length(l)
    )
    return far.reshape(ii.shape), kept


fractions = st.tuples(st.floats(0.0, 1.0), st.floats(0.0, 1.0))


@given(
    ss.cases(MAX_AREA),
    st.one_of(st.sampled_from([0.0, 30.0]), st.floats(0.0, 60.0)),
    fractions,
    st.sampled_from([1.0, 1.5, 2.0]),
)
def test_band_scan_keeps_the_same_vertices_as_testing_every_vertex(case, angle, frac, clearance):
    """The placement's scorer (:mod:`equimesh.planar.clearance`) keeps exactly the vertices the per-vertex test keeps."""
    vertices, l = case
    poly = as_polygon(vertices, l)
    offset = np.asarray(frac) @ equimesh.planar.lattice.lattice_basis(l, angle)
    old, new = kept_by_every_vertex(poly, l, angle, offset, clearance)
    assert np.array_equal(old, new)


@pytest.mark.parametrize("clearance", [1.0, 2.0, 3.0])
@pytest.mark.parametrize(
    "vertices",
    [rectangle(10.0, 8.0 * np.sqrt(3.0) / 2.0), rectangle(12.0, 12.0), regular_polygon(6, 6.0)],
    ids=["lattice rectangle", "square", "hexagon"],
)
def test_band_scan_on_vertices_exactly_at_clearance(vertices, clearance):
    """Boundaries along lattice rows: many vertices exactly ``clearance * l`` away, decided as before."""
    poly = as_polygon(vertices, 1.0)
    for angle in (0.0, 60.0 * 0.25, 30.0):
        old, new = kept_by_every_vertex(poly, 1.0, angle, (0.0, 0.0), clearance)
        assert np.array_equal(old, new)


def lattice_part_edges(mesh):
    """Edges of the lattice part K of a mesh (edges of its all-G1 triangles)."""
    tri = mesh.triangles[inv.lattice_mask(mesh)]
    if not len(tri):
        return 0
    return len(np.unique(np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1), axis=0))


@given(ss.cases(MAX_AREA))
def test_placement_deterministic_and_never_worse(case):
    """Same input, same placement; its objective is at least the default placement's, which it reports exactly."""
    vertices, l = case
    a = equimesh.best_lattice_placement(vertices, l)
    b = equimesh.best_lattice_placement(vertices.copy(), l)
    assert a == b
    assert a.lattice_edges >= a.default_lattice_edges
    assert a.gain >= 0.0
    poly = as_polygon(vertices)
    assert a.default_lattice_edges == lattice_edge_count(poly, l, 0.0, (0.0, 0.0))
    assert a.lattice_edges == lattice_edge_count(poly, l, a.angle, a.offset)
    assert 0.0 <= a.angle < 60.0


@given(ss.cases(MAX_AREA))
def test_placement_objective_is_a_lower_bound_on_g1(case):
    """The objective (edges of K) equals the edges of K in the mesh and is at most its G1 count; the mesh is valid."""
    vertices, l = case
    p = equimesh.best_lattice_placement(vertices, l)
    mesh = equimesh.uniform_triangulation(vertices, l, angle=p.angle, offset=p.offset)
    assert p.lattice_edges == lattice_part_edges(mesh)
    assert p.lattice_edges <= int(np.count_nonzero(mesh.edge_groups == G1))
    inv.check_theorem3(mesh, l)
    inv.check_triangulation(mesh, vertices, l)


def test_placement_runtime_on_a_1000_edge_mesh(record_property):
    """Runtime of the search on a polygon whose mesh has ~1,000 edges (printed, not asserted)."""
    vertices = rectangle(18.0, 18.0)
    start = time.perf_counter()
    p = equimesh.best_lattice_placement(vertices, 1.0)
    seconds = time.perf_counter() - start
    default = equimesh.uniform_triangulation(vertices, 1.0)
    best = equimesh.uniform_triangulation(vertices, 1.0, angle=p.angle, offset=p.offset)
    g1_default, g1_best = (int(np.count_nonzero(m.edge_groups == G1)) for m in (default, best))
    record_property("placement_seconds", seconds)
    print(
        f"best_lattice_placement on an 18x18 square ({len(default.edges)} mesh edges): {seconds:.3f} s, "
        f"{p.evaluations} placements, G1 {g1_default} -> {g1_best} (gain {p.gain:+.1%} in lattice edges)"
    )
    assert 800 <= len(default.edges) <= 1300
    assert g1_best >= p.lattice_edges >= p.default_lattice_edges


def test_gain_when_no_lattice_triangle_fits():
    """A polygon too small for any lattice triangle: the reported gain is 0, not -100%."""
    p = equimesh.best_lattice_placement(rectangle(1.5, 1.5), 1.0)
    assert p.lattice_edges == p.default_lattice_edges == 0
    assert p.gain == 0.0


def test_search_builds_the_region_once(monkeypatch):
    """Every evaluation of a search measures against the same shapely region (``Polygon.region``, built once)."""
    built = []
    monkeypatch.setattr(shapely, "Polygon", lambda *a: built.append(a) or shapely.geometry.Polygon(*a))
    equimesh.best_lattice_placement(regular_polygon(6, 6.0), 1.0, n_angles=2, n_offsets=2, refine=1)
    assert len(built) == 1
