"""Triangle meshes in (Section 4 with the user's mesh as the auxiliary triangulation): reading, checks, meshing.

What must hold: every output node lies on a triangle of the input mesh (to
1e-9 l), every member of the planar triangulation is in [l, 2l] (Theorem 3),
an opening of the input stays open, and every malformed mesh is refused in
one line (library: InvalidSurfaceError; command line: exit 2, nothing written).
"""

import importlib.util
import re

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from refusals import assert_one_line
from repository import SURFACES
from triangle_meshes import assert_on_input_surface, bad_meshes, roof

from equimesh import REL_TOL, EquimeshError, InvalidSurfaceError, TriangulatedSurface, mesh_surface
from equimesh.io import load_surface
from equimesh.mesh import half_edges
from equimesh.surface import pipeline
from equimesh.surface.charts.mesh_chart import (
    MeshChart,
)
from equimesh.surface.optimize import optimize_uv
from equimesh.testing.meshes import roof_mesh, wedge_mesh

L = 1.5


EXAMPLE = SURFACES / "roof_mesh.obj"


OPENING = (8.0, 12.0, 6.0, 10.0)  # x0, x1, y0, y1 of the opening of ROOF


@pytest.fixture(scope="module")
def roof_meshes():
    surface = TriangulatedSurface(*roof())
    return surface, {opt: mesh_surface(surface, L, optimize=opt) for opt in ("none", "bounded")}


def assert_opening_kept(mesh):
    """No node and no triangle inside the opening (the vault is a height field over x, y)."""
    x0, x1, y0, y1 = OPENING
    xy = mesh.points[:, :2]
    strictly = (xy[:, 0] > x0 + 1e-9) & (xy[:, 0] < x1 - 1e-9) & (xy[:, 1] > y0 + 1e-9) & (xy[:, 1] < y1 - 1e-9)
    assert not strictly.any()
    centroid = mesh.points[mesh.triangles].mean(axis=1)[:, :2]
    assert not np.any((centroid[:, 0] > x0) & (centroid[:, 0] < x1) & (centroid[:, 1] > y0) & (centroid[:, 1] < y1))


# ------------------------------------------------------------------ meshing


@pytest.mark.parametrize("optimize", ["none", "bounded"])
def test_roof_with_opening(roof_meshes, optimize):
    """Nodes on the input triangles, planar members in [l, 2l], the opening kept, its boundary nodes on its rim."""
    surface, meshes = roof_meshes
    mesh = meshes[optimize]
    assert_on_input_surface(mesh, surface, L)
    plane = mesh.stages.plane
    ratio = plane.edge_lengths() / L
    assert ratio.min() >= 1 - REL_TOL and ratio.max() <= 2 * (1 + REL_TOL)
    assert len(plane.info["boundary_rings"]) == 2  # the outer boundary and the opening
    assert_opening_kept(mesh)
    # The opening's boundary nodes lie on its rim, the outer ones on the outer rim.
    outer, hole = plane.info["boundary_rings"]
    rim = mesh.points[outer : outer + hole, :2]
    x0, x1, y0, y1 = OPENING
    on_rim = (
        np.isclose(rim[:, 0], x0) | np.isclose(rim[:, 0], x1) | np.isclose(rim[:, 1], y0) | np.isclose(rim[:, 1], y1)
    )
    assert on_rim.all()
    edge = mesh.points[:outer, :2]
    assert np.all(
        np.isclose(edge[:, 0], 0) | np.isclose(edge[:, 0], 20) | np.isclose(edge[:, 1], 0) | np.isclose(edge[:, 1], 14)
    )
    if optimize == "bounded":
        members = mesh.edge_lengths() / L
        assert members.min() >= 1 - REL_TOL and members.max() <= 2 * (1 + REL_TOL)


def assert_boundary_slid_along_the_loops(mesh):
    """Boundary nodes on their flattened loops (to 1e-12 of its length), corners where they were, some moved."""
    outline, plane = mesh.stages.outline, mesh.stages.plane
    start, moved = 0, 0
    for loop, corners, count in zip(outline.loops, outline.corners, plane.info["boundary_rings"]):
        nodes = np.arange(start, start + count)
        start += count
        length = loop.length
        assert np.all(
            shapely.distance(shapely.LinearRing(loop.points), shapely.points(mesh.uv[nodes])) <= 1e-12 * length
        )
        before = mesh.stages.remapped_uv[nodes]
        for corner in loop.at(corners):
            at = np.linalg.norm(before - corner, axis=1) <= REL_TOL * length
            assert at.sum() == 1 and np.array_equal(mesh.uv[nodes[at]], before[at])
        moved += int(np.count_nonzero(np.any(mesh.uv[nodes] != before, axis=1)))
    assert moved > 0


@pytest.mark.parametrize(
    "case, l",
    [
        ("steep vault", 1.2),  # 20 x 14 rising 8 (docs/decisions.md, "Boundary nodes slide under bounded")
        ("warped wedge", 1.0),  # refused with the boundary fixed: 1 of 588 members a hair over 2l
    ],
)
def test_bounded_slides_the_boundary_along_the_loops(case, l):
    """Under "bounded" every boundary node but the corners slides along its loop; every member in [l, 2l]."""
    v, t = roof_mesh(20.0, 14.0, (20, 14), 8.0) if case == "steep vault" else wedge_mesh()
    surface = TriangulatedSurface(v, t)
    mesh = mesh_surface(surface, l, optimize="bounded")
    members = mesh.edge_lengths() / l
    assert members.min() >= 1 - REL_TOL and members.max() <= 2 * (1 + REL_TOL)
    assert_on_input_surface(mesh, surface, l)
    assert_boundary_slid_along_the_loops(mesh)


def test_roof_boundary_slides_under_bounded(roof_meshes):
    assert_boundary_slid_along_the_loops(roof_meshes[1]["bounded"])


def test_infeasible_mesh_refusal_suggests_what_refines_a_mesh():
    """The refusal names the input mesh (not an auxiliary grid) and the objective that always meshes."""
    surface = TriangulatedSurface(*roof_mesh(10.0, 10.0, (2, 2), 0.0))
    chart = MeshChart(surface, surface.vertices[:, :2])
    uv, edges = np.array([[0.0, 0.0], [0.5, 0.0], [0.5, 0.5]]), np.array([[0, 1], [1, 2], [0, 2]])
    with pytest.raises(InvalidSurfaceError) as info:
        optimize_uv(chart, uv, edges, np.zeros(3), 1.0, fixed=[0, 1], objective="bounded")
    assert_one_line(str(info.value))
    assert re.search(
        r"members outside \[l, 2l\].*use a smaller l, a finer input mesh, or optimize='paper'", str(info.value)
    )


@settings(max_examples=8, deadline=None)
@given(
    rise=st.floats(0.0, 4.0),
    corner=st.tuples(st.integers(3, 7), st.integers(3, 5)),
    size=st.tuples(st.integers(1, 2), st.integers(1, 2)),
    l=st.floats(1.2, 1.8),
)
def test_generated_vaults_with_an_opening(rise, corner, size, l):
    """Vaults of any rise with an opening anywhere at least 3 cells (6) from the border, sides at least 2 > l: every
    invariant."""
    (i, j), (a, b) = corner, size
    v, t = roof_mesh(24.0, 16.0, (12, 8), rise, opening=(i, i + a, j, j + b))
    surface = TriangulatedSurface(v, t)
    mesh = mesh_surface(surface, l, optimize="none", placement="default")
    assert_on_input_surface(mesh, surface, l)
    ratio = mesh.stages.plane.edge_lengths() / l
    assert ratio.min() >= 1 - REL_TOL and ratio.max() <= 2 * (1 + REL_TOL)
    x0, x1, y0, y1 = 2.0 * i, 2.0 * (i + a), 2.0 * j, 2.0 * (j + b)
    centroid = mesh.points[mesh.triangles].mean(axis=1)[:, :2]
    assert not np.any((centroid[:, 0] > x0) & (centroid[:, 0] < x1) & (centroid[:, 1] > y0) & (centroid[:, 1] < y1))


def test_meshing_is_deterministic(roof_meshes):
    surface, meshes = roof_meshes
    again = mesh_surface(TriangulatedSurface(*roof()), L, optimize="none")
    assert np.array_equal(again.points, meshes["none"].points) and np.array_equal(
        again.triangles, meshes["none"].triangles
    )


def test_corners_of_the_outline_are_kept(roof_meshes):
    """The roof's four corners (90 degrees on the flattened mesh, above CORNER_TURN) are vertices of the outer ring."""
    surface, meshes = roof_meshes
    outline = meshes["none"].stages.outline
    flat = meshes["none"].stages.flattening.points
    corner_vertices = [i for i, p in enumerate(surface.vertices) if p[0] in (0.0, 20.0) and p[1] in (0.0, 14.0)]
    ring = {tuple(p) for p in outline.vertices}
    assert all(tuple(flat[i]) in ring for i in corner_vertices)
    # The opening's four corners too.
    hole = {tuple(p) for p in outline.holes[0]}
    opening = [i for i, p in enumerate(surface.vertices) if p[0] in (8.0, 12.0) and p[1] in (6.0, 10.0)]
    assert all(tuple(flat[i]) in hole for i in opening)


def test_example_roof_file_is_what_its_script_writes(tmp_path):
    spec = importlib.util.spec_from_file_location("make_mesh_roof", EXAMPLE.with_name("make_mesh_roof.py"))
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    script.write_obj(tmp_path / "roof.obj", *script.roof())
    assert (tmp_path / "roof.obj").read_bytes() == EXAMPLE.read_bytes()


def test_example_roof_with_a_skylight():
    """experiments/surfaces/roof_mesh.obj (a Triangle mesh of a vault with a round opening): the opening stays open."""
    surface = load_surface(EXAMPLE)
    assert [len(loop) for loop in surface.loops] == [108, 32]
    mesh = mesh_surface(surface, 2.5, optimize="none")
    assert_on_input_surface(mesh, surface, 2.5)
    ratio = mesh.stages.plane.edge_lengths() / 2.5
    assert ratio.min() >= 1 - REL_TOL and ratio.max() <= 2 * (1 + REL_TOL)
    # The rim is a 32-gon of radius 3 about (12, 10) in plan: nothing strictly inside its inscribed circle.
    inner = 3.0 * np.cos(np.pi / 32)
    centre = np.array([12.0, 10.0])
    assert np.linalg.norm(mesh.points[:, :2] - centre, axis=1).min() >= inner - 1e-9
    centroids = mesh.points[mesh.triangles].mean(axis=1)[:, :2]
    assert np.linalg.norm(centroids - centre, axis=1).min() > inner


@pytest.mark.parametrize(
    "opening, l, match",
    [
        (
            (1, 3, 3, 5),
            2.5,
            r"hole 0 is 2\.118.* from the boundary .*\(hole 0 \(the opening through \(2, 6, 0\.903808\)\)\)",
        ),
        (
            (4, 6, 3, 5),
            9.0,
            r"hole 0 \(the opening through \(8, 6, 2\.78163\)\) of the mesh has corners at \(12, 6, 2\.78163\) "
            r"and \(8, 6, 2\.78163\) only 3\.8768 apart on the flattened surface, closer than l = 9; use l <= 3\.876$",
        ),
        (
            (4, 5, 3, 4),
            2.5,
            r"hole 0 .* has corners at \(8, 8, 2\.78163\) and \(10, 8, 2\.92478\) only 1\.95073 apart .* use l <= "
            r"1\.95$",
        ),
        ((3, 4, 4, 5), 2.0, r"hole 0 .* has corners at .* only 1\.99.* apart .* closer than l = 2; use l <= 1\.99"),
        (
            (4, 6, 3, 5),
            30.0,
            r"the outer boundary of the mesh has corners at \(0, 14, 0\) and \(0, 0, 0\) only 14\.1196 apart",
        ),
    ],
)
def test_openings_and_boundaries_too_small_for_l(opening, l, match):
    """Problem 2's refusals and the rings' own, in one line, the opening located in space; the suggested l is
    accepted."""
    surface = TriangulatedSurface(*roof_mesh(20.0, 14.0, (10, 7), 3.0, opening=opening))
    with pytest.raises(InvalidSurfaceError, match=match) as info:
        mesh_surface(surface, l, optimize="none")
    assert_one_line(str(info.value))
    if "corners at" in str(info.value) and "outer" not in str(info.value):
        suggested = float(str(info.value).rsplit("use l <= ", 1)[1])
        mesh_surface(surface, suggested, optimize="none")


@pytest.mark.parametrize(
    "l, match",
    [
        (5.5, r"too small for l = 5\.5: its rim, 18\.389.* gives fewer than 3 parts"),
        (7.0, r"too small for l = 7: its rim is 18\.389"),
    ],
)
def test_round_opening_too_small_for_l(l, match):
    """The example's 32-gon skylight (no corner: one chain) is refused when no ring of 3 parts of at least l fits."""
    with pytest.raises(
        InvalidSurfaceError, match=r"hole 0 \(the opening through \(15, 10, 4\)\) of the mesh is " + match
    ):
        mesh_surface(load_surface(EXAMPLE), l, optimize="none")


def test_triangle_count_limit(monkeypatch):
    monkeypatch.setattr(pipeline, "MAX_GRID_CELLS", 60)
    with pytest.raises(EquimeshError, match="the triangle mesh has 132 triangles, more than the limit of 120"):
        mesh_surface(TriangulatedSurface(*roof()), L)


# ------------------------------------------------------------------ the mesh as given


def test_coincident_vertices_are_merged_and_orientation_made_consistent():
    """STL-like input (every triangle with its own vertices, random orientations) gives the indexed mesh."""
    v, t = roof()
    reference = TriangulatedSurface(v, t)
    rng = np.random.default_rng(1)
    soup = v[t].reshape(-1, 3)
    triangles = np.arange(len(soup)).reshape(-1, 3)
    flip = rng.random(len(triangles)) < 0.5
    triangles[flip] = triangles[flip][:, ::-1]
    got = TriangulatedSurface(soup, triangles)
    assert len(got.vertices) == len(reference.vertices) and len(got.triangles) == len(reference.triangles)
    # Each inner edge used once in each direction.
    he = half_edges(got.triangles)
    assert len({tuple(e) for e in he.tolist()}) == len(he)
    # Same triangles as the reference, up to one global orientation.
    key = lambda s: {tuple(np.round(s.vertices[tri], 12).ravel()) for tri in s.triangles}  # noqa: E731
    flipped = TriangulatedSurface(reference.vertices, reference.triangles[:, ::-1])
    assert key(got) in (key(reference), key(flipped))
    assert [len(loop) for loop in got.loops] == [34, 8]


@pytest.mark.parametrize("case", sorted(bad_meshes()))
def test_bad_meshes_are_refused_in_one_line(case):
    (v, t), match = bad_meshes()[case]
    with pytest.raises(InvalidSurfaceError, match=match) as info:
        TriangulatedSurface(v, t)
    assert_one_line(str(info.value))


def test_an_unsigned_index_out_of_range_is_shown_as_given():
    """A uint64 index of 2**64 - 1 is named as such, not as the -1 it wraps to in int64."""
    square = [[0.0, 0, 0], [1, 0, 0], [1, 1, 0]]
    with pytest.raises(
        InvalidSurfaceError, match=r"refers to a vertex outside 0 \.\. 2: \[0, 1, 18446744073709551615\]"
    ):
        TriangulatedSurface(square, np.array([[0, 1, 2**64 - 1]], dtype=np.uint64))
