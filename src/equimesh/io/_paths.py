"""Output paths: each one writable, none of them an input of the run, no two of them the same file.

:func:`check_writable` tries everything a write will need (folder, name length,
permission, a real temporary file) so that a run can refuse a bad output before
its expensive part; :func:`check_distinct` refuses an output that is an input
file (``roof.obj -o roof.obj``, also spelled ``./roof.obj``, through a symbolic
or a hard link, or in another case where the file system folds case) and two
outputs that are one file.  Files are compared as the file system sees them
(:func:`identity`): by their resolved folder and name, the name case-folded
where the file system folds case, and by device and inode (``os.stat``), never
by the spelling of their paths (docs/decisions.md, "No output overwrites an input").
"""

import math
import os
from pathlib import Path

from ..errors import OutputPathError
from ._atomic import probe_folder
from ._schema import os_reason, shown_path


def check_writable(path):
    """Check that ``path`` can be written; return True if its folder's file system folds case.

    Tried, in this order: the name and the whole path fit the file system's
    limits, the folder exists and is a folder, the target is not a folder nor a
    special file (a rename would replace it), and a temporary file can really be
    created (and is removed) in the folder.

    Raises
    ------
    OutputPathError
        one line naming the first problem.
    """
    path = Path(path)
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
        return probe_folder(folder, path.suffix)
    except OSError as exc:
        raise OutputPathError(f"cannot write {shown_path(path)}: {os_reason(exc)}") from None


def identity(path, folds_case):
    """What ``path`` names, as a set of keys: two paths name one file if their sets meet.

    The resolved folder (symbolic links and ``..`` followed) and the name,
    case-folded where the folder's file system folds case (``folds_case``); and,
    for an existing file, its device and inode, whatever link or spelling leads
    to it.
    """
    path = Path(path)
    name = path.name.casefold() if folds_case else path.name
    keys = {("path", os.path.normcase(os.path.realpath(path.parent)), name)}
    try:
        st = os.stat(path)
    except OSError:  # not there yet (or not to be looked at): its path alone names it
        return frozenset(keys)
    return frozenset(keys | {("file", st.st_dev, st.st_ino)})


def check_distinct(outputs, inputs=()):
    """Refuse an output that is an input file, and two outputs that are the same file.

    Parameters
    ----------
    outputs : iterable of ``(path, noun, folds_case)``
        every file a run writes, with what it is ("mesh", "member schedule")
        and whether its folder folds case (:func:`check_writable`).
    inputs : iterable of ``(path, noun)``
        every file the run reads; one that does not exist is left to its reader.

    Raises
    ------
    OutputPathError
        one line naming both files.
    """
    outputs = [(path, noun, folds, identity(path, folds)) for path, noun, folds in outputs]
    inputs = [(path, noun) for path, noun in inputs if os.path.exists(path)]
    for path, noun, folds, keys in outputs:
        for source, source_noun in inputs:
            if keys & identity(source, folds):  # one file only if in one folder, or by its inode
                raise OutputPathError(
                    f"the {noun} {shown_path(path)} is the {source_noun} {shown_path(source)}: writing it would "
                    "destroy the input; choose another output file"
                )
    for k, (path, noun, _, keys) in enumerate(outputs):
        for first, first_noun, _, first_keys in outputs[:k]:
            if keys & first_keys:
                raise OutputPathError(
                    f"the {first_noun} {shown_path(first)} and the {noun} {shown_path(path)} are the same file; "
                    "give each output its own file"
                )


def _pathconf(folder, name):
    """The file system's limit ``name`` at ``folder`` (bytes), or infinity where there is none or it cannot be asked."""
    try:
        limit = os.pathconf(folder, name)
    except (AttributeError, ValueError, OSError):  # no pathconf (Windows), unknown name
        return math.inf
    return math.inf if limit < 0 else limit
