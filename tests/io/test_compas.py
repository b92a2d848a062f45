"""COMPAS mesh JSON out (``io/_compas.py``), read back with compas.json_load: a valid compas Mesh whose edges carry
the member schedule and whose vertices carry the node schedule."""

import json

import numpy as np
import pytest
from conftest import TentMesh

from equimesh import length_classes
from equimesh.io import Products, write_surface_mesh

TOLERANCE = 0.01


def written(mesh, folder):
    """compas and the file of ``mesh`` written in ``folder`` (in the test itself, so that mutation testing sees
    which tests write)."""
    compas = pytest.importorskip("compas", reason="compas (the optional extra [compas]) is not installed")
    path = folder / "roof.compas.json"
    write_surface_mesh(mesh, path, tolerance=TOLERANCE)
    return compas, path


def test_the_file_is_a_valid_compas_mesh(tent_mesh, tmp_path):
    compas, path = written(tent_mesh, tmp_path)
    from compas.datastructures import Mesh

    mesh = compas.json_load(str(path))
    assert isinstance(mesh, Mesh)
    document = json.loads(path.read_text())
    assert document["dtype"] == "compas.datastructures/Mesh" and "guid" not in document
    Mesh.validate_data(document["data"])  # raises on a schema violation
    np.testing.assert_array_equal([mesh.vertex_coordinates(v) for v in mesh.vertices()], tent_mesh.points)
    np.testing.assert_array_equal([mesh.face_vertices(f) for f in mesh.faces()], tent_mesh.triangles)
    assert mesh.attributes["length"] == tent_mesh.length and mesh.attributes["tolerance"] == TOLERANCE


def test_edges_carry_the_member_schedule(tent_mesh, tmp_path):
    compas, path = written(tent_mesh, tmp_path)
    mesh = compas.json_load(str(path))
    classes = length_classes(tent_mesh.edge_lengths(), tent_mesh.length, TOLERANCE)
    members = Products(tent_mesh, TOLERANCE).members
    assert sorted(tuple(sorted(e)) for e in mesh.edges()) == [tuple(e) for e in tent_mesh.edges.tolist()]
    for row in members.itertuples():
        edge = (row.node_i, row.node_j)
        assert mesh.edge_attribute(edge, "member") == row.member
        assert mesh.edge_attribute(edge, "length") == row.length
        assert mesh.edge_attribute(edge, "class") == classes.member_class[row.member]
        assert mesh.edge_attribute(edge, "group") == row.group


def test_vertices_carry_the_node_schedule(tent_mesh, tmp_path):
    compas, path = written(tent_mesh, tmp_path)
    mesh = compas.json_load(str(path))
    nodes = Products(tent_mesh).nodes
    assert [mesh.vertex_attribute(v, "boundary") for v in mesh.vertices()] == nodes["boundary"].astype(bool).tolist()
    assert [mesh.vertex_attribute(v, "valence") for v in mesh.vertices()] == nodes["valence"].tolist()
    assert [mesh.vertex_degree(v) for v in mesh.vertices()] == nodes["valence"].tolist()
    assert [mesh.vertex_attribute(v, "min_angle") for v in mesh.vertices()] == nodes["min_angle"].tolist()
    assert [mesh.vertex_attribute(v, "max_angle") for v in mesh.vertices()] == nodes["max_angle"].tolist()
    assert [mesh.is_vertex_on_boundary(v) for v in mesh.vertices()] == nodes["boundary"].astype(bool).tolist()


def test_the_json_holds_booleans_and_floats_whatever_the_mesh_holds(tent_mesh, tmp_path):
    """``boundary`` is a JSON boolean; integer coordinates are written as the floats they are."""
    _, path = written(tent_mesh, tmp_path)
    vertices = json.loads(path.read_text())["data"]["vertex"]
    flags = [vertices[str(v)]["boundary"] for v in range(7)]
    assert flags == [True] * 6 + [False] and {type(f) for f in flags} == {bool}
    mesh = TentMesh()
    mesh.points = np.round(4 * mesh.points)
    write_surface_mesh(mesh, tmp_path / "float.compas.json")
    mesh.points = mesh.points.astype(int)
    write_surface_mesh(mesh, tmp_path / "int.compas.json")
    assert (tmp_path / "float.compas.json").read_bytes() == (tmp_path / "int.compas.json").read_bytes()
