"""What is mutated, against which tests: the algorithm modules and the test files that must kill their mutants.

Each selection is the property tests of that module plus the direct tests of its internals, kept small so
that one mutant costs a few seconds (mutmut runs, of the selection, only the tests that reach the mutated
function).
"""

#: The tests of polygons: their validation, their checks and Step 2 on their boundary.
_POLYGON_TESTS = [
    "tests/test_polygon.py",
    "tests/test_polygon_validation.py",
    "tests/test_hardening_planar.py",
    "tests/test_polygon_thresholds.py",
]

#: Module (a path from the repository's root) -> the test files that must kill its mutants.
MODULES = {
    "src/equimesh/planar/bounds.py": ["tests/test_bounds.py"],
    "src/equimesh/planar/lattice.py": ["tests/test_lattice.py"],
    "src/equimesh/planar/clearance.py": ["tests/test_clearance.py", "tests/test_lattice.py"],
    # argument checks, polygon validation and Step 2 on a polygon's boundary
    "src/equimesh/_checks.py": _POLYGON_TESTS,
    "src/equimesh/planar/polygon.py": _POLYGON_TESTS,
    "src/equimesh/planar/boundary/resample.py": _POLYGON_TESTS,
    "src/equimesh/planar/boundary/sides.py": _POLYGON_TESTS,
    "src/equimesh/planar/boundary/separation.py": _POLYGON_TESTS,
    "src/equimesh/planar/increment.py": ["tests/test_increment_steps.py"],
    "src/equimesh/planar/insertion/reference.py": ["tests/test_reference_engine.py", "tests/test_increment_steps.py"],
    "src/equimesh/planar/strip.py": ["tests/test_strip.py"],
    # Step 2 on surfaces (boundary resampling)
    "src/equimesh/surface/ring.py": ["tests/test_ring.py"],
    # Problem 2's lattice placement search
    "src/equimesh/planar/placement.py": ["tests/test_placement_search.py"],
    # the insertion's region and constrained Delaunay triangulation
    "src/equimesh/planar/insertion/region.py": ["tests/test_region.py"],
    # Step 2 at one sharp corner, decided on a grid
    "src/equimesh/planar/boundary/corner.py": ["tests/test_polygon_corner.py"],
    # Step 2 at sharp corners in a row, decided jointly
    "src/equimesh/planar/boundary/chain.py": ["tests/test_polygon_corner.py", "tests/test_coupled.py"],
}

#: The fast engine's kernels -> their tests.  The kernels are compiled by a call (``equimesh/_jit.py``), not
#: by a decorator, so mutmut mutates them and puts its trampolines in front of them; numba cannot compile a
#: trampoline, so their tests run the kernels as Python (:data:`ENVIRONMENT`), on small inputs.
KERNEL_MODULES = {
    "src/equimesh/planar/insertion/predicates.py": ["tests/test_fast_kernels.py"],
    "src/equimesh/planar/insertion/cdt.py": ["tests/test_fast_kernels.py"],
    "src/equimesh/planar/insertion/fast.py": ["tests/test_fast_kernels.py"],
}
MODULES.update(KERNEL_MODULES)

#: Module -> environment variables of its mutmut run, beyond the caller's.
ENVIRONMENT = dict.fromkeys(KERNEL_MODULES, {"NUMBA_DISABLE_JIT": "1"})
