"""The tables of a run (``io/_schedules.py``): the member schedule, the node schedule, the names of the classes."""

import itertools
from pathlib import Path

import numpy as np
import pytest

from equimesh import length_classes
from equimesh.io import Products, classes_path, member_schedule, node_schedule, output_formats
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


def test_member_schedule_of_one_triangle_row_by_row():
    """Each member's ends, length, group, class and deviation from l (here l = 0.5), in the documented columns."""
    lengths = [1.0, 1.0, np.sqrt(2.0)]
    classes = length_classes(lengths, 0.5, 0.01)
    table = member_schedule(_Triangle.points, _Triangle.edges.tolist(), _Triangle.edge_groups.tolist(), 0.5, classes)
    columns = ["member", "node_i", "node_j", "length", "group", "class", "deviation", "relative_deviation"]
    assert list(table.columns) == columns
    assert table["member"].tolist() == [0, 1, 2]
    assert table[["node_i", "node_j"]].to_numpy().tolist() == [[0, 1], [0, 2], [1, 2]]
    np.testing.assert_allclose(table["length"], lengths)
    assert table["class"].tolist() == [0, 0, 1]
    np.testing.assert_allclose(table["deviation"], [0.5, 0.5, np.sqrt(2.0) - 0.5])
    np.testing.assert_allclose(table["relative_deviation"], [1.0, 1.0, 2.0 * np.sqrt(2.0) - 1.0])
    assert "class" not in member_schedule(_Triangle.points, _Triangle.edges, _Triangle.edge_groups, 0.5)


def test_node_schedule_of_one_triangle():
    table = node_schedule((_Triangle.points * [1, 2, 3]).astype(int).tolist(), _Triangle.triangles, _Triangle.edges)
    assert list(table.columns) == ["node", "x", "y", "z", "boundary", "valence", "min_angle", "max_angle"]
    assert table["node"].tolist() == [0, 1, 2]
    coordinates = table[["x", "y", "z"]].to_numpy()
    assert coordinates.dtype == float and coordinates.tolist() == [[0, 0, 0], [1, 0, 0], [0, 2, 0]]
    assert table["boundary"].tolist() == [1, 1, 1] and table["valence"].tolist() == [2, 2, 2]
    np.testing.assert_allclose(table["min_angle"], [90.0, np.degrees(np.arctan(2.0)), np.degrees(np.arctan(0.5))])
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


def test_classes_go_beside_the_member_schedule():
    assert classes_path("out/roof.members.csv") == classes_path(Path("out/roof.members.csv"))
    assert str(classes_path("out/roof.members.csv")) == "out/roof.members.classes.csv"


def test_products_hold_what_they_were_given():
    plain = Products(_Triangle)
    assert (plain.dxf_labels, plain.parameters, plain.record) == (False, None, None)
    given = Products(_Triangle, 0.02, True, {"input": "t.json"}, {"date": "now"})
    assert (given.mesh, given.tolerance, given.dxf_labels) == (_Triangle, 0.02, True)
    assert (given.parameters, given.record) == ({"input": "t.json"}, {"date": "now"})


def test_the_csv_files_are_the_tables_without_an_index(tmp_path):
    """Node, member and classes CSV: a header of the columns, then one line per row; integers as integers (the
    boundary as 1 or 0) and floats as the shortest text that reads back to the same bits."""
    products = Products(_Triangle, 0.01)
    members = output_formats("members")[".csv"]
    files = {"m.csv": members.write, "c.csv": members.beside[0].write, "n.csv": output_formats("nodes")[".csv"].write}
    for name, write in files.items():
        write(tmp_path / name, products)
    lines = {name: (tmp_path / name).read_text().splitlines() for name in files}
    root2, off = repr(float(np.sqrt(2.0))), repr(float(np.sqrt(2.0) - 1.0))
    assert lines["m.csv"][0] == "member,node_i,node_j,length,group,class,deviation,relative_deviation"
    expected = ["0,0,1,1.0,G1,0,0.0,0.0", "1,0,2,1.0,G1,0,0.0,0.0", f"2,1,2,{root2},other,1,{off},{off}"]
    assert lines["m.csv"][1:] == expected
    assert lines["c.csv"][0] == ",".join(products.classes.table().columns) and len(lines["c.csv"]) == 3
    assert lines["n.csv"][0] == "node,x,y,z,boundary,valence,min_angle,max_angle"
    assert lines["n.csv"][1] == "0,0.0,0.0,0.0,1,2,90.0,90.0"
