"""Rhino files out (``io/_rhino_out.py``), read back with rhino3dm: the mesh, one line per member on the layer of its
length class, the nodes, each with its schedule row as user text."""

import numpy as np
import pytest
from conftest import TentMesh

from equimesh import length_classes
from equimesh.io import Products, write_surface_mesh
from equimesh.mesh import G1

TOLERANCE = 0.01


def read_back(mesh, folder):
    """rhino3dm and the model it reads of ``mesh`` written in ``folder`` (in the test itself, so that mutation
    testing sees which tests write)."""
    rhino3dm = pytest.importorskip("rhino3dm", reason="rhino3dm (the optional extra [rhino]) is not installed")
    path = folder / "roof.3dm"
    write_surface_mesh(mesh, path, tolerance=TOLERANCE)
    return rhino3dm, rhino3dm.File3dm.Read(str(path))


def objects_on(model, layer_name):
    layers = {layer.Index: layer.FullPath for layer in model.Layers}
    return [o for o in model.Objects if layers[o.Attributes.LayerIndex] == layer_name]


def test_the_mesh_reads_back(tent_mesh, tmp_path):
    rhino3dm, m = read_back(tent_mesh, tmp_path)
    (mesh,) = objects_on(m, "mesh")
    assert mesh.Attributes.Name == "mesh"
    geometry = mesh.Geometry
    assert isinstance(geometry, rhino3dm.Mesh)
    vertices = geometry.Vertices
    points = np.array([[p.X, p.Y, p.Z] for p in map(vertices.Point3dAt, range(len(vertices)))])
    np.testing.assert_array_equal(points, tent_mesh.points)  # the nodes to the last bit, as in the other formats
    faces = np.array([geometry.Faces[k][:3] for k in range(len(geometry.Faces))])
    np.testing.assert_array_equal(faces, tent_mesh.triangles)


def test_members_lie_on_the_layer_of_their_length_class(tent_mesh, tmp_path):
    """One sublayer of 'members' per class of equimesh.length_classes, named with its nominal length and count,
    holding exactly that class's members as lines between their nodes."""
    _, m = read_back(tent_mesh, tmp_path)
    classes = length_classes(tent_mesh.edge_lengths(), tent_mesh.length, TOLERANCE)
    names = Products(tent_mesh, TOLERANCE).class_names
    paths = [layer.FullPath for layer in m.Layers]
    assert [p for p in paths if p.startswith("members::")] == [f"members::{n}" for n in names]
    seen = 0
    for k, name in enumerate(names):
        lines = objects_on(m, f"members::{name}")
        assert len(lines) == classes.count[k] and f" - {classes.count[k]} members" in name
        for line in lines:
            member = int(line.Attributes.GetUserString("member"))
            i, j = tent_mesh.edges[member]
            assert classes.member_class[member] == k == int(line.Attributes.GetUserString("class"))
            assert float(line.Attributes.GetUserString("length")) == tent_mesh.edge_lengths()[member]
            assert line.Attributes.Name == f"member {member}"
            assert line.Attributes.GetUserString("group") == ("G1" if tent_mesh.edge_groups[member] == G1 else "other")
            ends = [line.Geometry.PointAtStart, line.Geometry.PointAtEnd]
            np.testing.assert_allclose([[p.X, p.Y, p.Z] for p in ends], tent_mesh.points[[i, j]])
        seen += len(lines)
    assert seen == len(tent_mesh.edges)


def test_nodes_are_points_with_their_figures(tent_mesh, tmp_path):
    _, m = read_back(tent_mesh, tmp_path)
    nodes = objects_on(m, "nodes")
    assert len(nodes) == len(tent_mesh.points)
    table = Products(tent_mesh).nodes
    for node in nodes:
        k = int(node.Attributes.GetUserString("node"))
        assert node.Attributes.Name == f"node {k}"
        p = node.Geometry.Location
        np.testing.assert_array_equal([p.X, p.Y, p.Z], tent_mesh.points[k])
        assert int(node.Attributes.GetUserString("valence")) == table["valence"][k]
        assert int(node.Attributes.GetUserString("boundary")) == (k < tent_mesh.n_boundary)
        assert float(node.Attributes.GetUserString("min_angle")) == table["min_angle"][k]
        assert float(node.Attributes.GetUserString("max_angle")) == table["max_angle"][k]


def test_every_layer_and_object_has_its_own_id_made_from_the_mesh(tent_mesh, tmp_path):
    """The ids depend on the mesh's nodes and triangles, not on their types: integer coordinates or 32-bit
    triangles give the same file."""
    rhino3dm, m = read_back(tent_mesh, tmp_path)
    ids = [layer.Id for layer in m.Layers] + [o.Attributes.Id for o in m.Objects]
    assert len(ids) == len(set(ids)) == len(m.Layers) + len(m.Objects)
    mesh = TentMesh()
    mesh.points = np.round(4 * mesh.points)
    write_surface_mesh(mesh, tmp_path / "float.3dm")
    mesh.points, mesh.triangles = mesh.points.astype(int), mesh.triangles.astype(np.int32)
    write_surface_mesh(mesh, tmp_path / "int.3dm")
    assert (tmp_path / "float.3dm").read_bytes() == (tmp_path / "int.3dm").read_bytes()
    other = rhino3dm.File3dm.Read(str(tmp_path / "float.3dm"))
    assert not {layer.Id for layer in other.Layers} & set(ids)  # another mesh, other ids
