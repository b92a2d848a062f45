"""Checks every chart must pass (Section 4 reads only evaluate and its derivatives)."""

import numpy as np


def central(f, u, v, h=1e-6):
    """Central differences of ``f(u, v)`` (an array or a tuple of arrays) in u and in v, as two lists."""

    def parts(x):
        return list(x) if isinstance(x, tuple) else [x]

    du = [(p - q) / (2 * h) for p, q in zip(parts(f(u + h, v)), parts(f(u - h, v)))]
    dv = [(p - q) / (2 * h) for p, q in zip(parts(f(u, v + h)), parts(f(u, v - h)))]
    return du, dv


def assert_derivatives_consistent(chart, u, v, atol):
    """First derivatives against differences of ``evaluate``; second ones (if any) against differences of the first."""
    su, sv = chart.derivatives(u, v)
    (fu,), (fv,) = central(chart.evaluate, u, v)
    np.testing.assert_allclose(su, fu, rtol=0, atol=atol)
    np.testing.assert_allclose(sv, fv, rtol=0, atol=atol)
    if hasattr(chart, "second_derivatives"):
        suu, suv, svv = chart.second_derivatives(u, v)
        (fuu, fuv), (fvu, fvv) = central(chart.derivatives, u, v)
        for got, want in ((suu, fuu), (suv, fuv), (suv, fvu), (svv, fvv)):
            np.testing.assert_allclose(got, want, rtol=0, atol=10 * atol)
