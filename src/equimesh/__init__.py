"""equimesh: uniform (equal-edge-length) triangle meshes after Katoh, Ohsaki and Xu.

Public verbs
------------
increment(vertices, l)            Problem 1, Algorithm INCREMENT (Section 2)
node_lower_bound(vertices, l)     lower bound on the optimum of Problem 1 (Theorem 2)
packing_upper_bound(vertices, l)  Oler's bound on l-separated point sets
"""

from .bounds import node_lower_bound, packing_upper_bound
from .errors import (
    EquimeshError,
    InvalidLengthError,
    InvalidPolygonError,
    InvalidSurfaceError,
    MeshTooLargeError,
)
from .increment import increment
from .mesh import G1, OTHER, PlanarMesh
from .tolerance import REL_TOL

__version__ = "0.1.0"

__all__ = [
    "G1",
    "OTHER",
    "REL_TOL",
    "EquimeshError",
    "InvalidLengthError",
    "InvalidPolygonError",
    "InvalidSurfaceError",
    "MeshTooLargeError",
    "PlanarMesh",
    "increment",
    "node_lower_bound",
    "packing_upper_bound",
]
