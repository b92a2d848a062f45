"""equimesh: uniform (equal-edge-length) triangle meshes after Katoh, Ohsaki and Xu.

Public verbs
------------
increment(vertices, l)            Problem 1, Algorithm INCREMENT (Section 2)
node_lower_bound(vertices, l)     lower bound on the optimum of Problem 1 (Theorem 2)
packing_upper_bound(vertices, l)  Oler's bound on l-separated point sets
mesh_surface(surface, l)          Section 4: uniform mesh of a parametric surface
uniform_triangulation(vertices, l) Problem 2: lattice + boundary strip (Section 3)
best_lattice_placement(vertices, l) lattice angle/offset maximising G1 (beyond the paper)
length_classes(lengths, l, tol)   fewest member-length classes at a tolerance (beyond the paper)
load_surface(path, object=None)   a surface from a file (.json, Rhino .3dm) (format by extension; JSON "type" by equimesh.io.SURFACE_TYPES)
surface_from_dict(d), surface_to_dict(surface)  the JSON description of a surface, both ways

Section 4 stages (what mesh_surface chains; public so that they can be timed and reused)
flatten(points3d, triangles)      step 2: eq. (1) flattening of the auxiliary triangulation
remap(surface, plane_points, flat_points, grid, outline=...)  step 4: eqs. (2)-(3), plane -> (u, v) -> surface
optimize_uv(surface, uv, edges, groups, l, fixed=...)  final step: (u, v) of the inner nodes

Errors: every bad input raises a subclass of EquimeshError (a ValueError) with a one-line
message; InternalError (a RuntimeError) means a proven guarantee failed on an output, a bug.
Layout: equimesh.planar (Problems 1 and 2), equimesh.surface (Section 4), equimesh.io (files),
equimesh.testing (input generators); see docs/architecture.md.
"""

from .planar.bounds import node_lower_bound, packing_upper_bound
from .errors import (
    EquimeshError,
    InternalError,
    InvalidLengthError,
    InvalidPolygonError,
    InvalidSurfaceError,
    InvalidToleranceError,
    MeshTooLargeError,
    MissingDependencyError,
    OutputPathError,
    SurfaceTooSmallError,
    SurfaceWarning,
)
from .classes import LengthClasses, length_classes
from .io import load_surface, surface_from_dict, surface_to_dict
from .surface.flatten import flatten
from .planar.increment import increment
from .mesh import G1, OTHER, PlanarMesh
from .surface.pipeline import SurfaceMesh, mesh_surface
from .surface.optimize import optimize_uv
from .planar.placement import Placement, best_lattice_placement
from .surface.remap import remap
from .surface.bezier import BezierSurface
from .surface.chart import Domain
from .surface.nurbs import NurbsSurface
from .planar.strip import uniform_triangulation
from .tolerance import REL_TOL

__version__ = "0.1.0"

__all__ = [
    "G1",
    "OTHER",
    "REL_TOL",
    "BezierSurface",
    "Domain",
    "EquimeshError",
    "InternalError",
    "InvalidLengthError",
    "InvalidPolygonError",
    "InvalidSurfaceError",
    "InvalidToleranceError",
    "LengthClasses",
    "MeshTooLargeError",
    "MissingDependencyError",
    "NurbsSurface",
    "OutputPathError",
    "PlanarMesh",
    "Placement",
    "SurfaceMesh",
    "SurfaceTooSmallError",
    "SurfaceWarning",
    "best_lattice_placement",
    "flatten",
    "increment",
    "length_classes",
    "load_surface",
    "mesh_surface",
    "node_lower_bound",
    "optimize_uv",
    "packing_upper_bound",
    "remap",
    "surface_from_dict",
    "surface_to_dict",
    "uniform_triangulation",
]
