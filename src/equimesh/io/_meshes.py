"""Meshes and member schedules out: output formats by extension, checks before any work, all-or-nothing writes.

Meshes are written through meshio in the format given by the file extension
(:data:`MESH_FORMATS`), member schedules as CSV (:data:`MEMBER_FORMATS`) with
their length classes (:mod:`equimesh.classes`) in a second CSV beside them.
:func:`check_output_path` tries everything a write will need (folder, name
length, permission) so that a run can refuse a bad output before its expensive
part (:func:`surface_mesh_writer` checks every file of a run once, before it,
and writes them after it); every output of one call is written to a temporary file and the files
are renamed together at the end (:func:`equimesh.io._atomic.atomic_paths`), so a
failure never leaves a partial file or half a set of files.
"""

import errno
import math
import os
from pathlib import Path

import meshio
import numpy as np
import pandas as pd

from ..classes import DEFAULT_TOLERANCE, length_classes
from ..errors import OutputPathError
from ..mesh import G1, edge_lengths
from ._atomic import atomic_paths, probe_folder
from ._schema import shown_path

#: Mesh output formats by extension (meshio format names).
MESH_FORMATS = {".obj": "obj", ".vtk": "vtk", ".vtu": "vtu", ".stl": "stl", ".ply": "ply", ".msh": "gmsh22"}

#: Member schedule formats by extension.
MEMBER_FORMATS = {".csv": "csv"}

#: The classes CSV of a member schedule ``m.csv`` is ``m.classes.csv`` (:func:`classes_path`).
CLASSES_SUFFIX = ".classes.csv"

#: Cell data a meshio format requires (one zero per triangle for each name).
_REQUIRED_CELL_DATA = {"gmsh22": ("gmsh:physical", "gmsh:geometrical")}


def check_output_path(path, formats):
    """Check that ``path`` can be written as one of ``formats`` (by extension); return the format.

    Tried, in this order: the extension is known, the name and the whole path
    fit the file system's limits, the folder exists and is a folder, the
    target is not a folder nor a special file (a rename would replace it), and
    a temporary file can really be created (and is removed) in the folder.

    Raises
    ------
    OutputPathError
        one line naming the first problem.
    """
    path = Path(path)
    fmt = formats.get(path.suffix.lower())
    if fmt is None:
        raise OutputPathError(
            f"unknown output extension {path.suffix!r} for {shown_path(path)}; use one of {sorted(formats)}"
        )
    folder = path.parent
    try:
        name_bytes, name_max = len(os.fsencode(path.name)), _pathconf(folder, "PC_NAME_MAX")
        if name_bytes > name_max:
            raise OutputPathError(
                f"output file name is {name_bytes} bytes long, more than the {name_max} this file system allows: "
                f"{shown_path(path.name)}"
            )
        path_bytes, path_max = len(os.fsencode(str(path))), _pathconf(folder, "PC_PATH_MAX")  # PATH_MAX counts a NUL
        if path_bytes >= path_max:
            raise OutputPathError(
                f"output path is {path_bytes} bytes long, more than the {path_max - 1} this system allows: "
                f"{shown_path(path)}"
            )
        if not folder.is_dir():
            state = "is not a folder" if folder.exists() else "does not exist"
            raise OutputPathError(f"output folder {state}: {shown_path(folder)}")
        if path.is_dir():
            raise OutputPathError(f"output {shown_path(path)} is a folder")
        if path.exists() and not path.is_file():
            raise OutputPathError(f"output {shown_path(path)} exists and is not a regular file")
        probe_folder(folder, path.suffix)
    except OSError as exc:
        reason = "path too long" if exc.errno == errno.ENAMETOOLONG else exc.strerror or type(exc).__name__
        raise OutputPathError(f"cannot write {shown_path(path)}: {reason}") from None
    return fmt


def write_mesh(path, points, triangles):
    """Write a triangle mesh to ``path`` (format by extension, see :data:`MESH_FORMATS`), atomically."""
    _write_all([_mesh_output(path, check_output_path(path, MESH_FORMATS), points, triangles)])


def member_schedule(points, edges, groups, l, classes=None):
    """The member schedule: one row per edge with its nodes, length, group, class and deviation from l.

    ``classes`` (:class:`equimesh.classes.LengthClasses` of these edges) adds
    the column ``class``, each member's length class.
    """
    e = np.asarray(edges)
    length = edge_lengths(points, e)
    columns = {
        "member": np.arange(len(e)),
        "node_i": e[:, 0],
        "node_j": e[:, 1],
        "length": length,
        "group": np.where(np.asarray(groups) == G1, "G1", "other"),
    }
    if classes is not None:
        columns["class"] = classes.member_class
    columns.update({"deviation": length - l, "relative_deviation": (length - l) / l})
    return pd.DataFrame(columns)


def classes_path(members):
    """Where the classes CSV of the member schedule ``members`` goes: ``<stem>.classes.csv`` beside it."""
    members = Path(members)
    return members.with_name(members.stem + CLASSES_SUFFIX)


def write_members(path, points, edges, groups, l, tolerance=DEFAULT_TOLERANCE):
    """Write :func:`member_schedule` as CSV to ``path`` and its length classes to :func:`classes_path`, atomically."""
    _check_members_paths(path)
    _write_all(_members_outputs(path, points, edges, groups, l, tolerance))


def write_surface_mesh(mesh, path, members=None, tolerance=DEFAULT_TOLERANCE):
    """Write a :class:`equimesh.SurfaceMesh` to ``path`` and, if given, its member schedule to ``members``.

    With ``members`` the schedule gets a ``class`` column and the classes at
    ``tolerance`` (:func:`equimesh.classes.length_classes`) go to
    :func:`classes_path`.  All or nothing: either every file is written
    completely or none is touched (a failure of a later write removes the
    earlier temporary files before any rename).
    """
    surface_mesh_writer(path, members)(mesh, tolerance)


def surface_mesh_writer(path, members=None, also=()):
    """Check every file :func:`write_surface_mesh` writes (:func:`check_output_path`); return the writer.

    The checks run now, before a run's expensive part, and only now: the
    returned ``write(mesh, tolerance=DEFAULT_TOLERANCE)`` writes ``mesh`` as
    :func:`write_surface_mesh` does, to the paths checked here.  ``also``
    holds further outputs of the run, ``(path, fill)`` pairs whose path the
    caller checked (``equimesh.io.report_output``, ``equimesh.io.plot_output``):
    ``fill(tmp, mesh, tolerance)`` writes one to a temporary file, renamed
    together with the others.
    """
    fmt = check_output_path(path, MESH_FORMATS)
    if members is not None:
        _check_members_paths(members)

    def write(mesh, tolerance=DEFAULT_TOLERANCE):
        outputs = [_mesh_output(path, fmt, mesh.points, mesh.triangles)]
        if members is not None:
            outputs += _members_outputs(members, mesh.points, mesh.edges, mesh.edge_groups, mesh.length, tolerance)
        outputs += [(out, lambda tmp, fill=fill: fill(tmp, mesh, tolerance)) for out, fill in also]
        _write_all(outputs)

    return write


def _mesh_output(path, fmt, points, triangles):
    cells = np.asarray(triangles, dtype=np.int32)
    zeros = np.zeros(len(cells), dtype=np.int32)
    cell_data = {name: [zeros] for name in _REQUIRED_CELL_DATA.get(fmt, ())}
    mesh = meshio.Mesh(np.asarray(points, dtype=float), [("triangle", cells)], cell_data=cell_data)
    return path, lambda tmp: mesh.write(tmp, file_format=fmt)


def _members_outputs(path, points, edges, groups, l, tolerance):
    """The schedule and the classes CSV (paths checked by the caller); floats as the shortest text that reads back to
    the same bits."""
    classes = length_classes(edge_lengths(points, edges), l, tolerance)
    schedule = member_schedule(points, edges, groups, l, classes)
    return [
        (path, lambda tmp: schedule.to_csv(tmp, index=False)),
        (classes_path(path), lambda tmp: classes.table().to_csv(tmp, index=False)),
    ]


def _check_members_paths(path):
    """:func:`check_output_path` of a member schedule and of its classes CSV."""
    check_output_path(path, MEMBER_FORMATS)
    check_output_path(classes_path(path), MEMBER_FORMATS)


def _write_all(outputs):
    """Write ``(path, write)`` pairs, ``write(tmp)`` filling a temporary file; rename them all at the end."""
    with atomic_paths(*(path for path, _ in outputs)) as tmps:
        for (_, write), tmp in zip(outputs, tmps):
            write(tmp)


def _pathconf(folder, name):
    """The file system's limit ``name`` at ``folder`` (bytes), or infinity where there is none or it cannot be asked."""
    try:
        limit = os.pathconf(folder, name)
    except (AttributeError, ValueError, OSError):  # no pathconf (Windows), unknown name
        return math.inf
    return math.inf if limit < 0 else limit
