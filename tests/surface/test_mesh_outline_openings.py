"""Openings cut out of fine triangle meshes (``surface/mesh_outline.py``): boundaries at the mesh's resolution.

What must hold: domes on 60 to 120 cells a side with round, elliptic and
polygonal openings cut out (the triangles inside removed, so that a curved
rim is a staircase of mesh edges and a polygon along grid lines and cell
diagonals keeps its corners at mesh vertices) are meshed at l well above the
mesh resolution with every member in [l, 2l] and every node on the input
triangles; the corners of the polygons and of the outer boundary are ring
vertices at their input vertices, fixed while the other boundary nodes slide;
an opening is refused only when it is narrower than l, in one line naming it,
and the l the refusal suggests is accepted.
"""

import re

import numpy as np
import pytest
from refusals import assert_one_line
from triangle_meshes import assert_boundary_slid_along_the_loops, assert_on_input_surface

from equimesh import REL_TOL, InvalidSurfaceError, TriangulatedSurface, mesh_surface
from equimesh.testing.meshes import ellipse, roof_mesh

SIZE, RISE = 30.0, 3.0  # a 30 x 30 dome rising 3


def dome(cells, openings):
    """The dome on ``cells`` x ``cells`` cells with the plan outlines ``openings`` cut out."""
    return TriangulatedSurface(*roof_mesh(SIZE, SIZE, (cells, cells), RISE, cut=openings))


def polygon(corner, shape, side):
    """A polygon along grid lines and the cells' diagonals, ``side`` across, its lower left corner at ``corner``."""
    half = side / 2
    outline = {
        "square": [(0, 0), (side, 0), (side, side), (0, side)],
        "hexagon": [(0, 0), (half, 0), (side, half), (side, side), (half, side), (0, half)],
        "triangle": [(0, 0), (side, 0), (side, side)],
        "slot": [(0, 0), (side, 0), (side, 4 * side), (0, 4 * side)],
    }[shape]
    return np.array(outline) + corner


def assert_corners_kept(mesh, surface, points):
    """Each plan point of ``points`` is a vertex of the input mesh and, flattened, a vertex of its ring and a corner."""
    flat = mesh.stages.flattening.points
    outline = mesh.stages.outline
    kept = [loop.at(corners) for loop, corners in zip(outline.loops, outline.corners)]
    for point in points:
        vertex = int(np.argmin(np.linalg.norm(surface.vertices[:, :2] - point, axis=1)))
        np.testing.assert_array_equal(surface.vertices[vertex, :2], point)
        p = flat[vertex]
        assert any(np.any(np.all(ring == p, axis=1)) for ring in outline.rings), point
        assert any(np.any(np.all(corner == p, axis=1)) for corner in kept), point


BORDER = [(0.0, 0.0), (SIZE, 0.0), (SIZE, SIZE), (0.0, SIZE)]
CASES = {
    # cells, l, openings: (plan outline, its corners)
    "90 cells, a round opening 3.3 l across": (90, 3.0, [(ellipse((15.0, 15.0), 5.0, 5.0), [])]),
    "60 cells, an ellipse and a hexagon": (
        60,
        3.0,
        [
            (ellipse((9.0, 20.0), 4.5, 3.0), []),
            (polygon((17.0, 4.0), "hexagon", 8.0), polygon((17.0, 4.0), "hexagon", 8.0)),
        ],
    ),
    "120 cells, a circle, a triangle and a small square": (
        120,
        2.0,
        [
            (ellipse((8.0, 8.0), 3.0, 3.0), []),
            (polygon((15.0, 15.0), "triangle", 8.0), polygon((15.0, 15.0), "triangle", 8.0)),
            (polygon((21.0, 4.0), "square", 3.0), polygon((21.0, 4.0), "square", 3.0)),
        ],
    ),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_openings_cut_out_of_fine_grids_are_meshed(case):
    """Every member in [l, 2l] under "bounded", every node on the input triangles, the corners kept and fixed."""
    cells, l, openings = CASES[case]
    surface = dome(cells, [outline for outline, _ in openings])
    assert len(surface.loops) == 1 + len(openings)
    mesh = mesh_surface(surface, l)
    members = mesh.edge_lengths() / l
    assert members.min() >= 1 - REL_TOL and members.max() <= 2 * (1 + REL_TOL)
    assert_on_input_surface(mesh, surface, l)
    assert_corners_kept(mesh, surface, BORDER + [p for _, corners in openings for p in corners])
    assert_boundary_slid_along_the_loops(mesh)


#: Openings of the 60-cell dome at l = 3 (6 mesh edges), their width (diameter, minor axis or side) in units of l.
WIDTHS = {
    "circle": lambda w: ellipse((15.0, 15.0), 1.5 * w, 1.5 * w),
    "ellipse": lambda w: ellipse((15.0, 15.0), 9.0, 1.5 * w),
    "slot": lambda w: polygon((14.0, 9.0), "slot", 3.0 * w),
    "square": lambda w: polygon((13.0, 13.0), "square", 3.0 * w),
}


@pytest.mark.parametrize(
    "shape, width",
    [
        ("circle", 0.8),
        ("circle", 1.5),
        ("circle", 2.0),
        ("ellipse", 2 / 3),
        ("ellipse", 1.5),
        ("slot", 2 / 3),
        ("slot", 4 / 3),
        ("square", 2 / 3),
        ("square", 7 / 6),
    ],
)
def test_an_opening_is_refused_only_when_narrower_than_l(shape, width):
    """Meshed when the opening is at least 7/6 l wide; refused in one line naming the opening when narrower than l,
    and meshed at the l the refusal suggests."""
    surface = dome(60, [WIDTHS[shape](width)])
    if width >= 1:
        mesh_surface(surface, 3.0, optimize="none")
        return
    with pytest.raises(InvalidSurfaceError, match=r"^hole 0 \(the opening through .*\) of the mesh is") as info:
        mesh_surface(surface, 3.0, optimize="none")
    message = str(info.value)
    assert_one_line(message)
    assert re.search("is (too small|narrower than l) ", message)
    mesh_surface(surface, float(re.search(r"use l <= ([0-9.]+)$", message).group(1)), optimize="none")
