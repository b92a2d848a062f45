"""COMPAS mesh JSON (``.compas.json``) out: a ``compas.datastructures.Mesh`` with the schedules as attributes.

The file is what ``compas.json_dump`` writes of the mesh and ``compas.json_load``
reads back (``{"dtype": "compas.datastructures/Mesh", "data": {...}}``, checked
against ``Mesh.DATASCHEMA``): vertices with ``x``, ``y``, ``z`` and the node
schedule's ``boundary`` (a bool), ``valence``, ``min_angle`` and ``max_angle``;
the triangles as faces; on each edge the member schedule's ``length``,
``class`` and ``group`` (and ``member``, its row); the mesh's attributes
``length`` (l) and ``tolerance``.  Written without COMPAS's random ``guid``, so
that the same mesh gives the same bytes (docs/decisions.md, "Same input, same bytes").
"""

import numpy as np

#: Member schedule columns written as edge attributes.
EDGE_ATTRIBUTES = ("member", "length", "class", "group")

#: Node schedule columns written as vertex attributes.
VERTEX_ATTRIBUTES = ("boundary", "valence", "min_angle", "max_angle")


def write_compas(tmp, products):
    """Write ``products``' mesh as a COMPAS mesh JSON file ``tmp``."""
    import compas
    from compas.datastructures import Mesh

    mesh = products.mesh
    out = Mesh.from_vertices_and_faces(
        np.asarray(mesh.points, dtype=float).tolist(), np.asarray(mesh.triangles).tolist()
    )
    out.attributes.update(length=float(mesh.length), tolerance=float(products.tolerance))
    nodes = products.nodes.assign(boundary=products.nodes["boundary"].astype(bool))
    for row in nodes[["node", *VERTEX_ATTRIBUTES]].to_dict("records"):
        out.vertex_attributes(row.pop("node"), list(row), list(row.values()))
    for row in products.members[["node_i", "node_j", *EDGE_ATTRIBUTES]].to_dict("records"):
        out.edge_attributes((row.pop("node_i"), row.pop("node_j")), list(row), list(row.values()))
    compas.json_dump(out, str(tmp), minimal=True)
