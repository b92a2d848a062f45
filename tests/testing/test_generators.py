"""The input generators of ``equimesh.testing.generators``: valid inputs by construction."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from strategies import seeds

from equimesh.planar.increment import validate_problem1
from equimesh.testing.generators import random_convex_polygon


@given(
    seeds,
    st.integers(4, 16),
    st.floats(1.0, 1000.0),
    st.floats(1.0, 100.0),
    st.sampled_from([0.0, 0.5, 0.99]),
)
def test_generator_builds_valid_problem1_polygons(seed, k, area, elongation, min_turn):
    """``random_convex_polygon`` gives a valid input by construction, of at least the target area."""
    rng = np.random.default_rng(seed)
    v = random_convex_polygon(rng, n_vertices=k, area=area, elongation=elongation, min_turn=min_turn)
    poly, _ = validate_problem1(v, 1.0)
    assert len(poly.vertices) == k
    assert poly.area >= area * (1.0 - 1e-12)
    capped = random_convex_polygon(
        np.random.default_rng(seed), n_vertices=k, area=area, elongation=elongation, max_area=60.0
    )
    assert validate_problem1(capped, 1.0)[0].area <= 60.0 * (1.0 + 1e-12)
