"""All-or-nothing writes (``io/_atomic.py``): a failed or interrupted write leaves the old file or no file, and no
temporary."""

import subprocess
import sys
import textwrap

import pytest

from equimesh.io._atomic import atomic_path, atomic_paths, atomic_write_text


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
    """SIGINT arriving in the rename phase is delivered after it, so a set of outputs is never split.

    Run in a fresh interpreter: a real SIGINT must not reach a pytest(-xdist) worker,
    whose SIGINT disposition is not Python's default handler.
    """
    code = textwrap.dedent(
        """
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
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert run.stdout.strip() == "interrupted after [True] True", run.stderr


def test_atomic_write_leaves_the_old_file_on_error(tmp_path):
    target = tmp_path / "x.txt"
    atomic_write_text(target, "old")
    with pytest.raises(RuntimeError), atomic_path(target) as tmp:
        tmp.write_text("half")
        raise RuntimeError("interrupted")
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["x.txt"]
