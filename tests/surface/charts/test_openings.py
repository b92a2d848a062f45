"""Surfaces with openings: holes given as closed polylines in (u, v) (surface/openings.py, beyond the paper).

What must hold: every member of the planar triangulation in [l, 2l] (Theorem 3
with holes), every node on the surface, no node inside a hole in (u, v), each
hole's boundary nodes on its polyline (and its vertices among them), the
optimisation leaving hole nodes where they are; holes survive a JSON round
trip; each bad hole is one line naming it, exit 2 on the command line.
"""

import json

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from invariants import check_edge_lengths
from repository import SURFACES

import equimesh
from equimesh._cli import main
from equimesh._geometry import inner_angle
from equimesh.errors import InvalidSurfaceError, SurfaceTooSmallError
from equimesh.io import load_surface, surface_from_dict, surface_to_dict
from equimesh.planar.boundary.sides import SHARP_CORNER
from equimesh.surface.auxiliary import auxiliary_grid
from equimesh.surface.charts.openings import Perforated
from equimesh.surface.flatten import flatten
from equimesh.surface.outline import densify
from equimesh.surface.remap import to_plane

SQUARE = [[0.3, 0.3], [0.45, 0.3], [0.45, 0.5], [0.3, 0.5]]
TRIANGLE = [[0.6, 0.4], [0.8, 0.45], [0.7, 0.7]]
NOTCHED = [
    [0.3, 0.3],
    [0.7, 0.3],
    [0.7, 0.7],
    [0.3, 0.7],
    [0.62, 0.5],
]  # the surface pokes into it, 49 degrees on the plane
CASES = {  # surface file, l, holes
    "nurbs one": ("nurbs_roof.json", 2.0, [SQUARE]),
    "nurbs two": ("nurbs_roof.json", 2.0, [SQUARE, TRIANGLE]),
    "bezier one": ("reference_dome.json", 3.3, [TRIANGLE]),
    "bezier two": ("reference_dome.json", 3.3, [SQUARE, TRIANGLE]),
    "sharp hole corner": ("nurbs_roof.json", 2.0, [[[0.3, 0.3], [0.7, 0.35], [0.3, 0.4]]]),
    "hole along auxiliary edges": ("nurbs_roof.json", 2.0, [[[0.2, 0.2], [0.6, 0.2], [0.6, 0.6], [0.2, 0.6]]]),
}


def check_openings(mesh, surface, holes, l):
    """The invariants of a surface mesh with openings."""
    check_edge_lengths(mesh.stages.plane, l)
    np.testing.assert_allclose(mesh.points, surface.evaluate(mesh.uv[:, 0], mesh.uv[:, 1]), rtol=0, atol=1e-9)
    rings = mesh.stages.plane.info["boundary_rings"]
    assert len(rings) == len(holes) + 1
    lower, upper = surface.domain.lower, surface.domain.upper
    outer = mesh.uv[: rings[0]]
    assert np.all(np.any((outer == lower) | (outer == upper), axis=1))
    start = np.cumsum(rings) - rings
    on_a_hole = np.zeros(len(mesh.uv), dtype=bool)
    for k, hole in enumerate(holes):
        polygon = shapely.Polygon(hole)
        ring = np.arange(start[k + 1], start[k + 1] + rings[k + 1])
        on_a_hole[ring] = True
        assert np.all(shapely.distance(polygon.exterior, shapely.points(mesh.uv[ring])) <= 1e-12)
        for vertex in np.asarray(hole, dtype=float):  # every hole vertex is a node, bit for bit
            assert np.any(np.all(mesh.uv[ring] == vertex, axis=1))
    for hole in holes:
        assert not np.any(shapely.Polygon(hole).contains(shapely.points(mesh.uv[~on_a_hole])))


@pytest.mark.parametrize("case", CASES)
def test_surface_with_openings_keeps_theorem_3_and_its_holes(case):
    name, l, holes = CASES[case]
    surface = load_surface(SURFACES / name)
    mesh = equimesh.mesh_surface(surface, l, holes=holes, optimize="none")
    check_openings(mesh, surface, holes, l)


def test_optimisation_leaves_hole_nodes_fixed():
    surface = load_surface(SURFACES / "nurbs_roof.json")
    mesh = equimesh.mesh_surface(surface, 2.0, holes=[SQUARE, TRIANGLE], optimize="paper")
    check_openings(mesh, surface, [SQUARE, TRIANGLE], 2.0)
    rings = mesh.stages.plane.info["boundary_rings"]
    assert np.array_equal(mesh.uv[rings[0] : sum(rings)], mesh.stages.remapped_uv[rings[0] : sum(rings)])


def test_bounded_slides_hole_nodes_along_their_edges():
    """Under "bounded" a hole's nodes slide along its edges in (u, v), its vertices fixed, members in [l, 2l]."""
    surface = load_surface(SURFACES / "nurbs_roof.json")
    mesh = equimesh.mesh_surface(surface, 3.0, holes=[SQUARE, TRIANGLE], optimize="bounded")
    check_openings(mesh, surface, [SQUARE, TRIANGLE], 3.0)  # on the polygons, every vertex a node bit for bit
    check_edge_lengths(mesh, 3.0)  # on the surface
    rings = mesh.stages.plane.info["boundary_rings"]
    assert np.any(mesh.uv[rings[0] : sum(rings)] != mesh.stages.remapped_uv[rings[0] : sum(rings)])


def test_holes_round_trip_through_json_for_every_type():
    for name in ("nurbs_roof.json", "reference_dome.json"):
        d = json.loads((SURFACES / name).read_text())
        d.pop("description")
        d["holes"] = [SQUARE, TRIANGLE]
        surface = surface_from_dict(d)
        assert isinstance(surface, Perforated)
        assert surface_to_dict(surface) == d


def test_holes_argument_and_carried_holes_are_one_path():
    surface = load_surface(SURFACES / "nurbs_roof.json")
    a = equimesh.mesh_surface(surface, 2.0, holes=[SQUARE], optimize="none", placement="default")
    b = equimesh.mesh_surface(Perforated(surface, [SQUARE]), 2.0, optimize="none", placement="default")
    assert np.array_equal(a.uv, b.uv) and np.array_equal(a.triangles, b.triangles)


@pytest.mark.parametrize(
    "holes, match",
    [
        (5, r'"holes" must be a list of polylines, got number'),
        ([[[0.3, 0.3], [0.4, 0.3]]], r"holes\[0\] needs at least 3 \[u, v\] points, got 2"),
        ([[[0.3, 0.3], [0.4, 0.3], [0.4, "a"]]], r"holes\[0\]\[2\]\[1\] must be a real number, got string a"),
        ([[[0.3, 0.3], [0.4, 0.3], [0.4, float("nan")]]], r"holes\[0\]\[2\]\[1\] is not a finite number"),
        (
            [[[0.3, 0.3], [1.4, 0.3], [0.4, 0.5]]],
            r"hole 0 is not inside the parameter domain \[0, 1\] x \[0, 1\]: its vertex 1",
        ),
        ([[[0.0, 0.3], [0.4, 0.3], [0.4, 0.5]]], r"hole 0 overlaps the boundary of the parameter domain"),
        ([SQUARE, [[0.35, 0.32], [0.5, 0.3], [0.5, 0.5]]], r"hole 0 and hole 1 overlap"),
        ([[[0.3, 0.3], [0.4, 0.4], [0.4, 0.3], [0.3, 0.4]]], r"hole 0 is not simple"),
    ],
)
def test_bad_holes_are_refused_in_one_line(holes, match):
    d = json.loads((SURFACES / "nurbs_roof.json").read_text())
    d["holes"] = holes
    with pytest.raises(InvalidSurfaceError, match=match) as info:
        surface_from_dict(d)
    assert "\n" not in str(info.value) and "np." not in str(info.value)


@pytest.mark.parametrize(
    "holes, l, error, match",
    [
        (
            [[[0.02, 0.3], [0.2, 0.3], [0.2, 0.5], [0.02, 0.5]]],
            2.0,
            InvalidSurfaceError,
            r"hole 0 comes within 1\.9\d* of the boundary of the surface on the flattened surface, at \(u, v\) = "
            r"\(0\.02, ",
        ),
        (
            [SQUARE, [[0.47, 0.3], [0.6, 0.3], [0.6, 0.5], [0.47, 0.5]]],
            2.0,
            InvalidSurfaceError,
            r"hole 0 comes within 0\.79\d* of hole 1 on the flattened surface",
        ),
        (
            [[[0.3, 0.3], [0.45, 0.3], [0.451, 0.31], [0.45, 0.5], [0.3, 0.5]]],
            1.0,
            SurfaceTooSmallError,
            r"edge \(2, 1\) of hole 0, from \(u, v\) = \(0\.451, 0\.31\) to \(0\.45, 0\.3\), is 0\.36\d* long",
        ),
    ],
)
def test_holes_too_close_for_l_are_refused_in_surface_terms(holes, l, error, match):
    surface = load_surface(SURFACES / "nurbs_roof.json")
    with pytest.raises(error, match=match) as info:
        equimesh.mesh_surface(surface, l, holes=holes, optimize="none")
    message = str(info.value)
    assert "\n" not in message and "polygon" not in message
    if error is SurfaceTooSmallError:  # a hole's edge as long as its ends' distance: that l is safe
        suggested = float(message.rsplit("use l <= ", 1)[1].split()[0])
        check_openings(
            equimesh.mesh_surface(surface, suggested, holes=holes, optimize="none"), surface, holes, suggested
        )


def test_command_line_refuses_a_bad_hole_with_exit_2_and_writes_nothing(tmp_path, capsys):
    d = json.loads((SURFACES / "nurbs_roof.json").read_text())
    d["holes"] = [[[0.3, 0.3], [1.4, 0.3], [0.4, 0.5]]]
    path = tmp_path / "roof.json"
    path.write_text(json.dumps(d))
    out = tmp_path / "mesh.obj"
    code = main(["mesh", str(path), "--length", "2", "-q", "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "hole 0 is not inside" in err and not out.exists()


@pytest.mark.parametrize("hole", [SQUARE, TRIANGLE, CASES["hole along auxiliary edges"][2][0]])
def test_densified_hole_is_linear_on_every_piece(hole):
    """Each piece of the densified polyline lies in one auxiliary triangle: eqs. (2)-(3) forward map its midpoint to its
    image's midpoint."""
    surface = load_surface(SURFACES / "nurbs_roof.json")
    grid = auxiliary_grid(15, 15, surface.domain)
    flat = flatten(surface.evaluate(grid.uv[:, 0], grid.uv[:, 1]), grid.triangles, uv=grid.uv).points
    dense, corners = densify(np.asarray(hole, dtype=float), grid)
    assert np.array_equal(dense[corners], np.asarray(hole, dtype=float))
    following = np.roll(dense, -1, axis=0)
    assert np.all(np.linalg.norm(following - dense, axis=1) > 0)
    image, image_next = to_plane(dense, flat, grid), to_plane(following, flat, grid)
    np.testing.assert_allclose(to_plane((dense + following) / 2, flat, grid), (image + image_next) / 2, atol=1e-9)


def test_a_notched_hole_gives_the_surface_a_sharp_corner_meshed_in_l_2l():
    """A corner of the meshed region below 60 degrees, on a hole: the plane members stay in [l, 2l]."""
    surface = load_surface(SURFACES / "nurbs_roof.json")
    mesh = equimesh.mesh_surface(surface, 2.0, holes=[NOTCHED], optimize="none")
    ring = mesh.stages.outline.holes[0].points
    assert min(inner_angle(ring, i) for i in range(len(ring))) < SHARP_CORNER
    check_openings(mesh, surface, [NOTCHED], 2.0)


@settings(max_examples=4, deadline=None)
@given(
    centre=st.tuples(st.floats(0.35, 0.65), st.floats(0.35, 0.65)),
    radius=st.floats(0.12, 0.2),
    turns=st.lists(st.floats(-5.0, 5.0), min_size=3, max_size=6),
)
def test_generated_openings_keep_every_invariant(centre, radius, turns):
    """A polygonal opening built from drawn values (n vertices on a circle, each angle jittered): always valid at l =
    3."""
    angles = np.radians(360.0 * np.arange(len(turns)) / len(turns) + np.array(turns))
    hole = np.column_stack([centre[0] + radius * np.cos(angles), centre[1] + radius * np.sin(angles)])
    surface = load_surface(SURFACES / "nurbs_roof.json")
    check_openings(equimesh.mesh_surface(surface, 3.0, holes=[hole], optimize="none"), surface, [hole.tolist()], 3.0)
