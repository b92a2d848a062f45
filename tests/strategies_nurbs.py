"""NURBS surfaces for the tests: random rational patches (a hypothesis strategy) and an exact rational cylinder."""

import numpy as np
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from equimesh import NurbsSurface


@st.composite
def nurbs(draw):
    """A NURBS surface of degrees 1..4 with distinct or repeated interior knots (at most p times), clamped or not."""
    parts = []
    for _ in range(2):
        p = draw(st.integers(1, 4))
        n = draw(st.integers(p + 1, p + 4))
        inner = sorted(draw(st.lists(st.integers(1, 9), min_size=n - p - 1, max_size=n - p - 1)))
        if any(inner.count(k) > p for k in inner):
            inner = sorted(set(inner)) + [10 + k for k in range(n - p - 1 - len(set(inner)))]
        clamped = draw(st.booleans())
        ends = ([0] * (p + 1), [20] * (p + 1)) if clamped else (list(range(-p, 1)), list(range(20, 21 + p)))
        parts.append((p, n, np.array(ends[0] + inner + ends[1], dtype=float) / 20.0))
    (p, nu, ku), (q, nv, kv) = parts
    net = draw(arrays(float, (nu, nv, 3), elements=st.floats(-10, 10)))
    weights = draw(arrays(float, (nu, nv), elements=st.floats(0.2, 5.0)))
    return NurbsSurface((p, q), ku, kv, net, weights)


def cylinder(radius=10.0, height=20.0):
    """Half a circular cylinder of the given radius: two rational quadratic quarter circles times a line."""
    r, w = radius, np.sqrt(0.5)
    arc = np.array([[r, 0], [r, r], [0, r], [-r, r], [-r, 0]], dtype=float)
    net = np.zeros((5, 2, 3))
    net[..., 0], net[..., 2] = arc[:, :1], arc[:, 1:]
    net[:, 1, 1] = height
    weights = np.repeat(np.array([1, w, 1, w, 1])[:, None], 2, axis=1)
    return NurbsSurface((2, 1), [0, 0, 0, 0.5, 0.5, 1, 1, 1], [0, 0, 1, 1], net, weights)
