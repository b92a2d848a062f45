"""DXF files (``.dxf``) out, with ezdxf: one 3-D line per member on a layer per length class, for CAD and CNC.

Each length class is a layer named by :attr:`Products.class_names
<equimesh.io._schedules.Products.class_names>` (``class 0 - 5.00012 - 312
members``); with ``dxf_labels`` each member's class id is also written as text
at its midpoint on the layer ``labels``, a tenth of l high.  DXF R2010.  The
same mesh gives the same bytes: ezdxf's creation and update times and its
random document ids are replaced by its fixed ones from creation to writing
(``ezdxf.options.write_fixed_meta_data_for_testing``), and the classes of the
entity types are registered in sorted order (docs/decisions.md, "Same input, same bytes").
"""

import contextlib

import numpy as np

#: The layer of the class labels.
LABELS_LAYER = "labels"

#: Height of a label, relative to l (docs/decisions.md, "Labels of a DXF file").
LABEL_HEIGHT = 0.1


def write_dxf(tmp, products):
    """Write ``products``' members (and with ``products.dxf_labels`` their classes as text) to the DXF file ``tmp``."""
    import ezdxf

    with _fixed_metadata(ezdxf):
        doc = _drawing(ezdxf, products)
        # ezdxf registers the class of each entity type in use in the order of a set of strings, which changes with
        # the interpreter's hash seed; registered first, in sorted order, they keep that order.
        for dxftype in sorted(doc.entitydb.dxf_types_in_use()):
            doc.classes.add_class(dxftype)
        doc.saveas(tmp)


def _drawing(ezdxf, products):
    mesh = products.mesh
    points = np.asarray(mesh.points, dtype=float)
    doc = ezdxf.new("R2010")
    msp = doc.modelspace()
    for name in products.class_names:
        doc.layers.add(name)
    if products.dxf_labels:
        doc.layers.add(LABELS_LAYER)
    height = LABEL_HEIGHT * float(mesh.length)
    for i, j, k in zip(*(products.members[c].tolist() for c in ("node_i", "node_j", "class"))):
        msp.add_line(points[i].tolist(), points[j].tolist(), dxfattribs={"layer": products.class_names[k]})
        if products.dxf_labels:
            middle = ((points[i] + points[j]) / 2).tolist()
            msp.add_text(str(k), height=height, dxfattribs={"layer": LABELS_LAYER}).set_placement(middle)
    return doc


@contextlib.contextmanager
def _fixed_metadata(ezdxf):
    """ezdxf's fixed times, ids and marker instead of the clock's and random ones, from the document's creation to
    its writing (both stamp it)."""
    before = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        yield
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = before
