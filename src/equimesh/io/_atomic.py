"""Atomic file writes: a result file is either the old one or the complete new one.

Each writer creates a temporary file in the destination folder (so that the
final :func:`os.replace` is a rename within one file system, atomic on POSIX
and Windows) and renames it over the destination only after it was written
completely; on error, interrupt included, the temporary file is removed.
:func:`atomic_paths` does the same for several files at once: every output of a
run is written to its temporary file first and the renames come last, so a
failure leaves none of the new files.
"""

import contextlib
import os
import signal
import tempfile
import threading
from pathlib import Path

#: Prefix of every temporary file.  Short and independent of the target's
#: name, so that the temporary name fits the file system's name limit
#: whenever the target's name does (only the target's suffix is kept).
TEMP_PREFIX = ".equimesh-"


def atomic_paths(*paths):
    """Yield a list of temporary paths, one beside each of ``paths``; rename them all once the block succeeds.

    The temporary names keep the suffix of their target so that writers that
    infer the format from it (``matplotlib.pyplot.savefig``, ``pandas``) still
    work.  Parent folders are created.  If the block raises (``KeyboardInterrupt``
    included) every temporary file is removed and no target is touched.  The
    renames themselves run with SIGINT held back, so an interrupt never leaves
    half of the set renamed.
    """
    paths = [Path(p) for p in paths]
    tmps = []
    try:
        for path in paths:
            path.parent.mkdir(parents=True, exist_ok=True)
            tmps.append(_temporary(path.parent, path.suffix))
        yield tmps
        with interrupts_held():
            for tmp, path in zip(tmps, paths):
                os.replace(tmp, path)
    except BaseException:
        for tmp in tmps:
            with contextlib.suppress(FileNotFoundError):
                os.unlink(tmp)
        raise


def atomic_path(path):
    """Yield a temporary path beside ``path``; on success rename it to ``path`` (see :func:`atomic_paths`)."""
    with atomic_paths(path) as (tmp,):
        yield tmp


def atomic_write_text(path, text):
    """Write ``text`` to ``path`` atomically as UTF-8, whatever the locale (see :func:`atomic_paths`)."""
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")


def probe_folder(folder, suffix):
    """Create and remove a temporary file in ``folder``, exactly as a write would; raise its ``OSError``.

    Returns True if the folder's file system folds case: the temporary file's
    name in the other case (``.EQUIMESH-...``, a name nobody else makes) is found.
    """
    tmp = _temporary(Path(folder), suffix)
    try:
        return tmp.with_name(tmp.name.swapcase()).exists()
    finally:
        os.unlink(tmp)


def _temporary(folder, suffix):
    fd, tmp = tempfile.mkstemp(prefix=TEMP_PREFIX, suffix=suffix, dir=folder)
    os.close(fd)
    with contextlib.suppress(OSError):  # a file system without permissions (FAT) keeps its own
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes 0600; give the usual permissions
    return Path(tmp)


def interrupts_held():
    """Hold SIGINT back for the duration of the block and deliver it afterwards.

    Only the main thread can set signal handlers, and only a handler installed
    from Python can be put back; elsewhere the block runs unprotected.
    """
    if threading.current_thread() is not threading.main_thread() or signal.getsignal(signal.SIGINT) is None:
        yield
        return
    held = []
    previous = signal.signal(signal.SIGINT, lambda *_: held.append(True))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if held:
            signal.raise_signal(signal.SIGINT)


# Context managers by a call, not by the decorator, so that mutation testing reaches their bodies (mutmut leaves
# decorated functions alone; docs/decisions.md, "Context managers made by a call").
atomic_paths = contextlib.contextmanager(atomic_paths)
atomic_path = contextlib.contextmanager(atomic_path)
interrupts_held = contextlib.contextmanager(interrupts_held)


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask
