"""asv benchmark suites for equimesh (run with ``make bench``).

Each ``bench_*.py`` module holds suites whose benchmark methods start with
``time_``, ``track_`` or ``peakmem_``; ``tests/tools/test_benchmarks.py`` checks it.
"""
