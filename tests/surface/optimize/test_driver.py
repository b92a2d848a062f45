"""The optimisation's driver (``surface/optimize/driver.py``): a surface that is not finite at a trial point is
refused."""

import numpy as np
import pytest
from surface_cases import Wrapped, plane_patch

import equimesh
from equimesh.errors import InvalidSurfaceError


def test_nan_during_the_optimisation_is_refused():
    surface = plane_patch()
    holed = Wrapped(surface, lambda u, v: (u > 0.4) & (u < 0.6))
    uv = np.array([[0.0, 0.0], [1.0, 0.0], [0.5, 0.5]])
    with pytest.raises(InvalidSurfaceError, match="not finite"):
        equimesh.optimize_uv(holed, uv, [[0, 1], [1, 2], [0, 2]], [1, 1, 1], 3.0, fixed=[0, 1])
