"""Section 4 of the paper: the surface pipeline stage by stage, and Table 1 / Figs 1-5.

Uses only equimesh's public API (``equimesh.mesh_surface``, ``equimesh.flatten``,
``equimesh.best_lattice_placement``, ``equimesh.uniform_triangulation``,
``equimesh.remap``, ``equimesh.optimize_uv``) and the experiment scripts
``experiments/table1.py`` and ``experiments/figures.py`` (loaded from their paths).

Input: the reference surface ``experiments/surfaces/reference_dome.json``
(a bicubic Bezier dome over 80 x 80), l = 5, a 15 x 15 auxiliary grid: the
paper's parameters.  Output size: 256 auxiliary nodes, about 350 mesh nodes
and 1000 members.
"""

import contextlib
import importlib.util
import io
import shutil
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

import equimesh

from .common import (
    FACTORISATIONS,
    PIPELINE_LENGTH,
    REFERENCE_SURFACE_JSON,
    REPO,
    SURFACE_GRID,
    SURFACE_LENGTH,
    reference_surface_json,
)


def _surface():
    return equimesh.surface_from_dict(reference_surface_json())


def _experiment(name):
    """``experiments/<name>.py`` as a module (it is a script, not part of the package)."""
    path = REPO / "experiments" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"_equimesh_bench_experiment_{name}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _quietly(function, *args):
    with contextlib.redirect_stdout(io.StringIO()):
        return function(*args)


def _starts(objectives, lengths):
    """The reference surface and, per objective and l of ``objectives`` and ``lengths``, the start that
    ``mesh_surface`` optimises (its ``stages``; default placement): the plane at l remapped, or at the larger spacing
    where sound joints need room (docs/decisions.md, "Sound joints").  The inputs of the optimisation suites."""
    surface = _surface()
    return surface, {
        (objective, l): equimesh.mesh_surface(
            surface, l, grid=SURFACE_GRID, optimize=objective, placement="default", max_nodes=None
        ).stages
        for objective in objectives
        for l in lengths
    }


def _optimise(cache, objective, l, factorisation=None, **boundary):
    """``equimesh.optimize_uv`` of the start of ``objective`` at ``l`` in ``cache`` (surface, stages by objective and
    l), its boundary as ``mesh_surface`` sets it up for ``objective`` unless ``boundary`` gives ``fixed`` and
    ``slides``."""
    surface, starts = cache
    stages = starts[objective, l]
    plane, uv = stages.plane, stages.remapped_uv
    if not boundary and objective == "bounded":  # its boundary slides
        slides, fixed = stages.outline.slides(plane, uv)
        boundary = {"slides": slides, "fixed": fixed}
    elif not boundary:
        boundary = {"slides": (), "fixed": np.arange(plane.n_boundary)}
    return equimesh.optimize_uv(
        surface,
        uv,
        plane.edges,
        plane.edge_groups,
        l,
        triangles=plane.triangles,
        objective=objective,
        factorisation=factorisation,
        **boundary,
    )


class SurfaceStages:
    """Each stage of ``equimesh.mesh_surface`` alone, on the reference surface (l = 5, 15 x 15 grid).

    ``setup_cache`` runs the pipeline once without the optimisation (about
    0.4 s) and keeps every stage; each ``time_`` method then repeats exactly one
    stage from the previous stage's output: flattening by eq. (1) (256 nodes,
    705 edges), the planar triangulation of Problem 2 with the lattice placement
    search (a 40-vertex polygon, about 350 nodes), remapping by eqs. (2)-(3)
    (about 310 inner and 40 boundary nodes), and the optimisation of the inner
    nodes' (u, v) (about 620 variables, the slowest stage).
    """

    number = 1
    repeat = (1, 5, 60.0)
    timeout = 300.0

    def setup_cache(self):
        surface = _surface()
        mesh = equimesh.mesh_surface(surface, SURFACE_LENGTH, grid=SURFACE_GRID, optimize="none")
        return surface, mesh

    def time_flattening(self, cache):
        """Step 2: minimise E of eq. (1) over the plane coordinates of the auxiliary nodes."""
        _, mesh = cache
        st = mesh.stages
        equimesh.flatten(st.auxiliary_points, st.grid.triangles, uv=st.grid.uv)

    def time_planar_triangulation(self, cache):
        """Step 3: lattice placement search plus Problem 2 on the flattened boundary polygon."""
        _, mesh = cache
        outline = mesh.stages.outline.vertices
        place = equimesh.best_lattice_placement(outline, SURFACE_LENGTH)
        equimesh.uniform_triangulation(outline, SURFACE_LENGTH, angle=place.angle, offset=place.offset)

    def time_remapping(self, cache):
        """Step 4 exactly as mesh_surface calls it: eqs. (2)-(3) inside, the outline for the boundary nodes,
        evaluate."""
        surface, mesh = cache
        st = mesh.stages
        plane = st.plane
        equimesh.remap(
            surface,
            plane.points,
            st.flattening.points,
            st.grid,
            on_boundary=np.arange(plane.n_boundary),
            outline=st.outline,
        )


class Optimisation:
    """The final optimisation (``equimesh.optimize_uv``) for both objectives, by mesh size.

    Input: the reference dome (default placement, 15 x 15 grid) at l = 5, 2.5
    and 1.25, remapped as ``mesh_surface`` does for each objective (:func:`_starts`):
    about 1,000, 4,200 and 17,300 members (370, 1,440 and 5,840 nodes) for "paper",
    a few per cent fewer at the smaller l for "bounded", whose plane is meshed
    again there.  "paper": G1 members, boundary fixed; "bounded": every member
    in [l, 2l], joints sound, boundary sliding.
    """

    params = (["paper", "bounded"], [5.0, 2.5, 1.25])
    param_names = ["objective", "l"]
    timeout = 600

    def setup_cache(self):
        return _starts(*self.params)

    def _run(self, cache, objective, l):
        surface, starts = cache
        return _optimise(cache, objective, l), surface, starts[objective, l].plane

    def time_optimisation(self, cache, objective, l):
        """One optimisation of the remapped reference dome."""
        self._run(cache, objective, l)

    def track_share_within_half_percent(self, cache, objective, l):
        """Share of all members within 0.5 % of l after the optimisation."""
        result, surface, mesh = self._run(cache, objective, l)
        points = surface.evaluate(result.uv[:, 0], result.uv[:, 1])
        ratio = np.linalg.norm(points[mesh.edges[:, 1]] - points[mesh.edges[:, 0]], axis=1) / l
        return float(np.mean(np.abs(ratio - 1.0) <= 0.005))

    track_share_within_half_percent.unit = "share"

    def track_jacobian_evaluations(self, cache, objective, l):
        """Jacobian evaluations of the solver, one per iteration (each about one factorisation): its work, whatever the
        load."""
        return self._run(cache, objective, l)[0].njev

    track_jacobian_evaluations.unit = "evaluations"


class Pipeline:
    """``equimesh.mesh_surface`` end to end with its defaults ("bounded", best placement, default node limit) on the
    reference surface at l = 1.66: about 3,200 nodes and 9,400 members."""

    number = 1
    repeat = (1, 3, 120.0)
    timeout = 600.0

    def setup(self):
        self.surface = _surface()

    def time_mesh_surface(self):
        """Every stage: auxiliary grid, flattening, placement search and Problem 2, remapping, "bounded"."""
        equimesh.mesh_surface(self.surface, PIPELINE_LENGTH)

    def track_members(self):
        """Members of the mesh timed (the size of the benchmark)."""
        return len(equimesh.mesh_surface(self.surface, PIPELINE_LENGTH).edges)

    track_members.unit = "members"


class Factorisations:
    """The "bounded" optimisation (``equimesh.optimize_uv``) with each factorisation of its normal equations.

    Input: the start of "bounded" on the reference dome at l = 2.5 and 1.25
    (about 4,100 and 16,700 members), as in :class:`Optimisation`; a
    factorisation whose library is not installed is skipped.
    """

    params = (list(FACTORISATIONS), [2.5, 1.25])
    param_names = ["factorisation", "l"]
    timeout = 900

    def setup_cache(self):
        return _starts(["bounded"], self.params[1])

    def setup(self, cache, factorisation, l):
        surface, starts = cache
        plane, uv = starts["bounded", l].plane, starts["bounded", l].remapped_uv
        try:  # every node fixed under the paper's objective, which bounds nothing: only the factorisation is checked
            equimesh.optimize_uv(
                surface, uv, plane.edges, plane.edge_groups, l, fixed=np.arange(len(uv)), factorisation=factorisation
            )
        except equimesh.EquimeshError as error:
            raise NotImplementedError(str(error)) from None

    def time_bounded_optimisation(self, cache, factorisation, l):
        """One "bounded" optimisation of the remapped reference dome."""
        _optimise(cache, "bounded", l, factorisation)

    def track_jacobian_evaluations(self, cache, factorisation, l):
        """Jacobian evaluations (one factorisation each, and those of rejected steps): the rounding of each
        factorisation takes the rounds on their own path."""
        return _optimise(cache, "bounded", l, factorisation).njev

    track_jacobian_evaluations.unit = "evaluations"


class Table1:
    """``experiments/table1.py`` and ``experiments/figures.py`` end to end, and the Table 1 figures.

    ``setup_cache`` runs table1.py once (about 6 s) into a temporary folder
    and keeps its CSV and mesh data in memory; ``time_table1`` runs it again
    (pipeline, statistics, CSV/Markdown/npz/provenance writing),
    ``time_figures`` draws Figs 1-5 (PNG and PDF) from the kept data, and the
    ``track_`` methods report Table 1's numbers for the reference surface, so
    that their history across commits shows in ``asv publish``.
    """

    number = 1
    repeat = (1, 3, 60.0)
    timeout = 300.0

    def setup_cache(self):
        table1 = _experiment("table1")
        folder = Path(tempfile.mkdtemp(prefix="equimesh-bench-table1-"))
        try:
            _quietly(table1.main, ["--surface", str(REFERENCE_SURFACE_JSON), "--out-dir", str(folder)])
            csv = (folder / "table1.csv").read_text(encoding="utf-8")
            npz = (folder / "table1_mesh.npz").read_bytes()
        finally:
            shutil.rmtree(folder, ignore_errors=True)
        return {"csv": csv, "npz": npz}

    def setup(self, cache):
        self.folder = Path(tempfile.mkdtemp(prefix="equimesh-bench-"))
        self.npz = self.folder / "table1_mesh.npz"
        self.npz.write_bytes(cache["npz"])
        self.table1 = _experiment("table1")
        self.figures = _experiment("figures")

    def teardown(self, cache):
        shutil.rmtree(self.folder, ignore_errors=True)

    def time_table1(self, cache):
        """python experiments/table1.py: mesh, Table 1 rows, extras, all files written."""
        _quietly(self.table1.main, ["--surface", str(REFERENCE_SURFACE_JSON), "--out-dir", str(self.folder / "out")])

    def time_figures(self, cache):
        """python experiments/figures.py: Figs 1-5 from the mesh data, PNG and PDF, with hidden-line removal."""
        _quietly(self.figures.main, ["--data", str(self.npz), "--fig-dir", str(self.folder / "figs")])

    @staticmethod
    def _value(cache, row, column):
        df = pd.read_csv(io.StringIO(cache["csv"]))
        return float(df[(df["row"] == row) & (df["source"] == "equimesh")][column].iloc[0])

    def track_g1_members(self, cache):
        """Table 1, plane (G1): number of members of length l on the plane (the paper: 774)."""
        return int(self._value(cache, "plane (G1)", "no. of members"))

    track_g1_members.unit = "members"

    def track_g1_std_before_optimisation(self, cache):
        """Table 1, final surf. (G1): std. dev. of the G1 lengths after remapping (the paper: 0.2780)."""
        return self._value(cache, "final surf. (G1)", "std. dev.")

    track_g1_std_before_optimisation.unit = "length"

    def track_g1_std_after_optimisation(self, cache):
        """Table 1, final opt. (G1): std. dev. of the G1 lengths after the optimisation (the paper: 0.1915)."""
        return self._value(cache, "final opt. (G1)", "std. dev.")

    track_g1_std_after_optimisation.unit = "length"

    def track_total_max_after_optimisation(self, cache):
        """Table 1, final opt (total): the longest member after the optimisation (the paper: 13.3777)."""
        return self._value(cache, "final opt (total)", "max.")

    track_total_max_after_optimisation.unit = "length"
