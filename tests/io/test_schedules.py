"""The tables of a run (``io/_schedules.py``): the member schedule, the node schedule, the names of the classes."""

import itertools

import numpy as np
import pytest

from equimesh import length_classes
from equimesh.io import Products, member_schedule, node_schedule
from equimesh.mesh import G1, OTHER


class _Triangle:
    points = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    triangles = np.array([[0, 1, 2]])
    edges = np.array([[0, 1], [0, 2], [1, 2]])
    edge_groups = np.array([G1, G1, OTHER])
    length = 1.0


def test_member_groups_follow_the_g1_constant():
    table = member_schedule(_Triangle.points, _Triangle.edges, _Triangle.edge_groups, 1.0)
    assert list(table["group"]) == ["G1", "G1", "other"]
    np.testing.assert_allclose(table["deviation"], [0.0, 0.0, np.sqrt(2.0) - 1.0])


def test_node_schedule_of_one_triangle():
    table = node_schedule(_Triangle.points, _Triangle.triangles, _Triangle.edges)
    assert list(table.columns) == ["node", "x", "y", "z", "boundary", "valence", "min_angle", "max_angle"]
    assert table["boundary"].tolist() == [1, 1, 1] and table["valence"].tolist() == [2, 2, 2]
    np.testing.assert_allclose(table["min_angle"], [90.0, 45.0, 45.0])
    np.testing.assert_allclose(table["max_angle"], table["min_angle"])


def test_node_schedule_agrees_with_the_mesh_and_its_members(tent_mesh):
    """Boundary nodes are the mesh's first n_boundary; valences count the members; angles are those of every pair
    of members at the node, measured one by one."""
    mesh = tent_mesh
    table = node_schedule(mesh.points, mesh.triangles, mesh.edges)
    assert np.flatnonzero(table["boundary"]).tolist() == list(range(mesh.n_boundary))
    assert table["valence"].sum() == 2 * len(mesh.edges)
    for node in range(len(mesh.points)):
        ends = [j for i, j in mesh.edges if i == node] + [i for i, j in mesh.edges if j == node]
        angles = [
            np.degrees(np.arccos(np.dot(a, b) / np.linalg.norm(a) / np.linalg.norm(b)))
            for a, b in itertools.combinations(mesh.points[ends] - mesh.points[node], 2)
        ]
        assert table["min_angle"][node] == pytest.approx(min(angles), abs=1e-9)
        assert table["max_angle"][node] == pytest.approx(max(angles), abs=1e-9)


def test_class_names_name_each_class_with_its_nominal_length_and_count(tent_mesh):
    products = Products(tent_mesh, 0.01)
    classes = length_classes(tent_mesh.edge_lengths(), tent_mesh.length, 0.01)
    assert len(products.class_names) == len(classes) == len(set(products.class_names))
    for k, name in enumerate(products.class_names):
        assert name.startswith(f"class {k} - ") and name.endswith(f" - {classes.count[k]} members")
        assert float(name.split(" - ")[1]) == pytest.approx(classes.nominal[k], rel=1e-5)
    assert products.members["class"].tolist() == classes.member_class.tolist()
