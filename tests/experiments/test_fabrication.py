"""Smoke test of experiments/fabrication.py: one developable surface, three methods, every output."""

import json
import re

import numpy as np
import pandas as pd
import pytest

from equimesh.classes import length_classes
from equimesh.mesh import edge_lengths
from equimesh.metrics import comparison_figures


@pytest.fixture
def fabrication(load_experiment):
    return load_experiment("fabrication")


def test_fabrication_writes_table_targets_classes_figures_and_provenance(fabrication, tmp_path):
    out, figs = tmp_path / "results", tmp_path / "figs"
    methods = ["equimesh bounded", "equimesh classes", fabrication.STRIP_FLIPPED, "gmsh Frontal-Delaunay"]
    args = ["--surfaces", "cylinder vault", "--methods", *methods, "--jobs", "1", "--out-dir", out, "--fig-dir", figs]
    assert fabrication.main([str(a) for a in args]) == 0

    df = pd.read_csv(out / "fabrication.csv")
    ran = [m for m in methods if m in fabrication.methods()[0]]
    assert df["method"].tolist() == ran and (df["status"] == "ok").all()
    assert (df["classes_1"] <= df["classes_05"]).all() and (df["top10_05"] >= df["largest_05"]).all()
    ours = df[df["method"].str.startswith("equimesh")]
    assert (ours["in_l_2l"] == 1.0).all() and (ours["deviation_max"] == 0.0).all()
    assert (ours["angle_min"] >= 30.0 - 1e-9).all()  # both keep sound joints

    sizes = pd.read_csv(out / "fabrication_classes.csv")
    for row in df.itertuples():
        assert sizes[sizes["method"] == row.method]["count"].sum() == row.members
    kinds = ("boundary", "strip", "interior")
    assert (df[[f"{k}_members" for k in kinds]].sum(axis=1) == df["members"]).all()
    near = sum(df[f"{k}_members"] * df[f"{k}_within_5"].fillna(0.0) for k in kinds)
    assert near.round().astype(int).tolist() == (df["within_5"] * df["members"]).round().astype(int).tolist()
    report = (out / "fabrication.md").read_text()
    assert "## Where the classes go" in report
    assert re.search(
        r"\| cylinder vault \| span / 16 \| equimesh classes \| \d+ \|( \d+ / \d+ / [\d.]+ % / [\d.]+ % \|){3}", report
    )
    assert "| cylinder vault | span / 16 | equimesh classes |" in report and "## Provenance" in report
    assert "## The targets of the fewest-classes objective" in report
    flipped = df[df["method"] == fabrication.STRIP_FLIPPED]
    assert flipped["flips"].notna().all() and df.loc[df["method"] != fabrication.STRIP_FLIPPED, "flips"].isna().all()
    flips = int(flipped["flips"].iloc[0])
    assert re.search(rf"\| cylinder vault \| span / 16 \| {flips} \| \d+ / [\d.]+ % \|  \| \d+ / [\d.]+ % \|", report)
    record = json.loads((out / "fabrication.provenance.json").read_text())
    assert record["parameters"]["methods"] == ran
    for stem in ("fabrication_frontier", "fabrication_member_types"):
        assert (figs / f"{stem}.png").stat().st_size > 0

    (figs / "fabrication_frontier.png").unlink()
    assert fabrication.main(["--plot-only", "--out-dir", str(out), "--fig-dir", str(figs)]) == 0
    assert (figs / "fabrication_frontier.png").stat().st_size > 0


def test_the_outline_held_equal_has_one_length_per_side(fabrication):
    """The lever "Step 2's spacing on the surface": each side's parts equal on the surface, held through the
    optimisation, so the outline's members need at most one class per side (the classes objective's own, sliding,
    need more); every member in [l, 2l], joints sound."""
    surface = {name: s for name, _, s in fabrication.surfaces()}["asymmetric dome"]
    l = fabrication.SPAN / fabrication.DIVISORS[0]

    def outline_classes(points, triangles):
        edges = np.sort(np.vstack([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
        edges, count = np.unique(edges, axis=0, return_counts=True)  # an outline member is one triangle's
        return len(length_classes(edge_lengths(points, edges[count == 1]), l, 0.005).count)

    points, triangles, _ = fabrication._outline_held(surface, l)
    figures = comparison_figures(points, triangles, l)
    assert figures["in_l_2l"] == 1.0 and 30.0 - 1e-9 <= figures["angle_min"] <= figures["angle_max"] <= 120.0
    assert outline_classes(points, triangles) <= 4
    assert outline_classes(*fabrication._equimesh("classes")(surface, l)[:2]) > 4


def test_strip_flips_bring_members_nearer_the_largest_classes_and_keep_a_valid_mesh(fabrication, monkeypatch):
    """The lever "the strip's connectivity": on the dome's classes mesh some inner members more than the tolerance
    from every nominal length of the ten largest classes are flipped; every member removed was that far, every one
    added lies within FLIP_REACH l of one of them, and their summed distance to those nominals falls; the triangles
    stay counter-clockwise in (u, v) with sound joints, every member in [l, 2l], the outline and the member count
    the same; with no reach nothing is flipped."""
    from equimesh.mesh import edge_keys, single_edges, unique_edges
    from equimesh.metrics import TOP_CLASSES, triangle_angles
    from equimesh.surface.optimize.jacobian import signed_areas
    from equimesh.surface.pipeline import mesh_surface

    surface = {name: s for name, _, s in fabrication.surfaces()}["asymmetric dome"]
    l = fabrication.SPAN / fabrication.DIVISORS[0]
    mesh = mesh_surface(surface, l, optimize="classes", max_nodes=None)
    triangles, flips = fabrication.strip_flips(mesh.points, mesh.uv, mesh.triangles, l)
    assert flips >= 1
    assert (signed_areas(mesh.uv, triangles) > 0).all() and triangle_angles(mesh.points, triangles).min() >= 30.0
    edges = unique_edges(triangles)
    assert len(edges) == len(mesh.edges)
    np.testing.assert_array_equal(
        np.sort(single_edges(triangles), axis=0), np.sort(single_edges(mesh.triangles), axis=0)
    )
    ratio = edge_lengths(mesh.points, edges) / l
    assert ((ratio >= 1.0 - 1e-9) & (ratio <= 2.0 + 1e-9)).all()

    sizes = length_classes(edge_lengths(mesh.points, mesh.edges), l, 0.005)
    nominals = sizes.nominal[sizes.largest(TOP_CLASSES)]

    def gaps(edges):
        return np.abs(edge_lengths(mesh.points, edges)[:, None] - nominals[None, :]).min(axis=1)

    n = len(mesh.uv)
    old, new = edge_keys(mesh.edges, n)[0], edge_keys(edges, n)[0]
    added, removed = edges[~np.isin(new, old)], mesh.edges[~np.isin(old, new)]
    assert 1 <= len(added) == len(removed) <= flips
    assert (gaps(removed) > 0.005 * l).all() and (gaps(added) <= fabrication.FLIP_REACH * l).all()
    assert gaps(edges).sum() < gaps(mesh.edges).sum()
    monkeypatch.setattr(fabrication, "FLIP_REACH", 0.0)
    assert fabrication.strip_flips(mesh.points, mesh.uv, mesh.triangles, l)[1] == 0
