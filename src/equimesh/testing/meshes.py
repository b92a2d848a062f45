"""Triangle meshes of roofs, closed-ended tubes and spherical caps, for the triangle-mesh input of Section 4 (tests,
examples, benchmarks, experiments)."""

import numpy as np
import shapely
import triangle


def roof_mesh(width, depth, cells, rise, opening=None, cut=()):
    """A vault ``z = rise sin(pi x / width) sin(pi y / depth)`` over ``[0, width] x [0, depth]``, triangulated on a
    grid.

    Parameters
    ----------
    width, depth : float
    cells : (int, int)
        Grid cells along x and y; each cell is cut into two triangles.
    rise : float
        Height of the crown (0: a flat rectangle).
    opening : (i0, i1, j0, j1), optional
        The cells ``i0 <= i < i1``, ``j0 <= j < j1`` are left out (an opening;
        keep it one cell away from the border).
    cut : sequence of (k, 2) array_like
        Openings drawn in plan: the triangles whose centroid lies inside one
        of these polygons are left out, so a round opening's rim is a
        staircase of mesh edges, as when faces are removed in a modeller;
        a polygon whose sides run along grid lines or the cells' diagonals
        (from ``(x_i, y_j)`` to ``(x_i+1, y_j+1)``) is cut exactly, its
        corners vertices of the mesh.

    Returns
    -------
    vertices : (N, 3) float array, triangles : (M, 3) int array
        Counter-clockwise seen from above; vertices no triangle uses are kept
        (the reader drops them).
    """
    nx, ny = cells
    x, y = np.meshgrid(np.linspace(0.0, width, nx + 1), np.linspace(0.0, depth, ny + 1), indexing="ij")
    z = rise * np.sin(np.pi * x / width) * np.sin(np.pi * y / depth)
    vertices = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    node = np.arange((nx + 1) * (ny + 1)).reshape(nx + 1, ny + 1)
    keep = np.ones((nx, ny), dtype=bool)
    if opening is not None:
        i0, i1, j0, j1 = opening
        keep[i0:i1, j0:j1] = False
    a, b, c, d = (n[keep] for n in (node[:-1, :-1], node[1:, :-1], node[1:, 1:], node[:-1, 1:]))
    triangles = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    if len(cut):
        centroid = vertices[triangles].mean(axis=1)
        inside = np.zeros(len(triangles), dtype=bool)
        for polygon in cut:
            inside |= shapely.contains_xy(shapely.Polygon(polygon), centroid[:, 0], centroid[:, 1])
        triangles = triangles[~inside]
    return vertices, triangles


def ellipse(centre, a, b, n=256):
    """A closed polygon of ``n`` points on the ellipse of semi-axes ``a`` (along x) and ``b`` (along y): a plan
    outline for ``roof_mesh(cut=...)``."""
    t = 2.0 * np.pi * np.arange(n) / n
    return np.column_stack([centre[0] + a * np.cos(t), centre[1] + b * np.sin(t)])


def wedge_mesh(angle=25.0, radius=30.0, opening=((15.0, 2.0), (18.0, 3.2)), warp=0.01, max_area=0.3):
    """A circular sector of ``angle`` degrees with a rectangular opening, warped to ``z = warp x y``.

    Triangulated by Triangle (quality 30 degrees, triangles of at most
    ``max_area``); the arc is a 9-point polyline.  With the defaults, the
    sharp corner's staggered boundary parts of exactly 2l come out a hair
    longer than 2l on the surface at l = 1, which only sliding boundary nodes fix
    (docs/decisions.md, "Boundary nodes slide under bounded").

    Returns
    -------
    vertices : (N, 3) float array, triangles : (M, 3) int array
    """
    a = np.radians(angle)
    t = np.linspace(0.0, a, 9)
    (x0, y0), (x1, y1) = opening
    arc = np.column_stack([radius * np.cos(t), radius * np.sin(t)])
    points = np.vstack([[0.0, 0.0], arc, [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]])
    n = len(t) + 1
    segments = [(i, (i + 1) % n) for i in range(n)] + [(n + i, n + (i + 1) % 4) for i in range(4)]
    mesh = triangle.triangulate(
        {"vertices": points, "segments": np.array(segments), "holes": np.array([[(x0 + x1) / 2, (y0 + y1) / 2]])},
        f"pq30a{max_area}",
    )
    v = mesh["vertices"]
    return np.column_stack([v, warp * v[:, 0] * v[:, 1]]), mesh["triangles"]


def closed_tube(radius, length, n_ring=24, n_cap=6):
    """An open cylinder closed by a hemisphere at one end, as ``(vertices, triangles)``: a disc with one boundary loop,
    which the flattening stretches to several times its area."""
    n_length = int(length / (2.0 * np.pi * radius / n_ring))
    quarter = np.pi / 2.0 * np.arange(1, n_cap + 1) / n_cap
    rings = [(radius * np.sin(a), -length - radius * np.cos(a)) for a in quarter]
    rings += [(radius, -length + length * k / n_length) for k in range(1, n_length + 1)]
    return _rings_about_a_pole(rings, [0.0, 0.0, -length - radius], n_ring)


def spherical_cap(radius, degrees, n_ring=24, n_rings=12):
    """The cap of a sphere within ``degrees`` of its pole, as ``(vertices, triangles)`` (near 180: a nearly closed
    sphere)."""
    polar = np.radians(degrees) * np.arange(1, n_rings + 1) / n_rings
    return _rings_about_a_pole([(radius * np.sin(a), -radius * np.cos(a)) for a in polar], [0.0, 0.0, -radius], n_ring)


def _rings_about_a_pole(rings, pole, n_ring):
    """A fan about ``pole``, then strips between rings of ``n_ring`` points at (radius, z) each."""
    phi = np.linspace(0.0, 2.0 * np.pi, n_ring, endpoint=False)
    points = [pole] + [[r * np.cos(p), r * np.sin(p), z] for r, z in rings for p in phi]
    faces = [(0, 1 + (j + 1) % n_ring, 1 + j) for j in range(n_ring)]
    for i in range(len(rings) - 1):
        for j in range(n_ring):
            a, b = 1 + i * n_ring + j, 1 + i * n_ring + (j + 1) % n_ring
            faces += [(a, b + n_ring, a + n_ring), (a, b, b + n_ring)]
    return np.array(points), np.array(faces)
