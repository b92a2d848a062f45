"""What is mutated, against which tests: the algorithm modules and the test files that must kill their mutants.

Each selection is the property tests of that module plus the direct tests of its internals, kept small so
that one mutant costs a few seconds (mutmut runs, of the selection, only the tests that reach the mutated
function).
"""

#: The tests of polygons: their validation, their checks and Step 2 on their boundary.
_POLYGON_TESTS = [
    "tests/planar/boundary/test_resample.py",
    "tests/planar/boundary/test_separation.py",
    "tests/planar/boundary/test_sides.py",
    "tests/planar/test_guarantees.py",
    "tests/planar/test_hostile_polygons.py",
    "tests/planar/test_limits.py",
    "tests/planar/test_local_frame.py",
    "tests/planar/test_polygon.py",
    "tests/planar/test_sharp_corner_meshes.py",
    "tests/test_checks.py",
    "tests/test_errors.py",
]

#: Module (a path from the repository's root) -> the test files that must kill its mutants.
MODULES = {
    "src/equimesh/planar/bounds.py": ["tests/planar/test_bounds.py"],
    "src/equimesh/planar/lattice.py": ["tests/planar/test_lattice.py"],
    "src/equimesh/planar/clearance.py": ["tests/planar/test_clearance.py", "tests/planar/test_lattice.py"],
    # argument checks, polygon validation and Step 2 on a polygon's boundary
    "src/equimesh/_checks.py": _POLYGON_TESTS,
    "src/equimesh/planar/polygon.py": _POLYGON_TESTS,
    "src/equimesh/planar/boundary/resample.py": _POLYGON_TESTS,
    "src/equimesh/planar/boundary/sides.py": _POLYGON_TESTS,
    "src/equimesh/planar/boundary/separation.py": _POLYGON_TESTS,
    "src/equimesh/planar/boundary/phase.py": ["tests/planar/boundary/test_phase.py"],
    "src/equimesh/planar/increment.py": ["tests/planar/test_increment.py"],
    "src/equimesh/planar/insertion/reference.py": [
        "tests/planar/insertion/test_reference.py",
        "tests/planar/test_increment.py",
    ],
    "src/equimesh/planar/strip.py": ["tests/planar/test_strip.py"],
    # Step 2 on surfaces (boundary resampling)
    "src/equimesh/surface/ring.py": ["tests/surface/test_ring.py"],
    # Section 4's step 2 (eq. (1)) and step 4 (eqs. (2)-(3) and the check of the remapped triangles)
    "src/equimesh/surface/flatten.py": ["tests/surface/test_flatten.py"],
    "src/equimesh/surface/remap.py": ["tests/surface/test_remap.py"],
    # Problem 2's lattice placement search
    "src/equimesh/planar/placement.py": ["tests/planar/test_placement.py"],
    # the insertion's region and constrained Delaunay triangulation
    "src/equimesh/planar/insertion/region.py": ["tests/planar/insertion/test_region.py"],
    # Step 2 at one sharp corner, decided on a grid
    "src/equimesh/planar/boundary/corner.py": [
        "tests/planar/boundary/test_corner.py",
        "tests/planar/boundary/test_chain.py",
    ],
    # Step 2 at sharp corners in a row, decided jointly
    "src/equimesh/planar/boundary/chain.py": [
        "tests/planar/boundary/test_corner.py",
        "tests/planar/boundary/test_chain.py",
    ],
}

#: The fast engine's kernels -> their tests.  The kernels are compiled by a call (``equimesh/_jit.py``), not
#: by a decorator, so mutmut mutates them and puts its trampolines in front of them; numba cannot compile a
#: trampoline, so their tests run the kernels as Python (:data:`ENVIRONMENT`), on small inputs.
KERNEL_MODULES = {
    "src/equimesh/planar/insertion/predicates.py": [
        "tests/planar/insertion/test_predicates.py",
        "tests/planar/insertion/test_cdt.py",
        "tests/planar/insertion/test_fast.py",
    ],
    "src/equimesh/planar/insertion/cdt.py": [
        "tests/planar/insertion/test_predicates.py",
        "tests/planar/insertion/test_cdt.py",
        "tests/planar/insertion/test_fast.py",
    ],
    "src/equimesh/planar/insertion/fast.py": [
        "tests/planar/insertion/test_predicates.py",
        "tests/planar/insertion/test_cdt.py",
        "tests/planar/insertion/test_fast.py",
    ],
    "src/equimesh/planar/insertion/candidates.py": [
        "tests/planar/insertion/test_predicates.py",
        "tests/planar/insertion/test_cdt.py",
        "tests/planar/insertion/test_fast.py",
    ],
    "src/equimesh/planar/insertion/buckets.py": [
        "tests/planar/insertion/test_buckets.py",
        "tests/planar/insertion/test_fast.py",
    ],
    "src/equimesh/planar/insertion/heap.py": [
        "tests/planar/insertion/test_heap.py",
        "tests/planar/insertion/test_fast.py",
    ],
    "src/equimesh/planar/insertion/arrays.py": [
        "tests/planar/insertion/test_fast.py",
    ],
}
MODULES.update(KERNEL_MODULES)

#: The final optimisation's modules -> their tests (direct tests on the tiny grids of ``tests/optimize_cases.py``).
#: The Jacobian's area gradients, the solver's sum of the normal matrix, the angle and the length gradients are
#: compiled by a call as the kernels are, so their tests run them as Python too.
OPTIMIZE_MODULES = {
    "src/equimesh/surface/optimize/slide.py": ["tests/surface/optimize/test_slide.py"],
    "src/equimesh/surface/optimize/jacobian.py": ["tests/surface/optimize/test_jacobian.py"],
    "src/equimesh/surface/optimize/solver.py": [
        "tests/surface/optimize/test_solver.py",
        "tests/surface/optimize/test_pardiso_cores.py",
    ],
    "src/equimesh/surface/optimize/cores.py": [
        "tests/surface/optimize/test_solver.py",
        "tests/surface/optimize/test_pardiso_cores.py",
    ],
    "src/equimesh/surface/optimize/ordering.py": ["tests/surface/optimize/test_ordering.py"],
    "src/equimesh/surface/optimize/joints.py": ["tests/surface/optimize/test_joints.py"],
    "src/equimesh/surface/optimize/members.py": ["tests/surface/optimize/test_members.py"],
    "src/equimesh/surface/optimize/problem.py": [
        "tests/surface/optimize/test_problem.py",
        "tests/surface/optimize/test_members.py",
    ],
    "src/equimesh/surface/optimize/objectives.py": ["tests/surface/optimize/test_objective_stages.py"],
    "src/equimesh/surface/optimize/class_rounds.py": ["tests/surface/optimize/test_objective_stages.py"],
    "src/equimesh/surface/optimize/driver.py": ["tests/surface/optimize/test_driver.py"],
    "src/equimesh/surface/optimize/beside.py": [
        "tests/surface/optimize/test_driver.py",
        "tests/surface/optimize/test_pardiso_cores.py",
    ],
}
MODULES.update(OPTIMIZE_MODULES)

#: The input side of the io layer -> its direct tests: output paths checked, files written all or none, surface
#: files read (OBJ and the other mesh formats, the JSON schemas of each surface type), meshes written.
IO_MODULES = {
    "src/equimesh/io/_paths.py": ["tests/io/test_paths.py"],
    "src/equimesh/io/_atomic.py": ["tests/io/test_atomic.py"],
    "src/equimesh/io/_obj.py": ["tests/io/test_obj.py"],
    "src/equimesh/io/_trimesh.py": ["tests/io/test_trimesh.py"],
    "src/equimesh/io/_schema.py": ["tests/io/test_schema.py"],
    "src/equimesh/io/_surfaces.py": ["tests/io/test_surfaces.py"],
    "src/equimesh/io/_meshes.py": ["tests/io/test_meshes.py"],
    "src/equimesh/io/_nurbs.py": ["tests/io/test_nurbs_schema.py"],
    "src/equimesh/io/_bezier.py": ["tests/io/test_surfaces.py"],
}
MODULES.update(IO_MODULES)

#: The checks of every returned mesh and the figures of its members -> their direct tests, on meshes of a few
#: triangles.
OUTPUT_MODULES = {
    "src/equimesh/surface/output_checks.py": ["tests/surface/test_output_checks.py"],
    "src/equimesh/classes.py": ["tests/test_classes.py"],
    "src/equimesh/metrics.py": ["tests/test_metrics.py"],
}
MODULES.update(OUTPUT_MODULES)

#: The optimisation's modules with compiled functions.
_COMPILED_OPTIMIZE = ["jacobian", "solver", "joints", "members", "problem"]

#: The output side of the io layer (and Rhino files in, provenance) -> their direct tests, on meshes of a few nodes
#: (``tent_mesh``; the report's ``square_mesh``), each writing in the test itself (docs/development.md).
WRITER_MODULES = {
    "src/equimesh/io/_outputs.py": ["tests/io/test_outputs.py"],
    "src/equimesh/io/_schedules.py": ["tests/io/test_schedules.py"],
    "src/equimesh/io/_rhino_out.py": ["tests/io/test_rhino_out.py"],
    "src/equimesh/io/_compas.py": ["tests/io/test_compas.py"],
    "src/equimesh/io/_dxf.py": ["tests/io/test_dxf.py"],
    "src/equimesh/io/_rhino.py": ["tests/io/test_rhino.py"],
    "src/equimesh/io/provenance.py": ["tests/io/test_provenance.py"],
    "src/equimesh/io/_view.py": ["tests/io/test_view.py"],
    "src/equimesh/io/_plot.py": ["tests/io/test_plot.py"],
    "src/equimesh/io/_report.py": ["tests/io/test_report.py"],
}
MODULES.update(WRITER_MODULES)

#: Module -> environment variables of its mutmut run, beyond the caller's.
ENVIRONMENT = dict.fromkeys(
    [*KERNEL_MODULES, *(f"src/equimesh/surface/optimize/{name}.py" for name in _COMPILED_OPTIMIZE)],
    {"NUMBA_DISABLE_JIT": "1"},
)
