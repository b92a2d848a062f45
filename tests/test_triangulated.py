"""Triangle meshes in (Section 4 with the user's mesh as the auxiliary triangulation): reading, checks, meshing.

What must hold: every output node lies on a triangle of the input mesh (to
1e-9 l), every member of the planar triangulation is in [l, 2l] (Theorem 3),
an opening of the input stays open, and every malformed mesh is refused in
one line (library: InvalidSurfaceError; command line: exit 2, nothing written).
"""

import importlib.util
import re
from pathlib import Path

import meshio
import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from test_io import assert_one_line

from equimesh import REL_TOL, EquimeshError, InvalidSurfaceError, TriangulatedSurface, mesh_surface
from equimesh._cli import main
from equimesh._geometry import inner_angle
from equimesh.io import load_surface
from equimesh.mesh import half_edges
from equimesh.surface import pipeline
from equimesh.surface.charts.mesh_chart import (
    MeshChart,
    _unfolded,
    conformal_start,
    flatten_mesh,
    flattening_start,
    harmonic_start,
)
from equimesh.surface.flatten import flatten, plane_start
from equimesh.surface.mesh_outline import CORNER_TURN, FIRM_TURN, loop_corners
from equimesh.surface.optimize import optimize_uv
from equimesh.testing.meshes import roof_mesh, wedge_mesh

L = 1.5
EXAMPLE = Path(__file__).resolve().parents[1] / "experiments" / "surfaces" / "roof_mesh.obj"
OPENING = (8.0, 12.0, 6.0, 10.0)  # x0, x1, y0, y1 of the opening of ROOF


def roof():
    """A 20 x 14 vault rising 3, 10 x 7 cells of 2 x 2, with the opening OPENING (cells 4-5 x 3-4) left out."""
    return roof_mesh(20.0, 14.0, (10, 7), 3.0, opening=(4, 6, 3, 5))


@pytest.fixture(scope="module")
def roof_meshes():
    surface = TriangulatedSurface(*roof())
    return surface, {opt: mesh_surface(surface, L, optimize=opt) for opt in ("none", "bounded")}


# ------------------------------------------------------------------ geometry helpers


def point_triangle_distance(p, a, b, c):
    """Distance from each point p (K, 3) to the triangle (a, b, c) (K, 3 each): the closest of its plane and edges."""
    n = np.cross(b - a, c - a)
    n = n / np.linalg.norm(n, axis=1, keepdims=True)
    height = np.einsum("ij,ij->i", p - a, n)
    q = p - height[:, None] * n
    inside = np.ones(len(p), dtype=bool)
    for x, y in ((a, b), (b, c), (c, a)):
        inside &= np.einsum("ij,ij->i", np.cross(y - x, q - x), n) >= 0
    edge = np.full(len(p), np.inf)
    for x, y in ((a, b), (b, c), (c, a)):
        t = np.clip(np.einsum("ij,ij->i", p - x, y - x) / np.einsum("ij,ij->i", y - x, y - x), 0, 1)
        edge = np.minimum(edge, np.linalg.norm(x + t[:, None] * (y - x) - p, axis=1))
    return np.where(inside, np.abs(height), edge)


def assert_on_input_surface(mesh, surface, l):
    """Every node within 1e-9 l of the input triangle its parameters fall in."""
    chart = MeshChart(surface, mesh.stages.flattening.points)
    k = chart.locate(mesh.uv[:, 0], mesh.uv[:, 1])[0]
    corners = surface.vertices[surface.triangles[k]]
    distance = point_triangle_distance(mesh.points, corners[:, 0], corners[:, 1], corners[:, 2])
    assert distance.max() <= 1e-9 * l, distance.max()


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
    """Item 52: under "bounded" every boundary node but the corners slides along its loop; every member in [l, 2l]."""
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
    """Vaults of any rise with an opening anywhere at least 3 cells (6) from the border, sides at least 2 > l: every invariant."""
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


@settings(max_examples=20, deadline=None)
@given(
    turns=st.lists(st.floats(0.0, 80.0), min_size=6, max_size=12),
    side=st.floats(0.3, 3.0),
)
def test_loop_corners(turns, side):
    """Corners turn by at least CORNER_TURN and are at least l apart around the loop, at least one; or two firm corners are too close."""
    # An open polyline from turning angles; the loop closes it with one more segment (the function reads only xy).
    heading = np.cumsum(np.radians(turns))
    xy = np.cumsum(side * np.column_stack([np.cos(heading), np.sin(heading)]), axis=0)
    turn = [abs(180 - inner_angle(xy, i)) for i in range(len(xy))]
    try:
        corners = loop_corners(xy, 1.0, lambda i, j: ValueError(i, j))
    except ValueError as exc:
        i, j = exc.args
        assert min(turn[i], turn[j]) >= FIRM_TURN and np.linalg.norm(xy[i] - xy[j]) < 1.0
        return
    assert len(corners) >= 1 and np.all(np.diff(corners) > 0)
    if len(corners) > 1:
        assert all(turn[c] >= CORNER_TURN for c in corners)
        gaps = np.linalg.norm(xy[np.roll(corners, -1)] - xy[corners], axis=1)
        assert gaps.min() >= 1.0


def cylinder_strip(angle, n_around=24, n_along=3, radius=5.0, length=6.0):
    """A developable strip: ``angle`` degrees of a cylinder, open along both straight sides."""
    phi = np.radians(angle) * np.arange(n_around + 1) / n_around
    z = length * np.arange(n_along + 1) / n_along
    p, q = np.meshgrid(phi, z, indexing="ij")
    vertices = np.column_stack([radius * np.cos(p.ravel()), radius * np.sin(p.ravel()), q.ravel()])
    node = np.arange(len(vertices)).reshape(n_around + 1, n_along + 1)
    a, b, c, d = node[:-1, :-1].ravel(), node[1:, :-1].ravel(), node[1:, 1:].ravel(), node[:-1, 1:].ravel()
    return vertices, np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])


def test_folding_projection_starts_from_the_conformal_map():
    """A 300-degree cylinder strip folds when projected on a plane: eq. (1) starts from the conformal map and develops it."""
    surface = TriangulatedSurface(*cylinder_strip(300.0))
    tri = surface.triangles
    assert not _unfolded(plane_start(surface.vertices, tri), tri)
    np.testing.assert_array_equal(flattening_start(surface), conformal_start(surface))
    assert flatten_mesh(surface).energy < 1e-12
    mesh = mesh_surface(surface, 2.0, optimize="none")
    assert_on_input_surface(mesh, surface, 2.0)
    roof_surface = TriangulatedSurface(*roof())  # a vault projects without folding
    np.testing.assert_array_equal(
        flattening_start(roof_surface), plane_start(roof_surface.vertices, roof_surface.triangles)
    )


def test_tutte_embedding_never_folds_a_disc():
    """Tutte's embedding (the last start) of the opening-free vault and of the strip: every triangle counter-clockwise."""
    for vertices, triangles in (roof_mesh(20.0, 14.0, (10, 7), 3.0), cylinder_strip(300.0)):
        surface = TriangulatedSurface(vertices, triangles)
        assert _unfolded(harmonic_start(surface), surface.triangles)


def test_openings_stay_open_on_a_curved_fine_mesh():
    """Eq. (1) alone lets this opening's rim cross itself; capped for the fold-over guard it stays a simple hole."""
    surface = TriangulatedSurface(*roof_mesh(20.0, 14.0, (40, 28), 5.0, opening=(16, 24, 12, 16)))
    bare = flatten(surface.vertices, surface.triangles)
    assert not shapely.LinearRing(bare.points[surface.loops[1]]).is_simple
    chart = MeshChart(surface, flatten_mesh(surface).points)  # checks that the flattening is one-to-one
    assert chart.outer == 0


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
            r"hole 0 .* has corners at \(8, 8, 2\.78163\) and \(10, 8, 2\.92478\) only 1\.95073 apart .* use l <= 1\.95$",
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
    """Problem 2's refusals and the rings' own, in one line, the opening located in space; the suggested l is accepted."""
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


def tetrahedron():
    v = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    return v, np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])


def torus_with_hole(n=8, m=6):
    a, b = np.meshgrid(2 * np.pi * np.arange(n) / n, 2 * np.pi * np.arange(m) / m, indexing="ij")
    v = np.column_stack(
        [(3 + np.cos(b.ravel())) * np.cos(a.ravel()), (3 + np.cos(b.ravel())) * np.sin(a.ravel()), np.sin(b.ravel())]
    )
    node = np.arange(n * m).reshape(n, m)
    nxt = np.roll(node, -1, axis=0)
    a0, b0, c0, d0 = node.ravel(), nxt.ravel(), np.roll(nxt, -1, axis=1).ravel(), np.roll(node, -1, axis=1).ravel()
    t = np.concatenate([np.column_stack([a0, b0, c0]), np.column_stack([a0, c0, d0])])
    return v, np.delete(t, [0, n * m], axis=0)  # one cell removed: a boundary loop, the handle stays


def moebius(n=12):
    s = np.arange(n + 1) / n * 2 * np.pi
    v = []
    for w in (-1.0, 1.0):
        v.append(
            np.column_stack(
                [(4 + w * np.cos(s / 2)) * np.cos(s), (4 + w * np.cos(s / 2)) * np.sin(s), w * np.sin(s / 2)]
            )
        )
    v = np.vstack([v[0][:-1], v[1][:-1]])
    lo, hi = np.arange(n), n + np.arange(n)
    t = [[lo[i], lo[(i + 1) % n], hi[(i + 1) % n]] for i in range(n - 1)] + [
        [lo[i], hi[(i + 1) % n], hi[i]] for i in range(n - 1)
    ]
    t += [[lo[n - 1], hi[0], lo[0]], [lo[n - 1], lo[0], hi[n - 1]]]  # the twist: the last cell glues lo to hi
    return v, np.array(t)


def bad_meshes():
    v, t = roof()
    square = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
    two = np.array([[0, 1, 2], [0, 2, 3]])
    nan = v.copy()
    nan[5, 2] = np.nan
    inf = v.copy()
    inf[7, 0] = np.inf
    fin = np.vstack([square, [[0.5, 0.5, 1.0]], [[0.5, 0.5, -1.0]]])
    return {
        "no triangles": ((v, np.zeros((0, 3), dtype=int)), "no triangles"),
        "NaN": ((nan, t), "vertex 5 of the triangle mesh is not finite"),
        "infinity": ((inf, t), "vertex 7 of the triangle mesh is not finite"),
        "index out of range": ((square, [[0, 1, 4]]), "refers to a vertex outside"),
        "repeated corner": ((square, [[0, 1, 1], [0, 2, 3]]), "two of its corners are the same point"),
        "zero area": ((np.vstack([square, [[2.0, 0, 0]]]), [[0, 1, 4], [0, 2, 3]]), r"degenerate \(zero area\)"),
        "triangle twice": ((square, [[0, 1, 2], [0, 2, 3], [2, 1, 0]]), "have the same corners"),
        "edge in three triangles": (
            (np.vstack([fin, [[0.5, 2.0, 0.0]]]), [[0, 2, 4], [0, 2, 5], [0, 2, 6]]),
            "belongs to 3 triangles",
        ),
        "bow tie": (
            (np.vstack([square, [[2.0, 1, 0], [2, 2, 0]]]), [[0, 1, 2], [2, 4, 5]]),
            "not manifold at the vertex",
        ),
        "two pieces": ((np.vstack([square, square + [5.0, 0, 0]]), np.vstack([two, two + 4])), "2 separate pieces"),
        "closed": (tetrahedron(), "cut it open first"),
        "Moebius": (moebius(), "not orientable"),
        "handle": (torus_with_hole(), "1 handle"),
    }


@pytest.mark.parametrize("case", sorted(bad_meshes()))
def test_bad_meshes_are_refused_in_one_line(case):
    (v, t), match = bad_meshes()[case]
    with pytest.raises(InvalidSurfaceError, match=match) as info:
        TriangulatedSurface(v, t)
    assert_one_line(str(info.value))


# ------------------------------------------------------------------ files


@pytest.mark.parametrize("ext", [".obj", ".stl", ".ply", ".vtk", ".vtu"])
def test_round_trip_through_each_format(tmp_path, ext):
    """Written by meshio, read back by load_surface: the same surface (STL and PLY store float32 coordinates)."""
    v, t = roof()
    path = tmp_path / f"roof{ext}"
    meshio.write(path, meshio.Mesh(v, [("triangle", t)]))
    got = load_surface(path)
    assert isinstance(got, TriangulatedSurface)
    reference = TriangulatedSurface(v, t)
    assert len(got.vertices) == len(reference.vertices) and len(got.triangles) == len(reference.triangles)
    np.testing.assert_allclose(np.sort(got.vertices, axis=0), np.sort(reference.vertices, axis=0), rtol=0, atol=1e-5)


def test_quadrilaterals_are_split(tmp_path):
    """A quad mesh is read as triangles, each quad cut along its shorter diagonal."""
    v = np.array([[0.0, 0, 0], [4, 0, 0], [4, 1, 0], [0, 1, 0], [8, 0, 1], [8, 1, 1]])
    path = tmp_path / "quads.vtu"
    meshio.write(path, meshio.Mesh(v, [("quad", np.array([[0, 1, 2, 3], [1, 4, 5, 2]])), ("line", np.array([[0, 1]]))]))
    got = load_surface(path)
    assert len(got.triangles) == 4 and len(got.loops) == 1


def unreadable(tmp_path):
    lines = tmp_path / "lines.vtu"
    meshio.write(lines, meshio.Mesh(np.eye(3), [("line", np.array([[0, 1], [1, 2]]))]))
    tetra = tmp_path / "tetra.vtu"
    meshio.write(tetra, meshio.Mesh(np.vstack([np.eye(3), [[0, 0, 0]]]), [("tetra", np.array([[0, 1, 2, 3]]))]))
    garbage = tmp_path / "garbage.stl"
    garbage.write_bytes(b"\x00" * 10)
    ply = tmp_path / "text.ply"
    ply.write_text("this is not a ply file\n")
    empty = tmp_path / "empty.obj"
    empty.write_text("")
    return {
        "empty": (empty, "has no points and no triangles"),
        "only lines": (lines, "has no triangles"),
        "volume cells": (tetra, "cells of type 'tetra'"),
        "garbage STL": (garbage, "cannot read"),
        "not PLY": (ply, "cannot read"),
    }


@pytest.mark.parametrize("case", ["empty", "only lines", "volume cells", "garbage STL", "not PLY"])
def test_unreadable_files_are_refused_in_one_line(tmp_path, case):
    path, match = unreadable(tmp_path)[case]
    with pytest.raises(InvalidSurfaceError, match=match) as info:
        load_surface(path)
    assert_one_line(str(info.value))
    assert path.name in str(info.value)


def test_unknown_extension_lists_the_mesh_formats(tmp_path):
    path = tmp_path / "roof.off"
    path.write_text("OFF\n")
    with pytest.raises(InvalidSurfaceError, match=r"\.obj.*\.ply.*\.stl.*\.vtk.*\.vtu"):
        load_surface(path)


# ------------------------------------------------------------------ the command line


def test_command_line_meshes_an_obj(tmp_path, capsys):
    v, t = roof()
    source = tmp_path / "roof.obj"
    meshio.write(source, meshio.Mesh(v, [("triangle", t)]))
    out = tmp_path / "out.vtu"
    assert main(["mesh", str(source), "--length", str(L), "--optimize", "none", "-q", "-o", str(out)]) == 0
    written = meshio.read(out)
    assert len(written.cells_dict["triangle"]) > 0


@pytest.mark.parametrize("case", sorted(bad_meshes()))
def test_command_line_refuses_bad_meshes(tmp_path, capsys, case):
    """Every malformed mesh, written as a .vtu file: one line, exit 2, nothing written."""
    (v, t), match = bad_meshes()[case]
    source = tmp_path / "bad.vtu"
    # meshio cannot read back an empty triangle block: a mesh of lines only has no triangles either.
    cells = [("line", np.array([[0, 1]]))] if case == "no triangles" else [("triangle", np.asarray(t, dtype=np.int64))]
    meshio.write(source, meshio.Mesh(np.asarray(v, dtype=float), cells))
    out = tmp_path / "out.vtu"
    assert main(["mesh", str(source), "--length", "1", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("equimesh: error: ") and re.search(match, err), err
    assert not out.exists()
