"""The report (equimesh.write_report): one self-contained HTML page showing what the view holds, byte-stable."""

import json
import re
import sys

import numpy as np
import pytest
import report_meshes

import equimesh
from equimesh import MissingDependencyError, OutputPathError, length_classes
from equimesh.io import output_formats, write_report

roof_mesh = report_meshes.roof_mesh  # the shared fixture

pytest.importorskip("plotly", reason="the report needs plotly: pip install 'equimesh[report]'")

RECORD = {
    "git": {"commit": "0" * 40, "dirty": False},
    "date": "2026-01-01T00:00:00+00:00",
    "python": "3.11.0",
    "implementation": "cpython",
    "platform": "Linux",
    "versions": {"equimesh": "0.1.0"},
    "parameters": {"input": "roof.json", "length": 3.0},
}
#: A tolerance at which the roof has fewer classes than are drawn on their own (24 of at most 40).
TOLERANCE = 0.02


@pytest.fixture(scope="module")
def roof_report(roof_mesh, tmp_path_factory):
    path = tmp_path_factory.mktemp("report") / "roof.html"
    write_report(roof_mesh, path, tolerance=TOLERANCE, record=RECORD)
    return path.read_text(encoding="utf-8")


def report_data(text):
    """The JSON the page's script draws from."""
    match = re.search(r'<script type="application/json" id="report-data">(.*?)</script>', text, re.S)
    return json.loads(match.group(1))


def decoded(array):
    """A plotly data array: a list, or ``{"dtype", "bdata"}`` (base64 of the raw values)."""
    if isinstance(array, dict):
        import base64

        return np.frombuffer(base64.b64decode(array["bdata"]), dtype=array["dtype"])
    return np.asarray(array, dtype=float)


def test_the_page_needs_nothing_but_itself(roof_report):
    assert roof_report.startswith("<!DOCTYPE html>") and roof_report.rstrip().endswith("</html>")
    assert not re.search(r"<script[^>]*\bsrc\s*=", roof_report)  # every script inlined, plotly's included
    assert not re.search(r"<link\b|<img\b|<iframe\b|@import", roof_report)
    assert "Plotly.newPlot" in roof_report and "data-ready" not in roof_report.split("<body>")[0]
    assert list(output_formats("report")) == [".html"]


def test_the_view_draws_every_member_once_in_one_line_set_per_class_and_the_outline(roof_mesh, roof_report):
    data = report_data(roof_report)
    traces = data["figures"]["view"]["data"]
    members = [traces[i] for i in data["members"]]
    classes = length_classes(roof_mesh.edge_lengths(), roof_mesh.length, TOLERANCE)
    assert len(members) == len(classes)  # few classes: each one line set
    drawn = 0
    for trace, colour, k in zip(members, data["colours"], range(len(classes))):
        x, dev = decoded(trace["x"]), decoded(trace["customdata"])
        assert len(x) == 3 * classes.count[k] and np.isnan(x[2::3]).all() and trace["line"]["color"] == colour
        assert trace["name"] == f"{equimesh.errors.number(classes.nominal[k])} ({classes.count[k]})"
        lengths = roof_mesh.edge_lengths()[classes.member_class == k]
        assert np.allclose(np.sort(dev[::3]), np.sort((lengths - 3.0) / 3.0), atol=1e-6)
        drawn += classes.count[k]
    assert drawn == len(roof_mesh.edges)
    outline = {t["name"]: t for t in traces if t["name"] in ("boundary", "openings")}
    rings = roof_mesh.stages.plane.info["boundary_rings"]
    assert len(decoded(outline["boundary"]["x"])) == 3 * rings[0]
    assert len(decoded(outline["openings"]["x"])) == 3 * sum(rings[1:])
    assert outline["openings"]["line"]["dash"] == "dash"


def test_the_histogram_band_and_windows_and_the_tables(roof_mesh, roof_report):
    data = report_data(roof_report)
    lengths = data["figures"]["lengths"]
    assert sum(decoded(t["y"]).sum() for t in lengths["data"]) == len(roof_mesh.edges)
    bands = [(s["x0"], s["x1"]) for s in lengths["layout"]["shapes"]]
    assert (3.0, 6.0) in bands and pytest.approx((3.0 - 0.06, 3.0 + 0.06)) in bands
    assert len(bands) == 2 + len(data["members"])  # and one window per drawn class
    angles = data["figures"]["angles"]["data"][0]
    assert decoded(angles["y"]).sum() == 3 * len(roof_mesh.triangles)
    classes = length_classes(roof_mesh.edge_lengths(), 3.0, TOLERANCE)
    table = roof_report.split("<h2>Length classes</h2>")[1].split("</table>")[0]
    assert table.count("<tr>") == 1 + len(classes)
    for k in range(len(classes)):
        assert f"<td>{k}</td><td>{classes.count[k]}</td><td>{equimesh.errors.number(classes.nominal[k])}</td>" in table


def test_the_run_summary_and_the_provenance(roof_mesh, roof_report):
    run = roof_report.split("<h2>Run</h2>")[1].split("</table>")[0]
    assert f"<th>nodes</th><td>{len(roof_mesh.points)}</td>" in run
    assert f"<th>members</th><td>{len(roof_mesh.edges)}</td>" in run and "seconds: flattening" in run
    shown = roof_report.split("<h2>Provenance</h2>")[1]
    for text in ("parameter: input</th><td>roof.json", "2026-01-01T00:00:00+00:00", "0" * 40, "version: plotly"):
        assert text in shown
    assert "<title>equimesh report: roof.json</title>" in roof_report


def test_same_mesh_and_record_same_bytes_and_a_provenance_of_its_own_by_default(roof_mesh, roof_report, tmp_path):
    write_report(roof_mesh, tmp_path / "again.html", tolerance=TOLERANCE, record=RECORD)
    assert (tmp_path / "again.html").read_text(encoding="utf-8") == roof_report
    write_report(roof_mesh, tmp_path / "now.html", tolerance="1%")
    now = (tmp_path / "now.html").read_text(encoding="utf-8")
    assert "parameter: tolerance</th><td>1%" in now and "version: numpy" in now


def test_more_classes_than_drawn_are_one_grey_line_set_and_one_row(roof_mesh, tmp_path):
    from equimesh.io._view import MAX_DRAWN_CLASSES, REST_COLOUR

    write_report(roof_mesh, tmp_path / "fine.html", tolerance=1e-6, record=RECORD)
    text = (tmp_path / "fine.html").read_text(encoding="utf-8")
    data = report_data(text)
    assert len(data["members"]) == MAX_DRAWN_CLASSES and data["colours"][-1] == REST_COLOUR
    assert "smaller classes" in text.split("<h2>Length classes</h2>")[1]


def test_an_unwritable_folder_or_no_plotly_is_refused_before_anything_is_written(roof_mesh, tmp_path, monkeypatch):
    with pytest.raises(OutputPathError, match="does not exist"):
        write_report(roof_mesh, tmp_path / "missing" / "r.html")
    with pytest.raises(OutputPathError, match="unknown extension"):
        write_report(roof_mesh, tmp_path / "r.htm")
    monkeypatch.setitem(sys.modules, "plotly", None)
    with pytest.raises(MissingDependencyError, match=r"pip install 'equimesh\[report\]'"):
        write_report(roof_mesh, tmp_path / "r.html")
    assert list(tmp_path.iterdir()) == []
