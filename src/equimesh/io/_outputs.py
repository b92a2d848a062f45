"""Every output of a run in one table: which file each output is, its formats by extension, checks, writing.

An output *slot* (:data:`OUTPUT_SLOTS`) is one file a run may write: the mesh
(``-o``), the member schedule (``--members``), the node schedule
(``--nodes``); the command line offers each slot as an option ``--<slot>``
(the mesh as ``-o``/``--output``).  A *format* (:data:`OUTPUT_FORMATS`, one
:class:`OutputFormat` row each, as meshio registers its formats) is an
extension of a slot with its writer, the optional extra it needs and what the
file holds; the command line's help, the message for an unknown extension and
the README's output table (:func:`output_table`) are made from the rows
(docs/decisions.md, "Output formats are one table").  A writer is
``write(tmp, products)``: it fills the temporary file ``tmp`` from a
:class:`~equimesh.io._schedules.Products`.

:func:`surface_mesh_writer` checks every file of a run before the run's
expensive part, and only then: the extension, the extra, the folder
(:func:`~equimesh.io._paths.check_writable`), that no output is an input file
and that no two outputs are one file (:func:`~equimesh.io._paths.check_distinct`).
It returns the writer, which writes every file to a temporary one and renames
them together at the end (:func:`~equimesh.io._atomic.atomic_paths`): a run
writes every file or none (docs/decisions.md, "Outputs checked first, written all or none").
"""

import functools
import importlib
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from ..classes import DEFAULT_TOLERANCE
from ..errors import MissingDependencyError, OutputPathError
from ._atomic import atomic_paths
from ._compas import write_compas
from ._dxf import write_dxf
from ._meshes import write_mesh
from ._paths import check_distinct, check_writable
from ._plot import write_figure
from ._report import write_report_html
from ._rhino_out import write_3dm
from ._schedules import Products, classes_path, write_classes_csv, write_members_csv, write_nodes_csv
from ._schema import shown_path


@dataclass(frozen=True)
class OutputSlot:
    """One file a run may write: ``noun`` names it in messages, ``metavar`` and ``help`` on the command line."""

    noun: str
    metavar: str
    help: str
    required: bool = False


@dataclass(frozen=True)
class Beside:
    """A file written beside a slot's file (the classes CSV of a member schedule): its path from the slot's path."""

    noun: str
    path: Callable
    write: Callable


@dataclass(frozen=True)
class OutputFormat:
    """One output format: the slot and extension it answers, its writer, what it holds, the extra it needs.

    ``extra`` names the optional dependency (``pip install 'equimesh[extra]'``)
    and ``module`` the import it provides; ``beside`` are the files written
    with it.
    """

    slot: str
    extension: str
    name: str
    holds: str
    write: Callable
    extra: str | None = None
    module: str | None = None
    beside: tuple = ()


#: The files a run may write, by slot name (the command line's option is ``--<slot>``).
OUTPUT_SLOTS = {
    "mesh": OutputSlot("mesh", "OUT", "the mesh", required=True),
    "members": OutputSlot(
        "member schedule",
        "CSV",
        "also write the member schedule, and its length classes to CSV's stem + '.classes.csv'",
    ),
    "nodes": OutputSlot("node schedule", "CSV", "also write the node schedule"),
    "report": OutputSlot(
        "report",
        "HTML",
        "also write a report: one self-contained HTML page (opens offline) with the mesh in 3-D coloured by length "
        "class or deviation from L, the length histogram, the classes, the angles, the run's summary and provenance",
    ),
    "plot": OutputSlot(
        "plot", "PNG", "also draw the mesh coloured by length class with the length histogram beside it"
    ),
}

_MESH = "the nodes and triangles"
_MESHIO = (
    (".obj", "obj", "Wavefront OBJ"),
    (".vtk", "vtk", "VTK legacy"),
    (".vtu", "vtu", "VTK XML"),
    (".stl", "stl", "STL (text)"),
    (".ply", "ply", "PLY (binary)"),
    (".msh", "gmsh22", "Gmsh 2.2"),
)

#: Every output format, in the order the help and the README list them.
OUTPUT_FORMATS = (
    *(OutputFormat("mesh", ext, name, _MESH, functools.partial(write_mesh, fmt=fmt)) for ext, fmt, name in _MESHIO),
    OutputFormat(
        "mesh",
        ".3dm",
        "Rhino",
        "the mesh on layer mesh; one line per member on a sublayer of members per length class, named with its "
        "nominal length and count; one point per node on layer nodes; each member's and node's schedule row as "
        "user text",
        write_3dm,
        extra="rhino",
        module="rhino3dm",
    ),
    OutputFormat(
        "mesh",
        ".compas.json",
        "COMPAS mesh JSON",
        "a compas.datastructures.Mesh (compas.json_load): vertices with boundary, valence, min_angle, max_angle; "
        "edges with member, length, class, group",
        write_compas,
        extra="compas",
        module="compas",
    ),
    OutputFormat(
        "mesh",
        ".dxf",
        "DXF R2010",
        "one 3-D line per member on a layer per length class, named with its nominal length and count; with "
        "--dxf-labels each member's class as text at its midpoint on layer labels",
        write_dxf,
        extra="dxf",
        module="ezdxf",
    ),
    OutputFormat(
        "members",
        ".csv",
        "CSV",
        "member, node_i, node_j, length, group (G1 or other), class, deviation, relative_deviation; and beside m.csv "
        "the length classes m.classes.csv: class, count, nominal_length, min_length, max_length",
        write_members_csv,
        beside=(Beside("length classes", classes_path, write_classes_csv),),
    ),
    OutputFormat(
        "nodes",
        ".csv",
        "CSV",
        "node, x, y, z, boundary (1 or 0), valence (members at the node), min_angle, max_angle (degrees between "
        "two members meeting at the node)",
        write_nodes_csv,
    ),
    OutputFormat(
        "report",
        ".html",
        "HTML",
        "one self-contained page (plotly inlined, opens offline): the mesh in 3-D by length class or deviation from "
        "L, the length histogram, the classes, the angles, the run's summary and provenance",
        write_report_html,
        extra="report",
        module="plotly",
    ),
    *(
        OutputFormat(
            "plot",
            f".{fmt}",
            name,
            "the mesh in 3-D by length class, the length histogram beside it",
            functools.partial(write_figure, fmt=fmt),
        )
        for fmt, name in (("png", "PNG"), ("svg", "SVG"), ("pdf", "PDF"))
    ),
)


def output_formats(slot):
    """The formats of ``slot`` by extension."""
    return {f.extension: f for f in OUTPUT_FORMATS if f.slot == slot}


def output_format(path, slot="mesh"):
    """The format of ``slot`` that ``path``'s extension selects, the longest one that matches (``.compas.json``).

    Raises
    ------
    OutputPathError
        no format of ``slot`` has that extension (the message lists those that do).
    """
    formats = output_formats(slot)
    name = Path(path).name.lower()
    matching = [ext for ext in formats if name.endswith(ext)]
    if not matching:
        suffix = Path(path).suffix
        raise OutputPathError(
            f"{f'unknown extension {suffix!r}' if suffix else 'no extension'} for the {OUTPUT_SLOTS[slot].noun} "
            f"{shown_path(path)}; use one of {', '.join(formats)}"
        )
    return formats[max(matching, key=len)]


def check_output_path(path, slot="mesh"):
    """Check that ``path`` can be written as an output of ``slot``; return its :class:`OutputFormat`.

    The extension selects a format (:func:`output_format`), the format's extra
    is installed, and the file can be written (folder, name length, permission:
    :func:`~equimesh.io._paths.check_writable`).  ``surface_mesh_writer`` checks
    every file of a run so, and that they are distinct.

    Raises
    ------
    OutputPathError
        one line naming the first problem.
    MissingDependencyError
        the format's extra is not installed (the message says how to install it).
    """
    return _checked(path, slot)[0]


def _checked(path, slot):
    fmt = output_format(path, slot)
    if fmt.module is not None:
        try:
            importlib.import_module(fmt.module)
        except ImportError:
            raise MissingDependencyError(
                f"{shown_path(path)}: writing {fmt.name} files ({fmt.extension}) needs {fmt.module}, "
                f"which is not installed: pip install 'equimesh[{fmt.extra}]'"
            ) from None
    return fmt, check_writable(path)


class RunWriter:
    """The outputs of one run, checked: ``writer(mesh, tolerance)`` writes them all or none; ``paths`` lists them."""

    def __init__(self, files, dxf_labels, parameters=None, record=None):
        self._files, self._dxf_labels, self._run = files, dxf_labels, (parameters, record)
        self.paths = [path for path, _ in files]

    def __call__(self, mesh, tolerance=DEFAULT_TOLERANCE):
        products = Products(mesh, tolerance, self._dxf_labels, *self._run)
        with atomic_paths(*self.paths) as tmps:
            for (_, write), tmp in zip(self._files, tmps):
                write(tmp, products)


def surface_mesh_writer(outputs, *, inputs=(), dxf_labels=False, parameters=None, record=None):
    """Check every file a run writes, before the run's expensive part; return its :class:`RunWriter`.

    Parameters
    ----------
    outputs : mapping
        a path (or None) per slot of :data:`OUTPUT_SLOTS`: ``{"mesh": "roof.3dm", "members": "roof.csv"}``.
    inputs : iterable of paths
        the files the run reads: no output may be one of them.
    dxf_labels : bool
        write each member's class as text in a DXF file.
    parameters, record : dict, optional
        what the run was given and its provenance record, for the report (:class:`~equimesh.io._schedules.Products`).

    Raises
    ------
    OutputPathError, MissingDependencyError
        one line: the first output that cannot be written (:func:`check_output_path`), an output that is an
        input file, two outputs that are one file.
    """
    unknown = sorted(set(outputs) - set(OUTPUT_SLOTS))
    if unknown:
        raise TypeError(f"unknown outputs {unknown}; the outputs are {sorted(OUTPUT_SLOTS)}")
    files, checked = [], []
    for slot, path in outputs.items():
        if path is None:
            continue
        fmt, folds = _checked(path, slot)
        files.append((Path(path), fmt.write))
        checked.append((path, OUTPUT_SLOTS[slot].noun, folds))
        for beside in fmt.beside:
            other = beside.path(path)
            files.append((other, beside.write))
            checked.append((other, beside.noun, _checked(other, slot)[1]))
    check_distinct(checked, [(path, "input") for path in inputs])
    return RunWriter(files, dxf_labels, parameters, record)


def write_surface_mesh(mesh, path, members=None, tolerance=DEFAULT_TOLERANCE, *, dxf_labels=False, **outputs):
    """Write a :class:`equimesh.SurfaceMesh` to ``path`` (format by extension, :data:`OUTPUT_FORMATS`) and, if
    given, its member schedule to ``members`` and the other outputs by slot (``nodes="nodes.csv"``).

    The schedule gets a ``class`` column and the classes at ``tolerance``
    (:func:`equimesh.classes.length_classes`) go to :func:`classes_path`.  All
    or nothing: either every file is written completely or none is touched.
    """
    surface_mesh_writer({"mesh": path, "members": members, **outputs}, dxf_labels=dxf_labels)(mesh, tolerance)


def write_report(mesh, path, *, tolerance=DEFAULT_TOLERANCE, parameters=None, record=None):
    """Write the report of ``mesh`` (a :class:`equimesh.SurfaceMesh` or :class:`equimesh.PlanarMesh`) to ``path``, an
    ``.html`` file, atomically (:mod:`equimesh.io._report`).

    ``parameters`` is what the run was given (input file, options), shown
    under provenance (default: l and the tolerance); ``record`` the
    provenance record to show (:func:`equimesh.io.provenance.provenance`;
    default: made now from ``parameters``).

    Raises
    ------
    OutputPathError
        ``path`` cannot be written (:func:`check_output_path`).
    MissingDependencyError
        plotly is not installed (``pip install 'equimesh[report]'``).
    """
    surface_mesh_writer({"report": path}, parameters=parameters, record=record)(mesh, tolerance)


def write_plot(mesh, path, *, tolerance=DEFAULT_TOLERANCE):
    """Draw ``mesh`` to ``path`` (``.png``, ``.svg`` or ``.pdf``), atomically (:mod:`equimesh.io._plot`)."""
    surface_mesh_writer({"plot": path})(mesh, tolerance)


def write_members(path, points, edges, groups, l, tolerance=DEFAULT_TOLERANCE):
    """Write :func:`member_schedule` of the members ``edges`` as CSV to ``path`` and their length classes to
    :func:`classes_path`, atomically."""
    surface_mesh_writer({"members": path})(_Members(points, edges, groups, l), tolerance)


@dataclass(frozen=True)
class _Members:
    """Members without a mesh: what the member schedule and its classes are written from."""

    points: object
    edges: object
    edge_groups: object
    length: float


def output_table():
    """The README's table of output formats (Markdown): option, extension, format, what the file holds, extra."""
    rows = ["| option | extension | format | holds | extra |", "|---|---|---|---|---|"]
    for f in OUTPUT_FORMATS:
        option = "-o" if f.slot == "mesh" else f"--{f.slot}"
        extra = f"`{f.extra}`" if f.extra else ""
        rows.append(f"| `{option}` | `{f.extension}` | {f.name} | {f.holds} | {extra} |")
    return "\n".join(rows)
