"""All-or-nothing writes (``io/_atomic.py``): a failed or interrupted write leaves the old file or no file, and no
temporary."""

import errno
import os
import signal
import stat
import subprocess
import sys
import textwrap
import threading
from pathlib import Path

import pytest
from hostile_paths import unwritable_folder

import equimesh
from equimesh.io._atomic import TEMP_PREFIX, atomic_path, atomic_paths, atomic_write_text, interrupts_held, probe_folder


def python(code, **environment):
    """Run ``code`` in a fresh interpreter that imports this ``equimesh``; its standard output, stripped."""
    env = {**os.environ, "PYTHONPATH": str(Path(equimesh.__file__).parents[1]), **environment}
    run = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, env=env)
    assert run.returncode == 0, run.stderr
    return run.stdout.strip()


def test_each_temporary_is_a_short_name_beside_its_target_with_its_suffix(tmp_path):
    """In the target's folder (a rename within one file system), created there and in new folders, named by the
    prefix and the target's suffix alone (so that it fits wherever the target's name does)."""
    targets = [tmp_path / ("a" * 200 + ".csv"), tmp_path / "new" / "deeper" / "m.obj"]
    with atomic_paths(*targets) as tmps:
        assert [t.parent for t in tmps] == [p.parent for p in targets]
        assert [t.suffix for t in tmps] == [".csv", ".obj"]
        assert all(t.name.startswith(TEMP_PREFIX) and len(t.name) < 30 and t.is_file() for t in tmps)
        for k, tmp in enumerate(tmps):
            tmp.write_text(str(k))
    assert [p.read_text() for p in targets] == ["0", "1"]
    assert sorted(p.name for p in tmp_path.rglob("*") if p.is_file()) == sorted(p.name for p in targets)


def test_written_files_have_the_usual_permissions(tmp_path):
    """Read and write for everyone the umask lets have them, as an ordinary ``open`` gives (not mkstemp's 0600)."""
    previous = os.umask(0o022)
    try:
        atomic_write_text(tmp_path / "x.txt", "x")
        with atomic_paths(tmp_path / "y.txt") as (tmp,):
            tmp.write_text("y")
    finally:
        os.umask(previous)
    assert [stat.S_IMODE((tmp_path / name).stat().st_mode) for name in ("x.txt", "y.txt")] == [0o644, 0o644]
    assert os.umask(previous) == previous  # the umask is left as it was


def test_a_file_system_that_refuses_permissions_is_written_all_the_same(tmp_path, monkeypatch):
    def refuse(*args, **kwargs):
        raise PermissionError(errno.EPERM, "Operation not permitted")

    monkeypatch.setattr(os, "chmod", refuse)
    atomic_write_text(tmp_path / "x.txt", "x")
    assert (tmp_path / "x.txt").read_text() == "x"


def test_text_is_written_as_utf8_whatever_the_locale(tmp_path):
    """Same input, same bytes: under an ASCII locale too (no UTF-8 mode, no locale coercion)."""
    path = tmp_path / "x.txt"
    atomic_write_text(path, "G\u00fcrtel \u2014 \u00e9")
    code = f"from equimesh.io._atomic import atomic_write_text; atomic_write_text({str(path)!r}, 'G\\u00fcrtel')"
    python(code, LC_ALL="C", PYTHONUTF8="0", PYTHONCOERCECLOCALE="0", PYTHONIOENCODING="ascii")
    assert path.read_bytes() == "G\u00fcrtel".encode()


def test_a_failed_rename_raises_its_error_and_leaves_no_temporary(tmp_path):
    """The second target is a folder holding a file: its rename fails after the first one was done."""
    first, second = tmp_path / "a.txt", tmp_path / "b.txt"
    (second / "inside").mkdir(parents=True)
    with pytest.raises(OSError) as err, atomic_paths(first, second) as tmps:
        for tmp in tmps:
            tmp.write_text("new")
    assert err.value.errno in (errno.EISDIR, errno.ENOTEMPTY, errno.EEXIST)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt", "b.txt"] and first.read_text() == "new"


def test_the_probe_leaves_the_folder_as_it_was_and_raises_what_a_write_would(tmp_path):
    (tmp_path / "kept.txt").write_text("x")
    assert probe_folder(tmp_path, ".csv") is False  # this folder tells a from A
    assert [p.name for p in tmp_path.iterdir()] == ["kept.txt"]
    with pytest.raises(OSError) as err:
        probe_folder(tmp_path, "." + "a" * os.pathconf(tmp_path, "PC_NAME_MAX"))
    assert err.value.errno == errno.ENAMETOOLONG
    with pytest.raises(OSError):
        probe_folder(unwritable_folder(tmp_path), ".obj")
    assert [p.name for p in tmp_path.iterdir()] == ["kept.txt"]


def test_writes_outside_the_main_thread_are_not_held_and_succeed(tmp_path):
    """Only the main thread can hold SIGINT: elsewhere the renames run unprotected, but they run."""
    failed = []

    def write():
        try:
            atomic_write_text(tmp_path / "x.txt", "x")
        except BaseException as exc:
            failed.append(exc)

    worker = threading.Thread(target=write)
    worker.start()
    worker.join()
    assert not failed and (tmp_path / "x.txt").read_text() == "x"


def test_failed_second_write_leaves_no_file(tmp_path):
    """Two outputs in one transaction: the second write fails, the first target is never created, old files stay."""
    first, second = tmp_path / "a.txt", tmp_path / "b.txt"
    second.write_text("old")
    with pytest.raises(OSError), atomic_paths(first, second) as (tmp1, tmp2):
        tmp1.write_text("new")
        raise OSError("disk full")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["b.txt"] and second.read_text() == "old"


def test_interrupt_inside_a_transaction_removes_the_temporaries(tmp_path):
    with pytest.raises(KeyboardInterrupt), atomic_paths(tmp_path / "a.txt", tmp_path / "b.txt") as tmps:
        for tmp in tmps:
            tmp.write_text("half")
        raise KeyboardInterrupt
    assert list(tmp_path.iterdir()) == []


def test_interrupt_during_the_renames_is_held_until_they_are_done():
    """SIGINT arriving in the rename phase is delivered after it, so a set of outputs is never split; the handler
    is put back.

    The interrupt itself is raised in a fresh interpreter: a real SIGINT must not reach a pytest(-xdist) worker,
    whose SIGINT disposition is not Python's default handler.
    """
    before = signal.getsignal(signal.SIGINT)
    with interrupts_held():
        assert signal.getsignal(signal.SIGINT) is not before
    assert signal.getsignal(signal.SIGINT) is before
    code = """
        import signal
        from equimesh.io._atomic import interrupts_held
        done = []
        try:
            with interrupts_held():
                signal.raise_signal(signal.SIGINT)
                done.append(True)
        except KeyboardInterrupt:
            print("interrupted after", done, signal.getsignal(signal.SIGINT) is signal.default_int_handler)
        """
    assert python(code) == "interrupted after [True] True"


def test_atomic_write_leaves_the_old_file_on_error(tmp_path):
    target = tmp_path / "x.txt"
    atomic_write_text(target, "old")
    with pytest.raises(RuntimeError), atomic_path(target) as tmp:
        tmp.write_text("half")
        raise RuntimeError("interrupted")
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["x.txt"]
