"""The variables of a final optimisation (``surface/optimize/problem.py``): which parameters move, and how far.

What must hold: the variable vector is the free nodes' (u, v), then the sliding nodes' arc positions, then the
offsets along the normal, and maps back to every node's (u, v), offset and point; the tangents are the points'
derivatives (with the normal's own derivative off the surface); the chain rule keeps a Jacobian's structure; the
bounds are the parameter domain, the slides' ranges and the tolerance; the trust region scales down only the nodes
that would move too far.  On the tiny grids of ``optimize_cases``.
"""

from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse
from optimize_cases import RIM, finite_difference, moved, patch, problem

from equimesh.errors import EquimeshError
from equimesh.surface.charts.chart import Domain
from equimesh.surface.optimize.joints import Joints, surface_angles
from equimesh.surface.optimize.problem import free_nodes, offset_points, parameter_box, unit_normals
from equimesh.surface.optimize.slide import Slide, along_polygon

SLIDING = [1, 2, 4, 5, 7, 8, 10, 11]  # the rim's nodes between the square's corners


def test_the_variables_of_free_nodes_and_sliding_ones():
    p, _ = problem(slides=True)
    (slide,) = p.slides
    assert list(slide.nodes) == SLIDING
    assert list(np.flatnonzero(p.variables)) == list(range(2 * RIM, 2 * RIM + 8))
    moving = np.zeros(32, dtype=bool)
    moving[2 * RIM :] = True
    moving[2 * np.array(SLIDING)] = moving[2 * np.array(SLIDING) + 1] = True
    np.testing.assert_array_equal(p.moving, moving)
    assert len(p.offset_nodes) == 0 and not np.any(p.offsets_of(p.x0))
    np.testing.assert_array_equal(p.sliding_variables, np.repeat([False, True], 8))
    np.testing.assert_array_equal(p.x0, np.concatenate([p.uv[RIM:].ravel(), slide.s]))
    np.testing.assert_allclose(p.uv_of(p.x0), p.uv, rtol=0, atol=1e-15)
    np.testing.assert_array_equal(p.uv_of(p.x0)[RIM:], p.uv[RIM:])


def test_the_variables_with_a_surface_tolerance():
    """Every node that moves has an offset, after the free parameters and the arc positions."""
    p, _ = problem(slides=True, surface_tolerance=0.5)
    np.testing.assert_array_equal(p.offset_nodes, [*SLIDING, 12, 13, 14, 15])
    assert p.offset_nodes.dtype == np.int64
    np.testing.assert_array_equal(p.sliding_variables, np.repeat([False, True, False], [8, 8, 12]))
    assert len(p.x0) == 28 and not np.any(p.x0[16:])
    x = moved(p, 1, offset=0.4)
    offsets = np.zeros(16)
    offsets[p.offset_nodes] = x[16:]
    np.testing.assert_array_equal(p.offsets_of(x), offsets)
    fixed_only, _ = problem(surface_tolerance=0.5)
    np.testing.assert_array_equal(fixed_only.offset_nodes, [12, 13, 14, 15])


def test_uv_of_takes_each_node_from_its_variables():
    p, _ = problem(slides=True)
    (slide,) = p.slides
    x = p.x0.copy()
    x[:8] = np.linspace(0.3, 0.7, 8)
    x[8:] = slide.s + 0.01
    uv = p.uv_of(x)
    np.testing.assert_array_equal(uv[RIM:].ravel(), x[:8])
    np.testing.assert_array_equal(uv[SLIDING], slide.uv(slide.s + 0.01))
    np.testing.assert_array_equal(uv[[0, 3, 6, 9]], p.uv[[0, 3, 6, 9]])
    assert not np.array_equal(p.uv_of(p.x0)[SLIDING], uv[SLIDING])


def test_points_off_the_flat_patch_are_their_offsets_above_it():
    """On the plane z = 0, parametrised along x and y, the unit normal is +z: a node's offset is its height."""
    p, _ = problem(rise=0.0, surface_tolerance=0.5)
    x = moved(p, 2, offset=0.4)
    points = p.points_of(x)
    np.testing.assert_allclose(points[:, 2], p.offsets_of(x), atol=1e-15)
    np.testing.assert_allclose(points[:, :2], 30.0 * p.uv_of(x), rtol=1e-14)
    normal, size = unit_normals(patch(rise=0.0), p.uv)
    np.testing.assert_allclose(normal, np.tile([0.0, 0.0, 1.0], (16, 1)), atol=1e-15)
    np.testing.assert_allclose(size, 900.0, rtol=1e-14)
    uv = p.uv_of(x)
    np.testing.assert_array_equal(offset_points(p.surface, uv), p.surface.evaluate(*uv.T))


def test_tangents_are_the_derivatives_of_the_points():
    """``d p / du`` and ``d p / dv`` of the free nodes at their variables, on the surface and off it (where the
    normal turns with (u, v))."""
    for tolerance, offset in ((0.0, 0.0), (0.8, 0.7)):
        p, _ = problem(seed=3, surface_tolerance=tolerance)
        x = moved(p, 4, offset=offset)
        su, sv = p.tangents(x)
        derivative = finite_difference(lambda y: p.points_of(y)[RIM:], x).reshape(4, 3, -1)
        for k in range(4):
            np.testing.assert_allclose(derivative[k, :, 2 * k], su[RIM + k], rtol=1e-6, atol=1e-6)
            np.testing.assert_allclose(derivative[k, :, 2 * k + 1], sv[RIM + k], rtol=1e-6, atol=1e-6)


def test_tangents_of_a_chart_without_second_derivatives_are_its_first():
    """A piecewise linear chart (a triangle mesh's) has no second derivatives: off the surface too, the tangents
    are the chart's first derivatives."""

    class Plain:
        def __init__(self, chart):
            self.evaluate, self.derivatives = chart.evaluate, chart.derivatives

    p, _ = problem(seed=3, surface_tolerance=0.8)
    p = replace(p, surface=Plain(p.surface))
    x = moved(p, 4, offset=0.7)
    su, sv = p.tangents(x)
    first = p.surface.derivatives(*p.uv_of(x).T)
    np.testing.assert_array_equal(su, first[0])
    np.testing.assert_array_equal(sv, first[1])


def test_the_chain_rule_keeps_the_structure():
    """A Jacobian over the moving (u, v) entries times ``d uv / d x``, with every entry kept: a sliding node on
    a side of the square moves along u or v only, so one of its two entries is scaled by zero."""
    for tolerance in (0.0, 0.5):
        p, _ = problem(slides=True, surface_tolerance=tolerance)
        x = moved(p, 5, size=0.002)
        rng = np.random.default_rng(6)
        dense = rng.standard_normal((5, int(p.moving.sum())))
        dense[rng.uniform(size=dense.shape) < 0.5] = 0.0
        jac = scipy.sparse.csr_matrix(dense)
        chained = p.chain(jac, x)
        assert chained.shape == (5, len(x)) and chained.nnz == jac.nnz
        duv = finite_difference(lambda y: p.uv_of(y).ravel()[p.moving], x)
        np.testing.assert_allclose(chained.toarray(), dense @ duv, atol=1e-7)
        if not tolerance:
            plain, _ = problem()
            assert plain.chain(jac, plain.x0) is jac


def test_the_chain_rule_scales_the_first_sliding_node_by_its_direction():
    """The rim slides from the top side's first node on, which moves along -u: its u entry is scaled by -1 and its v
    entry by 0, as the derivative of its (u, v) says."""
    p, _ = problem()
    rim = np.roll(np.arange(RIM), -6)  # from the corner (1, 1): node 7 moves towards (0, 1)
    square = np.array([[1.0, 1.0], [0.0, 1.0], [0.0, 0.0], [1.0, 0.0]])
    slide, _ = along_polygon(rim, square, p.uv[rim])
    p = replace(p, slides=(slide,))
    assert slide.nodes[0] == 7
    x = moved(p, 5, size=0.002)
    dense = np.random.default_rng(6).standard_normal((5, int(p.moving.sum())))
    duv = finite_difference(lambda y: p.uv_of(y).ravel()[p.moving], x)
    np.testing.assert_allclose(p.chain(scipy.sparse.csr_matrix(dense), x).toarray(), dense @ duv, atol=1e-7)


def test_what_at_keeps_is_read_only():
    """The (u, v), points and tangents kept for an ``x`` are shared by every caller at that ``x``: none can be
    written to, an array or each array of a tuple."""
    p, _ = problem(slides=True)
    x = moved(p, 2, size=0.002)
    kept = [p.uv_of(x), p.points_of(x), *p.tangents(x)]
    assert not any(array.flags.writeable for array in kept)
    with pytest.raises(ValueError, match="read-only"):
        p.points_of(x)[0, 0] = 0.0


def test_offset_columns_are_the_gradients_along_the_normal():
    """On the flat patch the normal is +z: the offsets' columns hold the z-derivatives of the residuals."""
    p, _ = problem(rise=0.0, slides=True, surface_tolerance=0.5)
    x = moved(p, 7, offset=0.3)
    elements = np.array([[0, 12], [13, 1], [14, 15]])
    grads = np.random.default_rng(8).standard_normal((3, 2, 3))
    columns = p.offset_columns(elements, grads, x).toarray()
    expected = np.zeros((3, len(x)))
    column = {node: 16 + k for k, node in enumerate(p.offset_nodes)}
    for j, (a, b) in enumerate(elements):
        for c, node in enumerate((a, b)):
            if node in column:
                expected[j, column[node]] += grads[j, c, 2]
    np.testing.assert_allclose(columns, expected, atol=1e-15)


def test_the_trust_region_scales_down_only_the_nodes_moving_too_far():
    """On the flat patch |X_u| = |X_v| = 30: a node whose step moves it 3 is scaled to the radius 1.5 (its
    direction kept), one moving 0.9 is not; a sliding node's step counts 30 per unit of arc, an offset 1."""
    p, _ = problem(rise=0.0, slides=True, surface_tolerance=0.5)
    limit = p.step_limit(1.5)
    direction = np.zeros(len(p.x0))
    direction[0:2] = [0.06, 0.08]  # node 12: moves 30 * 0.1 = 3
    direction[2:4] = [0.03, 0.0]  # node 13: 0.9
    direction[8] = 0.1  # node 1 along its side: 3
    direction[16] = 2.0  # node 1's offset: with its slide, sqrt(9 + 4)
    direction[20] = 1.0  # node 7's offset
    expected = direction.copy()
    expected[0:2] *= 0.5
    expected[[8, 16]] *= 1.5 / np.sqrt(13.0)
    expected[20] *= 1.0
    np.testing.assert_allclose(limit(direction), expected, rtol=1e-14)


def test_the_bounds_are_the_domain_the_slides_and_the_tolerance():
    p, _ = problem(slides=True, surface_tolerance=0.25)
    (slide,) = p.slides
    lower, upper = p.bounds
    np.testing.assert_array_equal(lower, np.concatenate([np.zeros(8), slide.lower, np.full(12, -0.25)]))
    np.testing.assert_array_equal(upper, np.concatenate([np.ones(8), slide.upper, np.full(12, 0.25)]))
    box = parameter_box(p.surface)
    np.testing.assert_array_equal(box[0], [0.0, 0.0])
    np.testing.assert_array_equal(box[1], [1.0, 1.0])

    class Wide:
        domain = Domain(u=(0.0, 2.0), v=(-1.0, 1.0))

    lower, upper = parameter_box(Wide())
    np.testing.assert_array_equal(lower, [0.0, -1.0])
    np.testing.assert_array_equal(upper, [2.0, 1.0])
    wide = replace(p, surface=Wide())
    np.testing.assert_array_equal(wide.bounds[0][:8], np.tile([0.0, -1.0], 4))
    np.testing.assert_array_equal(wide.bounds[1][:8], np.tile([2.0, 1.0], 4))


def test_two_slides_are_one_slide_split():
    """The rim's sliding nodes as two slides along the same square: the same variables in the same order, the
    same (u, v), points, bounds, trust region and chain rule."""
    for tolerance in (0.0, 0.5):
        one, _ = problem(slides=True, surface_tolerance=tolerance)
        (slide,) = one.slides
        halves = [
            Slide(slide.nodes[part], slide.loop, slide.s[part], slide.lower[part], slide.upper[part])
            for part in (slice(0, 3), slice(3, None))
        ]
        two = replace(one, slides=tuple(halves))
        x = moved(one, 3, size=0.01, offset=0.3)
        for name in ("moving", "offset_nodes", "sliding_variables", "x0"):
            np.testing.assert_array_equal(getattr(two, name), getattr(one, name))
        np.testing.assert_array_equal(two.uv_of(x), one.uv_of(x))
        np.testing.assert_array_equal(two.points_of(x), one.points_of(x))
        for a, b in zip(two.bounds, one.bounds):
            np.testing.assert_array_equal(a, b)
        direction = np.random.default_rng(4).standard_normal(len(x))
        np.testing.assert_array_equal(two.step_limit(0.5)(direction), one.step_limit(0.5)(direction))
        jac = scipy.sparse.csr_matrix(np.random.default_rng(5).standard_normal((3, int(one.moving.sum()))))
        np.testing.assert_array_equal(two.chain(jac, x).toarray(), one.chain(jac, x).toarray())


def test_free_nodes_are_those_neither_fixed_nor_sliding():
    p, _ = problem(slides=True)
    expected = np.zeros(16, dtype=bool)
    expected[[3, 12, 13, 14, 15]] = True
    fixed = [0, 6, 9]
    free = free_nodes(16, fixed, p.slides)
    assert free.dtype == bool
    np.testing.assert_array_equal(free, expected)
    mask = np.zeros(16, dtype=bool)
    mask[fixed] = True
    np.testing.assert_array_equal(free_nodes(16, mask, p.slides), expected)
    np.testing.assert_array_equal(free_nodes(4, np.array([1, 2]), ()), [True, False, False, True])
    np.testing.assert_array_equal(free_nodes(4, [], ()), [True] * 4)
    for fixed, message in (
        (np.ones(3, dtype=bool), r"^fixed as a mask must have one entry per node \(4\), got shape \(3,\)$"),
        ([0, 4], r"^entry 1 of fixed refers to a node outside 0 \.\. 3: \[4\]$"),
        ([0.5], r"^fixed must be an \(M, 1\) array of node indices, got shape \(1, 1\) of float64$"),
    ):
        with pytest.raises(EquimeshError, match=message):
            free_nodes(4, fixed, ())


def test_with_joints_the_members_and_the_angles_share_one_evaluation_per_x():
    """The joints of :meth:`UVProblem.with_joints` work on the problem they belong to: at one ``x`` the points the
    members see and those the angles see are one evaluation of the surface (the angles too are computed once)."""
    p, triangles = problem(seed=1)
    calls = []

    class Counted:
        def __getattr__(self, name):
            return getattr(p.surface, name)

        def evaluate(self, u, v):
            calls.append(len(u))
            return p.surface.evaluate(u, v)

    q = replace(p, surface=Counted()).with_joints(triangles, np.zeros(triangles.shape))
    assert q.joints.problem is q and q.joints is not None
    x = moved(q, 3)
    q.points_of(x)
    first = q.joints.angles(x)
    assert q.joints.angles(x) is first and q.sound(x)
    assert len(calls) == 1
    np.testing.assert_array_equal(first, surface_angles(q.points_of(x), triangles))


def test_sound_asks_the_joints():
    p, triangles = problem(seed=1)
    angles = surface_angles(p.points_of(p.x0), triangles)
    assert p.sound(p.x0)
    assert replace(p, joints=Joints(p, triangles, angles)).sound(p.x0)
    assert not replace(p, joints=Joints(p, triangles, angles + 1e-9)).sound(p.x0)
