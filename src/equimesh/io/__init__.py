"""Input and output: surface descriptions in, meshes and member schedules out, provenance.

* :mod:`._surfaces`   reading surfaces: input formats by extension, surface types by JSON ``"type"``;
* :mod:`._bezier`     the JSON schema of a Bezier surface (one row of the type table);
* :mod:`._nurbs`      the JSON schema of a NURBS surface (another row);
* :mod:`._rhino`      Rhino ``.3dm`` files (rhino3dm, optional): a NURBS surface or a single-face Brep;
* :mod:`._trimesh`    triangle meshes (.obj, .stl, .ply, .vtk, .vtu via meshio) as the auxiliary triangulation;
* :mod:`._schema`     checks shared by the schemas, plain text for messages;
* :mod:`._meshes`     writing meshes (meshio) and member schedules, checks of output paths;
* :mod:`._report`     the report of a run: one self-contained HTML page (plotly, optional);
* :mod:`._plot`       the plot of a run: the mesh by length class and the length histogram (matplotlib);
* :mod:`._view`       what the report and the plot draw: members by class, colours, bins, boundary;
* :mod:`._atomic`     atomic writes (temporary files, then renames), one file or a set;
* :mod:`.provenance`  git commit, date, versions and parameters beside every result.
"""

from ._meshes import (
    MEMBER_FORMATS,
    MESH_FORMATS,
    check_output_path,
    classes_path,
    member_schedule,
    surface_mesh_writer,
    write_members,
    write_mesh,
    write_surface_mesh,
)
from ._plot import PLOT_FORMATS, plot_output, write_plot
from ._report import REPORT_FORMATS, report_output, write_report
from ._rhino import to_rhino_surface
from ._surfaces import INPUT_FORMATS, SURFACE_TYPES, load_surface, surface_from_dict, surface_to_dict

__all__ = [
    "INPUT_FORMATS",
    "MEMBER_FORMATS",
    "MESH_FORMATS",
    "PLOT_FORMATS",
    "REPORT_FORMATS",
    "SURFACE_TYPES",
    "check_output_path",
    "classes_path",
    "load_surface",
    "member_schedule",
    "plot_output",
    "report_output",
    "surface_from_dict",
    "surface_mesh_writer",
    "surface_to_dict",
    "to_rhino_surface",
    "write_members",
    "write_mesh",
    "write_plot",
    "write_report",
    "write_surface_mesh",
]
