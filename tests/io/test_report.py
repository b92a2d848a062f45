"""The report (equimesh.write_report): one self-contained HTML page showing what the view holds, byte-stable.

The meshes are small (a fan of a dozen spokes, the square with an opening) and every test writes its page itself, so
that one page costs a fraction of a second; the browser tests (test_report_browser.py) open the roof's.
"""

import html
import json
import re
import sys
from types import SimpleNamespace

import numpy as np
import pytest
import report_meshes

from equimesh import MissingDependencyError, OutputPathError, length_classes
from equimesh.errors import number
from equimesh.io import output_formats, write_report
from equimesh.io._report import _script_json
from equimesh.io._view import BOUNDARY_COLOUR, REST_COLOUR, mesh_view
from equimesh.mesh import G1, OTHER, unique_edges
from equimesh.metrics import summary_rows

square_mesh = report_meshes.square_mesh  # the shared fixture

plotly = pytest.importorskip("plotly", reason="the report needs plotly: pip install 'equimesh[report]'")

RECORD = {
    "git": {"commit": "0" * 40, "dirty": False},
    "date": "2026-01-01T00:00:00+00:00",
    "python": "3.11.0",
    "implementation": "cpython",
    "platform": "Linux",
    "versions": {"equimesh": "0.1.0", "gone": None},
    "parameters": {"input": "roof.json", "length": 1.5, "grid": [8, 8]},
}
TOLERANCE = 0.02


def fan(n=12):
    """``n`` spokes from an apex at height 1 to a ring of growing radius, its nodes at heights 0 and 0.3 in turn;
    l = 1.5, the spokes G1, the time of two stages."""
    k = np.arange(n)
    radii = 1.0 + 0.02 * k
    ring = np.column_stack([radii * np.cos(2 * np.pi * k / n), radii * np.sin(2 * np.pi * k / n), 0.3 * (k % 2)])
    triangles = np.array([[i, (i + 1) % n, n] for i in range(n)])
    edges = unique_edges(triangles)
    return SimpleNamespace(
        points=np.vstack([ring, [0.0, 0.0, 1.0]]),
        triangles=triangles,
        edges=edges,
        edge_groups=np.where(edges[:, 1] == n, G1, OTHER).astype(np.int8),
        length=1.5,
        n_boundary=n,
        info={},
        stages=SimpleNamespace(seconds={"flattening": 0.25, "optimisation": 1.5}),
    )


def triangle(apex):
    """One triangle on the side from (0, 0, 0) to (1, 0, 0) with its third node at ``apex``, l = 1."""
    return SimpleNamespace(
        points=np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], apex]),
        triangles=np.array([[0, 1, 2]]),
        edges=np.array([[0, 1], [0, 2], [1, 2]]),
        edge_groups=np.zeros(3, np.int8),
        length=1.0,
        n_boundary=3,
        info={},
    )


def page(mesh, tmp_path, name="r.html", **kwargs):
    """The text of ``mesh``'s report, written in the test itself (so that mutation testing sees which tests
    write)."""
    write_report(mesh, tmp_path / name, **{"tolerance": TOLERANCE, "record": RECORD, **kwargs})
    return (tmp_path / name).read_text(encoding="utf-8")


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


def section(text, heading):
    return text.split(f"<h2>{heading}</h2>")[1].split("</section>")[0]


def test_the_page_needs_nothing_but_itself_and_holds_what_its_script_reads(tmp_path):
    text = page(fan(), tmp_path)
    assert text.startswith('<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n')
    assert text.endswith("</script>\n</body>\n</html>\n")
    assert not re.search(r"<script[^>]*\bsrc\s*=", text)  # every script inlined, plotly's included
    assert not re.search(r"<link\b|<img\b|<iframe\b|@import", text)
    assert "Plotly.newPlot" in text and "data-ready" not in text.split("<body>")[0]
    assert (
        '<meta charset="utf-8">\n<meta name="viewport" content="width=device-width, initial-scale=1">\n<title>' in text
    )
    assert "</script>\n</head>\n<body>\n<h1>" in text
    assert (
        "</section>\n<section><h2>Member lengths</h2>" in text
        and "</section>\n<section><h2>Triangle angles</h2>" in text
    )
    assert "<style>\n/* The report's page" in text and "\n<script>\n" in text  # the style and the script inlined
    for ident in ("view", "lengths", "angles"):
        assert f'<div id="{ident}" class="figure"' in text
    assert '<div id="view" class="figure" style="height: 640px"></div>' in text
    controls = section(text, "The mesh").split("<div")[0]
    assert controls == (
        '<p class="controls">Colour members by '
        '<label><input type="radio" name="colour" value="class" checked> length class</label> '
        '<label><input type="radio" name="colour" value="deviation"> deviation from l</label>'
        " &middot; drag to rotate, scroll to zoom, click a legend entry to hide it</p>"
    )
    headings = re.findall(r"<section><h2>([^<]*)</h2>", text)
    assert headings == ["The mesh", "Member lengths", "Length classes", "Triangle angles", "Run", "Provenance"]
    assert list(output_formats("report")) == [".html"]


def test_the_title_and_the_lead(tmp_path):
    mesh = fan()
    text = page(mesh, tmp_path, record={**RECORD, "parameters": {"input": "<roof> & co.json"}})
    assert "<title>equimesh report: &lt;roof&gt; &amp; co.json</title>" in text
    assert "<h1>&lt;roof&gt; &amp; co.json</h1>" in text
    view = mesh_view(mesh, TOLERANCE)
    lead = (
        f"13 nodes, 24 members (12 in the equal-length group G1), 12 triangles at l = 1.5; {len(view.classes)} "
        "length classes at +-2 % of l."
    )
    assert f'<p class="lead">{lead}</p>' in text
    assert "<title>equimesh report: mesh</title>" in page(mesh, tmp_path, record={**RECORD, "parameters": {}})


def test_the_view_draws_every_member_once_in_one_line_set_per_class_and_the_outline(square_mesh, tmp_path):
    mesh = square_mesh
    data = report_data(page(mesh, tmp_path))
    figure = data["figures"]["view"]
    traces = figure["data"]
    classes = length_classes(mesh.edge_lengths(), mesh.length, TOLERANCE)
    members = [traces[i] for i in data["members"]]
    assert data["members"] == list(range(len(classes)))  # few classes: each one line set
    drawn = 0
    for trace, colour, k in zip(members, data["colours"], range(len(classes))):
        x, dev = decoded(trace["x"]), decoded(trace["customdata"])
        assert (
            len(x) == 3 * classes.count[k]
            and np.isnan(x[2::3]).all()
            and trace["line"] == {"color": colour, "width": 3}
        )
        assert trace["name"] == f"{number(classes.nominal[k])} ({classes.count[k]})" and trace["mode"] == "lines"
        lengths = mesh.edge_lengths()[classes.member_class == k]
        assert np.allclose(np.sort(dev[::3]), np.sort((lengths - 1.0) / 1.0), atol=1e-6) and dev.dtype == np.float32
        assert trace["hovertemplate"] == "deviation from l: %{customdata:+.3%}<extra>%{fullData.name}</extra>"
        assert trace["legendgroup"] == "classes"
        assert trace["legendgrouptitle"] == {"text": "classes: nominal (members)"}
        drawn += classes.count[k]
    assert drawn == len(mesh.edges)
    outline = {t["name"]: t for t in traces if t["name"] in ("boundary", "openings")}
    outer, opening = mesh.info["boundary_rings"]
    assert len(decoded(outline["boundary"]["x"])) == 3 * outer
    assert len(decoded(outline["openings"]["x"])) == 3 * opening
    for name, dash in (("boundary", "solid"), ("openings", "dash")):
        assert outline[name]["line"] == {"color": BOUNDARY_COLOUR, "width": 7, "dash": dash}
        assert outline[name]["legendgroup"] == "outline" and outline[name]["hoverinfo"] == "skip"
        assert outline[name]["legendgrouptitle"] == {"text": "outline"}
    layout = figure["layout"]
    assert layout["margin"] == {"l": 0, "r": 0, "t": 36, "b": 0} and layout["uirevision"] == "view"
    assert layout["legend"] == {"itemsizing": "constant", "groupclick": "toggleitem", "y": 1.0}
    scene = layout["scene"]
    assert scene["aspectmode"] == "manual" and scene["camera"] == {"eye": {"x": 0.85, "y": -0.85, "z": 0.65}}
    assert scene["aspectratio"] == {"x": 1.0, "y": 1.0, "z": 0.05}  # a flat square: a thin box, not a plane
    assert [scene[f"{a}axis"]["title"]["text"] for a in "xyz"] == ["x", "y", "z"]
    assert plotly_white(figure)


def plotly_white(figure):
    """Whether ``figure`` (as the page holds it) is drawn with plotly's "plotly_white" template."""
    return figure["layout"]["template"] == plotly.io.templates["plotly_white"].to_plotly_json()


def test_the_scene_has_the_mesh_proportions(tmp_path):
    """Whatever the mesh's size: a tenth of the fan is in the same box."""
    mesh = fan()
    small = SimpleNamespace(**vars(mesh) | {"points": mesh.points / 10, "length": 0.15})
    for m, name in ((mesh, "fan.html"), (small, "small.html")):
        ratio = report_data(page(m, tmp_path, name=name))["figures"]["view"]["layout"]["scene"]["aspectratio"]
        span = np.ptp(m.points, axis=0)
        np.testing.assert_allclose([ratio[a] for a in "xyz"], span / span.max())
    line = report_data(page(mesh, tmp_path))["figures"]["view"]["data"][0]
    first = decoded(line["x"])[:3], decoded(line["y"])[:3], decoded(line["z"])[:3]
    members = mesh_view(mesh, TOLERANCE).groups[0].members
    i, j = mesh.edges[members[0]]
    np.testing.assert_allclose(np.array(first)[:, :2].T, mesh.points[[i, j]].astype(np.float32))
    assert all(decoded(line[a]).dtype == np.float32 for a in "xyz")  # as WebGL draws them


def test_the_histogram_band_and_windows(tmp_path):
    mesh = fan()
    view = mesh_view(mesh, TOLERANCE)
    data = report_data(page(mesh, tmp_path))
    lengths = data["figures"]["lengths"]
    edges, counts = view.histogram()
    width = edges[1] - edges[0]
    assert sum(decoded(t["y"]).sum() for t in lengths["data"]) == len(mesh.edges)
    for trace, group, count in zip(lengths["data"], view.groups, counts):
        keep = count > 0
        np.testing.assert_allclose(decoded(trace["x"]), (0.5 * (edges[:-1] + edges[1:]))[keep])
        assert decoded(trace["y"]).tolist() == count[keep].tolist() and trace["width"] == pytest.approx(width)
        assert trace["marker"] == {"color": group.colour, "line": {"width": 0}} and trace["name"] == group.label
        assert trace["hovertemplate"] == "%{x:.6g}: %{y} members<extra>%{fullData.name}</extra>"
    layout = lengths["layout"]
    shapes = layout["shapes"]
    assert [(s["x0"], s["x1"], s["fillcolor"]) for s in shapes[:2]] == [
        (1.5, 3.0, "rgba(44, 160, 44, 0.10)"),
        (pytest.approx(1.5 - 0.03), pytest.approx(1.5 + 0.03), "rgba(44, 160, 44, 0.35)"),
    ]
    assert all((s["y0"], s["y1"]) == (0, 1) for s in shapes[:2])
    windows = [(s["x0"], s["x1"], s["fillcolor"], s["y0"], s["y1"]) for s in shapes[2:]]
    nominal = [view.classes.nominal[g.classes[0]] for g in view.groups]
    expected = [(n - 0.03, n + 0.03, g.colour, 0.97, 1.0) for n, g in zip(nominal, view.groups)]
    for got, want in zip(windows, expected):
        assert got[:2] == pytest.approx(want[:2]) and got[2:] == want[2:]
    assert len(windows) == len(view.groups)
    for s in shapes:
        assert (s["type"], s["xref"], s["yref"], s["layer"], s["line"]) == ("rect", "x", "paper", "below", {"width": 0})
    assert [(a["x"], a["text"]) for a in layout["annotations"]] == [(1.5, "l"), (3.0, "2l")]
    for a in layout["annotations"]:
        assert (a["y"], a["yref"], a["showarrow"], a["yanchor"]) == (1.0, "paper", False, "bottom")
    assert (layout["barmode"], layout["bargap"], layout["showlegend"], layout["height"]) == ("stack", 0, False, 420)
    assert layout["margin"] == {"l": 60, "r": 20, "t": 40, "b": 50} and plotly_white(lengths)
    title = f"member length (bins of {number(width)}; shaded: [l, 2l] and l +- 2 %)"
    assert layout["xaxis"]["title"]["text"] == title
    assert layout["yaxis"]["title"]["text"] == "members (log scale)" and layout["yaxis"]["type"] == "log"
    assert layout["yaxis"]["range"] == pytest.approx([-0.1, np.log10(counts.sum(0).max()) + 0.1])


def test_the_angles(tmp_path):
    mesh = fan()
    view = mesh_view(mesh, TOLERANCE)
    angles = report_data(page(mesh, tmp_path))["figures"]["angles"]
    (bars,) = angles["data"]
    edges, counts = view.angle_histogram()
    assert decoded(bars["y"]).tolist() == counts.tolist() and decoded(bars["y"]).sum() == 3 * len(mesh.triangles)
    np.testing.assert_allclose(decoded(bars["x"]), np.arange(180) + 0.5)
    assert bars["width"] == 1.0 and bars["marker"] == {"color": "#1f77b4", "line": {"width": 0}}
    assert bars["hovertemplate"] == "%{x:.1f} deg: %{y} angles<extra></extra>"
    layout = angles["layout"]
    (line,) = layout["shapes"]
    assert (line["x0"], line["x1"], line["line"]) == (60.0, 60.0, {"color": "#555555", "dash": "dash", "width": 1})
    assert (layout["bargap"], layout["height"], layout["margin"]) == (0, 320, {"l": 60, "r": 20, "t": 20, "b": 50})
    assert layout["xaxis"]["title"]["text"] == "interior angle (degrees; dashed: 60)"
    assert layout["xaxis"]["range"] == [0, 180] and layout["yaxis"]["title"]["text"] == "angles"
    assert plotly_white(angles)


def test_the_deviation_colours(tmp_path):
    mesh = fan()
    deviation = report_data(page(mesh, tmp_path))["deviation"]
    assert deviation["colorscale"] == [[0.0, "#2166ac"], [0.5, "#1a9850"], [1.0, "#b2182b"]]
    assert deviation["limit"] == pytest.approx(np.abs(mesh_view(mesh).deviation).max())
    exact = triangle([0.5, np.sqrt(3) / 2, 0.0])
    limit = report_data(page(exact, tmp_path, name="exact.html"))["deviation"]["limit"]
    assert limit == 1e-9  # an equilateral triangle of side l: the floor, not 0


def test_the_script_data_cannot_end_its_element(tmp_path):
    text = page(fan(), tmp_path)
    raw = re.search(r'<script type="application/json" id="report-data">(.*?)</script>', text, re.S).group(1)
    assert "</" not in raw and "<\\/extra>" in raw  # the hover templates' </extra>, escaped
    assert raw.startswith('{"figures":{"view":{"data":[{')  # compact
    with pytest.raises(ValueError):
        _script_json({"limit": float("nan")})  # not JSON: refused, not written as NaN


def test_the_classes_table(tmp_path):
    mesh = fan()
    view = mesh_view(mesh, TOLERANCE)
    c = view.classes
    table = section(page(mesh, tmp_path), "Length classes")
    head = (
        "<table><thead><tr><th></th><th>class</th><th>members</th><th>nominal length</th><th>nominal / l</th>"
        "<th>shortest</th><th>longest</th></tr></thead><tbody>"
    )
    assert table.startswith(head) and table.endswith("</tbody></table>")
    rows = re.findall(r"<tr>.*?</tr>", table.split("<tbody>")[1])
    assert len(rows) == len(c) == len(view.groups)
    for k, (row, group) in enumerate(zip(rows, view.groups)):
        swatch = f'<td><span class="swatch" style="background: {group.colour}"></span></td>'
        assert row == (
            f"<tr>{swatch}<td>{k}</td><td>{c.count[k]}</td><td>{number(c.nominal[k])}</td>"
            f"<td>{c.nominal[k] / 1.5:.4f}</td><td>{number(c.min[k])}</td><td>{number(c.max[k])}</td></tr>"
        )


def test_more_classes_than_drawn_are_one_grey_line_set_and_one_row(tmp_path):
    from equimesh.io._view import MAX_DRAWN_CLASSES

    mesh = fan(60)
    text = page(mesh, tmp_path, tolerance=1e-6)
    data = report_data(text)
    view = mesh_view(mesh, 1e-6)
    assert len(data["members"]) == MAX_DRAWN_CLASSES and data["colours"][-1] == REST_COLOUR
    rest = view.groups[-1]
    k = np.asarray(rest.classes)
    c = view.classes
    row = (
        f'<tr><td><span class="swatch" style="background: {REST_COLOUR}"></span></td>'
        f'<td colspan="2">{html.escape(rest.label)}</td><td colspan="2">'
        f"{number(c.nominal[k].min())} to {number(c.nominal[k].max())}</td>"
        f"<td>{number(c.min[k].min())}</td><td>{number(c.max[k].max())}</td></tr>"
    )
    assert section(text, "Length classes").split("<tbody>")[1].endswith(row + "</tbody></table>")
    shapes = data["figures"]["lengths"]["layout"]["shapes"]
    assert len(shapes) == 2 + MAX_DRAWN_CLASSES - 1  # a window per class drawn on its own, none for the rest


def rows_of(table):
    return re.findall(r"<tr><th>(.*?)</th><td>(.*?)</td></tr>", table)


def test_the_run_summary(tmp_path):
    mesh = fan()
    mesh.length = 1.2345678  # l to the last digit
    view = mesh_view(mesh, TOLERANCE)
    table = section(page(mesh, tmp_path), "Run")
    assert table.startswith('<table class="rows"><tbody>') and table.endswith("</tbody></table>")
    rows = summary_rows(view.lengths, 1.2345678, TOLERANCE, view.points, view.triangles)
    summary = [(html.escape(k), html.escape(v)) for k, v in rows]
    angles = [r for r in rows_of(table) if r[0] == "triangle angles"]
    assert rows_of(table) == [
        ("nodes", "13"),
        ("triangles", "12"),
        ("target length l", "1.2345678"),
        ("in the equal-length group G1", "12"),
        *summary,
        ("seconds: flattening", "0.25"),
        ("seconds: optimisation", "1.50"),
    ]
    (lo_hi,) = angles
    lo, hi = (float(v) for v in re.findall(r"[\d.]+", lo_hi[1]))
    assert lo_hi[1] == f"{lo:.1f} to {hi:.1f} degrees" and 0 < lo < 60 < hi < 180
    del mesh.stages  # a mesh without stages (a planar one): no seconds to show
    assert "seconds:" not in section(page(mesh, tmp_path, name="s.html"), "Run")


def test_the_provenance(tmp_path):
    mesh = fan()
    table = section(page(mesh, tmp_path), "Provenance")
    cells = "".join(f"<tr><th>{k}</th><td>{v}</td></tr>" for k, v in rows_of(table))
    assert table == f'<table class="rows"><tbody>{cells}</tbody></table>'
    assert rows_of(table) == [
        ("parameter: input", "roof.json"),
        ("parameter: length", "1.5"),
        ("parameter: grid", "[8, 8]"),
        ("date", "2026-01-01T00:00:00+00:00"),
        ("git commit", "0" * 40),
        ("python", "3.11.0 (cpython)"),
        ("platform", "Linux"),
        ("version: equimesh", "0.1.0"),
        ("version: gone", "not installed"),
        ("version: plotly", plotly.__version__),
    ]
    dirty = section(page(mesh, tmp_path, record={**RECORD, "git": {"commit": None, "dirty": True}}), "Provenance")
    assert ("git commit", "not a git checkout (with uncommitted changes)") in rows_of(dirty)
    bare = section(page(mesh, tmp_path, record={}), "Provenance")
    assert rows_of(bare)[:4] == [
        ("date", ""),
        ("git commit", "not a git checkout"),
        ("python", " ()"),
        ("platform", ""),
    ]


def test_same_mesh_and_record_same_bytes_and_a_provenance_of_its_own_by_default(tmp_path):
    mesh = fan()
    first = page(mesh, tmp_path)
    assert page(mesh, tmp_path, name="again.html") == first
    now = page(mesh, tmp_path, name="now.html", tolerance="1%", record=None)
    assert "parameter: tolerance</th><td>1%" in now and "parameter: length</th><td>1.5" in now
    assert "version: numpy" in now
    given = page(mesh, tmp_path, name="given.html", record=None, parameters={"input": "fan.json"})
    assert "parameter: input</th><td>fan.json" in given and "parameter: length" not in given


def test_an_unwritable_folder_or_no_plotly_is_refused_before_anything_is_written(tmp_path, monkeypatch):
    mesh = fan()
    with pytest.raises(OutputPathError, match="does not exist"):
        write_report(mesh, tmp_path / "missing" / "r.html")
    with pytest.raises(OutputPathError, match="unknown extension"):
        write_report(mesh, tmp_path / "r.htm")
    monkeypatch.setitem(sys.modules, "plotly", None)
    with pytest.raises(MissingDependencyError, match=r"pip install 'equimesh\[report\]'"):
        write_report(mesh, tmp_path / "r.html")
    monkeypatch.setitem(sys.modules, "plotly", plotly)
    monkeypatch.setitem(sys.modules, "plotly.graph_objects", None)  # plotly there, but not all of it
    with pytest.raises(MissingDependencyError) as err:
        write_report(mesh, tmp_path / "r.html")
    assert str(err.value) == "the report (--report) needs plotly: pip install 'equimesh[report]'"
    assert list(tmp_path.iterdir()) == []


def test_one_member_per_bin_gets_a_log_axis_around_1(tmp_path):
    layout = report_data(page(triangle([0.3, 1.2, 0.0]), tmp_path, tolerance=0.01))["figures"]["lengths"]["layout"]
    assert layout["yaxis"]["range"] == pytest.approx([-0.1, 0.1])
