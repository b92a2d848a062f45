"""The plot of a run: the mesh coloured by length class and the histogram of member lengths beside it (matplotlib).

:func:`equimesh.io.write_plot` draws, headless (a :class:`matplotlib.figure.Figure`, no
pyplot), the same :class:`~equimesh.io._view.MeshView` as the report: on the
left the mesh in 3-D, each member in its class's colour, the outer boundary
solid and the openings dashed; on the right the member lengths stacked by class
with the band [l, 2l] and the window ``l +- tolerance l``.  The picture is
:data:`PLOT_SIZE` at :data:`PLOT_DPI` (1200 x 520 pixels as PNG); the files
carry no date, so the same mesh gives the same bytes.
"""

import numpy as np

from ..classes import DEFAULT_TOLERANCE
from ..errors import number
from ._view import BOUNDARY_COLOUR, mesh_view

#: Plot formats by extension, and the metadata that would make two writes of one mesh differ (left out).
_NO_DATE = {"png": {"Software": None}, "svg": {"Date": None}, "pdf": {"CreationDate": None}}

#: Size of the picture in inches, and its resolution.
PLOT_SIZE = (12.0, 5.2)
PLOT_DPI = 100


def write_figure(tmp, products, fmt):
    """The plot's writer in matplotlib's format ``fmt`` (``png``, ``svg``, ``pdf``; a row of
    :data:`~equimesh.io._outputs.OUTPUT_FORMATS` each, with ``fmt`` bound): :func:`plot_figure` of
    ``products.mesh`` to ``tmp``, with no date."""
    import matplotlib

    with matplotlib.rc_context({"svg.hashsalt": "equimesh"}):  # SVG ids from a fixed salt, not a random one
        figure = plot_figure(products.mesh, products.tolerance)
        figure.savefig(tmp, format=fmt, dpi=PLOT_DPI, metadata=_NO_DATE[fmt])


def plot_figure(mesh, tolerance=DEFAULT_TOLERANCE):
    """The :class:`matplotlib.figure.Figure` of :func:`write_plot`."""
    from matplotlib.figure import Figure  # here, not at the top: ``import equimesh.io`` stays without matplotlib

    view = mesh_view(mesh, tolerance)
    fig = Figure(figsize=PLOT_SIZE, dpi=PLOT_DPI)
    grid = fig.add_gridspec(1, 2, width_ratios=(1.25, 1.0), left=0.0, right=0.98, bottom=0.11, top=0.9, wspace=0.08)
    _draw_mesh(fig.add_subplot(grid[0], projection="3d"), view)
    _draw_lengths(fig.add_subplot(grid[1]), view)
    fig.suptitle(
        f"{len(view.points)} nodes, {len(view.edges)} members, {len(view.classes)} length classes at "
        f"+-{100 * view.tolerance:.3g} % of l = {number(view.l)}",
        fontsize=11,
    )
    return fig


def _draw_mesh(ax, view):
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    p = view.points
    colours = np.empty(len(view.edges), dtype=object)
    for group in view.groups:
        colours[group.members] = group.colour
    ax.add_collection3d(Line3DCollection(p[view.edges], colors=list(colours), linewidths=0.8))
    for edges, style, label in ((view.boundary, "-", "boundary"), (view.openings, "--", "openings")):
        if len(edges):
            ax.add_collection3d(
                Line3DCollection(p[edges], colors=BOUNDARY_COLOUR, linewidths=1.6, linestyles=style, label=label)
            )
    lo, hi = p.min(axis=0), p.max(axis=0)
    span = np.maximum(hi - lo, 1e-9 * max(float((hi - lo).max()), 1.0))
    ax.set(xlim=(lo[0], hi[0]), ylim=(lo[1], hi[1]), zlim=(lo[2], lo[2] + span[2]))
    ax.set_box_aspect(span, zoom=1.15)
    ax.set_axis_off()
    if len(view.boundary) or len(view.openings):
        ax.legend(loc="upper left", fontsize=8, frameon=False)


def _draw_lengths(ax, view):
    edges, counts = view.histogram()
    l, t = view.l, view.tolerance * view.l
    ax.axvspan(l, 2 * l, color="#2ca02c", alpha=0.10, lw=0, label="[l, 2l]")
    ax.axvspan(l - t, l + t, color="#2ca02c", alpha=0.35, lw=0, label=f"l +- {100 * view.tolerance:.3g} %")
    ax.stackplot(
        np.repeat(edges, 2)[1:-1],
        np.repeat(counts, 2, axis=1),
        colors=[g.colour for g in view.groups],
        linewidth=0,
    )
    ax.set_xlim(edges[0], edges[-1])
    ax.set_yscale("symlog", linthresh=1.0)
    ax.set_ylim(0, 1.5 * max(counts.sum(axis=0).max(), 1))
    ax.set_xlabel("member length (coloured by length class)")
    ax.set_ylabel("members (logarithmic above 1)")
    ax.legend(loc="upper right", fontsize=8, frameon=False)
