"""How strong the property tests are: mutation testing of the algorithm modules with mutmut.

For each algorithm module (Problem 1: ``increment.py`` and the reference
insertion engine with its triangulation ``_region.py``; Problem 2: ``strip.py``,
``lattice.py``, ``_clearance.py``, ``placement.py``; ``bounds.py``; Step 2
boundary resampling and separation in ``polygon.py``, two sharp corners
decided jointly in ``_coupled.py`` and, on surfaces, ``surface/ring.py``)
mutmut makes small
changes to the code (an operator, a constant, a comparison), one at a time, and
runs the tests selected for that module in :data:`MODULES`.  A mutant is
*killed* when a test fails, *survived* when every test passes.  A survivor is
either a gap in the tests (then a test is added that kills it) or an
*equivalent* mutant that no test can kill; the argument for each equivalent
survivor is in :data:`EQUIVALENT`, and the report lists every survivor with it.

Writes::

    results/mutation.md      per module: mutants, killed, survived, timed out,
                             score over the non-equivalent mutants, every survivor
    results/mutation.json    the same counts and survivors, machine-readable
    results/mutation.provenance.json

Each module runs in its own copy of ``src/``, ``tests/`` and ``pyproject.toml``
under ``--work-dir`` (default ``.mutation/``, gitignored), whose
``[tool.mutmut]`` table names only that module and its tests; mutmut itself
comes from the ``[mutation]`` extra (``make mutation`` installs it).  The
report is rewritten after each module, and modules already in
``results/mutation.json`` from an earlier run are kept, so the modules can be
run one at a time; ``--resume`` continues an interrupted module where mutmut
stopped instead of starting it afresh, and ``--survivors`` runs only the
survivors of the module's last run again, against the current tests (after
adding the tests that should kill them), keeping every other verdict.
``--functions F,G,...`` runs only the mutants of the functions named (after
they changed): their verdicts replace theirs in the module's row, and every
other function's stand from the last full run (each row keeps its verdicts
per function with the function's hash, and a function not named whose hash
changed since is refused); with ``--survivors`` or ``--so-far`` it reruns
or reports that run of the functions only.  ``--unexplained`` is
``--survivors`` for the survivors not argued equivalent in :data:`EQUIVALENT`
only (the others keep their verdicts).

Usage::

    python experiments/mutation_report.py [--max-children 2] [MODULE ...]
    python experiments/mutation_report.py src/equimesh/planar/bounds.py
    python experiments/mutation_report.py --functions _run,_grid_chain src/equimesh/planar/polygon.py
"""

import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _common.py, also when loaded by file path
import _common  # noqa: E402

from equimesh.io._atomic import atomic_write_text  # noqa: E402
from equimesh.io.provenance import provenance_path, write_provenance  # noqa: E402

NAME = "mutation"
ROOT = Path(__file__).resolve().parent.parent

#: Module -> the test files that must kill its mutants.  Each selection is
#: the property tests of that module plus the direct tests of its internals,
#: kept small so that one mutant costs a few seconds.
MODULES = {
    "src/equimesh/planar/bounds.py": ["tests/test_bounds.py"],
    "src/equimesh/planar/lattice.py": ["tests/test_lattice.py"],
    "src/equimesh/planar/clearance.py": ["tests/test_clearance.py", "tests/test_lattice.py"],
    "src/equimesh/planar/polygon.py": [
        "tests/test_polygon.py",
        "tests/test_polygon_validation.py",
        "tests/test_hardening_planar.py",
        "tests/test_polygon_thresholds.py",
    ],
    "src/equimesh/planar/increment.py": ["tests/test_increment_steps.py"],
    "src/equimesh/planar/insertion/reference.py": ["tests/test_reference_engine.py", "tests/test_increment_steps.py"],
    "src/equimesh/planar/strip.py": ["tests/test_strip.py"],
    # --- Step 2 on surfaces (boundary resampling) ---
    "src/equimesh/surface/ring.py": ["tests/test_ring.py"],
    # --- Problem 2's lattice placement search ---
    "src/equimesh/planar/placement.py": ["tests/test_placement_search.py"],
    # --- the insertion's region and constrained Delaunay triangulation ---
    "src/equimesh/planar/insertion/region.py": ["tests/test_region.py"],
    # --- Step 2 at one sharp corner, decided on a grid ---
    "src/equimesh/planar/boundary/corner.py": ["tests/test_polygon_corner.py"],
    # --- end of planar/_corner.py ---
    # --- Step 2 at two sharp corners sharing a side ---
    "src/equimesh/planar/boundary/chain.py": ["tests/test_polygon_corner.py", "tests/test_coupled.py"],
    # --- end of the two sharp corners ---
}

# --- the fast engine's numba kernels ---
#: The fast engine's kernels -> their tests.  The kernels are compiled by a
#: call (``equimesh/_jit.py``), not by a decorator, so mutmut mutates them
#: and puts its trampolines in front of them; numba cannot compile a
#: trampoline, so their tests run the kernels as Python (:data:`ENVIRONMENT`),
#: on small inputs.
KERNEL_MODULES = {
    "src/equimesh/planar/insertion/predicates.py": ["tests/test_fast_kernels.py"],
    "src/equimesh/planar/insertion/cdt.py": ["tests/test_fast_kernels.py"],
    "src/equimesh/planar/insertion/fast.py": ["tests/test_fast_kernels.py"],
}
MODULES.update(KERNEL_MODULES)
#: Module -> environment variables of its mutmut run, beyond the caller's.
ENVIRONMENT = dict.fromkeys(KERNEL_MODULES, {"NUMBA_DISABLE_JIT": "1"})
# --- end of the fast engine's kernels ---

#: Equivalent mutants, by module: (why no test can tell them from the
#: original, the mutated lines as mutmut prints them after "+", stripped).
_LAST_AXIS = "equivalent: np.sort sorts along the last axis by default, axis 1 of these 2-D arrays"
_NEGATIVE_RESHAPE = "equivalent: numpy (2.x) reads any negative dimension of reshape as the one it infers"
_EQUIVALENT_GROUPS = {
    "src/equimesh/planar/polygon.py": [
        (
            "equivalent: for any spacing >= 2 the lower bound ceil(L / 2l) of split_counts decides, so a default of 3 "
            "gives the same parts as 2",
            [
                "def split_counts(lengths, l, spacing=3.0):",
                "def resample_boundary(poly, l, spacing=3.0):",
                "def side_positions(lengths, angles, l, spacing=3.0):",
            ],
        ),
        (
            "equivalent: every use of the lengths divides them by l or multiplies them by float fractions, so integer "
            "lengths give the same floats",
            ["lengths = np.asarray(lengths, dtype=None)", "lengths = np.asarray(lengths, )"],
        ),
        (
            "equivalent: shapely.prepare only builds an index that speeds up the covers test; None is ignored",
            ["shapely.prepare(None)"],
        ),
        (
            "equivalent: the only caller, _ring_vertices, always passes of",
            ['def _check_no_repeated_vertex(v, of="XXXX"):'],
        ),
        (
            "equivalent: the integers 0 .. k - 1 are exact as floats, and every use divides them by the float "
            "denominator",
            ["return np.arange(k, dtype=None), float(k)", "return np.arange(k, ), float(k)"],
        ),
        (
            "equivalent: a point at exactly K l is at least K l sin theta >= (1 - REL_TOL) l from the other side, so it "
            "changes no gap below (1 - REL_TOL) l, the only gaps the search compares (a larger one passes at_least first)",
            ["a, b = a[a <= reach], b[b < reach]", "a, b = a[a < reach], b[b <= reach]"],
        ),
        (
            "equivalent: once no free side is dirty a further pass processes no side and changes nothing; the early "
            "return only saves the passes",
            ["if not dirty | set(free):"],
        ),
        (
            "equivalent: count only bounds the multiples k l of a chain; those past length - l leave a middle below l "
            "in every candidate that holds them (skipped), so a count one lower or any higher gives the same candidates",
            [
                "count = math.floor(length / l / (1.0 + REL_TOL))",
                "count = math.floor(length / l * (1.0 - REL_TOL))",
                "count = math.floor(length / l * (2.0 + REL_TOL))",
            ],
        ),
        (
            "equivalent: a chain point at the side's length leaves a middle below l in every candidate that holds it, "
            "and such candidates are skipped",
            [
                "start, end = start[start <= length], end[end < length]",
                "start, end = start[start < length], end[end <= length]",
            ],
        ),
        (
            "equivalent: far < (1 - REL_TOL) l already implies beta < 2 (1 - REL_TOL) l cos theta (the chord at radius "
            "(1 - REL_TOL) l is below it only there), so any looser bound on beta decides nothing",
            [
                "if beta <= 2.0 * lp * (1.0 - REL_TOL) and far < (1.0 - REL_TOL) * lp:",
                "if beta < 2.0 * lp / (1.0 - REL_TOL) and far < (1.0 - REL_TOL) * lp:",
                "if beta < 3.0 * lp * (1.0 - REL_TOL) and far < (1.0 - REL_TOL) * lp:",
                "if beta < 2.0 * lp * (1.0 + REL_TOL) and far < (1.0 - REL_TOL) * lp:",
                "if beta < 2.0 * lp * (2.0 - REL_TOL) and far < (1.0 - REL_TOL) * lp:",
            ],
        ),
        (
            "equivalent: ends is [(a, b) for a in the leaving range for b in the arriving range], so ends[-2] has the "
            "leaving far end of ends[-1] and ends[1] its arriving far end",
            [
                "((i + 1, ends[-2][0], leaving), (i - 1, ends[-1][1], arriving))]",
                "((i + 1, ends[-1][0], leaving), (i - 1, ends[+1][1], arriving))]",
            ],
        ),
        (
            "equivalent: _ring_vertices reads the label only as a truth value (label or 'a polygon', of if label), and "
            "None is as false as the empty label",
            ["v = _ring_vertices(_parse_vertices(vertices), None)"],
        ),
        (
            "equivalent: at a straight corner (theta = pi) the chord is a + b >= 2 (1 - REL_TOL) l, never below "
            "(1 - REL_TOL) l",
            ["if theta <= math.pi and max(_chord(a, b, theta) for a, b in ends) < (1.0 - REL_TOL) * lp:"],
        ),
        (
            "equivalent: a ring has at least 3 distinct vertices (checked before), so a second vertex unlike the first "
            "exists, and the vertices are all collinear with the first and that one, or not, whichever it is",
            ["other = int(np.flatnonzero(np.any(local != local[0], axis=1))[1])"],
        ),
        (
            "equivalent: two consecutive collinear edges with dot product exactly 0 need an edge of length 0, a "
            "repeated vertex, refused before",
            ["spike = (orient_sign(a, b, np.roll(b, -1, axis=0)) == 0) & (np.sum(e_in * e_out, axis=1) <= 0)"],
        ),
        (
            "equivalent: two equal vertices are one distinct vertex whether the closing copy is dropped or not: the "
            "same error",
            ["if len(v) > 2 and np.array_equal(v[0], v[-1]):"],
        ),
        (
            "equivalent: no numpy dtype kind is X",
            [
                'if raw.dtype.kind not in "XXiufOXX":',
                'isinstance(value, numbers.Real) or (np.ndim(value) == 0 and np.asarray(value).dtype.kind in "XXiufXX")',
            ],
        ),
        (
            "equivalent: _check_simple reads the local coordinates, the vertices, their indices and the label, never "
            "the frame",
            ["_check_simple(Polygon(v, index, None, local, label=label))"],
        ),
        (
            "equivalent: _from_corner reads its corner only as i == c, and T_0 (side run[0] - 1) is neither corner "
            "run[0] nor run[1] of a ring of at least 3 sides",
            [
                "for i, points, c, leaving in ((edges[0], found[0], run[1], False), (edges[-1], found[-1], run[-1], True)):"
            ],
        ),
        (
            "equivalent: _run gets the angles of a planar ring (from resample_boundary or _unplaceable_chain), whose "
            "inner angles sum to (n - 2) 180 or, for a hole, (n + 2) 180 degrees, so some corner is not sharp; neither "
            "loop passes it, so a run never holds more than the n - 1 corners the bound allows",
            [
                "while len(run) <= n - 1 and _stagger_count(angles[(run[-1] + 1) % n]) and joined(run[-1]):",
                "while len(run) < n + 1 and _stagger_count(angles[(run[-1] + 1) % n]) and joined(run[-1]):",
                "while len(run) <= n - 1 and _stagger_count(angles[run[0] - 1]) and joined((run[0] - 1) % n):",
                "while len(run) < n + 1 and _stagger_count(angles[run[0] - 1]) and joined((run[0] - 1) % n):",
            ],
        ),
        (
            "equivalent: a run of two through corner j is (j - 1, j) or (j, j + 1), both already among the pairs of j",
            ["if len(run) >= 2 and (r, run) not in runs:"],
        ),
        (
            "equivalent: a run of two through corner c is [c, c + 1] or [c - 1, c], the two pair trials of c tried just "
            "before on the same sides (list(sides), unchanged until a trial is taken), so _grid_chain returns the same "
            "and the trial fails again",
            [
                "trial = trial and (keep is PAIR or len(run) >= 2) and _grid_chain(trial, lengths, angles, l, spacing, run)"
            ],
        ),
        (
            "equivalent: d runs over (-1, 0, 1), so {k - d} is the same set as {k + d}",
            ["touched |= {(k - d) % n for k in run for d in (-1, 0, 1)}"],
        ),
        (
            "equivalent: the turn at the lowest-leftmost vertex is never straight: its neighbours lie in the closed "
            "half-plane right of or above it, so collinear neighbours would be on one ray from it, a fold refused before",
            ["counter_clockwise = orient_sign(local[low - 1], local[low], local[(low + 1) % len(v)]) >= 0"],
        ),
    ],
    "src/equimesh/planar/insertion/reference.py": [
        (
            "equivalent: the keys a n + b of sorted pairs a < b <= m (m the largest index) are unique for any n >= m: "
            "for each a they fill [a n + a + 1, a n + m], disjoint intervals; only equality is used",
            [
                "n = int(max(t.max(), pairs.max(initial=0))) - 1",
                "n = int(max(t.max(), pairs.max(initial=0))) + 2",
                "n = int(max(t.max(), pairs.max(initial=1))) + 1",
            ],
        ),
        (_LAST_AXIS, ["edges = np.sort(half_edges(t), )", "p = np.sort(pairs, )", "t = np.sort(triangles, )"]),
        (
            "equivalent: the sentinel is only compared with 0 (split[best] < 0), and -2 is as negative as -1",
            ["split = np.concatenate([np.full(len(radii), -2), mid_segments])"],
        ),
        (_NEGATIVE_RESHAPE, ["segments = np.array(region.segments, dtype=np.int64).reshape(-2, 2)"]),
        (
            "equivalent: the pairs looked up are constraint segments, each an edge of exactly one triangle of the "
            "region (it lies on one side of every constraint), so no two equal keys meet a query and the order among "
            "equal keys is never seen",
            [
                "order = np.argsort(keys, kind=None)",
                "order = np.argsort(keys, )",
                'order = np.argsort(keys, kind="STABLE")',
            ],
        ),
    ],
    "src/equimesh/planar/lattice.py": [
        (_NEGATIVE_RESHAPE, ["tri = tri.reshape(-2, 3)"]),
        (_LAST_AXIS, ["undirected = np.sort(half_edges(tri), )"]),
        (
            "equivalent: only the first 3 n entries are read (order indexes the 3 n half-edges), the same as with 3 "
            "copies",
            ["owner = np.tile(np.arange(n), 4)"],
        ),
        (
            "equivalent: scipy reads directed as a truth value, and None is false",
            ["_, labels = connected_components(graph, directed=None)"],
        ),
        (
            "equivalent: scipy's connected_components has connection='weak' by default, and the weak components of a "
            "directed graph are those of the undirected one",
            ["_, labels = connected_components(graph, )", "_, labels = connected_components(graph, directed=True)"],
        ),
        (
            "equivalent: in the polygon's local frame the lower-left corner of its bounding box is the origin (Frame), "
            "so lo[0] == lo[1] == 0",
            [
                "corners = np.array([[lo[1], lo[1]], [hi[0], lo[1]], [lo[0], hi[1]], [hi[0], hi[1]]])",
                "corners = np.array([[lo[0], lo[1]], [hi[0], lo[1]], [lo[1], hi[1]], [hi[0], hi[1]]])",
            ],
        ),
        (
            "equivalent: added to the float product, an integer offset is converted to float as dtype=float would",
            [
                "return np.asarray(offset, dtype=None) + np.asarray(ij, dtype=float) @ lattice_basis(l, angle)",
                "return np.asarray(offset, ) + np.asarray(ij, dtype=float) @ lattice_basis(l, angle)",
            ],
        ),
        (
            "equivalent: multiplied by the float basis, integer indices are converted to float as dtype=float would",
            [
                "return np.asarray(offset, dtype=float) + np.asarray(ij, dtype=None) @ lattice_basis(l, angle)",
                "return np.asarray(offset, dtype=float) + np.asarray(ij, ) @ lattice_basis(l, angle)",
            ],
        ),
    ],
    # --- planar/_clearance.py (the row-by-row lattice clearance) ---
    "src/equimesh/planar/clearance.py": [
        (
            "equivalent: the band only grows (a wider reach, a longer stretch of the segment per row: u1 = ua - t_lo du "
            "lies on the other side of ua, so the stretch still holds ua + t_lo du .. ua + t_hi du); it still visits every "
            "(vertex, segment) pair within reach = (1 + 2 DOUBT) distance, and a pair farther than that is beyond the "
            "doubtful window, so the distance it adds leaves the vertex kept iff inside, as before",
            [
                "reach = (2.0 + 2.0 * DOUBT) * distance",
                "reach = (1.0 + 2.0 / DOUBT) * distance",
                "reach = (1.0 + 3.0 * DOUBT) * distance",
                "t_lo, t_hi = np.clip(np.minimum(t1, t2), None, 1.0), np.clip(np.maximum(t1, t2), 0.0, 1.0)",
                "t_lo, t_hi = np.clip(np.minimum(t1, t2), 0.0, 1.0), np.clip(np.maximum(t1, t2), 0.0, None)",
                "t_lo, t_hi = np.clip(np.minimum(t1, t2), 0.0, 1.0), np.clip(np.maximum(t1, t2), 1.0, 1.0)",
                "t_lo, t_hi = np.clip(np.minimum(t1, t2), 0.0, 1.0), np.clip(np.maximum(t1, t2), 0.0, 2.0)",
                "u1, u2 = ua[seg, 0] - t_lo * du, ua[seg, 0] + t_hi * du",
            ],
        ),
        (
            "equivalent: a row of the band is within w of the segment, so min(t1, t2) <= 1, max(t1, t2) >= 0 and, for a "
            "flat segment, row - w - va <= 0, each up to one rounding: the bound removed or moved decides only when a "
            "rounding crosses it, moving the stretch by |du| ulps, which changes only pairs at the band's edge, about "
            "reach > threshold (1 + DOUBT) away: they decide nothing",
            [
                "t1 = np.where(None, 0.0, (row - w - ua[seg, 1]) / np.where(flat, 1.0, dv))",
                "t_lo, t_hi = np.clip(np.minimum(t1, t2), 0.0, None), np.clip(np.maximum(t1, t2), 0.0, 1.0)",
                "t_lo, t_hi = np.clip(np.minimum(t1, t2), 0.0, 2.0), np.clip(np.maximum(t1, t2), 0.0, 1.0)",
                "t_lo, t_hi = np.clip(np.minimum(t1, t2), 0.0, 1.0), np.clip(np.maximum(t1, t2), None, 1.0)",
            ],
        ),
        (
            "equivalent: for a flat segment the outer np.where replaces the quotient; dividing by 2.0 avoids the "
            "division by zero as 1.0 does",
            [
                "t1 = np.where(flat, 0.0, (row - w - ua[seg, 1]) / np.where(flat, 2.0, dv))",
                "t2 = np.where(flat, 1.0, (row + w - ua[seg, 1]) / np.where(flat, 2.0, dv))",
            ],
        ),
        (
            "equivalent: for a flat segment t1 = 0, and with t2 = 2 the clipped min and max are 0 and 1, as with t2 = 1",
            ["t2 = np.where(flat, 2.0, (row + w - ua[seg, 1]) / np.where(flat, 1.0, dv))"],
        ),
        (
            "equivalent: the crossing column is clipped to [0, ni], so row ni + 1 of toggles is never written, and only "
            "rows 0 .. ni - 1 are summed",
            ["toggles = np.zeros((ni + 2, nj), dtype=np.int64)"],
        ),
        (
            "equivalent: shapely's coordinates are float64 already",
            [
                "rings = [np.asarray(r.coords, dtype=None)[:-1] for r in (shape.exterior, *shape.interiors)]",
                "rings = [np.asarray(r.coords, )[:-1] for r in (shape.exterior, *shape.interiors)]",
            ],
        ),
        (
            "equivalent: pairing each vertex with the previous one gives the same segments, each from its other end; the "
            "distance and the crossing abscissa differ by roundings only: outside the doubtful window the band is right "
            "by a margin of DOUBT threshold, 10^8 ulps, and a crossing moved across an integer flips the parity of a "
            "vertex within a rounding of the boundary only, never kept (clearance >= 1)",
            ["b = np.vstack([np.roll(r, +1, axis=0) for r in rings])"],
        ),
        (
            "equivalent: the threshold moves by 2 REL_TOL distance, 50 times less than the doubtful window DOUBT "
            "threshold: a vertex the band decides is on the same side of both thresholds, and one in the window is "
            "decided by shapely's at_least, which reads distance, not threshold",
            ["threshold = (1.0 + REL_TOL) * distance"],
        ),
        (
            "equivalent: near == threshold is in the doubtful window, decided by shapely",
            ["kept = inside & (near >= threshold)"],
        ),
        (
            "equivalent: at |near - threshold| == DOUBT threshold exactly the band's answer near > threshold is shapely's: "
            "the two distances differ by a few ulps, 10^8 times less",
            ["doubt = np.flatnonzero(np.abs(near - threshold) < DOUBT * threshold)"],
        ),
    ],
    # --- end of planar/_clearance.py ---
    # --- surface/ring.py (Step 2 on a closed polyline) ---
    "src/equimesh/surface/ring.py": [
        (
            "equivalent: every arc length asked for is at least 0 = arc[0] (the stretches start at a >= 0, the distances "
            "of _arc_at_distance are reached at arc >= 0), so searchsorted(..., 'right') - 1 is never below 0",
            ['idx = np.clip(np.searchsorted(arc, s, side="right") - 1, None, len(arc) - 2)'],
        ),
        (
            "equivalent: _at_arc replaces its first and last points (and parameters) by the polyline's ends, so the first "
            "and last arc lengths asked for decide nothing",
            [
                "p, q = (_at_arc(pts, pts, arc, np.array([1.0, x, arc[-1]]))[0][1] for pts, arc, x in ((ahead, arcs[leaving], s), (back, back_arc, t)))",
                "p, q = (_at_arc(pts, pts, arc, np.array([0.0, x, arc[+1]]))[0][1] for pts, arc, x in ((ahead, arcs[leaving], s), (back, back_arc, t)))",
                "p, q = (_at_arc(pts, pts, arc, np.array([0.0, x, arc[-2]]))[0][1] for pts, arc, x in ((ahead, arcs[leaving], s), (back, back_arc, t)))",
                "candidates = [np.array([1.0, length])]",
                "head, tail = [1.0] if a > 0 else [], [b] if b < length else []",
            ],
        ),
        (
            "equivalent: _at_arc is given the points as parameters too, so its parameters [1] are its points [0]",
            [
                "p, q = (_at_arc(pts, pts, arc, np.array([0.0, x, arc[-1]]))[1][1] for pts, arc, x in ((ahead, arcs[leaving], s), (back, back_arc, t)))"
            ],
        ),
        (
            "equivalent: corners are indices (a sequence of int, documented): any integer dtype indexes and slices alike",
            ["corners = np.asarray(corners, dtype=None)", "corners = np.asarray(corners, )"],
        ),
    ],
    # --- end of surface/ring.py ---
    # --- planar/placement.py (Problem 2's lattice placement search) ---
    "src/equimesh/planar/placement.py": [
        (
            "equivalent: check_count's least defaults to 1",
            ['n_angles = check_count(n_angles, "n_angles", )', 'n_offsets = check_count(n_offsets, "n_offsets", )'],
        ),
        (
            "equivalent: the search scores with the default engine, the fast one, and planar_estimate reads the strip "
            "estimate only for the reference engine",
            ["check_size(*planar_estimate(poly, l, None, DEFAULT_ENGINE), max_nodes, l)"],
        ),
    ],
    # --- end of planar/placement.py ---
    # --- planar/insertion/_region.py (the constrained Delaunay triangulation) ---
    "src/equimesh/planar/insertion/region.py": [
        (
            "equivalent: Triangle's Python binding converts vertices and holes to double itself (integer points and "
            "seeds give the same triangles: tests/test_region.py::test_integer_input_is_the_same_numbers)",
            [
                'data = {"vertices": np.asarray(points, dtype=None), "segments": np.asarray(segments, dtype=np.int32)}',
                'data = {"vertices": np.asarray(points, ), "segments": np.asarray(segments, dtype=np.int32)}',
                'data["holes"] = np.asarray(holes, dtype=None)',
                'data["holes"] = np.asarray(holes, )',
            ],
        ),
    ],
    # --- end of planar/insertion/_region.py ---
    # --- planar/_corner.py (Step 2 at one sharp corner, decided on a grid) ---
    "src/equimesh/planar/boundary/corner.py": [
        (
            "equivalent: np.unique merges the node 0 (or a multiple past top, removed by the filter) with the 0.0 "
            "already there; arange(k) is arange(0, k)",
            [
                "nodes = [np.arange(math.floor(top / step) + 1) * step]",
                "nodes = [np.arange(1, math.floor(top / step) + 2) * step]",
                "nodes.append(length - np.arange(math.floor(length / step)) * step)",
                "edges = np.arange(math.ceil(_horizon(lengths, reach, l) / step) + 2) * step",
            ],
        ),
        (
            "equivalent: no node is 0 (multiples k >= 1 of the step, and a far end less fewer than length / step "
            "steps), and np.unique would merge one with the 0.0 already there",
            ["return np.unique(np.concatenate([[0.0], nodes[(nodes >= 0.0) & (nodes <= top)], *kept]))"],
        ),
        (
            "equivalent: np.concatenate with the float nodes makes the kept points float whatever their dtype",
            [
                "kept = [np.asarray(points, dtype=None) for points in fixed if points is not None]",
                "kept = [np.asarray(points, ) for points in fixed if points is not None]",
            ],
        ),
        (
            "equivalent: at u sin theta == l the bound G(u) = u cos theta is at most u, already a lower bound",
            ["if sides[i - 1] != s and u * sin <= l:"],
        ),
        (
            "equivalent: the backward pass reaches i = -1 again, the last point, whose push it has just done (max "
            "is idempotent)",
            ["for i in range(len(sides) - 1, -2, -1):"],
        ),
        (
            "equivalent: the push at i = 1 acts only when the first two points of the order are on one side; until it "
            "first binds both iterate alike, and it binds only when z[1] > z[0] + 2l >= 3l; z only grows, so then the "
            "other side's first point, after z[1] in the order, is more than 2l from the corner in both, and _placed "
            "refuses both",
            ["for i in range(len(sides) - 1, +1, -1):"],
        ),
        (
            "equivalent: a part ends at least (1 - tol) l past where it starts, so no part ends in position 0 (the "
            "corner) or 1 (the first node or cell, at most l / 16 from the corner) whatever index > 0 says",
            ["step = part & (allowed & (index >= 0))[None, :]", "step = part & (allowed & (index > 1))[None, :]"],
        ),
        (
            "equivalent: without allowed a side may step past its short far end (or a long side past K l + 2l, which "
            "needs a step out of a point past K l, where it stops); such a point never ends its side and is the last "
            "point of every later state, so no extra state completes or is on the way to one that does",
            ["step = part & (allowed | (index > 0))[None, :]"],
        ),
        (
            "equivalent: with axis=None every target is kept, also those with nothing fresh: or-ing in nothing and "
            "keeping their parents changes no state, and marking them dirty only makes the sweep look at them again",
            ["grown = fresh.any(axis=None)"],
        ),
        (
            "equivalent: best starts below 0 only to lose to any value; -2 loses as -1 does (short > 0)",
            ["best = np.full((self.n, self.n), -2.0)"],
        ),
        (
            "equivalent: a corner of the two cells with v == u lies on the diagonal inside both, where the value "
            "2 (1 - c) t^2 grows with t, so the diagonal's end t = last, which is checked, is at least as large",
            ["best = np.where(v2 > u2, np.maximum(best, u2 * u2 + v2 * v2 - 2.0 * c * u2 * v2), best)"],
        ),
        (
            "equivalent: search indexes only layers 0 and 1 of reached and parent",
            ["reached = np.zeros((3, n, n), dtype=bool)", "parent = np.full((3, n, n), -1, dtype=np.int64)"],
        ),
        (
            "equivalent: np.full of a Python int makes int64 arrays without dtype too (numpy 2, 64-bit platforms)",
            ["parent = np.full((2, n, n), -1, dtype=None)", "parent = np.full((2, n, n), -1, )"],
        ),
        (
            "equivalent: the initial parent is never read: _path reads the parents of reached states with p > 0, each "
            "set when the state is first reached",
            ["parent = np.full((2, n, n), +1, dtype=np.int64)", "parent = np.full((2, n, n), -2, dtype=np.int64)"],
        ),
        (
            "equivalent: dirty is read only as truth values; a float array of 0 and 1 (or None stored as False in a "
            "bool array) reads alike",
            ["dirty = np.zeros((2, n), dtype=None)", "dirty = np.zeros((2, n), )", "dirty[s, p] = None"],
        ),
    ],
    # --- end of planar/_corner.py ---
    "src/equimesh/planar/increment.py": [
        (
            "equivalent: for Problem 1 (no strip estimate) planar_estimate returns the polygon's estimate without "
            "reading the engine",
            ["check_size(*planar_estimate(poly, l, None, None), max_nodes, l)"],
        ),
        (
            "equivalent: a list of no hole seeds is empty whatever its width",
            ["region = Region(boundary.points, boundary.segments, np.zeros((0, 3)))  # convex: no hole"],
        ),
        (
            "equivalent in effect: the seed (0, 0) is the lower-left corner of the bounding box in the local frame, "
            "a vertex of the convex polygon or a point outside it, in the interior of no triangle; Triangle carves "
            "nothing from it (every test passes with it)",
            ["region = Region(boundary.points, boundary.segments, np.zeros((1, 2)))  # convex: no hole"],
        ),
    ],
    "src/equimesh/planar/strip.py": [
        (
            "equivalent: np.full of a Python int makes int64 arrays without dtype too (numpy 2, 64-bit platforms)",
            [
                "lat_index = np.full(len(lat.points), -1, dtype=None)",
                "lat_index = np.full(len(lat.points), -1, )",
                "ij = np.full((len(points), 2), np.iinfo(np.int64).min, dtype=None)",
                "ij = np.full((len(points), 2), np.iinfo(np.int64).min, )",
            ],
        ),
        (
            "equivalent: the sentinel is only compared with 0 (lat_index < 0), and every entry is overwritten before use",
            ["lat_index = np.full(len(lat.points), -2, dtype=np.int64)"],
        ),
        (
            "equivalent: both engines convert the region's segments to int64 first "
            "(np.array(region.segments, dtype=np.int64))",
            ["np.vstack([boundary.segments, lat_index[lat.boundary_edges]]).astype(None),"],
        ),
        (
            "equivalent: lattice vertices on the boundary of K are numbered after the boundary points of P (at least "
            "3), so no entry of lat_index is 0",
            ["interior = np.flatnonzero(lat_index <= 0)", "interior = np.flatnonzero(lat_index < 1)"],
        ),
        (
            "equivalent: a point off the lattice has ij = (min int64, min int64), so an edge with one such end has an "
            "ij difference of magnitude about 2^63 (wrapping) and one with two has (0, 0): neither is a neighbour "
            "step, so lattice_adjacent drops it as the & did",
            [
                "both = is_lattice[mesh_edges[:, 0]] | is_lattice[mesh_edges[:, 1]]",
                "both = is_lattice[mesh_edges[:, 1]] & is_lattice[mesh_edges[:, 1]]",
            ],
        ),
        (_NEGATIVE_RESHAPE, ["v = real_array(value, name, EquimeshError).reshape(-2)"]),
    ],
}
# --- planar/_coupled.py (sharp corners in a row decided jointly) ---
_TRUTH_CELLS = "equivalent: _Chain and _side read cells only as a truth value, and None is as false as False"
_COUPLED_EQUIVALENT_GROUPS = {
    "src/equimesh/planar/boundary/chain.py": [
        (
            _TRUTH_CELLS,
            [
                "found = _Chain(thetas, lengths, l, level, cells=None, radii=inf).search()",
                "if level <= CORNER_REFINEMENTS and _Chain(thetas, lengths, l, level, cells=None, radii=inf).search():",
            ],
        ),
        (
            "equivalent: _Chain reads radii[0] to radii[2 m - 1] only (two per corner), so more radii are never read",
            ["inf = (math.inf,) * (3 * len(thetas))"],
        ),
        (
            "equivalent: shared reads only the first two angles of the slice it is given",
            [
                "return thetas[1] is None or all(shared(thetas[k - 1 : k + 2], lengths[k], l) for k in range(1, len(thetas)))"
            ],
        ),
        (
            "equivalent: the cells are a relaxation (docs/proofs.md): no grid of cells refutes a chain the search places, "
            "so without the search at the finest search grid the loop goes on to finer cells, refutes nothing and "
            "returns False as well; the search only ends it earlier",
            ["if level < CORNER_REFINEMENTS and _Chain(thetas, lengths, l, level, cells=False, radii=inf).search():"],
        ),
        (
            "equivalent: a lone corner's T_2 is its corner alone (the dummy side): its cross is all True without reading "
            "its (lo, hi), search reads its lo at an empty path, and its parts are read only as truth values (any, "
            "and), where float zeros are as false as bool ones",
            [
                "dummy = (np.zeros(1), np.zeros(2), np.ones(1, dtype=bool), np.zeros((1, 1), dtype=bool))",
                "dummy = (np.zeros(1), np.zeros(1), np.ones(1, dtype=bool), np.zeros((1, 1), dtype=None))",
                "dummy = (np.zeros(1), np.zeros(1), np.ones(1, dtype=bool), np.zeros((1, 1), ))",
            ],
        ),
        (
            "equivalent: the dead prefixes only save work: a prefix tried again reduces only sets already reduced "
            "(cached in tested, no step counted) and fails again",
            ["self.dead.add(None)"],
        ),
        (
            "equivalent: when is only compared with 0 (reached or not) and with the round before a reached position "
            "(at least 0), and -2 is as unreached as -1",
            ["when = np.full(len(left), -2)"],
        ),
        (
            "equivalent: no part leads to position 0 (the corner, at 0: a part to it would be negative; a lone corner's "
            "dummy side has no part), so it is never fresh again",
            [
                "fresh = parts[fresh].any(axis=0) & left & (when <= 0)",
                "fresh = parts[fresh].any(axis=0) & left & (when < 1)",
            ],
        ),
        (
            "equivalent: for nodes lo is hi (one array), and a search on cells is only asked whether it is None",
            ["return tuple(side[1][path[1:]] for side, path in zip(self.sides, [first, *paths, last]))"],
        ),
        (
            "equivalent: _cross reads only the first two entries (lo, hi) of the sides it is given",
            [
                "self.back = _cross(thetas[0], sides[1][:3], sides[0][:2], l, tol, (radii[1], radii[0]))",
                "self.back = _cross(thetas[0], sides[1][:2], sides[0][:3], l, tol, (radii[1], radii[0]))",
                "cross = _cross(thetas[k], (lengths[k] - hi, lengths[k] - lo), sides[k + 1][:3], l, tol, (radii[2 * k], "
                "radii[2 * k + 1]))",
            ],
        ),
        (
            "equivalent: a long side is longer than K l + 3l and its nodes stop at K l + 2l, so every node is at most "
            "length - l before its end whatever the bound (the bound is redundant)",
            [
                "ends = (lo >= reach) & (lo < length - l) if long_ else lo == length",
                "ends = (lo >= reach) & (lo <= length + l) if long_ else lo == length",
            ],
        ),
        (
            "equivalent: kinds are 0 to 5, so a seventh column of allowed is never indexed",
            ["allowed = np.array([[j in follows[i] for j in range(7)] for i in range(6)])"],
        ),
        (
            "equivalent: the only node at 0 (the corner) is already in, and np.unique merges the copy",
            [
                "lo = hi = np.unique(np.concatenate([[0.0], nodes[(nodes >= 0.0) & (nodes <= top)]]))",
                "nodes = np.arange(count) * step",
            ],
        ),
        (
            "equivalent: np.arange(n) is np.arange(0, n)",
            [
                "edges = np.arange(count + 1) * step",
                "nodes = np.concatenate([nodes, length - np.arange(count) * step])",
            ],
        ),
        (
            "equivalent: count - 1 steps already reach top (ceil(top / step) step >= top): a further node lies past "
            "top, a further node from the far end below 0, and a further edge starts past top, all dropped",
            ["edges = np.arange(0, count + 2) * step", "count = math.ceil(top / step) + 2"],
        ),
    ],
}
# --- end of planar/_coupled.py ---
# --- the fast engine's numba kernels ---
_LONGER_BUFFER = (
    "equivalent: a longer buffer; only h[:n] is read, and n never exceeds the original length (each "
    "Grow-Expansion adds at most one component, and the original has room for all of them)"
)
_KERNEL_EQUIVALENT_GROUPS = {
    "src/equimesh/planar/insertion/predicates.py": [
        (
            _LONGER_BUFFER,
            [
                "h = np.empty(3)",
                "h = np.empty(14)",
                "h = np.empty(3 * (nux * nvy + nuy * nvx) + 1)",
                "h = np.empty(2 * (nux * nvy + nuy * nvx) + 2)",
                "h = np.empty(3 * (nux * nux + nuy * nuy) + 1)",
                "h = np.empty(2 * (nux * nux + nuy * nuy) + 2)",
                "h = np.empty(3 * (na * nbc + nb * nca + nc * nab) + 1)",
                "h = np.empty(2 * (na * nbc + nb * nca + nc * nab) + 2)",
            ],
        ),
        (
            "equivalent: Shewchuk's own orient2d returns det when |det| >= the bound (predicates.c: det >= errbound), "
            "so equality proves the sign too, and every caller reads only the sign (compared with 0, np.sign)",
            ["if abs(det) >= _CCW_BOUND * (abs(left) + abs(right)):"],
        ),
        (
            "equivalent: the bound's 96 eps^2 term exceeds the second-order error, so the error is strictly below "
            "_ICC_BOUND * permanent when the permanent is positive and |det| equal to it proves the sign; at a zero "
            "permanent every product is 0 (no underflow in the documented range), the exact value too; callers read "
            "only the sign",
            ["if abs(det) >= _ICC_BOUND * permanent:"],
        ),
    ],
    "src/equimesh/planar/insertion/cdt.py": [
        (
            "equivalent: the bounding-box test only answers False early, and two of its four conditions cannot hold "
            "together (a box left of the other and the other left of it), so each mutant still answers False only for "
            "disjoint boxes, and every other pair goes on to the exact test",
            [
                "if max(px, qx) < min(ax, bx) or max(ax, bx) < min(px, qx) or max(py, qy) < min(ay, by) and max(ay, by) < min(py, qy):",
                "if max(px, qx) < min(ax, bx) or max(ax, bx) < min(px, qx) and max(py, qy) < min(ay, by) or max(ay, by) < min(py, qy):",
                "if max(px, qx) < min(ax, bx) and max(ax, bx) < min(px, qx) or max(py, qy) < min(ay, by) or max(ay, by) < min(py, qy):",
            ],
        ),
        (
            "equivalent: d1 .. d4 are signs in {-1, 0, 1}; the mutant differs only when one end (say q, d2 = 0) lies on "
            "the other segment's line while that segment's ends are strictly on both sides of line pq: then the lines "
            "meet at q, between a and b, and the segments touch, the answer of the on-segment test (d1 / 0 is +-inf as "
            "Python, 0 / 0 is nan and not < 0)",
            [
                "if d1 / d2 < 0 and d3 * d4 < 0:",
                "if d1 * d2 <= 0 and d3 * d4 < 0:",
                "if d1 * d2 < 1 and d3 * d4 < 0:",
                "if d1 * d2 < 0 and d3 / d4 < 0:",
                "if d1 * d2 < 0 and d3 * d4 <= 0:",
                "if d1 * d2 < 0 and d3 * d4 < 1:",
            ],
        ),
        (
            "equivalent: the walk's direction only decides where it goes next; locate answers from a triangle only after "
            "the closed-containment test (then t, or the lower of t and its neighbour across the edge holding the point, "
            "the only triangles containing it), and else scans every slot after max_steps or when it leaves the "
            "triangulation: the same answer",
            [
                "t = N[t, 0 if (o0 < 0.0) and False else (1 if o1 < 0.0 else 2)]",
                "t = N[t, 0 if (o0 < 0.0) or True else (1 if o1 < 0.0 else 2)]",
                "t = N[t, 1 if o0 < 0.0 else (1 if o1 < 0.0 else 2)]",
                "t = N[t, 0 if o0 <= 0.0 else (1 if o1 < 0.0 else 2)]",
                "t = N[t, 0 if o0 < 1.0 else (1 if o1 < 0.0 else 2)]",
                "t = N[t, 0 if o0 < 0.0 else (1 if (o1 < 0.0) and False else 2)]",
                "t = N[t, 0 if o0 < 0.0 else (1 if (o1 < 0.0) or True else 2)]",
                "t = N[t, 0 if o0 < 0.0 else (2 if o1 < 0.0 else 2)]",
                "t = N[t, 0 if o0 < 0.0 else (1 if o1 <= 0.0 else 2)]",
                "t = N[t, 0 if o0 < 0.0 else (1 if o1 < 1.0 else 2)]",
            ],
        ),
        (
            "equivalent: a stricter acceptance still accepts only triangles that contain the point, where the answer is "
            "right; a triangle it rejects sends the walk on, and in the end to the scan, which gives the same answer",
            [
                "if o0 > 0.0 and o1 >= 0.0 and o2 >= 0.0:",
                "if o0 >= 1.0 and o1 >= 0.0 and o2 >= 0.0:",
                "if o0 >= 0.0 and o1 > 0.0 and o2 >= 0.0:",
                "if o0 >= 0.0 and o1 >= 1.0 and o2 >= 0.0:",
                "if o0 >= 0.0 and o1 >= 0.0 and o2 > 0.0:",
                "if o0 >= 0.0 and o1 >= 0.0 and o2 >= 1.0:",
            ],
        ),
        (
            "equivalent: stopping a walk early (at slot 0, or at a point on an edge) only hands the query over: "
            "locate's to the scan, which returns the lowest slot containing the point (for a point inside an edge the "
            "lower of its two triangles, the walk's own answer); walk's (status -1) to the engine's brute-force "
            "visibility test and locate, which decide the same",
            ["if t <= 0:", "if t < 1:", "if zeros >= 1:"],
        ),
        (
            "equivalent: np.full takes the dtype of its fill value -1 (int64); float keys and counts of small integers "
            "are exact and sort, search and compare as the integers; the directed half-edge keys are unique, so the "
            "sort's stability is never seen; order[pos] / 3 stored into the int64 N truncates as // does",
            [
                "keys = np.empty(3 * nt, dtype=None)",
                "keys = np.empty(3 * nt, )",
                "order = np.argsort(keys, kind=None)",
                "order = np.argsort(keys, )",
                'order = np.argsort(keys, kind="MERGESORT")',
                "N = np.full((nt, 3), -1, dtype=None)",
                "N = np.full((nt, 3), -1, )",
                "S = np.full((nt, 3), -1, dtype=None)",
                "S = np.full((nt, 3), -1, )",
                "N[t, e] = order[pos] / 3",
                "count = np.zeros(len(SA), dtype=None)",
                "count = np.zeros(len(SA), )",
            ],
        ),
        (
            "equivalent under the engine's contract (checked first: every constraint is an edge of exactly one "
            "triangle): a constraint edge has no triangle across it (n < 0), so the constraint tests of the cavity and "
            "of its boundary decide nothing that n < 0 and the mark do not",
            [
                "if S[t, e] >= 0 and n < 0 or mark[n] == stamp:",
                "if S[t, e] > 0 or n < 0 or mark[n] == stamp:",
                "if S[t, e] >= 1 or n < 0 or mark[n] == stamp:",
                "if inside and s > 0:",
                "if inside and s >= 1:",
            ],
        ),
        (
            "equivalent: the new point lies strictly inside the star of its cavity (inside a cavity triangle, or on an "
            "edge between two: both contain it strictly in their circumcircles; never on an unsplit constraint, within "
            "REL_TOL l of which no circumcentre is pushed), so no fan triangle is flat",
            ["if orient2d(P[u, 0], P[u, 1], P[v, 0], P[v, 1], px, py) < 0.0 or vstamp[u] == stamp:"],
        ),
        (
            "equivalent: the cavity's boundary is a closed polygon, so the second loop of fill links edges 1 and 2 of "
            "every fan triangle, overwriting these first values; and any negative S means no segment (only S >= 0 is "
            "tested)",
            [
                "N[t, 0], N[t, 2], N[t, 2] = outer, -1, -1",
                "N[t, 0], N[t, 1], N[t, 2] = outer, +1, -1",
                "N[t, 0], N[t, 1], N[t, 2] = outer, -2, -1",
                "N[t, 0], N[t, 1], N[t, 2] = outer, -1, +1",
                "N[t, 0], N[t, 1], N[t, 2] = outer, -1, -2",
                "S[t, 0], S[t, 1], S[t, 2] = edges[f, 3], -2, -1",
                "S[t, 0], S[t, 1], S[t, 2] = edges[f, 3], -1, -2",
            ],
        ),
        (
            "equivalent: v occurs once in the outer triangle, followed by u (it has the edge v -> u), so the first j "
            "with V[outer, j] == v is the j with V[outer, j + 1] == u",
            ["if V[outer, j] == v or V[outer, (j + 1) % 3] == u:"],
        ),
        (
            "equivalent: the caller reads only status < 0 and then computes the triangle itself (locate)",
            ["return -2, -1", "return -1, +1", "return -1, -2"],
        ),
        (
            "equivalent: a zero orientation of the line gc with a vertex returned -1 just before, so s0, s1, s2 are "
            "nonzero here and <= 0 is < 0, >= 0 is > 0",
            [
                "if s2 <= 0.0 and s0 > 0.0:",
                "if s2 < 0.0 and s0 >= 0.0:",
                "elif s1 <= 0.0 and s2 > 0.0:",
                "elif s1 < 0.0 and s2 >= 0.0:",
                "elif s0 <= 0.0 and s1 > 0.0:",
                "elif s0 < 0.0 and s1 >= 0.0:",
            ],
        ),
        (
            "equivalent: o_out == 0 would put c on the line of the edge the segment gc leaves t by, where gc meets that "
            "line, hence on the edge itself and in the closed triangle t, which was tested before",
            ["if o_out > 0.0:"],
        ),
        (
            "equivalent: the line gc crosses the interior of t (g is inside the first triangle, and the walk enters each "
            "later one across an edge), so s0, s1, s2, nonzero here, are not all of one sign; the first two branches miss "
            "only the signs (-, +, +) and (-, +, -), where s0 < 0 < s1 holds anyway",
            ["elif s0 < 0.0 or s1 > 0.0:", "elif s0 < 1.0 and s1 > 0.0:"],
        ),
        (
            "equivalent: o_out is negative here: c is not in t, and on the line from g it lies past the edge the line "
            "leaves t by",
            ["if o_out >= 1.0:"],
        ),
        (
            "equivalent: these returns of walk are never reached: the else (the signs of a line through t's interior are "
            "never all one), o_out >= 0 (c, not in t, lies past the edge the line leaves t by), t < 0 (under the "
            "engine's contract every boundary edge is a constraint, where the walk stopped) and the loop's end (one step "
            "per triangle the segment crosses, and the engine allows n_slots + 1)",
            ["return +1, -1"],
        ),
    ],
    "src/equimesh/planar/insertion/fast.py": [
        (
            "equivalent: as floats 1.0 / 0.0 these flags are only read as truth values and written True / False",
            [
                "salive = np.ones(len(SA), dtype=None)",
                "salive = np.ones(len(SA), )",
                "alive = np.ones(n_slots, dtype=None)",
                "alive = np.ones(n_slots, )",
            ],
        ),
        (
            "equivalent: as floats these counters and slot numbers stay exact integers (far below 2^53); they are only "
            "incremented, compared for equality with integer stamps and versions, and copied into int64 arrays",
            [
                "ver = np.zeros(n_slots, dtype=None)",
                "ver = np.zeros(n_slots, )",
                "mark = np.zeros(n_slots, dtype=None)",
                "mark = np.zeros(n_slots, )",
                "vstamp = np.zeros(n, dtype=None)",
                "vstamp = np.zeros(n, )",
                "free = np.empty(n_slots, dtype=None)",
                "free = np.empty(n_slots, )",
            ],
        ),
        (
            "equivalent: run raises on any status but _OK before it reads the arrays returned with it",
            ["return -2 - s, P0, T0, SEG0, np.empty(None)", "return -2 - s, P0, T0, SEG0, np.empty(1)"],
        ),
        (
            "equivalent: a buffer's capacity is checked against the need before every use (len(edges) against k + 2, "
            "len(HK) against the pushes to come, len(P) against n) and grown then; a longer values, vfan or vstamp "
            "than the array checked, or an unused column, is never read; the heap's arrays start empty, and the first "
            "_room (need 4 n_slots > 1) grows both to one length, 2 len(HK) + need, so a row more in either at the start "
            "changes nothing after it",
            [
                "edges = np.empty((_CAVITY - 2, 4), dtype=np.int64)",
                "edges = np.empty((_CAVITY + 3, 4), dtype=np.int64)",
                "edges = np.empty((_CAVITY + 2, 5), dtype=np.int64)",
                "HK, HI = np.empty((1, 3)), np.empty((0, 3), dtype=np.int64)",
                "HK, HI = np.empty((0, 3)), np.empty((1, 3), dtype=np.int64)",
                "HK, HI = np.empty((0, 4)), np.empty((0, 3), dtype=np.int64)",
                "HK, HI = np.empty((0, 3)), np.empty((0, 4), dtype=np.int64)",
                "size = 3 * len(HK) + need",
                "P, values = _grown(P, 2 * n), _grown(values, 3 * n)",
                "vfan, vstamp = _grown(vfan, 3 * n), _grown(vstamp, 2 * n)",
                "vfan, vstamp = _grown(vfan, 2 * n), _grown(vstamp, 3 * n)",
            ],
        ),
        (
            "equivalent: compacting or growing the heap earlier (never later) changes only its array, hence only the "
            "order in which entries with identical keys (value, x, y) surface; such entries are one point (a circumcentre "
            "shared by cocircular triangles; a circumcentre within REL_TOL l of a constraint is never pushed, so never "
            "equals a midpoint), inserted once with the same value, and its cavity, grown from any triangle containing "
            "it, is the same, so the same triangles follow (when the point lies on the edge between two of them, the "
            "fan may take their slots in the other order: the same mesh, its triangles listed in another order)",
            [
                "HK, HI, nh = _room(HK, HI, nh, 5 * m, ver, salive)",
                "if n + need >= len(HK):",
                "if 3 * (n + need) > len(HK):",
                "if 2 * (n + need) >= len(HK):",
            ],
        ),
        (
            "equivalent: the guard before _room only spares the call; _room checks the room itself, so calling it more "
            "often changes nothing",
            ["if nh + 5 * m > len(HK):", "if nh + 4 * m >= len(HK):"],
        ),
        (
            "equivalent: heapify sifts down from a higher index, a leaf (indices from k // 2 have no child below k), "
            "which _sift_down writes back unchanged",
            ["for i in range(k // 2 + 1, -1, -1):", "for i in range(k // 2, -1, -1):"],
        ),
        (
            "equivalent: stamps are only compared for equality with marks that start at 0, and are incremented before "
            "each use, so starting from 1 or stepping by 2 marks nothing falsely",
            ["nh, m, stamp = 0, n_slots, 1", "stamp += 2"],
        ),
        (
            "equivalent: growing a buffer earlier or larger (the need is checked again before every use): the cavity, "
            "its boundary edges and fan slots, the triangle arrays, SB and salive beside the SA that is checked; edges "
            "first grow at k >= 65, where 2 k - 2 >= k + 2",
            [
                "cav = _grown(cav, 3 * len(cav))",
                "if k + 3 > len(edges):",
                "if k + 2 >= len(edges):",
                "edges = _grown(edges, 2 * k - 2)",
                "edges = _grown(edges, 3 * k + 2)",
                "edges = _grown(edges, 2 * k + 3)",
                "if k + 3 > len(slots):",
                "if k + 2 >= len(slots):",
                "slots = _grown(slots, 3 * k + 2)",
                "slots = _grown(slots, 2 * k + 3)",
                "if m >= n_free + len(V) - n_slots:",
                "size = 3 * len(V) + m",
                "if n_segs + 3 > len(SA):",
                "if n_segs + 2 >= len(SA):",
                "SA, SB, salive = _grown(SA, 2 * len(SA) + 2), _grown(SB, 3 * len(SB) + 2), _grown(salive, 2 * len(SA) + 2)",
                "SA, SB, salive = _grown(SA, 2 * len(SA) + 2), _grown(SB, 2 * len(SB) + 3), _grown(salive, 2 * len(SA) + 2)",
                "SA, SB, salive = _grown(SA, 2 * len(SA) + 2), _grown(SB, 2 * len(SB) + 2), _grown(salive, 3 * len(SA) + 2)",
                "SA, SB, salive = _grown(SA, 2 * len(SA) + 2), _grown(SB, 2 * len(SB) + 2), _grown(salive, 2 * len(SA) + 3)",
            ],
        ),
        (
            "equivalent: cavity returns -1 (buffer too short) or k >= 1 (the start triangle is always in), and "
            "cavity_boundary -1 or m >= 3 (a cavity's boundary is a closed polygon)",
            ["while k <= 0:", "while k < 1:", "if m <= 0:", "if m < 1:"],
        ),
        ("equivalent: r is -1 (no candidate) or at least (1 - REL_TOL) l > 0", ["if r <= 0.0:", "if r > 0.0:"]),
        (
            "equivalent: the callers compare a rejected circumcentre's r with 0 only (r >= 0.0 when it is pushed, r < 0.0 "
            "when it surfaces), and -2 is as negative as -1; they never read its triangle",
            ["return -2.0, cx, cy, -1", "return -1.0, cx, cy, +1", "return -1.0, cx, cy, -2"],
        ),
        (
            "equivalent: under a0 != b0 (a1 != b1), a0 <= b0 is a0 < b0 (a1 <= b1 is a1 < b1)",
            ["return a0 <= b0", "return a1 <= b1"],
        ),
        (
            "equivalent: _visible_circumcentre compares the gap only with REL_TOL l and SLIVER_GAP l = reach / 2, so "
            "a search that is exact up to reach / 2 and never reports less than the distance decides the same. No "
            "segment from the point to a constraint point nearer than reach crosses an edge at exactly reach; and under "
            "the engine's contract every boundary edge is a constraint, so a non-constraint edge has a triangle across "
            "it (n >= 0), and the mutant with 'and' only searches farther",
            [
                "if n < 0 or _edge_distance(P, V[t, e], V[t, (e + 1) % 3], x, y) >= reach:",
                "if n < 0 and _edge_distance(P, V[t, e], V[t, (e + 1) % 3], x, y) > reach:",
            ],
        ),
        (
            "equivalent: a search reach far larger than 2 SLIVER_GAP l only searches farther: the gap stays exact up to "
            "SLIVER_GAP l and is never below the distance, and only there does it decide (argument of _gap's search)",
            [
                "return np.array([(1.0 - REL_TOL) * l, (1.0 + REL_TOL) * l, REL_TOL * l, SLIVER_GAP * l, _REACH / SLIVER_GAP * l])"
            ],
        ),
        (
            "equivalent: known = None before the loop is as false as False; in the loop, a search that never finds a "
            "triangle known adds triangles again until its buffer is full and then measures every constraint: the exact "
            "distance, which decides as the search's does (only up to reach / 2 = SLIVER_GAP l does the gap decide)",
            ["known = None", "known = known and seen[j] == n"],
        ),
        (
            "equivalent: the candidates of slots[0], a live triangle of the last fan, pushed again after an entry is "
            "skipped, are copies of entries in the heap (same key, triangle, version and segment) or are refused again "
            "(the state is the one that refused them when they surfaced); the first copy to surface is processed as the "
            "original would be, and the others are then stale or refused alike",
            ["m = 1"],
        ),
        (
            "equivalent: the fan of a cavity of k triangles has k + 2 of them (k + 1 when the point splits a segment; a "
            "cavity that is not a disc fails fill and the run raises), so every slot freed is taken again by the same "
            "insertion and alive is True for every slot below n_slots whenever it is read",
            ["alive[cav[i]] = None", "alive[cav[i]] = True"],
        ),
        (
            "equivalent: versions are only compared for equality with the version an entry was pushed with, and a slot's "
            "version still takes a new value at each retirement",
            ["ver[cav[i]] -= 1", "ver[cav[i]] += 2"],
        ),
        ("equivalent: None stored in a NumPy bool array is False", ["salive[s] = None"]),
        (
            "equivalent: denom is 0 only when a = b, and then the numerator is 0 too: t = 0 either way",
            ["t = ((x - ax) * abx + (y - ay) * aby) / (denom if denom > 0 else 2.0)"],
        ),
        (
            "equivalent: a walk takes one step per triangle its segment crosses, so it needs all n_slots steps only when "
            "it crosses every triangle, and then c is strictly inside the last or on a constraint (a triangle across an "
            "edge holding c would be one it did not cross): one step fewer gives status -1, and the brute-force test and "
            "locate decide the same and find the same triangle; more steps are never taken",
            [
                "status, where = walk(P, V, N, S, t, gx, gy, cx, cy, n_slots - 1)",
                "status, where = walk(P, V, N, S, t, gx, gy, cx, cy, n_slots + 2)",
            ],
        ),
        (
            "equivalent: locate's answer, the lowest live slot containing the point, does not depend on its step bound "
            "(its walk answers the same, else the scan does)",
            [
                "where = locate(P, V, N, alive, n_slots, t, cx, cy, n_slots - 1)",
                "where = locate(P, V, N, alive, n_slots, t, cx, cy, n_slots + 2)",
            ],
        ),
        (
            "equivalent: an entry of a split segment s belongs to the triangle that had s as an edge, the start of the "
            "split's cavity, so its version is stale and it is skipped whatever the segment test says",
            [
                "if ver[t] != version or (s > 0 and not salive[s]):",
                "if ver[t] != version or (s >= 1 and not salive[s]):",
            ],
        ),
        (
            _NEGATIVE_RESHAPE,
            [
                "points = np.array(region.points, dtype=float).reshape(-2, 2)",
                "segments = np.array(region.segments, dtype=np.int64).reshape(-2, 2)",
            ],
        ),
        (
            "equivalent: constrained_delaunay returns int64 triangles already",
            [
                "points, np.ascontiguousarray(triangles, dtype=None), segments, _limits(l)",
                "points, np.ascontiguousarray(triangles, ), segments, _limits(l)",
            ],
        ),
        (
            "equivalent: status 0 means the walk found gc touching a constraint; the brute-force test then finds it too "
            "and returns -1 as the branch for status 0 does",
            ["if status <= 0:", "if status < 1:"],
        ),
    ],
}
# --- end of the fast engine's kernels ---
# --- the sharp-corner Step 2: polygon.py's grid decisions and planar/_corner.py, the last survivors ---
_SHARP_EQUIVALENT_GROUPS = {
    "src/equimesh/planar/polygon.py": [
        (
            "equivalent: inner_angle is never exactly 60: np.degrees of the floats next to pi / 3 are 59.99999999999999 "
            "and 60.00000000000001 (reflex angles are past 180), so < 60 and <= 60 agree",
            ["if not angle <= SHARP_CORNER:", "if not max(angles) <= SHARP_CORNER:"],
        ),
        (
            "equivalent: with no second corner (theta_2 None) _Pair reads neither B's length nor radii[2:] (B is a dummy "
            "side of one position)",
            [
                "(theta, None), (sides[1], sides[0], 1.0), lp, (radii[1], radii[0], 0.0, 0.0)",
                "(theta, None), (sides[1], sides[0], 0.0), lp, (radii[1], radii[0], 1.0, 0.0)",
                "(theta, None), (sides[1], sides[0], 0.0), lp, (radii[1], radii[0], 0.0, 1.0)",
            ],
        ),
        (
            "equivalent: the halving never reaches k = 64: a side is at most sqrt(2) MAX_EXTENT l = 2^16.5 l, so from "
            "k = 49 on the triangle lies within REL_TOL l / 2 of its corner, a point of P, inside P grown by REL_TOL l",
            ["for k in range(65):", "return 1.0, 0.0", "return 0.0, 1.0"],
        ),
        (
            "equivalent: a side left dirty is settled again with the neighbours it was settled with (else they would "
            "have marked it dirty), and _short_side then keeps it: it is the first candidate separating both corners "
            "or, if none does, none of the same candidates has a larger gap; the extra passes change nothing",
            ["dirty.discard(None)"],
        ),
        (
            "equivalent: _grid_side reads leaving only as a truth value, and None is as false as False",
            ["trial[c - 1] = _grid_side(lengths[c - 1], a, _from_corner(sides, lengths, c, c - 1), None, l, spacing)"],
        ),
        (
            "equivalent: _from_corner reads c only in i == c, and i = c - 1 is no more c than None is",
            [
                "trial[c - 1] = _grid_side(lengths[c - 1], a, _from_corner(sides, lengths, None, c - 1), False, l, spacing)"
            ],
        ),
    ],
}
# --- end of the sharp-corner Step 2's last survivors ---
EQUIVALENT = {
    (module, line): why
    for table in (_EQUIVALENT_GROUPS, _KERNEL_EQUIVALENT_GROUPS, _COUPLED_EQUIVALENT_GROUPS, _SHARP_EQUIVALENT_GROUPS)
    for module, groups in table.items()
    for why, lines in groups
    for line in lines
}

#: pytest options for every mutant run: stop at the first failure.
PYTEST_ARGS = ["-p", "no:cacheprovider", "-q", "-x"]

#: mutmut stops a mutant after ``2 * TIMEOUT_MULTIPLIER * (its tests' time + 1 s)``
#: of CPU time (timed out, counted as killed).  mutmut's default, 15, let a
#: mutant that never stops inserting run for 4 minutes on a loaded machine; a
#: surviving mutant runs its tests in their own time, so 3 leaves a margin of 6.
TIMEOUT_MULTIPLIER = 3.0

STATUSES = ("killed", "survived", "timeout", "no tests", "suspicious", "skipped", "segfault", "not checked")


def parse_args(argv=None):
    p = _common.parser(__doc__)
    p.add_argument("modules", nargs="*", help="module paths (default: every module of MODULES)")
    p.add_argument("--max-children", type=int, default=2, help="parallel mutant runs (default 2)")
    p.add_argument("--work-dir", type=Path, default=ROOT / ".mutation", help="scratch folder (default .mutation/)")
    p.add_argument("--resume", action="store_true", help="keep the scratch copy of a module and its finished mutants")
    p.add_argument(
        "--so-far",
        action="store_true",
        help="write the rows of interrupted modules from the mutants already run (runs nothing)",
    )
    p.add_argument(
        "--survivors",
        action="store_true",
        help="run only the last run's survivors again, against the current tests (keeps the other verdicts)",
    )
    p.add_argument(
        "--unexplained",
        action="store_true",
        help="as --survivors, but only the survivors not argued equivalent in EQUIVALENT",
    )
    p.add_argument(
        "--functions",
        type=lambda text: text.split(","),
        metavar="F,G,...",
        help="run only the mutants of these functions of one module (comma-separated; Class.method for a "
        "method); the others keep the verdicts of its last full run",
    )
    _common.add_output_options(p, fig_dir=False)
    args = p.parse_args(argv)
    unknown = [m for m in args.modules if m not in MODULES]
    if unknown:
        p.error(f"unknown module {unknown[0]!r}; known: {', '.join(MODULES)}")
    if args.functions and (len(args.modules) != 1 or args.resume):
        p.error("--functions needs exactly one module, and no --resume")
    return args


def mutmut_table(module):
    """The ``[tool.mutmut]`` table that mutates ``module`` only, against its tests."""

    def toml_list(items):
        return "[" + ", ".join(json.dumps(i) for i in items) + "]"

    return "\n".join(
        [
            "",
            "[tool.mutmut]",
            'source_paths = ["src"]',
            f"only_mutate = {toml_list([module])}",
            f"pytest_add_cli_args_test_selection = {toml_list(MODULES[module])}",
            f"pytest_add_cli_args = {toml_list(PYTEST_ARGS)}",
            f"timeout_multiplier = {TIMEOUT_MULTIPLIER}",
            "",
        ]
    )


def prepare(module, work_dir, keep=None):
    """The copy of the project for ``module``'s mutants; returns its folder.

    ``keep=None`` makes a fresh copy; ``"resume"`` and ``"so-far"`` keep an
    existing one with its tests; ``"survivors"`` keeps it with the current tests.  Either way the
    ``[tool.mutmut]`` table is the current one (mutmut resets the verdicts its
    change can alter).
    """
    folder = work_dir / re.sub(r"[^A-Za-z0-9]+", "_", module)
    fresh = keep is None or not folder.exists()
    if fresh:
        shutil.rmtree(folder, ignore_errors=True)
        folder.mkdir(parents=True)
        shutil.copytree(ROOT / "src", folder / "src", ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    if fresh or keep == "survivors":
        shutil.copytree(
            ROOT / "tests", folder / "tests", ignore=shutil.ignore_patterns("__pycache__", "*.pyc"), dirs_exist_ok=True
        )
    text = (ROOT / "pyproject.toml").read_text()
    (folder / "pyproject.toml").write_text(text + mutmut_table(module))
    return folder


def mutmut(folder, *args, environment=None):
    """Run ``mutmut *args`` in ``folder`` with ``environment`` added; its standard output."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}  # mutmut puts mutants/src first itself
    env.update(environment or {})
    done = subprocess.run([sys.executable, "-m", "mutmut", *args], cwd=folder, env=env, capture_output=True, text=True)
    if done.returncode:
        raise SystemExit(f"mutmut {' '.join(args)} failed in {folder}: {done.stderr.strip().splitlines()[-1:]}")
    return done.stdout


def mutated_line(folder, name):
    """The line of the mutant ``name`` as mutmut shows it (the first "+" line of its diff)."""
    for line in mutmut(folder, "show", name).splitlines():
        if line.startswith("+") and not line.startswith("+++"):
            return line[1:].strip()
    return ""


def statuses(folder):
    """Mutant name -> status (killed, survived, ...) of the mutants in ``folder``."""
    return dict(re.findall(r"^\s*(\S+): (.+)$", mutmut(folder, "results", "--all", "true"), re.M))


def _function(mangled):
    """The function of a mutant or of mutmut's mangled name, as ``--functions`` names it.

    ``equimesh.planar.polygon.x__run__mutmut_3`` -> ``_run``, ``xǁPolygonǁarea`` -> ``Polygon.area``.
    """
    return mangled.rsplit("__mutmut_", 1)[0].rpartition(".")[2][2:].replace("ǁ", ".")


def _glob(module, function):
    """mutmut's name pattern of the mutants of ``function`` in ``module`` (a path under ``src/``)."""
    dotted = ".".join(Path(module).with_suffix("").parts[1:])
    return f"{dotted}.x{'ǁ' if '.' in function else '_'}{function.replace('.', 'ǁ')}__mutmut_*"


def _by_function(status, hashes):
    """Function -> its hash and the count of its mutants per status (only those present)."""
    rows = {_function(f): {"hash": h} for f, h in hashes.items()}
    for name, verdict in status.items():
        row = rows.setdefault(_function(name), {"hash": None})
        row[verdict] = row.get(verdict, 0) + 1
    return rows


def _hashes(folder, module):
    """mutmut's hash of each function of ``module`` (mangled name -> hash) in the scratch copy ``folder``."""
    meta = folder / "mutants" / (module + ".meta")
    return json.loads(meta.read_text())["hash_by_function_name"]


def _scored(row):
    """``row`` with its survivors' arguments, the equivalent count and the score filled in."""
    for s in row["survivors"]:
        s["equivalent"] = EQUIVALENT.get((row["module"], s["line"]))
    row["equivalent"] = sum(s["equivalent"] is not None for s in row["survivors"])
    left_out = row["equivalent"] + row["no tests"] + row["skipped"] + row.get("not checked", 0)
    relevant = row["mutants"] - left_out
    row["score"] = (row["killed"] + row["timeout"]) / relevant if relevant else 1.0
    return row


def merged(before, part, functions):
    """The row of a full run ``before`` with the verdicts of ``functions`` replaced by those of ``part``.

    ``part`` is :func:`run_module`'s row of a run of those functions only.
    Functions gone from the module are dropped; one not named must have the
    hash it had in ``before`` (its verdicts still hold), else SystemExit.
    The functions run again since the full run accumulate in ``rerun``.
    """
    module = before["module"]
    if "by_function" not in before:
        raise SystemExit(f"{NAME}: the row of {module} has no verdicts per function: run the module in full first")
    now = part["by_function"]
    missing = sorted(set(functions) - set(now))
    if missing:
        raise SystemExit(f"{NAME}: {module} has no function {missing[0]!r}")
    stale = [f for f in now if f not in functions and before["by_function"].get(f, {}).get("hash") != now[f]["hash"]]
    if stale:
        raise SystemExit(f"{NAME}: {module}: {', '.join(stale)} changed since its full run: name it in --functions")
    by_function = {f: now[f] if f in functions else before["by_function"][f] for f in now}
    counts = {s: sum(row.get(s, 0) for row in by_function.values()) for s in STATUSES}
    kept = [
        s
        for s in before["survivors"]
        if _function(s["mutant"]) in by_function and _function(s["mutant"]) not in functions
    ]
    survivors = sorted(kept + part["survivors"], key=lambda s: _natural(s["mutant"]))
    named = [f for f in dict.fromkeys([*before.get("rerun", {}).get("functions", ()), *functions]) if f in by_function]
    mutants = sum(count for f in named for s, count in by_function[f].items() if s != "hash")
    rerun = {"functions": named, "mutants": mutants, "seconds": part["seconds"]}
    return _scored(
        {
            **before,
            "mutants": sum(counts.values()),
            **counts,
            "survivors": survivors,
            "by_function": by_function,
            "rerun": rerun,
        }
    )


def run_module(
    module, work_dir, max_children, keep=None, seconds=None, progress=print, functions=None, unexplained=False
):
    """Mutate ``module``, run its tests on every mutant; its counts and survivors.

    With ``keep="so-far"`` nothing runs: the row counts the mutants that an
    interrupted run checked (the rest are "not checked", outside the score),
    and its time is the sum of mutmut's times of the mutants run (their last
    runs), a little below the wall time.
    With ``keep="survivors"`` only the survivors of the last run are run again
    (:func:`prepare`; the test selection must be the same, or mutmut resets
    every verdict), and ``seconds`` is the time of that last full run.  mutmut
    maps each test to the functions it calls once, when it first sees the
    test: a survivor is run against new tests and the tests that reached its
    function before, so kill it with a new test (or run the module afresh).
    With ``functions`` only their mutants run, and the row counts those
    only (:func:`merged` puts it in the module's row).  With ``unexplained``
    only the survivors not argued in :data:`EQUIVALENT` run again.
    """
    folder = prepare(module, work_dir, keep)
    full = keep not in ("survivors", "so-far") or not (folder / "mutants").exists()
    again = (
        []
        if full
        else sorted(
            n for n, s in statuses(folder).items() if s == "survived" and (not functions or _function(n) in functions)
        )
    )
    if unexplained:
        again = [n for n in again if EQUIVALENT.get((module, mutated_line(folder, n))) is None]
    progress(
        f"{NAME}: {module} against {' '.join(MODULES[module])}"
        + ("" if full else ", so far" if keep == "so-far" else f", {len(again)} survivors again")
    )
    start = time.perf_counter()
    if keep == "so-far":
        if full:
            raise SystemExit(f"{NAME}: no interrupted run of {module} in {folder}")
        meta = [json.loads(f.read_text()) for f in (folder / "mutants").rglob("*.meta")]
        seconds = sum(d or 0.0 for m in meta for d in m["durations_by_key"].values())
    elif full or again:
        names = again or [_glob(module, f) for f in functions or ()]
        mutmut(folder, "run", "--max-children", str(max_children), *names, environment=ENVIRONMENT.get(module))
    if full or seconds is None:
        seconds = time.perf_counter() - start
    status = statuses(folder)
    by_function = _by_function(status, _hashes(folder, module))
    if functions:
        status = {n: s for n, s in status.items() if _function(n) in functions}
    counts = {s: sum(v == s for v in status.values()) for s in STATUSES}
    survivors = [
        {"mutant": name, "line": mutated_line(folder, name)}
        for name in sorted((n for n, s in status.items() if s == "survived"), key=_natural)
    ]
    row = _scored(
        {
            "module": module,
            "tests": MODULES[module],
            "environment": ENVIRONMENT.get(module, {}),
            "mutants": len(status),
            **counts,
            "seconds": round(seconds),
            "survivors": survivors,
            "by_function": by_function,
        }
    )
    progress(
        f"{NAME}: {module}: {len(status)} mutants, {counts['killed']} killed, "
        f"{counts['survived']} survived ({row['equivalent']} equivalent), {seconds:.0f} s"
    )
    return row


def _natural(name):
    """Sort key: mutant names with their numbers compared as numbers."""
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", name)]


def report(modules, record):
    """The Markdown report of ``modules`` (a list of :func:`run_module` results)."""
    body = [
        "A mutant is killed when one of its module's tests fails.  Score = (killed + timed out) /",
        "(mutants - equivalent survivors - mutants no test reaches).  Goal: >= 90 % per module.",
        "",
        "| module | tests | mutants | killed | survived | equivalent | timed out | no tests | score | time |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for m in modules:
        tests = " ".join([*(f"{k}={v}" for k, v in m.get("environment", {}).items()), ", ".join(m["tests"])])
        body.append(
            f"| `{m['module']}` | {tests} | {m['mutants']} | {m['killed']} | {m['survived']} "
            f"| {m['equivalent']} | {m['timeout']} | {m['no tests']} | {100 * m['score']:.1f} % | {m['seconds']} s |"
        )
    for m in modules:
        body += ["", f"## Survivors in `{m['module']}`", ""]
        if m.get("rerun"):
            body += [
                f"Only the mutants of {', '.join(f'`{f}`' for f in m['rerun']['functions'])} "
                f"({m['rerun']['mutants']}) were run again (`--functions`, the last run {m['rerun']['seconds']} s); the other "
                "functions' verdicts and the time are from the module's last full run.",
                "",
            ]
        if m.get("not checked"):
            how = (
                "`--functions` with the functions left runs them" if m.get("rerun") else "`--resume` continues the run"
            )
            body += [
                f"Interrupted: {m['not checked']} of {m['mutants']} mutants not run (not in the score; {how}).",
                "",
            ]
        if not m["survivors"]:
            body.append("None.")
        for s in m["survivors"]:
            why = s["equivalent"] or "**not explained: a test is missing**"
            body.append(f"- `{s['mutant']}`: `{s['line']}` — {why}")
    return _common.markdown_report(
        "Mutation testing of the algorithm modules",
        "`make mutation` (`python experiments/mutation_report.py`)",
        body,
        record,
    )


def _rows(json_path):
    """Module -> its row in ``json_path`` (from earlier runs), for the modules still in :data:`MODULES`."""
    previous = json.loads(json_path.read_text())["modules"] if json_path.exists() else []
    return {m["module"]: m for m in previous if m["module"] in MODULES}


def main(argv=None):
    args = parse_args(argv)
    wanted = args.modules or list(MODULES)
    json_path = args.out_dir / f"{NAME}.json"
    args.out_dir.mkdir(parents=True, exist_ok=True)
    for module in wanted:
        keep = (
            "survivors"
            if args.survivors or args.unexplained
            else "resume"
            if args.resume
            else "so-far"
            if args.so_far
            else None
        )
        before = _rows(json_path).get(module, {})
        seconds = (before.get("rerun", {}) if args.functions else before).get("seconds")
        row = run_module(
            module,
            args.work_dir,
            args.max_children,
            keep,
            seconds,
            functions=args.functions,
            unexplained=args.unexplained,
        )
        done = _rows(json_path)  # read again: another process may have run other modules meanwhile
        if args.functions:
            if module not in done:
                raise SystemExit(f"{NAME}: no full run of {module} in {json_path}: run it without --functions first")
            row = merged(done[module], row, args.functions)
        done[module] = row
        modules = [done[m] for m in MODULES if m in done]
        atomic_write_text(json_path, json.dumps({"modules": modules}, indent=1) + "\n")
        parameters = {
            "modules": [m["module"] for m in modules],
            "max_children": args.max_children,
            "pytest_args": PYTEST_ARGS,
        }
        record = write_provenance(provenance_path(json_path), parameters)
        atomic_write_text(args.out_dir / f"{NAME}.md", report(modules, record))
    return 0


if __name__ == "__main__":
    sys.exit(main())
