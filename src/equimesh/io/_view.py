"""What a picture of a mesh shows: members by length class, their colours, the length histogram, the boundary.

The report (:mod:`._report`, HTML) and the plot (:mod:`._plot`, matplotlib)
draw the same things from one :class:`MeshView`: each member in the colour of
its length class (:func:`equimesh.length_classes` at the run's tolerance), the
outer boundary and the openings, and a histogram of member lengths whose bins
are as wide as the tolerance, so that the window ``l +- tolerance l`` is two
bins.  At most :data:`MAX_DRAWN_CLASSES` classes get a colour of their own; the
smallest of the others are drawn together in grey
(docs/decisions.md, "The report and the plot draw the same view").
"""

import math
from dataclasses import dataclass

import numpy as np

from ..classes import DEFAULT_TOLERANCE, LengthClasses, length_classes
from ..errors import number
from ..mesh import G1, edge_lengths, single_edges
from ..metrics import triangle_angles

#: Classes drawn each as one line set in a colour of its own (the largest by member count); the other classes are
#: one grey line set.  A legend of more entries cannot be read, and every line set costs the browser a draw call.
MAX_DRAWN_CLASSES = 40

#: Colours of the drawn classes, cycled in order of length so that neighbouring classes differ: matplotlib's
#: "tab10" without its grey, which marks the classes not drawn on their own.
PALETTE = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#bcbd22", "#17becf")
REST_COLOUR = "#7f7f7f"
#: The outer boundary (solid) and the openings (dashed) are drawn in this colour, wider than the members.
BOUNDARY_COLOUR = "#000000"

#: Histogram bins of member length at most: bins are ``tolerance l`` wide, or a whole multiple of it when
#: the lengths span more than this many.
MAX_BINS = 2000
#: Width of the bins of the angle histogram, in degrees.
ANGLE_BIN = 1.0


@dataclass(frozen=True)
class Group:
    """Members drawn alike: one drawn length class, or every class not drawn on its own (``label`` says which)."""

    label: str
    colour: str
    members: np.ndarray  #: indices into the mesh's edges
    classes: tuple  #: the class ids of the group


@dataclass(frozen=True)
class MeshView:
    """A mesh as the report and the plot show it (see :func:`mesh_view`).

    Attributes
    ----------
    points : (N, 3) float, the nodes (planar meshes get z = 0).
    triangles : (M, 3) int.
    edges : (E, 2) int, the members.
    lengths : (E,) float, member lengths.
    l, tolerance : the target length and the class tolerance (relative to l).
    classes : LengthClasses of the members at ``tolerance``.
    groups : tuple of Group, the drawn classes in order of length, then the rest (if any).
    boundary, openings : (B, 2) and (O, 2) int, edges of the outer boundary and of the openings.
    n_g1 : members in the equal-length group G1.
    """

    points: np.ndarray
    triangles: np.ndarray
    edges: np.ndarray
    lengths: np.ndarray
    l: float
    tolerance: float
    classes: LengthClasses
    groups: tuple
    boundary: np.ndarray
    openings: np.ndarray
    n_g1: int

    @property
    def deviation(self):
        """Relative deviation of each member from l, ``(L - l) / l``."""
        return (self.lengths - self.l) / self.l

    def histogram(self):
        """``(edges, counts)``: bin edges of member length and the counts of each group, ``(len(groups), bins)``."""
        edges = length_bins(self.lengths, self.l, self.tolerance)
        counts = np.stack([np.histogram(self.lengths[g.members], bins=edges)[0] for g in self.groups])
        return edges, counts

    def angle_histogram(self):
        """``(edges, counts)`` of the interior angles of the triangles in degrees, bins :data:`ANGLE_BIN` wide."""
        edges = np.arange(0.0, 180.0 + ANGLE_BIN / 2, ANGLE_BIN)
        return edges, np.histogram(triangle_angles(self.points, self.triangles), bins=edges)[0]


def mesh_view(mesh, tolerance=DEFAULT_TOLERANCE):
    """The :class:`MeshView` of a :class:`equimesh.SurfaceMesh` or :class:`equimesh.PlanarMesh` at ``tolerance``."""
    points = np.asarray(mesh.points, dtype=float)
    if points.shape[1] == 2:
        points = np.column_stack([points, np.zeros(len(points))])
    edges = np.asarray(mesh.edges, dtype=np.int64)
    lengths = edge_lengths(points, edges)
    classes = length_classes(lengths, mesh.length, tolerance)
    boundary, openings = boundary_edges(mesh.triangles, _outer_ring_size(mesh))
    return MeshView(
        points=points,
        triangles=np.asarray(mesh.triangles, dtype=np.int64),
        edges=edges,
        lengths=lengths,
        l=float(mesh.length),
        tolerance=classes.tolerance,
        classes=classes,
        groups=class_groups(classes),
        boundary=boundary,
        openings=openings,
        n_g1=int(np.count_nonzero(np.asarray(mesh.edge_groups) == G1)),
    )


def class_groups(classes, max_drawn=MAX_DRAWN_CLASSES):
    """The groups of :class:`MeshView`: the ``max_drawn`` largest classes in order of length, then the rest.

    When there are more than ``max_drawn`` classes, the ``max_drawn - 1``
    largest (ties: the shorter first) are drawn on their own and the others
    together.  Colours follow :data:`PALETTE` in order of length.
    """
    k = len(classes)
    if k <= max_drawn:
        drawn = np.arange(k)
    else:
        drawn = np.sort(classes.largest(max_drawn - 1))
    order = np.argsort(classes.member_class, kind="stable")
    starts = np.searchsorted(classes.member_class[order], np.arange(k + 1))
    members = [order[starts[c] : starts[c + 1]] for c in range(k)]
    groups = [
        Group(
            label=f"{number(classes.nominal[c], 6)} ({classes.count[c]})",
            colour=PALETTE[i % len(PALETTE)],
            members=members[c],
            classes=(int(c),),
        )
        for i, c in enumerate(drawn)
    ]
    rest = np.setdiff1d(np.arange(k), drawn)
    if rest.size:
        count = int(classes.count[rest].sum())
        groups.append(
            Group(
                label=f"{rest.size} smaller classes ({count})",
                colour=REST_COLOUR,
                members=np.sort(np.concatenate([members[c] for c in rest])),
                classes=tuple(int(c) for c in rest),
            )
        )
    return tuple(groups)


def length_bins(lengths, l, tolerance, max_bins=MAX_BINS):
    """Bin edges of member length: ``tolerance l`` wide (or a whole multiple of it), with l an edge; at most
    ``max_bins`` (at least 2) bins.

    The window ``l +- tolerance l`` of the run's tolerance is then two whole
    bins (one, when the width had to be widened to keep ``max_bins``).  The
    ends are rounded out to whole steps, which can add a bin: the step grows
    until they fit (a step as wide as the span leaves two bins at most).
    """
    lengths = np.asarray(lengths, dtype=float)
    lo, hi = (float(lengths.min()), float(lengths.max())) if lengths.size else (l, l)
    width = tolerance * l
    first, last = math.floor((lo - l) / width), math.ceil((hi - l) / width)
    last = max(last, first + 1)
    step = max(1, math.ceil((last - first) / max_bins))
    while (step * math.ceil(last / step) - step * math.floor(first / step)) // step > max_bins:
        step += 1
    first, last = step * math.floor(first / step), step * math.ceil(last / step)
    return l + width * np.arange(first, last + 1, step)


def boundary_edges(triangles, outer_ring_size):
    """``(outer, openings)``: the edges of exactly one triangle, on the outer boundary and on the openings.

    The meshes of equimesh number the outer boundary's nodes first
    (``outer_ring_size`` of them, :attr:`equimesh.SurfaceMesh.n_boundary`),
    so an edge of one triangle whose two nodes are among them is on the outer
    boundary, and any other on an opening.
    """
    border = np.unique(np.sort(single_edges(triangles), axis=1), axis=0)
    outer = (border < outer_ring_size).all(axis=1)
    return border[outer], border[~outer]


def _outer_ring_size(mesh):
    """Nodes on the outer boundary ring: the first ``boundary_rings`` entry of the planar mesh's info."""
    info = mesh.info if hasattr(mesh, "info") else mesh.stages.plane.info
    return int(info.get("boundary_rings", (mesh.n_boundary,))[0])
