"""The mp twin of the basis keeps its digits whatever the phase p t/d (issue 38).

``gamma_basis_mp('1', 1, 1e-27, dps=15)`` gave entry [1, 1] = -0.7013 where 65 digits give -0.5869: the
phase p t/d ~ 1e27 was formed with dps + 10 digits.  Here |p t/d| runs up to 10^(dps+20).  References:
(1) the same entry asked with dps + k + 40 digits, where even the old code's working precision exceeds
the phase's size, compared at dps digits; (2) the float ``gamma_basis`` for float input, whose phase is
reduced by a different route (``careful_phase``: python-flint balls of the exact phase) -- agreement to
1e-12 shows the two phase routes and the series agree.
"""
import math

import mpmath
import numpy as np
import pytest

import suslov as sf


def close(a, b, digits):
    return all(abs(a[i, j] - b[i, j]) <= mpmath.mpf(10) ** (1 - digits) for i in range(3) for j in range(3))


@pytest.mark.parametrize("dps", [15, 30])
@pytest.mark.parametrize("k", [0, 10, 25, "dps+10", "dps+20"])
@pytest.mark.parametrize("p, t", [(1, "1"), (3, "-0.75")])
def test_digits_kept_at_large_phase(dps, k, p, t):
    k = dps + int(k[4:]) if isinstance(k, str) else k
    d = f"1e-{k}"
    got = sf.gamma_basis_mp(t, p, d, dps=dps)
    reference = sf.gamma_basis_mp(t, p, d, dps=dps + k + 40)
    with mpmath.workdps(dps + k + 40):
        assert close(got, reference, dps)


@pytest.mark.parametrize("d", [1e-27, 1e-35, 3.7e-30])
def test_the_audit_case_and_the_float_route(d):
    got = sf.gamma_basis_mp("1", 1, d, dps=15)
    assert abs(got[1, 1] - mpmath.mpf("-0.586927651873997")) < 1e-14 or d != 1e-27   # the audit's 65-digit value
    floats = sf.gamma_basis(1.0, 1, d)
    assert np.allclose(np.array(got.tolist(), dtype=float), floats, atol=1e-12, rtol=0)


def test_decimal_strings_are_not_rounded_to_dps_before_the_phase():
    """d = '1.000000000000000000001e-20' differs from 1e-20 in the 22nd digit; the phase 1e20 turns that
    into a change of 0.1 rad, which dps = 15 must show (the string is read with the digits the phase needs)."""
    a = sf.gamma_basis_mp("1", 1, "1e-20", dps=15)
    b = sf.gamma_basis_mp("1", 1, "1.000000000000000000001e-20", dps=15)
    with mpmath.workdps(60):
        phase_a, phase_b = mpmath.mpf(10) ** 20, 1 / mpmath.mpf("1.000000000000000000001e-20")
        assert abs(phase_a - phase_b - mpmath.mpf("0.1")) < 1e-3
    assert abs(a[1, 1] - b[1, 1]) > 1e-3


def test_a_phase_beyond_the_precision_limit_is_refused_with_the_digits_it_needs():
    with pytest.raises(ValueError, match=r"needs \d+ working digits for dps=9990"):
        sf.gamma_basis_mp("1", 1, "1e-100", dps=9990)
    assert math.isfinite(float(sf.gamma_basis_mp("1", 1, "1e-100", dps=15)[0, 0]))
