"""The outline of a triangle mesh (``surface/mesh_outline.py``): the corners of a boundary loop."""

import numpy as np
import pytest
from conftest import exercised
from hypothesis import given, settings
from hypothesis import strategies as st

from equimesh._geometry import inner_angle
from equimesh.surface.mesh_outline import CORNER_TURN, FIRM_TURN, loop_corners


@pytest.mark.exercised("the loop's corners are found", share=0.5)
@settings(max_examples=20, deadline=None)
@given(
    turns=st.lists(st.floats(0.0, 80.0), min_size=6, max_size=12),
    side=st.floats(0.3, 3.0),
)
def test_loop_corners(turns, side):
    """Corners turn by at least CORNER_TURN and are at least l apart around the loop, at least one; or two firm corners
    are too close."""
    # An open polyline from turning angles; the loop closes it with one more segment (the function reads only xy).
    heading = np.cumsum(np.radians(turns))
    xy = np.cumsum(side * np.column_stack([np.cos(heading), np.sin(heading)]), axis=0)
    turn = [abs(180 - inner_angle(xy, i)) for i in range(len(xy))]
    try:
        corners = loop_corners(xy, 1.0, lambda i, j: ValueError(i, j))
    except ValueError as exc:
        exercised("the loop's corners are found", False)
        i, j = exc.args
        assert min(turn[i], turn[j]) >= FIRM_TURN and np.linalg.norm(xy[i] - xy[j]) < 1.0
        return
    exercised("the loop's corners are found", True)
    assert len(corners) >= 1 and np.all(np.diff(corners) > 0)
    if len(corners) > 1:
        assert all(turn[c] >= CORNER_TURN for c in corners)
        gaps = np.linalg.norm(xy[np.roll(corners, -1)] - xy[corners], axis=1)
        assert gaps.min() >= 1.0
