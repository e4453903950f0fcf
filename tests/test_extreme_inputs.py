"""Finite input gives finite, right output at the ends of float64 (issue 38 items).

Expected values from mpmath at 40 digits, not from the code under test.
"""
import mpmath
import numpy as np
import pytest

import suslov as sf


@pytest.mark.parametrize("d", [1e-3, 1e150, 1e300])
def test_omega_at_extreme_d(d):
    w1, w2 = sf.omega(1.0, 3, d)
    with mpmath.workdps(40):
        e1 = 3 / mpmath.mpf(d) * mpmath.tanh(1)
        e2 = -3 / mpmath.mpf(d) * mpmath.sqrt(mpmath.mpf(d) ** 2 + 1) * mpmath.sech(1)
    assert np.isfinite(w1) and np.isfinite(w2)
    assert abs(float(w1) - float(e1)) <= 1e-15 * abs(float(e1))
    assert abs(float(w2) - float(e2)) <= 1e-15 * abs(float(e2))


@pytest.mark.parametrize("scale", [1e-300, 1e-150, 1e150, 1e200, 1e300])
def test_omega_general_is_scale_invariant(scale):
    """u, v are homogeneous of degree 0 in the entries (eq:o12): a scaled tensor has the same omega."""
    entries = (2.0, 1.0, 0.3, -0.5)
    with mpmath.workdps(40):
        I11, I22, I13, I23 = (mpmath.mpf(x) for x in entries)
        D, r, t = I11 * I23**2 + I13**2 * I22, mpmath.sqrt(I11 * I22), mpmath.mpf("0.5")
        e1 = (-I11 * I22 * I23 * mpmath.tanh(t) + I13 * I22 * r * mpmath.sech(t)) / D
        e2 = (I11 * I13 * I22 * mpmath.tanh(t) + I11 * I23 * r * mpmath.sech(t)) / D
    w1, w2 = sf.omega_general(0.5, *(x * scale for x in entries))
    assert abs(float(w1) - float(e1)) <= 1e-14 and abs(float(w2) - float(e2)) <= 1e-14
