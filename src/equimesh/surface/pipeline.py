"""Section 4 end to end: a uniform triangle mesh of a parametric surface or of a triangle mesh.

A triangle mesh (:class:`~equimesh.surface.charts.triangulated.TriangulatedSurface`)
is its own auxiliary triangulation: step 1 is skipped, its flattening is the
chart (:mod:`equimesh.surface.charts.mesh_chart`) and its boundary loops the outline
(:mod:`equimesh.surface.mesh_outline`); steps 3-5 are shared.

1. auxiliary triangulation of the chart's parameter rectangle (:mod:`equimesh.surface.auxiliary`,
   :mod:`equimesh.surface.charts.chart`);
   the surface is refused if it is not finite, singular or folds
   (:mod:`equimesh.surface.regularity`), or if the mesh would be too large
   (:data:`UNOPTIMIZED_MAX_NODES`, the objective's ``max_nodes``, :data:`MAX_GRID_CELLS`);
2. flattening by eq. (1) (:mod:`equimesh.surface.flatten`);
3. the flattened boundary, and the images of any openings of the chart
   (:mod:`equimesh.surface.charts.openings`), as a polygon with holes
   (:mod:`equimesh.surface.outline`) triangulated by Problem 2
   (:func:`equimesh.uniform_triangulation`), with the lattice
   placement chosen by :func:`equimesh.best_lattice_placement` by default; its
   refusals are restated in the surface's terms (:mod:`equimesh.surface.messages`);
4. remapping to (u, v) by eqs. (2)-(3) and to the surface (:mod:`equimesh.surface.remap`);
5. optimisation of the (u, v) of the inner nodes (:mod:`equimesh.surface.optimize`).

Steps 1-4 are :mod:`equimesh.surface.front`'s.  Under sound joints, when the
remapped mesh lacks area (:func:`~equimesh.surface.optimize.joints.joint_spacing`),
steps 3-4 run again at ``(1 + D) l`` on the same flattening (steps 1-2 do
not depend on l), and their refusals name that spacing and the l given
(:mod:`equimesh.surface.plane_length`).

Every stage is kept in :class:`SurfaceMesh.stages` for tables and figures.
"""

import time
from dataclasses import dataclass, field

import numpy as np

from .._checks import check_length
from ..classes import DEFAULT_TOLERANCE, check_tolerance
from ..errors import EquimeshError, InvalidSurfaceError
from ..mesh import G1, edge_lengths
from ..planar.insertion import DEFAULT_ENGINE, check_engine
from ..planar.limits import check_max_nodes
from ..planar.strip import BOUNDARY_SPACING, check_spacing
from .auxiliary import check_grid_size
from .charts.openings import Perforated
from .charts.triangulated import TriangulatedSurface
from .front import chart_front, mesh_front
from .mesh_outline import check_feature_angle
from .optimize import OBJECTIVES, optimize_uv
from .optimize.joints import joint_bounds, joint_spacing
from .optimize.problem import offset_points
from .output_checks import (
    check_catalogue_holds,
    check_deviation,
    check_fabrication_options,
    check_joints,
    check_members,
    check_orientation,
)
from .plane_length import PlaneLength
from .regularity import evaluate

#: Default limit on the node count of a surface mesh without the final
#: optimisation (``optimize="none"``); :func:`mesh_surface` refuses, before any
#: expensive work, a request estimated to exceed it.  With the fast engine and
#: the row-by-row clearance of the placement search, `equimesh mesh --optimize
#: none` on an idle 2-core machine took 3.2 s for the reference dome at 36,847
#: nodes, 12 s for the saddle at 184,518 and 30 s (0.74 GB) at 565,740
#: (docs/performance.md, "Section 4 without optimisation").
UNOPTIMIZED_MAX_NODES = 500_000

#: Limit on the auxiliary grid's cells n_u * n_v (a triangle mesh given as the
#: auxiliary triangulation may have twice as many triangles): flattening by eq. (1) took
#: 9 s at 100 x 100, 41 s (0.6 GB) at 200 x 200 and 251 s (1.3 GB) at
#: 300 x 300 (docs/performance.md).
MAX_GRID_CELLS = 40_000

#: The final optimisation when none is named (a key of :data:`~equimesh.surface.optimize.OBJECTIVES`, or "none").
DEFAULT_OPTIMIZE = "bounded"

#: Lattice placements: "best" searches the most lattice edges (beyond the paper), "default" is angle 0, offset
#: (0, 0), "classes" searches from "best" the fewest length classes
#: (:func:`~equimesh.planar.placement.fewest_classes_placement`).
PLACEMENTS = ("best", "default", "classes")


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
    seconds : dict, wall time of each stage (steps 3-4 summed over both planes when sound joints mesh the plane
        again at a larger spacing; steps 1-2 run once).
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
    n_boundary : the first ``n_boundary`` nodes lie on the surface boundary (the
        outer boundary, then each opening's, ``stages.plane.info["boundary_rings"]``).
    stages : Stages.
    offsets : (N,) float, each node's distance from the surface along its unit normal
        (``points = X^s(uv) + offsets N(uv)``; zero unless ``surface_tolerance`` > 0).
    """

    points: np.ndarray
    triangles: np.ndarray
    edges: np.ndarray
    edge_groups: np.ndarray
    uv: np.ndarray
    length: float
    n_boundary: int
    stages: Stages
    offsets: np.ndarray = None

    def edge_lengths(self):
        return edge_lengths(self.points, self.edges)

    @property
    def g1_mask(self):
        return self.edge_groups == G1

    def deviation(self):
        """``(max, mean)`` distance of the nodes from the surface (``|offsets|``; 0 on the surface)."""
        d = np.abs(self.offsets) if self.offsets is not None and len(self.offsets) else np.zeros(1)
        return float(d.max()), float(d.mean())


def mesh_surface(
    surface,
    l,
    *,
    holes=None,
    grid=(15, 15),
    optimize=DEFAULT_OPTIMIZE,
    placement="best",
    boundary_spacing=BOUNDARY_SPACING,
    max_nodes="default",
    progress=None,
    engine=DEFAULT_ENGINE,
    tolerance=DEFAULT_TOLERANCE,
    lengths=None,
    surface_tolerance=0.0,
    feature_angle=None,
):
    """Mesh a surface with members as equal as possible (Section 4).

    Parameters
    ----------
    surface : Chart or TriangulatedSurface
        An object with ``evaluate(u, v)`` and ``derivatives(u, v)`` on its
        ``domain`` (:class:`~equimesh.surface.charts.chart.Chart`; [0, 1]^2 if it has
        none), e.g. :class:`equimesh.BezierSurface` or :class:`equimesh.NurbsSurface`;
        or a triangle mesh (:class:`equimesh.TriangulatedSurface`), which is
        then the auxiliary triangulation itself: its boundary loops are the
        outer boundary and the openings, every node lies on one of its
        triangles, and its boundary nodes stay fixed in the optimisation, or
        under "bounded" slide along their loops (corners fixed).
    l : float
        Target member length.
    holes : sequence of (k, 2) array_like, optional
        Openings: closed polylines in (u, v) inside the domain
        (:class:`~equimesh.surface.charts.openings.Perforated`, which a surface may
        carry already, e.g. from a JSON ``"holes"`` field).  Each is mapped
        to the flattened plane and kept open by Problem 2; its boundary nodes
        lie on its polyline and stay fixed in the optimisation, or under
        "bounded" slide along its edges (its vertices fixed).
    grid : (int, int)
        Auxiliary grid n_u x n_v (step 1), at most :data:`MAX_GRID_CELLS`
        cells; not used for a triangle mesh.
    optimize : "bounded", "classes", "paper" or "none"
        Final optimisation of the nodes' (u, v) (see
        :data:`equimesh.surface.optimize.OBJECTIVES`), or none.  "bounded"
        (beyond the paper, the default) keeps every member in [l, 2l] with as
        many as possible at one length, boundary nodes sliding along their
        side, loop or hole edge; "classes" (beyond) seeks the fewest length
        classes at ``tolerance``; both keep every angle at least 30 degrees
        (:mod:`~equimesh.surface.optimize.joints`; steps 3 to 4 run again at
        a larger spacing when the remapped mesh lacks the area that needs,
        :func:`~equimesh.surface.optimize.joints.joint_spacing`); "paper" is the paper's.
    placement : "best", "default" or "classes"
        Lattice placement of Problem 2 (:data:`PLACEMENTS`).
    boundary_spacing : float
        Step 2 spacing of the boundary, in units of l.
    max_nodes : int, None or "default"
        Refuse, before flattening, a mesh estimated (from the surface area of
        the auxiliary triangulation and the lattice density ``2 / (sqrt(3) l^2)``)
        to need more nodes; None means no limit.  "default" is
        :data:`UNOPTIMIZED_MAX_NODES`, or the objective's ``max_nodes``
        (:data:`~equimesh.surface.optimize.OBJECTIVES`):
        runs within the defaults take at most about two minutes on a small
        machine.
    progress : callable, optional
        Called as ``progress(stage, seconds)`` after each stage.
    engine : str
        Insertion engine of Problem 2 (:data:`equimesh.planar.insertion.ENGINES`).
    tolerance : float or str
        Fabrication tolerance of a length class, relative to l: what "classes" counts.
    lengths : sequence of float or str, optional
        Stock lengths in [l, 2l] ("classes" only, :func:`equimesh.classes.check_catalogue`).
    surface_tolerance : float
        ``D`` in [0, l): how far a moving node may leave the surface along its
        normal (:attr:`SurfaceMesh.offsets`; "bounded" and "classes").
    feature_angle : float, optional
        Triangle meshes only: the turn (degrees) at the scale of l above which
        a boundary vertex is a corner (:func:`~equimesh.surface.mesh_outline.loop_corners`);
        None: :data:`~equimesh.surface.mesh_outline.DEFAULT_FEATURE_ANGLE`.

    Returns
    -------
    SurfaceMesh

    Raises
    ------
    InvalidSurfaceError
        The surface is not finite, singular or folds over
        (:mod:`equimesh.surface.regularity`), or it cannot be meshed with
        this ``l``; the message names the side, corner or (u, v) at fault.
    MeshTooLargeError
        The estimated node count exceeds ``max_nodes``.
    InvalidCatalogueError
        A bad ``lengths``, or one that cannot hold a side of the outline.
    InternalError
        A returned mesh would break a check of :mod:`~equimesh.surface.output_checks`.
    """
    l = check_length(l)
    tolerance = check_tolerance(tolerance)
    if not (isinstance(optimize, str) and (optimize == "none" or optimize in OBJECTIVES)):
        raise EquimeshError(f"optimize must be 'none' or one of {sorted(OBJECTIVES)}, got {optimize!r}")
    if placement not in PLACEMENTS:
        raise EquimeshError(f"placement must be one of {PLACEMENTS}, got {placement!r}")
    catalogue, surface_tolerance = check_fabrication_options(optimize, lengths, surface_tolerance, l)
    boundary_spacing = check_spacing(boundary_spacing)  # Problem 2's own check, needed by step 3 already
    limit = _node_limit(max_nodes, optimize)
    engine = check_engine(engine)
    if holes is not None:
        if isinstance(surface, TriangulatedSurface):
            raise EquimeshError(
                "holes= cuts openings out of a parametric surface; a triangle mesh's openings are its boundary loops"
            )
        if not (hasattr(surface, "evaluate") and hasattr(surface, "derivatives")):
            raise InvalidSurfaceError("surface must provide evaluate(u, v) and derivatives(u, v) to take holes=")
        surface = Perforated(surface, holes)
    seconds = {}
    clock = _Clock(seconds, progress)
    angle = check_feature_angle(feature_angle, meshed=isinstance(surface, TriangulatedSurface))
    if angle is None:
        front = chart_front(surface, *_grid_pair(grid), l, limit, clock)
    else:
        _check_triangle_count(surface)
        front = mesh_front(surface, l, limit, clock, angle)
    boundary = OBJECTIVES[optimize].boundary if optimize in OBJECTIVES else "equal"
    outlined, chosen, plane, mapped_uv, mapped_points = front.remapped(
        PlaneLength(l), limit, boundary_spacing, boundary, placement, tolerance, engine, clock
    )
    if optimize in OBJECTIVES and OBJECTIVES[optimize].sound_joints:
        factor = joint_spacing(mapped_points, plane.triangles, l)  # the plane again, if the start lacks area
        if factor > 1.0:  # steps 3-4 only, unguarded: Problem 2 has meshed the plane at l already, with more nodes
            outlined, chosen, plane, mapped_uv, mapped_points = front.remapped(
                PlaneLength(l, factor), None, boundary_spacing, boundary, placement, tolerance, engine, clock
            )

    result = None
    chart = front.chart
    final_uv, final_points, offsets = mapped_uv, mapped_points, np.zeros(len(mapped_uv))
    if optimize != "none":
        record = OBJECTIVES[optimize]
        slides, fixed = (
            outlined.outline.slides(plane, mapped_uv) if record.slides else ((), np.arange(plane.n_boundary))
        )
        if catalogue is not None:
            check_catalogue_holds(catalogue, mapped_points, plane, fixed, l, tolerance)
        result = optimize_uv(
            chart,
            mapped_uv,
            plane.edges,
            plane.edge_groups,
            l,
            fixed=fixed,
            slides=slides,
            triangles=plane.triangles,
            objective=optimize,
            surface_tolerance=surface_tolerance,
            tolerance=tolerance,
            catalogue=catalogue,
        )
        final_uv, offsets = result.uv, result.offsets
        check_orientation(final_uv, plane.triangles, "the optimisation")
        final_points = offset_points(chart, final_uv, offsets if surface_tolerance > 0 else None)
        check_deviation(final_points, evaluate(chart, final_uv), surface_tolerance)
        if record.bounds_members:
            check_members(final_points, plane.edges, l)
        if record.sound_joints:
            check_joints(final_points, plane.triangles, joint_bounds(chart, mapped_uv, plane.triangles))
        clock("optimisation of inner nodes")

    stages = Stages(
        front.grid,
        front.points,
        front.flattening,
        outlined.outline,
        chosen,
        plane,
        mapped_uv,
        mapped_points,
        result,
        seconds,
    )
    return SurfaceMesh(
        final_points,
        plane.triangles,
        plane.edges,
        plane.edge_groups,
        final_uv,
        l,
        plane.n_boundary,
        stages,
        offsets,
    )


class _Clock:
    """Records the wall time of consecutive stages and reports each to ``progress``."""

    def __init__(self, seconds, progress):
        self.seconds, self.progress, self.last = seconds, progress, time.perf_counter()

    def __call__(self, stage):
        now = time.perf_counter()
        self.seconds[stage] = self.seconds.get(stage, 0.0) + now - self.last  # a stage run twice: the sum
        self.last = now
        if self.progress is not None:
            self.progress(stage, self.seconds[stage])


def _check_triangle_count(surface):
    """Refuse a triangle mesh with more triangles than a :data:`MAX_GRID_CELLS`-cell auxiliary grid has."""
    if len(surface.triangles) > 2 * MAX_GRID_CELLS:
        raise EquimeshError(
            f"the triangle mesh has {len(surface.triangles)} triangles, more than the limit of {2 * MAX_GRID_CELLS} "
            f"(those of a {MAX_GRID_CELLS}-cell auxiliary grid: flattening time and memory grow with them); "
            "coarsen it first"
        )


def _grid_pair(grid):
    """(n_u, n_v) from ``grid``, positive integers with at most :data:`MAX_GRID_CELLS` cells."""
    try:
        n_u, n_v = grid
    except (TypeError, ValueError):
        raise EquimeshError(f"grid must be a pair (n_u, n_v), got {grid!r}") from None
    n_u, n_v = check_grid_size(n_u, n_v)
    if n_u * n_v > MAX_GRID_CELLS:
        raise EquimeshError(
            f"auxiliary grid {n_u} x {n_v} has {n_u * n_v} cells, more than the limit of {MAX_GRID_CELLS} "
            "(flattening time and memory grow with it); use a coarser grid"
        )
    return n_u, n_v


def _node_limit(max_nodes, optimize):
    """The node limit: a positive int, None (no limit) or "default" (:data:`UNOPTIMIZED_MAX_NODES` or the
    objective's with the factorisation in use)."""
    return check_max_nodes(
        max_nodes, UNOPTIMIZED_MAX_NODES if optimize == "none" else OBJECTIVES[optimize].node_limit()
    )
