"""A user's triangle mesh as the auxiliary triangulation of Section 4 (step 1 given, not built).

Section 4 meshes a surface through an auxiliary triangulation of it: step 1
builds one from a parameter grid, steps 2-4 only need its nodes and triangles.
A :class:`TriangulatedSurface` is that triangulation given directly (a mesh
exported by a modeller).  Steps 2-4 then run on it unchanged (flattening by
eq. (1), Problem 2 on the flattened outline, remapping by eq. (2)), and the
flattening itself serves as the parameter plane
(:class:`~equimesh.surface.charts.mesh_chart.MeshChart`).

What eq. (1) and the remapping need, and what is checked here (each refusal
one :class:`~equimesh.errors.InvalidSurfaceError` line naming the vertex or
triangle at fault):

* finite coordinates, at least one triangle, vertex indices in range;
* exactly coincident vertices are one vertex (STL stores every triangle
  separately), vertices used by no triangle are dropped;
* no degenerate triangle: two corners the same vertex, or the sine of the
  angle at its first corner at most :data:`~equimesh.tolerance.SINGULAR_SIN`
  (its edges parallel to within about 2e-4 degrees, the regularity test of
  parametric surfaces), or a triangle given twice;
* manifold: every edge in at most two triangles, and the triangles around
  every vertex one fan (a disc or a half-disc), not two fans touching there;
* one connected piece, orientable (the triangles are then oriented
  consistently, the first one's orientation kept), and at least one boundary
  loop ("cut it open first");
* no handle (Euler characteristic ``V - E + F = 2 - b`` for ``b`` boundary
  loops): a surface with a handle cannot be flattened onto a plane region.

The boundary loops follow the oriented boundary edges, so the surface is on
their left.
"""

import numpy as np
import scipy.sparse
import scipy.sparse.csgraph

from ..._checks import finite_rows, index_rows
from ...errors import InvalidSurfaceError, coordinates
from ...mesh import edge_keys, half_edges
from ...tolerance import SINGULAR_SIN


class TriangulatedSurface:
    """A connected, manifold, orientable triangle mesh with at least one boundary loop.

    Parameters
    ----------
    vertices : (N, 3) array_like of float
    triangles : (M, 3) array_like of int
        Indices into ``vertices``; either orientation, made consistent.

    Attributes
    ----------
    vertices : (N', 3) float array
        Coincident vertices merged, unused ones dropped, in their input order.
    triangles : (M, 3) int array
        Consistently oriented.
    loops : tuple of int arrays
        The boundary loops, each a closed vertex cycle with the surface on its
        left (in the triangles' orientation), the longest (in space) first.

    Raises
    ------
    InvalidSurfaceError
        One line naming what is wrong (see the module docstring).
    """

    def __init__(self, vertices, triangles):
        v, t = _parse(vertices, triangles)
        v, t = _merge(v, t)
        _check_degenerate(v, t)
        _check_manifold(v, t)
        t = _orient_consistently(v, t)
        loops = _boundary_loops(v, t)
        n_edges = len(_edges(t)[2])
        handles = (2 - len(loops) - (len(v) - n_edges + len(t))) // 2
        if handles:
            raise InvalidSurfaceError(
                f"the triangle mesh has {handles} handle{'s' if handles > 1 else ''} (genus {handles}, Euler "
                "characteristic "
                f"{len(v) - n_edges + len(t)} with {len(loops)} boundary loops); only a disc with openings can be "
                "flattened, "
                "cut it open first"
            )
        length = [float(np.linalg.norm(v[np.roll(loop, -1)] - v[loop], axis=1).sum()) for loop in loops]
        order = sorted(range(len(loops)), key=lambda k: (-length[k], int(loops[k].min())))
        self.vertices, self.triangles = v, t
        self.loops = tuple(loops[k] for k in order)


def _parse(vertices, triangles):
    v = finite_rows(vertices, 3, "triangle mesh vertices", "vertex {} of the triangle mesh", InvalidSurfaceError)
    if np.asarray(triangles).size == 0:
        raise InvalidSurfaceError("the mesh has no triangles")
    return v, index_rows(triangles, 3, len(v), "triangles", "triangle {}", "vertex", InvalidSurfaceError)


def _merge(v, t):
    """Merge exactly coincident vertices (into the first of them) and drop unused ones, keeping their order."""
    _, first, inverse = np.unique(v, axis=0, return_index=True, return_inverse=True)
    t = first[inverse.ravel()][t]  # each vertex -> the first index with the same coordinates
    used, t = np.unique(t, return_inverse=True)
    return v[used], t.reshape(-1, 3)


def _check_degenerate(v, t):
    same = np.flatnonzero((t[:, 0] == t[:, 1]) | (t[:, 1] == t[:, 2]) | (t[:, 2] == t[:, 0]))
    if same.size:
        k = int(same[0])
        a, b, c = t[k]
        twice = a if a in (b, c) else b
        raise InvalidSurfaceError(
            f"triangle {k} of the mesh is degenerate: two of its corners are the same point {coordinates(v[twice])}"
        )
    e1, e2 = v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]
    scale = np.max(np.abs(np.concatenate([e1, e2], axis=1)), axis=1, keepdims=True)
    e1, e2 = e1 / scale, e2 / scale  # no overflow or underflow in the products below
    sine = np.linalg.norm(np.cross(e1, e2), axis=1) / (np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1))
    flat = np.flatnonzero(~(sine > SINGULAR_SIN))
    if flat.size:
        k = int(flat[0])
        raise InvalidSurfaceError(
            f"triangle {k} of the mesh is degenerate (zero area): its corners "
            f"{', '.join(coordinates(v[i]) for i in t[k])} "
            "are collinear"
        )
    key = np.sort(t, axis=1)
    _, first, counts = np.unique(key, axis=0, return_index=True, return_counts=True)
    if np.any(counts > 1):
        k = int(first[np.flatnonzero(counts > 1)].min())
        twice = np.flatnonzero(np.all(key == key[k], axis=1))
        raise InvalidSurfaceError(f"triangles {int(twice[0])} and {int(twice[1])} of the mesh have the same corners")


def _edges(t):
    """Half-edges (3M, 2), their undirected edge ids, their triangles, and the two half-edges of each inner edge."""
    he = half_edges(t)
    _, edge = np.unique(edge_keys(he)[0], return_inverse=True)
    count = np.bincount(edge)
    order = np.argsort(edge, kind="stable")
    pairs = order[count[edge[order]] == 2].reshape(-1, 2)
    return he, edge, count, np.tile(np.arange(len(t)), 3), pairs


def _check_manifold(v, t):
    he, edge, count, tri, pairs = _edges(t)
    over = np.flatnonzero(count > 2)
    if over.size:
        a, b = he[np.flatnonzero(edge == over[0])[0]]
        raise InvalidSurfaceError(
            f"the mesh is not manifold: the edge from {coordinates(v[a])} to {coordinates(v[b])} belongs to "
            f"{int(count[over[0]])} triangles (at most 2)"
        )
    # Corners (3 * triangle + slot) joined across each inner edge, at both of its ends: the corners
    # of a vertex form one class exactly when its triangles make one fan.  Half-edge h runs from
    # the corner in slot h // M of triangle h % M to the next slot.
    m = len(t)

    def corner(h, end):
        return 3 * (h % m) + (h // m + end) % 3

    ends = [(corner(pairs[:, 0], e), corner(pairs[:, 1], e)) for e in (0, 1)]
    same_start = he[pairs[:, 0], 0] == he[pairs[:, 1], 0]
    rows = np.concatenate([ends[0][0], ends[1][0]])
    cols = np.concatenate([np.where(same_start, ends[0][1], ends[1][1]), np.where(same_start, ends[1][1], ends[0][1])])
    _, label = _components(rows, cols, 3 * m)
    fans = np.unique(np.column_stack([t.ravel(), label]), axis=0)[:, 0]
    many = np.flatnonzero(np.bincount(fans, minlength=len(v)) > 1)
    if many.size:
        raise InvalidSurfaceError(
            f"the mesh is not manifold at the vertex {coordinates(v[int(many[0])])}: separate fans of triangles meet "
            "there "
            "(pieces touching at one point)"
        )
    n, label = _components(tri[pairs[:, 0]], tri[pairs[:, 1]], m)
    if n > 1:
        sizes = np.bincount(label)
        raise InvalidSurfaceError(
            f"the mesh has {n} separate pieces (of {', '.join(str(int(s)) for s in sizes[:5])}"
            f"{', ...' if n > 5 else ''} triangles); mesh one connected surface at a time"
        )


def _components(rows, cols, n):
    graph = scipy.sparse.coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
    return scipy.sparse.csgraph.connected_components(graph, directed=False)


def _orient_consistently(v, t):
    """Flip triangles so that every inner edge is used in opposite directions; refuse a non-orientable mesh.

    Two triangles using their shared edge in the same direction need opposite
    flips.  The flips are propagated along a breadth-first tree of the
    triangles (triangle 0 kept); an inner edge whose triangles then still use
    it in the same direction closes an odd cycle: a Moebius strip.
    """
    he, _, _, tri, pairs = _edges(t)
    a, b = tri[pairs[:, 0]], tri[pairs[:, 1]]
    same = (he[pairs[:, 0], 0] == he[pairs[:, 1], 0]).astype(np.int64)
    m = len(t)
    adjacency = scipy.sparse.coo_matrix((np.r_[same, same] + 1, (np.r_[a, b], np.r_[b, a])), shape=(m, m)).tocsr()
    order, parent = scipy.sparse.csgraph.breadth_first_order(adjacency, 0, directed=False, return_predecessors=True)
    key = np.r_[a, b] * m + np.r_[b, a]
    sorter = np.argsort(key)
    child = order[1:]
    parity = np.r_[same, same][sorter[np.searchsorted(key, parent[child] * m + child, sorter=sorter)]]
    flip = np.zeros(m, dtype=np.int64)
    flips, parents, parities = flip.tolist(), parent[child].tolist(), parity.tolist()
    for k, p, s in zip(child.tolist(), parents, parities):
        flips[k] = flips[p] ^ s
    flip = np.array(flips)
    bad = np.flatnonzero((flip[a] ^ flip[b]) != same)
    if bad.size:
        x, y = he[pairs[bad[0], 0]]
        raise InvalidSurfaceError(
            "the mesh is not orientable (a Moebius strip): its triangles cannot be oriented consistently "
            f"across the edge from {coordinates(v[x])} to {coordinates(v[y])}"
        )
    t = t.copy()
    t[flip == 1] = t[flip == 1][:, ::-1]
    return t


def _boundary_loops(v, t):
    """The closed boundary vertex cycles, following the oriented boundary half-edges."""
    he, edge, count, _, _ = _edges(t)
    boundary = he[count[edge] == 1]
    if not len(boundary):
        raise InvalidSurfaceError(
            "the mesh is a closed surface without boundary; cut it open first (remove the triangles of an opening "
            "or cut along a seam)"
        )
    following = dict(zip(boundary[:, 0].tolist(), boundary[:, 1].tolist()))
    loops, seen = [], set()
    for start in sorted(following):
        if start in seen:
            continue
        loop = [start]
        while following[loop[-1]] != start:
            loop.append(following[loop[-1]])
        seen.update(loop)
        loops.append(np.array(loop, dtype=np.int64))
    return loops
