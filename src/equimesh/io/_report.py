"""The report of a run: one self-contained HTML file with the mesh in 3-D, its member lengths, classes and angles.

:func:`equimesh.io.write_report` writes a page that opens offline in any browser: plotly's
JavaScript bundle (the optional extra ``report``) is inlined, so the page needs
no network (docs/decisions.md, "The report is one HTML file with plotly
inlined").  It shows, from one :class:`~equimesh.io._view.MeshView`:

* the mesh in 3-D, to rotate and zoom, each length class one line set in its
  colour (the legend gives its nominal length and member count; a click hides
  it), the outer boundary and the openings marked; a toggle colours the
  members by their deviation from l instead (``#deviation`` in the address
  opens the page so);
* a histogram of member lengths, stacked by class, with the band [l, 2l], the
  window ``l +- tolerance l`` and each drawn class's tolerance window;
* the classes table, the distribution of the triangles' angles, the run's
  summary (:func:`equimesh.metrics.summary_rows`) and its provenance (input,
  parameters, versions, date, seconds per stage).

The page sets ``data-ready`` on its ``<html>`` element once every figure is
drawn.  The same mesh and the same provenance record give the same bytes.
"""

import html
import importlib.resources
import json

import numpy as np

from ..errors import MissingDependencyError, number
from ..metrics import summary_rows
from ._view import BOUNDARY_COLOUR, mesh_view
from .provenance import provenance

#: Report formats by extension.
#: Colour scale of the deviation from l (blue: short, green: l, red: long), from -m to +m, m the largest deviation.
DEVIATION_SCALE = [[0.0, "#2166ac"], [0.5, "#1a9850"], [1.0, "#b2182b"]]

#: Line widths in pixels of the 3-D view: members, boundary and openings.
MEMBER_WIDTH = 3
BOUNDARY_WIDTH = 7

#: Height of the 3-D view in pixels, and where its camera starts (plotly's scene units; its default is 1.25 on each
#: axis, which crops a wide flat roof).
VIEW_HEIGHT = 640
CAMERA_EYE = {"x": 0.85, "y": -0.85, "z": 0.65}
#: Smallest side of the scene's box relative to its largest, so that a flat mesh is a thin box, not a plane.
MIN_ASPECT = 0.05


def write_report_html(tmp, products):
    """The report's writer (a row of :data:`~equimesh.io._outputs.OUTPUT_FORMATS`): the page of
    ``products.mesh`` at ``products.tolerance``, with the run's provenance ``products.record`` (made now from
    ``products.parameters`` when the caller gave none; by default l and the tolerance)."""
    mesh, tolerance = products.mesh, products.tolerance
    given = (
        {"length": float(mesh.length), "tolerance": tolerance} if products.parameters is None else products.parameters
    )
    record = provenance(given) if products.record is None else products.record
    with open(tmp, "w", encoding="utf-8", newline="\n") as f:
        f.write(report_html(mesh, tolerance, record))


def report_html(mesh, tolerance, record):
    """The report's HTML text (see the module docstring) with the provenance ``record``."""
    plotly = _plotly()
    view = mesh_view(mesh, tolerance)
    record = {**record, "versions": {**record.get("versions", {}), "plotly": plotly.__version__}}
    title = str(record.get("parameters", {}).get("input", "mesh"))
    figures = {
        "view": _view_figure(view),
        "lengths": _length_figure(view),
        "angles": _angle_figure(view),
    }
    data = {
        "figures": {k: json.loads(plotly.io.to_json(v, engine="json")) for k, v in figures.items()},
        "members": list(range(len(view.groups))),
        "colours": [g.colour for g in view.groups],
        "deviation": {"colorscale": DEVIATION_SCALE, "limit": _deviation_limit(view)},
    }
    seconds = getattr(getattr(mesh, "stages", None), "seconds", {}) or {}
    body = [
        f"<h1>{html.escape(title)}</h1>",
        f'<p class="lead">{_lead(view)}</p>',
        '<section><h2>The mesh</h2><p class="controls">Colour members by '
        '<label><input type="radio" name="colour" value="class" checked> length class</label> '
        '<label><input type="radio" name="colour" value="deviation"> deviation from l</label>'
        " &middot; drag to rotate, scroll to zoom, click a legend entry to hide it</p>"
        f'<div id="view" class="figure" style="height: {VIEW_HEIGHT}px"></div></section>',
        '<section><h2>Member lengths</h2><div id="lengths" class="figure"></div></section>',
        f"<section><h2>Length classes</h2>{_classes_table(view)}</section>",
        '<section><h2>Triangle angles</h2><div id="angles" class="figure"></div></section>',
        f"<section><h2>Run</h2>{_rows_table(_run_rows(view, seconds))}</section>",
        f"<section><h2>Provenance</h2>{_rows_table(_provenance_rows(record))}</section>",
    ]
    return "\n".join(
        [
            "<!DOCTYPE html>",
            '<html lang="en">',
            "<head>",
            '<meta charset="utf-8">',
            '<meta name="viewport" content="width=device-width, initial-scale=1">',
            f"<title>equimesh report: {html.escape(title)}</title>",
            f"<style>\n{_asset('_report.css')}</style>",
            f"<script>{plotly.offline.get_plotlyjs()}</script>",
            "</head>",
            "<body>",
            *body,
            f'<script type="application/json" id="report-data">{_script_json(data)}</script>',
            f"<script>\n{_asset('_report.js')}</script>",
            "</body>",
            "</html>",
            "",
        ]
    )


# --------------------------------------------------------------------------- figures


def _view_figure(view):
    """The 3-D view: one line set per group (customdata: each vertex's member deviation), boundary, openings."""
    go = _plotly().graph_objects
    fig = go.Figure()
    deviation = view.deviation
    for group in view.groups:
        fig.add_trace(
            _line_set(
                go,
                view.points,
                view.edges[group.members],
                name=group.label,
                line={"color": group.colour, "width": MEMBER_WIDTH},
                customdata=np.repeat(deviation[group.members], 3).astype(np.float32),
                hovertemplate="deviation from l: %{customdata:+.3%}<extra>%{fullData.name}</extra>",
                legendgroup="classes",
                legendgrouptitle={"text": "classes: nominal (members)"},
            )
        )
    for name, edges, dash in (("boundary", view.boundary, "solid"), ("openings", view.openings, "dash")):
        if len(edges):
            outline = {"legendgroup": "outline", "legendgrouptitle": {"text": "outline"}, "hoverinfo": "skip"}
            line = {"color": BOUNDARY_COLOUR, "width": BOUNDARY_WIDTH, "dash": dash}
            fig.add_trace(_line_set(go, view.points, edges, name=name, line=line, **outline))
    fig.update_layout(
        template="plotly_white",
        margin={"l": 0, "r": 0, "t": 36, "b": 0},
        scene={
            "aspectmode": "manual",
            "aspectratio": _aspect(view.points),
            "xaxis_title": "x",
            "yaxis_title": "y",
            "zaxis_title": "z",
            "camera": {"eye": CAMERA_EYE},
        },
        legend={"itemsizing": "constant", "groupclick": "toggleitem", "y": 1.0},
        uirevision="view",
    )
    return fig


def _aspect(points):
    """The scene's box: the mesh's extent along x, y and z over its largest, each at least :data:`MIN_ASPECT`."""
    span = np.ptp(points, axis=0)
    ratio = span / float(span.max())
    return dict(zip("xyz", np.maximum(ratio, MIN_ASPECT).tolist()))


def _line_set(go, points, edges, **style):
    """One line set of ``edges``: a Scatter3d through each edge's two ends and a NaN break (float32, as WebGL draws
    them), with ``style``."""
    p = np.full((len(edges), 3, 3), np.nan, dtype=np.float32)
    p[:, 0], p[:, 1] = points[edges[:, 0]], points[edges[:, 1]]
    flat = p.reshape(-1, 3)
    return go.Scatter3d(x=flat[:, 0], y=flat[:, 1], z=flat[:, 2], mode="lines", **style)


def _length_figure(view):
    """Member lengths: bars stacked by group, the band [l, 2l], the window l +- tol l, each class's window."""
    go = _plotly().graph_objects
    edges, counts = view.histogram()
    centres, width = 0.5 * (edges[:-1] + edges[1:]), float(edges[1] - edges[0])
    fig = go.Figure()
    for group, count in zip(view.groups, counts):
        keep = count > 0
        fig.add_trace(
            go.Bar(
                x=centres[keep],
                y=count[keep],
                width=width,
                name=group.label,
                marker={"color": group.colour, "line": {"width": 0}},
                hovertemplate="%{x:.6g}: %{y} members<extra>%{fullData.name}</extra>",
            )
        )
    l, t = view.l, view.tolerance * view.l
    shapes = [
        _band(l, 2 * l, "rgba(44, 160, 44, 0.10)", 0, 1),
        _band(l - t, l + t, "rgba(44, 160, 44, 0.35)", 0, 1),
    ]
    for group in view.groups:
        if len(group.classes) == 1:
            nominal = view.classes.nominal[group.classes[0]]
            shapes.append(_band(nominal - t, nominal + t, group.colour, 0.97, 1.0))
    annotations = [
        {"x": l, "y": 1.0, "yref": "paper", "text": "l", "showarrow": False, "yanchor": "bottom"},
        {"x": 2 * l, "y": 1.0, "yref": "paper", "text": "2l", "showarrow": False, "yanchor": "bottom"},
    ]
    fig.update_layout(
        template="plotly_white",
        barmode="stack",
        bargap=0,
        showlegend=False,
        height=420,
        margin={"l": 60, "r": 20, "t": 40, "b": 50},
        shapes=shapes,
        annotations=annotations,
        xaxis_title=f"member length (bins of {number(width)}; shaded: [l, 2l] and l +- {100 * view.tolerance:.3g} %)",
        yaxis={
            "title": "members (log scale)",
            "type": "log",
            "range": [-0.1, np.log10(max(counts.sum(0).max(), 1)) + 0.1],
        },
    )
    return fig


def _band(x0, x1, colour, y0, y1):
    return {
        "type": "rect",
        "xref": "x",
        "yref": "paper",
        "x0": float(x0),
        "x1": float(x1),
        "y0": y0,
        "y1": y1,
        "fillcolor": colour,
        "line": {"width": 0},
        "layer": "below",
    }


def _angle_figure(view):
    """Interior angles of the triangles, bins of one degree, 60 degrees marked."""
    go = _plotly().graph_objects
    edges, counts = view.angle_histogram()
    fig = go.Figure(
        go.Bar(
            x=0.5 * (edges[:-1] + edges[1:]),
            y=counts,
            width=float(edges[1] - edges[0]),
            marker={"color": "#1f77b4", "line": {"width": 0}},
            hovertemplate="%{x:.1f} deg: %{y} angles<extra></extra>",
        )
    )
    fig.add_vline(x=60.0, line={"color": "#555555", "dash": "dash", "width": 1})
    fig.update_layout(
        template="plotly_white",
        bargap=0,
        height=320,
        margin={"l": 60, "r": 20, "t": 20, "b": 50},
        xaxis={"title": "interior angle (degrees; dashed: 60)", "range": [0, 180]},
        yaxis_title="angles",
    )
    return fig


def _deviation_limit(view):
    """Half the range of the deviation colour scale: the largest deviation from l, relative to l (at least 1e-9)."""
    return max(float(np.abs(view.deviation).max(initial=0.0)), 1e-9)


# --------------------------------------------------------------------------- tables


def _lead(view):
    return (
        f"{len(view.points)} nodes, {len(view.edges)} members ({view.n_g1} in the equal-length group G1), "
        f"{len(view.triangles)} triangles at l = {number(view.l)}; {len(view.classes)} length classes at "
        f"+-{100 * view.tolerance:.3g} % of l."
    )


def _classes_table(view):
    """The drawn classes in order of length, then the others in one row (all of them in the classes CSV)."""
    c = view.classes
    rows = [
        "<table><thead><tr><th></th><th>class</th><th>members</th><th>nominal length</th><th>nominal / l</th>"
        "<th>shortest</th><th>longest</th></tr></thead><tbody>"
    ]
    for group in view.groups:
        swatch = f'<td><span class="swatch" style="background: {group.colour}"></span></td>'
        if len(group.classes) == 1:
            k = group.classes[0]
            rows.append(
                f"<tr>{swatch}<td>{k}</td><td>{c.count[k]}</td><td>{number(c.nominal[k])}</td>"
                f"<td>{c.nominal[k] / view.l:.4f}</td><td>{number(c.min[k])}</td><td>{number(c.max[k])}</td></tr>"
            )
        else:
            k = np.asarray(group.classes)
            rows.append(
                f'<tr>{swatch}<td colspan="2">{html.escape(group.label)}</td><td colspan="2">'
                f"{number(c.nominal[k].min())} to {number(c.nominal[k].max())}</td>"
                f"<td>{number(c.min[k].min())}</td><td>{number(c.max[k].max())}</td></tr>"
            )
    rows.append("</tbody></table>")
    return "".join(rows)


def _run_rows(view, seconds):
    rows = [
        ("nodes", f"{len(view.points)}"),
        ("triangles", f"{len(view.triangles)}"),
        ("target length l", number(view.l, None)),
        ("in the equal-length group G1", f"{view.n_g1}"),
        *summary_rows(view.lengths, view.l, view.tolerance, view.points, view.triangles),
    ]
    rows += [(f"seconds: {stage}", f"{s:.2f}") for stage, s in seconds.items()]
    return rows


def _provenance_rows(record):
    git = record.get("git") or {}
    commit = git.get("commit") or "not a git checkout"
    if git.get("dirty"):
        commit += " (with uncommitted changes)"
    rows = [
        *((f"parameter: {k}", _text(v)) for k, v in record.get("parameters", {}).items()),
        ("date", str(record.get("date", ""))),
        ("git commit", commit),
        ("python", f"{record.get('python', '')} ({record.get('implementation', '')})"),
        ("platform", str(record.get("platform", ""))),
    ]
    rows += [(f"version: {k}", v or "not installed") for k, v in record.get("versions", {}).items()]
    return rows


def _rows_table(rows):
    cells = "".join(f"<tr><th>{html.escape(k)}</th><td>{html.escape(v)}</td></tr>" for k, v in rows)
    return f'<table class="rows"><tbody>{cells}</tbody></table>'


def _text(value):
    return value if isinstance(value, str) else json.dumps(value)


# --------------------------------------------------------------------------- assets


def _plotly():
    """The plotly package, or MissingDependencyError naming the extra."""
    try:
        import plotly.graph_objects  # noqa: F401
        import plotly.io  # noqa: F401
        import plotly.offline  # noqa: F401
    except ImportError:
        raise MissingDependencyError("the report (--report) needs plotly: pip install 'equimesh[report]'") from None
    import plotly

    return plotly


def _asset(name):
    """A file shipped beside this module (the page's script and style), as text."""
    return importlib.resources.files(__package__).joinpath(name).read_text(encoding="utf-8")


def _script_json(data):
    """``data`` as JSON that cannot end the ``<script>`` element holding it."""
    return json.dumps(data, separators=(",", ":"), allow_nan=False).replace("</", "<\\/")
