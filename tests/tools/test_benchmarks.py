"""The asv suites in benchmarks/benchmarks/ import, are discoverable and run.

asv silently skips a method whose name lacks a ``time_``/``track_``/``peakmem_``
prefix and reports an import error only at benchmark time, so both are checked
here, together with one cheap run of every benchmark on its smallest
parameters and a fingerprint of the frozen inputs (benchmarks/benchmarks/common.py
is append-only).
"""

import ast
import importlib.util
import inspect
import itertools
import sys

import numpy as np
import pytest
from repository import BENCHMARKS

import equimesh

BENCH_DIR = BENCHMARKS / "benchmarks"


BENCH_FILES = sorted(BENCH_DIR.glob("bench_*.py"))


PACKAGE = "_equimesh_asv_benchmarks"  # a private name: never clashes with benchmarks/


PREFIXES = ("time_", "track_", "peakmem_")


NOT_BENCHMARKS = {"setup", "teardown", "setup_cache"}


def _import(module):
    """Import ``benchmarks/benchmarks/<module>.py`` from its path, as asv does (a package)."""
    if PACKAGE not in sys.modules:
        spec = importlib.util.spec_from_file_location(
            PACKAGE, BENCH_DIR / "__init__.py", submodule_search_locations=[str(BENCH_DIR)]
        )
        package = importlib.util.module_from_spec(spec)
        sys.modules[PACKAGE] = package
        spec.loader.exec_module(package)
    name = f"{PACKAGE}.{module}"
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, BENCH_DIR / f"{module}.py")
        mod = importlib.util.module_from_spec(spec)
        sys.modules[name] = mod
        try:
            spec.loader.exec_module(mod)
        except BaseException:
            del sys.modules[name]
            raise
    return sys.modules[name]


def _suites(module):
    """Benchmark suite classes defined in ``module`` (not imported into it)."""
    return [
        cls
        for _, cls in inspect.getmembers(module, inspect.isclass)
        if cls.__module__ == module.__name__ and not cls.__name__.startswith("_")
    ]


def _benchmark_methods(cls):
    """Every public callable a suite defines, except asv's set-up/tear-down hooks."""
    return [
        name
        for name, value in inspect.getmembers(cls)
        if not name.startswith("_") and callable(value) and name not in NOT_BENCHMARKS
    ]


def _param_grid(cls):
    """asv's parameter lists of a suite (``params`` may be one list or a list of lists)."""
    params = getattr(cls, "params", None)
    if params is None:
        return []
    if not params or not isinstance(params[0], (list, tuple)):
        return [list(params)]
    return [list(p) for p in params]


def _all_suites():
    return [
        pytest.param(path.stem, cls.__name__, id=f"{path.stem}.{cls.__name__}")
        for path in BENCH_FILES
        for cls in _suites(_import(path.stem))
    ]


def test_there_are_benchmark_modules():
    assert BENCH_FILES, f"no bench_*.py in {BENCH_DIR}"


@pytest.mark.parametrize("module", [p.stem for p in BENCH_FILES])
def test_module_imports_and_defines_suites(module):
    assert _suites(_import(module)), f"{module} defines no benchmark suite class"


@pytest.mark.parametrize("module", [p.stem for p in BENCH_FILES])
def test_module_uses_only_the_public_api(module):
    """Benchmarks use ``import equimesh`` and names in ``equimesh.__all__``, nothing private."""
    tree = ast.parse((BENCH_DIR / f"{module}.py").read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("equimesh"):
            pytest.fail(f"{module}: 'from {node.module} import ...'; use 'import equimesh'")
        if isinstance(node, ast.Import):
            for alias in node.names:
                assert alias.name == "equimesh" or not alias.name.startswith("equimesh"), (
                    f"{module}: 'import {alias.name}'; use 'import equimesh'"
                )
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "equimesh":
            assert node.attr in equimesh.__all__, f"{module}: equimesh.{node.attr} is not public"


@pytest.mark.parametrize(("module", "suite"), _all_suites())
def test_every_method_is_a_benchmark_asv_will_run(module, suite):
    cls = getattr(_import(module), suite)
    methods = _benchmark_methods(cls)
    assert methods, f"{suite} has no benchmark method"
    skipped = [m for m in methods if not m.startswith(PREFIXES)]
    assert not skipped, f"asv would silently skip {suite}.{skipped}: prefix them with {PREFIXES}"
    grid = _param_grid(cls)
    if grid and hasattr(cls, "param_names"):
        assert len(cls.param_names) == len(grid), f"{suite}: param_names do not match params"


@pytest.mark.parametrize(("module", "suite"), _all_suites())
def test_every_benchmark_runs_on_its_smallest_parameters(module, suite):
    """One call of each benchmark, as asv would make it, on the first value of every parameter."""
    cls = getattr(_import(module), suite)
    args = [values[0] for values in _param_grid(cls)]
    cache = [cls().setup_cache()] if hasattr(cls, "setup_cache") else []
    for name in _benchmark_methods(cls):
        bench = cls()
        if hasattr(bench, "setup"):
            bench.setup(*cache, *args)
        try:
            result = getattr(bench, name)(*cache, *args)
            if name.startswith("track_"):
                assert isinstance(result, (int, float)) and np.isfinite(result), (name, result)
        finally:
            if hasattr(bench, "teardown"):
                bench.teardown(*cache, *args)


def test_smallest_parameters_come_first():
    """The smoke test above runs the first value of each parameter, so keep it the cheapest."""
    common = _import("common")
    for sizes in (common.POLYGON_AREAS, common.NODE_COUNTS, common.PROBLEM2_AREAS):
        assert list(sizes) == sorted(sizes)
    assert common.ENGINES[0] == "fast", "the reference engine is slow: keep it off the smoke test"


# Fingerprints of the frozen inputs: (vertex count, sum of |coordinates|, sum of squares).
# If one of these fails, an input in common.py changed -- add a new input instead.
FROZEN = {
    ("square", 25): (4, 20.0, 100.0),
    ("rectangle_8to1", 25): (4, 31.81980515339464, 406.25000000000006),
    ("random_convex", 25): (7, 27.880677665404995, 67.23865273585292),
    ("random_convex", 400): (7, 111.52271066161998, 1075.8184437736468),
}


@pytest.mark.parametrize(("shape", "area"), list(FROZEN))
def test_frozen_inputs_are_unchanged(shape, area):
    common = _import("common")
    v = common.polygon(shape, area)
    n, s, q = FROZEN[shape, area]
    assert len(v) == n
    assert np.isclose(np.abs(v).sum(), s, rtol=1e-12, atol=1e-12)
    assert np.isclose((v * v).sum(), q, rtol=1e-12, atol=1e-12)


def test_frozen_scaling_squares_are_unchanged():
    common = _import("common")
    assert [float(common.square_for_nodes(n)[2, 0]) for n in (1000, 10000, 100000)] == pytest.approx(
        [38.34824944236852, 121.26781251816648, 383.4824944236852], rel=1e-12
    )


def test_frozen_inputs_are_valid_problem1_inputs():
    common = _import("common")
    for shape, area in itertools.product(common.SHAPES, common.POLYGON_AREAS):
        v = common.polygon(shape, area)
        assert np.isclose(common.polygon_area(v), area), (shape, area)
        # Raises unless convex, every inner angle >= 90 degrees and every edge >= l.
        equimesh.node_lower_bound(v, common.L)
