"""The plot (equimesh.write_plot): a PNG of the expected size, not blank, the class colours drawn, byte-stable."""

import numpy as np
import pytest
import report_meshes
from matplotlib.image import imread

from equimesh import OutputPathError
from equimesh.io import output_formats, write_plot
from equimesh.io._plot import PLOT_DPI, PLOT_SIZE
from equimesh.io._view import PALETTE

large_mesh = report_meshes.large_mesh  # the shared fixture
roof_mesh = report_meshes.roof_mesh  # the shared fixture


def colour_share(pixels, colour, distance=40):
    rgb = np.array([int(colour[i : i + 2], 16) for i in (1, 3, 5)])
    return float(np.mean(np.linalg.norm(pixels - rgb, axis=-1) < distance))


def test_the_png_has_the_expected_size_and_shows_the_mesh_and_the_histogram(roof_mesh, tmp_path):
    path = tmp_path / "roof.png"
    write_plot(roof_mesh, path)
    pixels = (imread(path)[..., :3] * 255).round().astype(int)
    assert pixels.shape == (round(PLOT_SIZE[1] * PLOT_DPI), round(PLOT_SIZE[0] * PLOT_DPI), 3)
    assert colour_share(pixels, "#ffffff", 10) < 0.95  # not blank
    half = pixels.shape[1] // 2
    mesh, histogram = pixels[:, :half], pixels[:, half:]
    assert sum(colour_share(mesh, c) for c in PALETTE) > 0.01 and colour_share(mesh, "#000000", 60) > 0.002
    assert sum(colour_share(histogram, c) for c in PALETTE) > 0.002


@pytest.mark.parametrize("suffix", sorted(output_formats("plot")))
def test_same_mesh_same_bytes_in_every_format(roof_mesh, tmp_path, suffix):
    write_plot(roof_mesh, tmp_path / f"a{suffix}")
    write_plot(roof_mesh, tmp_path / f"b{suffix}")
    assert (tmp_path / f"a{suffix}").read_bytes() == (tmp_path / f"b{suffix}").read_bytes()


def test_a_planar_mesh_is_drawn_too(large_mesh, tmp_path):
    write_plot(large_mesh, tmp_path / "large.png", tolerance="1%")
    assert (tmp_path / "large.png").stat().st_size > 0


def test_an_unwritable_folder_or_an_unknown_extension_writes_nothing(roof_mesh, tmp_path):
    with pytest.raises(OutputPathError, match="does not exist"):
        write_plot(roof_mesh, tmp_path / "missing" / "p.png")
    with pytest.raises(OutputPathError, match="unknown extension"):
        write_plot(roof_mesh, tmp_path / "p.jpg")
    assert list(tmp_path.iterdir()) == []
