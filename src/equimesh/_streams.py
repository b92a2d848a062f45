"""The command line's standard streams: what it prints only reports a run, and what the library prints is silenced.

:func:`say` prints the progress lines, the summary, the notes and the error line of ``equimesh``; a stream that
cannot take them does not change the run's outcome.  :func:`library_quiet` keeps numpy's warnings and the C code's
prints on descriptor 1 out of a run (docs/decisions.md, "What is printed only reports a run").
"""

import contextlib
import os
import sys
import warnings


def say(text, stream=None):
    """Print ``text`` on ``stream`` (standard error by default): progress, the summary, notes, the error line.

    They only report a run, whose outcome is its exit code and its files: a stream that is closed or full (a reader
    that quit, ``2>/dev/full``) is pointed at the null device and the run goes on, so it neither fails after its
    outputs are written nor stops before them.
    """
    stream = sys.stderr if stream is None else stream
    if stream is None:  # the descriptor was closed when the interpreter started
        return
    try:
        print(text, file=stream, flush=True)
    except (OSError, ValueError):  # a broken pipe, a full device, a closed file
        try:
            null = os.open(os.devnull, os.O_WRONLY)
            if null != stream.fileno():
                os.dup2(null, stream.fileno())
                os.close(null)
        except (OSError, ValueError):
            pass


@contextlib.contextmanager
def library_quiet():
    """Keep the run's outcome the only thing printed: no floating-point RuntimeWarnings, no C-level stdout.

    The library checks its results (finite, every theorem) and raises one
    error of its own; the warnings numpy emits on the way to that error, and
    the messages Triangle's C code prints on file descriptor 1 before its
    RuntimeError, would only add lines to it.
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        try:
            saved = os.dup(1)
        except OSError:  # descriptor 1 is closed: the null device holds it meanwhile, so no file opened takes it
            saved = None
        if sys.stdout is not None:
            sys.stdout.flush()
        null = os.open(os.devnull, os.O_WRONLY)  # descriptor 1 itself if that was closed
        if null != 1:
            os.dup2(null, 1)
            os.close(null)
        try:
            yield
        finally:
            if saved is None:
                os.close(1)
            else:
                os.dup2(saved, 1)
                os.close(saved)
