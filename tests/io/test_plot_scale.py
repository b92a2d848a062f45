"""The plot of a mesh of more than 10^5 members (equimesh.write_plot): drawn, whatever its size."""

import report_meshes

from equimesh.io import write_plot

large_mesh = report_meshes.large_mesh  # the shared fixture


def test_a_planar_mesh_of_more_than_100000_members_is_drawn(large_mesh, tmp_path):
    write_plot(large_mesh, tmp_path / "large.png", tolerance="1%")
    assert (tmp_path / "large.png").stat().st_size > 0
