"""equimesh: uniform (equal-edge-length) triangle meshes after Katoh, Ohsaki and Xu.

Public verbs
------------
increment(vertices, l)            Problem 1, Algorithm INCREMENT (Section 2)
node_lower_bound(vertices, l)     lower bound on the optimum of Problem 1 (Theorem 2)
packing_upper_bound(vertices, l)  Oler's bound on l-separated point sets
mesh_surface(surface, l)          Section 4: uniform mesh of a parametric surface (holes=: openings in (u, v)) or a
triangle mesh
uniform_triangulation(vertices, l) Problem 2: lattice + boundary strip (Section 3)
best_lattice_placement(vertices, l) lattice angle/offset maximising G1 (beyond the paper)
length_classes(lengths, l, tol)   fewest member-length classes at a tolerance (beyond the paper)
load_surface(path, object=None)   a surface from a file (.json, Rhino .3dm, triangle meshes .obj .stl .ply .vtk .vtu)
(format by extension; JSON "type" by equimesh.io.SURFACE_TYPES)
surface_from_dict(d), surface_to_dict(surface)  the JSON description of a surface, both ways
write_report(mesh, path)          the run's report: one self-contained HTML page (3-D view, lengths, classes)
write_plot(mesh, path)            the mesh by length class and the length histogram, as PNG, SVG or PDF

Section 4 stages (what mesh_surface chains; public so that they can be timed and reused)
flatten(points3d, triangles)      step 2: eq. (1) flattening of the auxiliary triangulation
remap(surface, plane_points, flat_points, grid, outline=...)  step 4: eqs. (2)-(3), plane -> (u, v) -> surface
optimize_uv(surface, uv, edges, groups, l, fixed=...)  final step: (u, v) of the inner nodes

Errors: every bad input raises a subclass of EquimeshError (a ValueError) with a one-line
message; InternalError (a RuntimeError) means a proven guarantee failed on an output, a bug.
Layout: equimesh.planar (Problems 1 and 2), equimesh.surface (Section 4), equimesh.io (files),
equimesh.testing (input generators); see docs/architecture.md.
"""

import importlib

from .errors import EquimeshError as EquimeshError
from .errors import InternalError as InternalError
from .errors import InvalidLengthError as InvalidLengthError
from .errors import InvalidMethodError as InvalidMethodError
from .errors import InvalidPolygonError as InvalidPolygonError
from .errors import InvalidSurfaceError as InvalidSurfaceError
from .errors import InvalidToleranceError as InvalidToleranceError
from .errors import MeshTooLargeError as MeshTooLargeError
from .errors import MissingDependencyError as MissingDependencyError
from .errors import OutputPathError as OutputPathError
from .errors import SurfaceTooSmallError as SurfaceTooSmallError
from .errors import SurfaceWarning as SurfaceWarning
from .tolerance import REL_TOL as REL_TOL

#: Where each public verb and type lives.  They are imported on first use
#: (PEP 562), so that ``import equimesh._cli`` loads no numpy, scipy or
#: shapely: the command line imports them inside ``main``, where a Ctrl-C
#: during the (seconds long, on a busy machine) import is one line and exit
#: code 130 like any other interrupt (tests/cli/test_cli.py).
_EXPORTS = {
    "G1": ".mesh",
    "OTHER": ".mesh",
    "PlanarMesh": ".mesh",
    "BezierSurface": ".surface.charts.bezier",
    "Domain": ".surface.charts.chart",
    "LengthClasses": ".classes",
    "NurbsSurface": ".surface.charts.nurbs",
    "Perforated": ".surface.charts.openings",
    "Placement": ".planar.placement",
    "SurfaceMesh": ".surface.pipeline",
    "TriangulatedSurface": ".surface.charts.triangulated",
    "best_lattice_placement": ".planar.placement",
    "flatten": ".surface.flatten",
    "increment": ".planar.increment",
    "length_classes": ".classes",
    "load_surface": ".io",
    "mesh_surface": ".surface.pipeline",
    "node_lower_bound": ".planar.bounds",
    "optimize_uv": ".surface.optimize",
    "packing_upper_bound": ".planar.bounds",
    "remap": ".surface.remap",
    "surface_from_dict": ".io",
    "surface_to_dict": ".io",
    "uniform_triangulation": ".planar.strip",
    "write_plot": ".io",
    "write_report": ".io",
}


def __getattr__(name):
    """A public verb or type (imported on first use), or a subpackage such as ``equimesh.planar``."""
    if name in _EXPORTS:
        value = getattr(importlib.import_module(_EXPORTS[name], __name__), name)
    else:
        try:
            value = importlib.import_module(f".{name}", __name__)
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
            raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS))


__version__ = "0.1.0"

__all__ = sorted(
    [
        "REL_TOL",
        "EquimeshError",
        "InternalError",
        "InvalidLengthError",
        "InvalidMethodError",
        "InvalidPolygonError",
        "InvalidSurfaceError",
        "InvalidToleranceError",
        "MeshTooLargeError",
        "MissingDependencyError",
        "OutputPathError",
        "SurfaceTooSmallError",
        "SurfaceWarning",
        *_EXPORTS,
    ]
)
