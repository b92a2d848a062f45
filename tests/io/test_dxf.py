"""DXF out (``io/_dxf.py``), read back with ezdxf: one 3-D line per member on the layer of its length class, and with
labels the class as text at each member's midpoint."""

import numpy as np
import pytest
from conftest import TentMesh

from equimesh import length_classes
from equimesh.io import Products, write_surface_mesh
from equimesh.io._dxf import LABELS_LAYER

TOLERANCE = 0.01


def drawing(mesh, folder, labels):
    """The drawing ezdxf reads of ``mesh`` written in ``folder`` (in the test itself, so that mutation testing sees
    which tests write)."""
    ezdxf = pytest.importorskip("ezdxf", reason="ezdxf (the optional extra [dxf]) is not installed")
    path = folder / "roof.dxf"
    write_surface_mesh(mesh, path, tolerance=TOLERANCE, dxf_labels=labels)
    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors  # a drawing CAD programs open
    return doc


LABELS = pytest.mark.parametrize("labels", [False, True], ids=["plain", "labels"])


@LABELS
def test_members_are_lines_on_the_layer_of_their_class(tent_mesh, tmp_path, labels):
    doc = drawing(tent_mesh, tmp_path, labels)
    classes = length_classes(tent_mesh.edge_lengths(), tent_mesh.length, TOLERANCE)
    names = Products(tent_mesh, TOLERANCE).class_names
    assert set(names) <= {layer.dxf.name for layer in doc.layers}
    lines = doc.modelspace().query("LINE")
    assert len(lines) == len(tent_mesh.edges)
    ends = {(tuple(line.dxf.start), tuple(line.dxf.end)): line.dxf.layer for line in lines}
    for member, (i, j) in enumerate(tent_mesh.edges):
        key = (tuple(tent_mesh.points[i]), tuple(tent_mesh.points[j]))
        assert ends[key] == names[classes.member_class[member]]
    for k, name in enumerate(names):
        assert len(doc.modelspace().query(f'LINE[layer=="{name}"]')) == classes.count[k]


@LABELS
def test_labels_give_each_member_its_class_at_its_midpoint(tent_mesh, tmp_path, labels):
    doc = drawing(tent_mesh, tmp_path, labels)
    texts = doc.modelspace().query("TEXT")
    if not labels:
        assert len(texts) == 0
        return
    classes = length_classes(tent_mesh.edge_lengths(), tent_mesh.length, TOLERANCE)
    assert len(texts) == len(tent_mesh.edges) and {t.dxf.layer for t in texts} == {LABELS_LAYER}
    middles = (tent_mesh.points[tent_mesh.edges[:, 0]] + tent_mesh.points[tent_mesh.edges[:, 1]]) / 2
    placed = {tuple(np.round(t.dxf.insert, 9)): t.dxf.text for t in texts}
    for member, middle in enumerate(middles):
        assert placed[tuple(np.round(middle, 9))] == str(classes.member_class[member])


def test_a_dxf_r2010_drawing_with_labels_a_tenth_of_l_high(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    mesh = TentMesh()
    mesh.points, mesh.length = 2.5 * mesh.points, 2.5
    write_surface_mesh(mesh, tmp_path / "big.dxf", tolerance=TOLERANCE, dxf_labels=True)
    doc = ezdxf.readfile(tmp_path / "big.dxf")
    assert doc.dxfversion == "AC1024"  # R2010
    texts = doc.modelspace().query("TEXT")
    assert len(texts) == len(mesh.edges) and [t.dxf.height for t in texts] == pytest.approx([0.25] * len(texts))


def test_the_classes_in_use_come_first_in_sorted_order(tent_mesh, tmp_path):
    """Not in the order of a set of strings, which changes with the interpreter's hash seed."""
    doc = drawing(tent_mesh, tmp_path, labels=True)
    names = [c.dxf.name for c in doc.classes]
    in_use = sorted(set(doc.entitydb.dxf_types_in_use()) & set(names))
    assert len(in_use) > 1 and names[: len(in_use)] == in_use
