"""Input and output: surface descriptions in, meshes and member schedules out, provenance.

* :mod:`._surfaces`   reading surfaces: input formats by extension, surface types by JSON ``"type"``;
* :mod:`._bezier`     the JSON schema of a Bezier surface (one row of the type table);
* :mod:`._nurbs`      the JSON schema of a NURBS surface (another row);
* :mod:`._rhino`      Rhino ``.3dm`` files (rhino3dm, optional): a NURBS surface or a single-face Brep;
* :mod:`._trimesh`    triangle meshes (.obj, .stl, .ply, .vtk, .vtu) as the auxiliary triangulation;
* :mod:`._obj`        Wavefront OBJ files: positions and faces, whatever else a modeller writes beside them;
* :mod:`._schema`     checks shared by the schemas, plain text for messages;
* :mod:`._meshes`     writing meshes (meshio) and member schedules, checks of output paths;
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
from ._rhino import to_rhino_surface
from ._surfaces import INPUT_FORMATS, SURFACE_TYPES, load_surface, surface_from_dict, surface_to_dict

__all__ = [
    "INPUT_FORMATS",
    "MEMBER_FORMATS",
    "MESH_FORMATS",
    "SURFACE_TYPES",
    "check_output_path",
    "classes_path",
    "load_surface",
    "member_schedule",
    "surface_from_dict",
    "surface_mesh_writer",
    "surface_to_dict",
    "to_rhino_surface",
    "write_members",
    "write_mesh",
    "write_surface_mesh",
]
