"""Paths that a write or a read must refuse, built the same way on every machine the tests run on."""

import os
import tempfile
from pathlib import Path

import pytest


def unwritable_folder(tmp_path):
    """An existing folder in which creating a file fails.

    A folder without write permission does that for an ordinary user; root
    ignores permissions, so as root a read-only system folder (``/sys``) stands
    in, and the test is skipped only if no such folder exists.
    """
    if os.geteuid() != 0:
        folder = tmp_path / "locked"
        folder.mkdir()
        folder.chmod(0o555)
        return folder
    for candidate in (Path("/sys"), Path("/proc")):
        if candidate.is_dir():
            try:
                fd, name = tempfile.mkstemp(dir=candidate)
            except OSError:
                return candidate
            os.close(fd)
            os.unlink(name)
    pytest.skip("running as root and no read-only folder found to stand in for an unwritable one")


def fifo(path):
    """A named pipe at ``path`` (a special file: reading it would block, renaming over it would replace it)."""
    if not hasattr(os, "mkfifo"):
        pytest.skip("no named pipes on this system")
    os.mkfifo(path)
    return path


def name_max(folder):
    """The longest file name (bytes) the file system at ``folder`` allows."""
    return os.pathconf(folder, "PC_NAME_MAX")


def plain_file(folder, name="plain"):
    """A regular file ``folder / name``: a path through it names no folder."""
    path = folder / name
    path.write_text("x")
    return path
