"""Input and output: surface descriptions in, meshes and member schedules out, provenance.

* :mod:`._meshes`     reading surface JSON, writing meshes (meshio) and member schedules;
* :mod:`._atomic`     atomic writes (temporary file, then rename);
* :mod:`.provenance`  git commit, date, versions and parameters beside every result.
"""

from ._meshes import MESH_FORMATS, OutputPathError, check_output_path, load_surface, member_schedule, write_members, write_mesh

__all__ = [
    "MESH_FORMATS",
    "OutputPathError",
    "check_output_path",
    "load_surface",
    "member_schedule",
    "write_members",
    "write_mesh",
]
