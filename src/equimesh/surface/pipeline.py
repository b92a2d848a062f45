"""Section 4 end to end: a uniform triangle mesh of a parametric surface.

1. auxiliary triangulation of the parameter square (:mod:`equimesh.surface.auxiliary`);
2. flattening by eq. (1) (:mod:`equimesh.surface.flatten`);
3. the flattened boundary as a polygon (:mod:`equimesh.surface.outline`) triangulated
   by Problem 2 (:func:`equimesh.uniform_triangulation`), with the lattice
   placement chosen by :func:`equimesh.best_lattice_placement` by default;
4. remapping to (u, v) by eqs. (2)-(3) and to the surface (:mod:`equimesh.surface.remap`);
5. optimisation of the (u, v) of the inner nodes (:mod:`equimesh.surface.optimize`).

Every stage is kept in :class:`SurfaceMesh.stages` for tables and figures.
"""

import time
from dataclasses import dataclass, field

import numpy as np

from .._geometry import orient
from .auxiliary import auxiliary_grid
from ..errors import EquimeshError, InvalidSurfaceError, MeshTooLargeError
from .flatten import flatten
from ..mesh import edge_lengths
from .optimize import OBJECTIVES, optimize_uv
from .outline import resample_outline
from ..planar.placement import best_lattice_placement
from ..planar.polygon import check_length
from .remap import locate
from ..planar.strip import BOUNDARY_SPACING, uniform_triangulation

#: Default limit on the node count of a surface mesh; :func:`mesh_surface`
#: refuses (before any expensive work) a request estimated to exceed it.
MAX_NODES = 200_000

#: Lattice placements: "best" searches (beyond the paper), "default" is angle 0, offset (0, 0).
PLACEMENTS = ("best", "default")


@dataclass(frozen=True)
class Stages:
    """Every intermediate result of :func:`mesh_surface`.

    Attributes
    ----------
    grid : AuxiliaryGrid (step 1).
    auxiliary_points : (N0, 3) surface points X_i^s0 of the auxiliary nodes.
    flattening : Flattening (step 2, X_i^p0 in ``flattening.points``).
    outline : Outline, the polygon handed to Problem 2 (step 3).
    placement : Placement or None, the lattice placement used.
    plane : PlanarMesh, the triangulation on the plane with G1 labels (step 3).
    remapped_uv, remapped_points : (N, 2) and (N, 3), step 4.
    optimization : UVOptimization or None (final step).
    seconds : dict, wall time of each stage.
    """

    grid: object
    auxiliary_points: np.ndarray
    flattening: object
    outline: object
    placement: object
    plane: object
    remapped_uv: np.ndarray
    remapped_points: np.ndarray
    optimization: object
    seconds: dict = field(default_factory=dict, compare=False)


@dataclass(frozen=True)
class SurfaceMesh:
    """A triangle mesh of a surface.

    Attributes
    ----------
    points : (N, 3) float, on the surface.
    triangles : (M, 3) int, counter-clockwise in (u, v).
    edges : (E, 2) int, unique, sorted.
    edge_groups : (E,) int8, G1 (equal length on the plane) or OTHER.
    uv : (N, 2) float, the parameters of each node.
    length : the target length l.
    n_boundary : the first ``n_boundary`` nodes lie on the surface boundary.
    stages : Stages.
    """

    points: np.ndarray
    triangles: np.ndarray
    edges: np.ndarray
    edge_groups: np.ndarray
    uv: np.ndarray
    length: float
    n_boundary: int
    stages: Stages

    def edge_lengths(self):
        return edge_lengths(self.points, self.edges)

    @property
    def g1_mask(self):
        return self.edge_groups == 1


def mesh_surface(
    surface,
    l,
    *,
    grid=(15, 15),
    optimize="paper",
    placement="best",
    boundary_spacing=BOUNDARY_SPACING,
    max_nodes=MAX_NODES,
    progress=None,
):
    """Mesh a parametric surface with members as equal as possible (Section 4).

    Parameters
    ----------
    surface : object with ``evaluate(u, v)`` and ``derivatives(u, v)``
        E.g. :class:`equimesh.BezierSurface`; (u, v) in [0, 1]^2.
    l : float
        Target member length.
    grid : (int, int)
        Auxiliary grid n_u x n_v (step 1).
    optimize : "paper" or "none"
        Final optimisation of the inner nodes' (u, v) (see
        :data:`equimesh.surface.optimize.OBJECTIVES`), or none.
    placement : "best" or "default"
        Lattice placement of Problem 2.
    boundary_spacing : float
        Step 2 spacing of the boundary, in units of l.
    max_nodes : int
        Refuse meshes estimated to need more nodes.
    progress : callable, optional
        Called as ``progress(stage, seconds)`` after each stage.

    Returns
    -------
    SurfaceMesh
    """
    l = check_length(l)
    if optimize != "none" and optimize not in OBJECTIVES:
        raise EquimeshError(f"optimize must be 'none' or one of {sorted(OBJECTIVES)}, got {optimize!r}")
    if placement not in PLACEMENTS:
        raise EquimeshError(f"placement must be one of {PLACEMENTS}, got {placement!r}")
    if not (hasattr(surface, "evaluate") and hasattr(surface, "derivatives")):
        raise InvalidSurfaceError("surface must provide evaluate(u, v) and derivatives(u, v)")
    seconds = {}
    clock = _Clock(seconds, progress)

    aux = auxiliary_grid(*_grid_pair(grid))
    x_s0 = np.asarray(surface.evaluate(aux.uv[:, 0], aux.uv[:, 1]), dtype=float).reshape(-1, 3)
    if not np.all(np.isfinite(x_s0)):
        raise InvalidSurfaceError("surface evaluates to non-finite points on the auxiliary grid")
    clock("auxiliary triangulation")

    flat = flatten(x_s0, aux.triangles, uv=aux.uv)
    clock("flattening (eq. 1)")

    _check_size(flat.points, aux.triangles, l, max_nodes)
    corners = np.flatnonzero(aux.boundary_corner)
    outline = resample_outline(flat.points, aux.uv, aux.boundary, corners, l, boundary_spacing)
    chosen = best_lattice_placement(outline.vertices, l) if placement == "best" else None
    angle, offset = (chosen.angle, chosen.offset) if chosen else (0.0, (0.0, 0.0))
    plane = uniform_triangulation(outline.vertices, l, angle=angle, offset=offset, boundary_spacing=boundary_spacing)
    clock("planar triangulation (Problem 2)")

    uv = np.empty((plane.n_nodes, 2))
    uv[: plane.n_boundary] = _boundary_uv(plane.points[: plane.n_boundary], outline)
    uv[plane.n_boundary :] = locate(plane.points[plane.n_boundary :], flat.points, aux).uv
    remapped = _evaluate(surface, uv)
    clock("remapping (eqs. 2-3)")

    result = None
    final_uv = uv
    if optimize != "none":
        result = optimize_uv(
            surface,
            uv,
            plane.edges,
            plane.edge_groups,
            l,
            fixed=np.arange(plane.n_boundary),
            triangles=plane.triangles,
            objective=optimize,
        )
        final_uv = result.uv
        clock("optimisation of inner nodes")

    stages = Stages(aux, x_s0, flat, outline, chosen, plane, uv, remapped, result, seconds)
    return SurfaceMesh(
        remapped if result is None else _evaluate(surface, final_uv),
        plane.triangles,
        plane.edges,
        plane.edge_groups,
        final_uv,
        l,
        plane.n_boundary,
        stages,
    )


class _Clock:
    """Records the wall time of consecutive stages and reports each to ``progress``."""

    def __init__(self, seconds, progress):
        self.seconds, self.progress, self.last = seconds, progress, time.perf_counter()

    def __call__(self, stage):
        now = time.perf_counter()
        self.seconds[stage] = now - self.last
        self.last = now
        if self.progress is not None:
            self.progress(stage, self.seconds[stage])


def _grid_pair(grid):
    try:
        n_u, n_v = grid
    except (TypeError, ValueError):
        raise EquimeshError(f"grid must be a pair (n_u, n_v), got {grid!r}") from None
    return n_u, n_v


def _evaluate(surface, uv):
    return np.asarray(surface.evaluate(uv[:, 0], uv[:, 1]), dtype=float).reshape(-1, 3)


def _check_size(plane_points, triangles, l, max_nodes):
    """Estimate the node count (lattice density plus boundary) and refuse it above ``max_nodes``."""
    p = plane_points[triangles]
    area = 0.5 * np.abs(orient(p[:, 0], p[:, 1], p[:, 2])).sum()
    estimate = int(area / (np.sqrt(3.0) / 2.0 * l * l))
    if estimate > max_nodes:
        raise MeshTooLargeError(
            f"l = {l:.6g} would need about {estimate} nodes, more than the limit of {max_nodes}; "
            "raise the limit (max_nodes / --max-nodes) or use a larger l"
        )


def _boundary_uv(ring, outline):
    """(u, v) of the plane mesh's boundary nodes: exact at outline vertices, linear along outline edges.

    Every outline edge runs along one side of the parameter square, so the
    result lies exactly on the boundary of [0, 1]^2.
    """
    index = {tuple(p): k for k, p in enumerate(outline.vertices)}
    matched = np.array([index.get(tuple(p), -1) for p in ring])
    known = np.flatnonzero(matched >= 0)
    uv = np.empty((len(ring), 2))
    uv[known] = outline.uv[matched[known]]
    for i in np.flatnonzero(matched < 0):
        a = known[known < i].max() if np.any(known < i) else known.max()
        b = known[known > i].min() if np.any(known > i) else known.min()
        pa, pb = outline.vertices[matched[a]], outline.vertices[matched[b]]
        t = np.linalg.norm(ring[i] - pa) / np.linalg.norm(pb - pa)
        uv[i] = outline.uv[matched[a]] + t * (outline.uv[matched[b]] - outline.uv[matched[a]])
    return uv
