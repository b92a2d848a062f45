"""The tables every output of a run is written from: the member schedule, its length classes, the node schedule.

:class:`Products` holds a mesh, the fabrication tolerance and the writers'
options, and computes each table once, when the first output asks for it; every
writer of the registry (``io/_outputs.py``) takes the temporary file to fill and
a :class:`Products`.  The three CSV files (member schedule, classes, nodes) are
written here; floats are written as the shortest text that reads back to the
same bits (pandas' default), so a schedule read back regroups alike.
"""

from functools import cached_property
from pathlib import Path

import numpy as np
import pandas as pd

from ..classes import DEFAULT_TOLERANCE, length_classes
from ..errors import number
from ..mesh import G1, edge_lengths
from ..metrics import NODE_COLUMNS, node_figures

#: The classes CSV of a member schedule ``m.csv`` is ``m.classes.csv`` (:func:`classes_path`).
CLASSES_SUFFIX = ".classes.csv"


def member_schedule(points, edges, groups, l, classes=None):
    """The member schedule: one row per edge with its nodes, length, group, class and deviation from l.

    ``classes`` (:class:`equimesh.classes.LengthClasses` of these edges) adds
    the column ``class``, each member's length class.
    """
    e = np.asarray(edges)
    length = edge_lengths(points, e)
    columns = {
        "member": np.arange(len(e)),
        "node_i": e[:, 0],
        "node_j": e[:, 1],
        "length": length,
        "group": np.where(np.asarray(groups) == G1, "G1", "other"),
    }
    if classes is not None:
        columns["class"] = classes.member_class
    columns.update({"deviation": length - l, "relative_deviation": (length - l) / l})
    return pd.DataFrame(columns)


def node_schedule(points, triangles, edges):
    """The node schedule: one row per node with its id, coordinates and :func:`equimesh.metrics.node_figures`
    (``boundary`` as 1 or 0, angles in degrees)."""
    p = np.asarray(points, dtype=float)
    figures = node_figures(p, triangles, edges)
    columns = {"node": np.arange(len(p)), "x": p[:, 0], "y": p[:, 1], "z": p[:, 2]}
    columns.update({name: figures[name] for name in NODE_COLUMNS})
    columns["boundary"] = columns["boundary"].astype(np.int8)
    return pd.DataFrame(columns)


def classes_path(members):
    """Where the classes CSV of the member schedule ``members`` goes: ``<stem>.classes.csv`` beside it."""
    members = Path(members)
    return members.with_name(members.stem + CLASSES_SUFFIX)


class Products:
    """A mesh and everything its outputs are written from, each table computed on first use.

    Parameters
    ----------
    mesh
        an object with ``points`` (N, 3), ``triangles`` (M, 3), ``edges``
        (E, 2), ``edge_groups`` (E,) and ``length`` (l), e.g. a
        :class:`equimesh.SurfaceMesh`.
    tolerance : float
        the fabrication tolerance of the length classes, relative to l.
    dxf_labels : bool
        write each member's class as text in a DXF file.
    parameters : dict, optional
        what the run was given (input file, options), shown by the report.
    record : dict, optional
        the run's provenance record (:func:`equimesh.io.provenance.provenance`) for the report; made from
        ``parameters`` when None.
    """

    def __init__(self, mesh, tolerance=DEFAULT_TOLERANCE, dxf_labels=False, parameters=None, record=None):
        self.mesh, self.tolerance, self.dxf_labels = mesh, tolerance, dxf_labels
        self.parameters, self.record = parameters, record

    @cached_property
    def classes(self):
        """:class:`equimesh.classes.LengthClasses` of the members at the tolerance."""
        return length_classes(edge_lengths(self.mesh.points, self.mesh.edges), self.mesh.length, self.tolerance)

    @cached_property
    def members(self):
        """:func:`member_schedule` with the ``class`` column."""
        m = self.mesh
        return member_schedule(m.points, m.edges, m.edge_groups, m.length, self.classes)

    @cached_property
    def nodes(self):
        """:func:`node_schedule`."""
        return node_schedule(self.mesh.points, self.mesh.triangles, self.mesh.edges)

    @cached_property
    def class_names(self):
        """One name per length class, for the layers of CAD files: ``class 3 - 5.00213 - 42 members`` (id, nominal
        length, count; no character a DXF or Rhino layer name may not hold)."""
        c = self.classes
        return [f"class {k} - {number(c.nominal[k])} - {c.count[k]} members" for k in range(len(c))]


def write_members_csv(tmp, products):
    products.members.to_csv(tmp, index=False)


def write_classes_csv(tmp, products):
    products.classes.table().to_csv(tmp, index=False)


def write_nodes_csv(tmp, products):
    products.nodes.to_csv(tmp, index=False)
