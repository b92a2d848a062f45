"""Rhino files (``.3dm``) out, with rhino3dm: the mesh, one line per member on a layer per length class, the nodes.

Layers: ``mesh`` (the triangle mesh), ``nodes`` (one point per node, named
``node k``), and ``members`` with one sublayer per length class, named by
:attr:`Products.class_names <equimesh.io._schedules.Products.class_names>`
(``members::class 0 - 5.00012 - 312 members``), holding one line per member
(named ``member k``).  Each member and node carries the columns of its row of
the member or node schedule that identify it (:data:`MEMBER_TEXT`,
:data:`NODE_TEXT`) as user text (``GetUserString("length")``), floats as the
shortest text that reads back to the same bits.

The same mesh gives the same bytes: every layer and object has an id derived
from the mesh (a name-based UUID), the file is encoded in memory (a file
written by its name would hold that name, the temporary one), and its revision
history carries no time (docs/decisions.md, "Same input, same bytes").
"""

import base64
import hashlib
import uuid

import numpy as np

#: Member schedule columns each member line carries as user text (the rest is in the schedule's CSV).
MEMBER_TEXT = ("member", "class", "group", "length")

#: Node schedule columns each node point carries as user text.
NODE_TEXT = ("node", "boundary", "valence", "min_angle", "max_angle")

#: The namespace of the name-based ids of layers and objects.
_NAMESPACE = uuid.UUID("5f1c9a8e-3b1d-5a47-9c55-0d6e2f0b8a31")


def write_3dm(tmp, products):
    """Write ``products``' mesh, members and nodes to the Rhino file ``tmp``."""
    import rhino3dm

    mesh = products.mesh
    points = np.asarray(mesh.points, dtype=float)
    digest = hashlib.sha256(points.tobytes() + np.asarray(mesh.triangles, dtype=np.int64).tobytes()).hexdigest()

    def ident(name):
        return uuid.uuid5(_NAMESPACE, f"{digest} {name}")

    model = rhino3dm.File3dm()
    model.Revision = 1  # a first revision already: writing then stamps no creation and edit times

    def layer(name, parent=None):
        new = rhino3dm.Layer()
        new.Name, new.Id = name, ident(f"layer {parent} {name}")
        if parent is not None:
            new.ParentLayerId = model.Layers[parent].Id
        return model.Layers.Add(new)

    def attributes(index, name, values):
        a = rhino3dm.ObjectAttributes()
        a.LayerIndex, a.Name, a.Id = index, name, ident(name)
        for key, value in values.items():
            a.SetUserString(key, str(value))
        return a

    surface = rhino3dm.Mesh()
    for x, y, z in points.tolist():
        surface.Vertices.AddPoint3d(x, y, z)
    for i, j, k in np.asarray(mesh.triangles).tolist():
        surface.Faces.AddFace(i, j, k)
    model.Objects.AddMesh(surface, attributes(layer("mesh"), "mesh", {}))

    members = layer("members")
    classes = [layer(name, members) for name in products.class_names]
    ends = products.members[["node_i", "node_j"]].to_numpy()
    for (i, j), row in zip(ends, products.members[list(MEMBER_TEXT)].to_dict("records")):
        line = attributes(classes[row["class"]], f"member {row['member']}", row)
        model.Objects.AddLine(rhino3dm.Point3d(*points[i]), rhino3dm.Point3d(*points[j]), line)
    nodes = layer("nodes")
    for p, row in zip(points, products.nodes[list(NODE_TEXT)].to_dict("records")):
        model.Objects.AddPoint(rhino3dm.Point3d(*p), attributes(nodes, f"node {row['node']}", row))
    tmp.write_bytes(base64.b64decode(model.Encode()))
