"""The plot (equimesh.write_plot): the figure the module describes (the mesh in 3-D by class with its outline, the
stacked length histogram with the band [l, 2l] and the window l +- t l), a PNG of the expected size, byte-stable."""

from types import SimpleNamespace

import matplotlib
import numpy as np
import pytest
import report_meshes
from conftest import TentMesh
from matplotlib.colors import to_rgba
from matplotlib.font_manager import FontProperties
from matplotlib.image import imread

from equimesh import OutputPathError
from equimesh.io import Products, output_formats, write_plot
from equimesh.io._plot import PLOT_DPI, PLOT_SIZE, plot_figure
from equimesh.io._view import BOUNDARY_COLOUR, PALETTE, mesh_view
from equimesh.mesh import G1

square_mesh = report_meshes.square_mesh  # the shared fixture


def colour_share(pixels, colour, distance=40):
    rgb = np.array([int(colour[i : i + 2], 16) for i in (1, 3, 5)])
    return float(np.mean(np.linalg.norm(pixels - rgb, axis=-1) < distance))


def test_the_png_has_the_expected_size_and_shows_the_mesh_and_the_histogram(square_mesh, tmp_path):
    path = tmp_path / "square.png"
    write_plot(square_mesh, path)
    pixels = (imread(path)[..., :3] * 255).round().astype(int)
    assert pixels.shape == (round(PLOT_SIZE[1] * PLOT_DPI), round(PLOT_SIZE[0] * PLOT_DPI), 3)
    assert colour_share(pixels, "#ffffff", 10) < 0.95  # not blank
    half = pixels.shape[1] // 2
    mesh, histogram = pixels[:, :half], pixels[:, half:]
    assert sum(colour_share(mesh, c) for c in PALETTE) > 0.002 and colour_share(mesh, "#000000", 60) > 0.002
    assert sum(colour_share(histogram, c) for c in PALETTE) > 0.002


@pytest.mark.parametrize("suffix", sorted(output_formats("plot")))
def test_same_mesh_same_bytes_in_every_format(tent_mesh, tmp_path, suffix):
    write_plot(tent_mesh, tmp_path / f"a{suffix}")
    write_plot(tent_mesh, tmp_path / f"b{suffix}")
    assert (tmp_path / f"a{suffix}").read_bytes() == (tmp_path / f"b{suffix}").read_bytes()


def test_an_unwritable_folder_or_an_unknown_extension_writes_nothing(tent_mesh, tmp_path):
    with pytest.raises(OutputPathError, match="does not exist"):
        write_plot(tent_mesh, tmp_path / "missing" / "p.png")
    with pytest.raises(OutputPathError, match="unknown extension"):
        write_plot(tent_mesh, tmp_path / "p.jpg")
    assert list(tmp_path.iterdir()) == []


def test_the_title_the_size_and_the_layout(tent_mesh):
    """The counts and the tolerance in the title; the mesh on the left, a little wider than the histogram."""
    fig = plot_figure(tent_mesh, "1%")
    assert fig.get_suptitle() == "7 nodes, 12 members, 3 length classes at +-1 % of l = 1"
    assert tuple(fig.get_size_inches()) == PLOT_SIZE and fig.dpi == PLOT_DPI
    mesh_axes, lengths_axes = fig.axes
    assert mesh_axes.name == "3d" and lengths_axes.name == "rectilinear" and not mesh_axes.axison
    grid = lengths_axes.get_subplotspec().get_gridspec()
    assert grid.get_geometry() == (1, 2) and grid.get_width_ratios() == (1.25, 1.0)
    assert mesh_axes.get_subplotspec().get_gridspec() is grid
    assert mesh_axes.get_subplotspec().colspan == range(0, 1) and lengths_axes.get_subplotspec().colspan == range(1, 2)
    assert (grid.left, grid.right, grid.bottom, grid.top, grid.wspace) == (0.0, 0.98, 0.11, 0.9, 0.08)


def title_size(fig):
    (title,) = (t for t in fig.texts if t.get_text() == fig.get_suptitle())
    return title.get_fontsize()


def small_text():
    """The size of matplotlib's default legend text, which the plot's legends stay below."""
    return FontProperties(size=matplotlib.rcParams["legend.fontsize"]).get_size_in_points()


def legend_corner(axes):
    """Where the legend of ``axes`` is drawn (after a draw), ``("upper", "left")`` and so on; the legend."""
    legend = axes.get_legend()
    box, frame = legend.get_window_extent(), axes.get_window_extent()
    vertical = "upper" if box.y0 > (frame.y0 + frame.y1) / 2 else "lower"
    horizontal = "left" if box.x1 < (frame.x0 + frame.x1) / 2 else "right"
    return (vertical, horizontal), legend


def test_each_member_in_its_class_colour_and_the_outline_wider_in_black(square_mesh):
    view = mesh_view(square_mesh, 0.01)
    fig = plot_figure(square_mesh, 0.01)
    fig.draw_without_rendering()
    axes = fig.axes[0]
    members, boundary, openings = axes.collections
    assert len(members.get_segments()) == len(view.edges)
    expected = np.empty((len(view.edges), 4))
    for group in view.groups:
        expected[group.members] = to_rgba(group.colour)
    np.testing.assert_array_equal(members.get_colors(), expected)
    assert (len(boundary.get_segments()), len(openings.get_segments())) == (len(view.boundary), len(view.openings))
    default = matplotlib.rcParams["lines.linewidth"]
    assert members.get_linewidths()[0] < default  # members finer than a line of matplotlib's, the outline bolder
    for outline, label in ((boundary, "boundary"), (openings, "openings")):
        assert outline.get_label() == label and outline.get_linewidths()[0] > default
        np.testing.assert_array_equal(outline.get_colors(), [to_rgba(BOUNDARY_COLOUR)])
    assert boundary.get_linestyles()[0][1] is None and openings.get_linestyles()[0][1] is not None  # solid, dashed
    corner, legend = legend_corner(axes)
    assert corner == ("upper", "left") and [t.get_text() for t in legend.get_texts()] == ["boundary", "openings"]
    assert not legend.get_frame_on() and legend.get_texts()[0].get_fontsize() < small_text() < title_size(fig)


def test_the_mesh_fills_its_box(tent_mesh, square_mesh):
    """The axes hold the bounding box, in its proportions; a flat mesh gets a sliver of height (1e-9 of its extent,
    or of 1 for a mesh smaller than that)."""
    axes = plot_figure(tent_mesh).axes[0]
    np.testing.assert_allclose(
        [axes.get_xlim(), axes.get_ylim(), axes.get_zlim()], [[-1, 1], [-0.866, 0.866], [0, 0.5]], atol=1e-3
    )
    aspect = axes.get_box_aspect()
    np.testing.assert_allclose(aspect / aspect[0], [1.0, np.sqrt(3) / 2, 0.25])
    assert plot_figure(square_mesh).axes[0].get_zlim() == (0.0, 5e-9)
    far = SimpleNamespace(**vars(square_mesh) | {"points": square_mesh.points + 10.0})  # the extent, not the corner
    assert plot_figure(far).axes[0].get_zlim() == (0.0, 5e-9)
    small = SimpleNamespace(**vars(square_mesh) | {"points": square_mesh.points / 10, "length": 0.1})
    assert plot_figure(small).axes[0].get_zlim() == (0.0, 1e-9)
    assert small.points[:, 0].max() == 0.5  # smaller than 1


def test_a_mesh_without_openings_has_the_boundary_alone_in_its_legend(tent_mesh):
    fig = plot_figure(tent_mesh)
    members, boundary = fig.axes[0].collections
    assert [t.get_text() for t in fig.axes[0].get_legend().get_texts()] == ["boundary"]


def test_the_lengths_stacked_by_class_with_the_band_and_the_window():
    mesh = TentMesh()
    mesh.points, mesh.length = 2.5 * mesh.points, 2.5  # l = 2.5: the band and the window scale with l
    view = mesh_view(mesh, 0.01)
    fig = plot_figure(mesh, 0.01)
    fig.draw_without_rendering()
    axes = fig.axes[1]
    band, window = axes.patches
    assert (band.get_label(), band.get_x(), band.get_width()) == ("[l, 2l]", 2.5, 2.5)
    assert (window.get_label(), window.get_x()) == ("l +- 1 %", 2.475) and window.get_width() == pytest.approx(0.05)
    assert band.get_facecolor()[:3] == window.get_facecolor()[:3] == to_rgba("#2ca02c")[:3]
    assert band.get_alpha() < window.get_alpha() < 1 and band.get_linewidth() == window.get_linewidth() == 0
    edges, counts = view.histogram()
    stacks = axes.collections
    assert [tuple(s.get_facecolor()[0]) for s in stacks] == [to_rgba(g.colour) for g in view.groups]
    assert all(s.get_linewidth()[0] == 0 for s in stacks)
    top = stacks[-1].get_paths()[0].vertices
    assert top[:, 0].min() == edges[0] and top[:, 0].max() == edges[-1] and top[:, 1].max() == counts.sum(axis=0).max()
    assert axes.get_xlim() == (edges[0], edges[-1]) and axes.get_ylim() == (0.0, 9.0)  # 1.5 times the most in a bin
    assert axes.get_yscale() == "symlog" and axes.yaxis.get_transform().linthresh == 1.0
    assert axes.get_xlabel() == "member length (coloured by length class)"
    assert axes.get_ylabel() == "members (logarithmic above 1)"
    corner, legend = legend_corner(axes)
    assert corner == ("upper", "right") and [t.get_text() for t in legend.get_texts()] == ["[l, 2l]", "l +- 1 %"]
    assert not legend.get_frame_on() and legend.get_texts()[0].get_fontsize() < small_text() < title_size(fig)


def test_one_member_per_bin_still_gets_a_y_axis_to_1_5():
    triangle = SimpleNamespace(
        points=np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.3, 1.2, 0.0]]),
        triangles=np.array([[0, 1, 2]]),
        edges=np.array([[0, 1], [0, 2], [1, 2]]),
        edge_groups=np.array([G1, G1, G1]),
        length=1.0,
        n_boundary=3,
        info={},
    )
    assert plot_figure(triangle, 0.01).axes[1].get_ylim() == (0.0, 1.5)


def test_the_y_axis_reaches_1_5_times_the_fullest_bin_not_the_largest_class(tent_mesh):
    """At 2 %, nine members in one class fall in two bins of six and three."""
    view = mesh_view(tent_mesh, 0.02)
    _, counts = view.histogram()
    assert counts.sum(axis=0).max() == 6 and max(len(g.members) for g in view.groups) == 9
    assert plot_figure(tent_mesh, 0.02).axes[1].get_ylim() == (0.0, 9.0)


def test_more_groups_than_matplotlib_has_colours_keep_theirs():
    """A fan of ten spokes of ten lengths: each class its colour of the palette, not matplotlib's cycle."""
    angles = np.arange(10) * np.pi / 5
    radii = 1.0 + 0.04 * np.arange(10)
    ring = np.column_stack([radii * np.cos(angles), radii * np.sin(angles), np.zeros(10)])
    triangles = np.array([[k, (k + 1) % 10, 10] for k in range(10)])
    edges = np.unique(
        np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [0, 2]]]), 1), axis=0
    )
    fan = SimpleNamespace(
        points=np.vstack([ring, [0.0, 0.0, 0.0]]),
        triangles=triangles,
        edges=edges,
        edge_groups=np.zeros(len(edges), dtype=np.int8),
        length=1.0,
        n_boundary=10,
        info={},
    )
    view = mesh_view(fan, 0.005)
    assert len(view.groups) > len(PALETTE)
    stacks = plot_figure(fan, 0.005).axes[1].collections
    assert [tuple(s.get_facecolor()[0]) for s in stacks] == [to_rgba(g.colour) for g in view.groups]


def test_a_writer_writes_its_format_whatever_the_file_is_called(tent_mesh, tmp_path):
    """The temporary file gets the format of the row, with no date and no software stamp; the tolerance given."""
    starts = {".png": b"\x89PNG", ".svg": b"<?xml", ".pdf": b"%PDF"}
    stamps = {".png": b"Software", ".svg": b"<dc:date>", ".pdf": b"/CreationDate"}
    for extension, fmt in output_formats("plot").items():
        fmt.write(tmp_path / "plain", Products(tent_mesh, 0.05))
        data = (tmp_path / "plain").read_bytes()
        assert data.startswith(starts[extension]) and stamps[extension] not in data
        fmt.write(tmp_path / "default", Products(tent_mesh))
        assert (tmp_path / "default").read_bytes() != data  # the tolerance reaches the picture


def test_the_resolution_is_the_plots_whatever_matplotlib_is_set_to(tent_mesh, tmp_path):
    with matplotlib.rc_context({"figure.dpi": 72, "savefig.dpi": 72}):
        assert plot_figure(tent_mesh).dpi == PLOT_DPI
        write_plot(tent_mesh, tmp_path / "p.png")
    assert imread(tmp_path / "p.png").shape[:2] == (round(PLOT_SIZE[1] * PLOT_DPI), round(PLOT_SIZE[0] * PLOT_DPI))
