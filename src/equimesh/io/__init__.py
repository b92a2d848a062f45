"""Input and output: surface descriptions in, meshes, schedules and CAD files out, provenance.

* :mod:`._surfaces`    reading surfaces: input formats by extension, surface types by JSON ``"type"``;
* :mod:`._bezier`      the JSON schema of a Bezier surface (one row of the type table);
* :mod:`._nurbs`       the JSON schema of a NURBS surface (another row);
* :mod:`._rhino`       Rhino ``.3dm`` files in (rhino3dm, optional): a NURBS surface or a single-face Brep;
* :mod:`._trimesh`     triangle meshes (.obj, .stl, .ply, .vtk, .vtu) as the auxiliary triangulation;
* :mod:`._obj`         Wavefront OBJ files: positions and faces, whatever else a modeller writes beside them;
* :mod:`._schema`      checks shared by the schemas, plain text for messages;
* :mod:`._outputs`     every output of a run: slots, formats by extension (one table), checks, all-or-nothing writes;
* :mod:`._schedules`   the tables outputs are written from: member schedule, length classes, node schedule;
* :mod:`._meshes`      meshes out through meshio, without its time stamp;
* :mod:`._rhino_out`   Rhino ``.3dm`` files out (rhino3dm): mesh, members on a layer per class, nodes;
* :mod:`._compas`      COMPAS mesh JSON out (compas, optional);
* :mod:`._dxf`         DXF out (ezdxf, optional): members as 3-D lines on a layer per class;
* :mod:`._paths`       output paths: writable, none an input, no two the same file;
* :mod:`._report`      the report of a run: one self-contained HTML page (plotly, optional);
* :mod:`._plot`        the plot of a run: the mesh by length class and the length histogram (matplotlib);
* :mod:`._view`        what the report and the plot draw: members by class, colours, bins, boundary;
* :mod:`._atomic`      atomic writes (temporary files, then renames), one file or a set;
* :mod:`.provenance`   git commit, date, versions and parameters beside every result.
"""

from ._outputs import (
    OUTPUT_FORMATS,
    OUTPUT_SLOTS,
    OutputFormat,
    OutputSlot,
    check_output_path,
    output_format,
    output_formats,
    output_table,
    surface_mesh_writer,
    write_members,
    write_plot,
    write_report,
    write_surface_mesh,
)
from ._rhino import to_rhino_surface
from ._schedules import Products, classes_path, member_schedule, node_schedule
from ._surfaces import INPUT_FORMATS, SURFACE_TYPES, load_surface, surface_from_dict, surface_to_dict

__all__ = [
    "INPUT_FORMATS",
    "OUTPUT_FORMATS",
    "OUTPUT_SLOTS",
    "OutputFormat",
    "OutputSlot",
    "Products",
    "SURFACE_TYPES",
    "check_output_path",
    "classes_path",
    "load_surface",
    "member_schedule",
    "node_schedule",
    "output_format",
    "output_formats",
    "output_table",
    "surface_from_dict",
    "surface_mesh_writer",
    "surface_to_dict",
    "to_rhino_surface",
    "write_members",
    "write_plot",
    "write_report",
    "write_surface_mesh",
]
