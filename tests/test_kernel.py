"""The run-time kernel (suslov.kernel), unit by unit, against independent references.

References: mpmath at 40 digits (tanh, sech, cos, sin of the phase, trigonometric sums),
direct expansion of cos^m(th/2) sin^n(th/2) (Fourier matrices), plain power sums (Horner),
and polynomial identities (sparse arithmetic).
"""
import doctest
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from suslov.kernel import (
    contexts,
    fourier,
    frames,
    horner,
    phase,
    sparse,
    trig_series,
    validate,
)


@pytest.fixture(autouse=True)
def forty_digits():
    with mpmath.workdps(40):
        yield


@pytest.mark.parametrize("module", [contexts, fourier, frames, horner, phase, sparse, trig_series, validate])
def test_doctests(module):
    assert doctest.testmod(module).failed == 0


def test_tanh_sech_full_relative_accuracy():
    ts = np.array([0.0, 1e-300, -1e-8, 1e-3, 0.5, -3.0, 25.0, -40.0, 300.0, 700.0, -745.0, 800.0])
    T, S = contexts.FLOAT.tanh_sech(ts)
    for t, tv, sv in zip(ts, T, S):
        rt, rs = mpmath.tanh(t), mpmath.sech(t)
        assert abs(tv - rt) <= 2.3e-16 * abs(rt)
        assert abs(sv - rs) <= 2.3e-16 * rs or (rs < 1e-300 and abs(sv) < 1e-300)


def test_phase_cos_sin_against_mpmath_for_large_phases():
    rng = np.random.default_rng(5)
    t = rng.uniform(-1e4, 1e4, 50)
    for p, d in ((15, 0.37), (1, 1e-3), (51, 2.0)):
        c, s = phase.phase_cos_sin(p, d, t)
        for tv, cv, sv in zip(t, c, s):
            angle = mpmath.mpf(p) / mpmath.mpf(d) * mpmath.mpf(tv)
            assert abs(cv - mpmath.cos(angle)) < 5e-16 and abs(sv - mpmath.sin(angle)) < 5e-16


def test_half_pi_parts_near_odd_integers():
    for p in (1 + 1e-13, 3 - 1e-13, 2.6, 2.4, -0.7):
        s, c = phase.half_pi_parts(p)
        assert abs(c - abs(mpmath.cospi(mpmath.mpf(p) / 2))) <= 1e-15 * abs(mpmath.cospi(mpmath.mpf(p) / 2)) + 1e-300
        assert abs(s - abs(mpmath.sinpi(mpmath.mpf(p) / 2))) <= 2e-16


@pytest.mark.parametrize("p", [1, 2, 5, 8])
def test_fourier_matrices_reproduce_the_rational_functions(p):
    C, S = fourier.fourier_matrices(p)
    for th in (mpmath.mpf("0.3"), mpmath.mpf("1.7"), mpmath.mpf("2.9")):
        x = mpmath.cot(th / 2)
        for m in range(2 * p + 1):
            series = sum(C[m][k] * mpmath.cos(k * th) + S[m][k] * mpmath.sin(k * th) for k in range(p + 1)) / 4**p
            assert abs(series - x**m / (1 + x * x) ** p) < mpmath.mpf(10) ** -30


def test_trig_series_matches_direct_sums():
    rng = np.random.default_rng(2)
    p = 7
    coefficients = rng.normal(size=(2 * (p + 1), 4))
    t = rng.uniform(-30, 30, 1000)
    T, S = contexts.FLOAT.tanh_sech(t)
    values = trig_series.evaluate(T, S, coefficients, block=128)
    for i in (0, 17, 999):
        th = 2 * mpmath.atan(mpmath.exp(-t[i]))
        for j in range(4):
            exact = sum(coefficients[k, j] * mpmath.cos(k * th) + coefficients[p + 1 + k, j] * mpmath.sin(k * th)
                        for k in range(p + 1))
            assert abs(values[j, i] - exact) < 1e-14 * np.abs(coefficients).sum()


def test_horner_combination_against_plain_power_sums():
    rng = np.random.default_rng(3)
    n = 9
    A = rng.normal(size=(3, n + 1))
    w = rng.normal(size=(2, 200)) * 3
    g = rng.normal(size=(3, 200))
    s = np.maximum(np.abs(w[0]), np.abs(w[1]))
    got = horner.combination(A, w[0], w[1], g, block=64) * s**n
    k = np.arange(n + 1)
    plain = sum(g[i] * (A[i][:, None] * w[0] ** (n - k)[:, None] * w[1] ** k[:, None]).sum(axis=0) for i in range(3))
    assert np.allclose(got, plain, rtol=1e-12, atol=1e-12 * np.abs(plain).max())
    assert horner.combination(A, np.zeros(1), np.zeros(1), g[:, :1])[0] == 0.0


def test_sparse_polynomial_identities():
    x, y = sparse.Sparse.gens(2)
    assert ((x + y) * (x - y)) == x**2 - y**2
    u, = sparse.Sparse.gens(1)
    q, exact = ((u**2 - 1) * (u + Fraction(1, 3))).divide_exact(u**2 - 1)
    assert exact and q == u + Fraction(1, 3)
    _, exact = (u**3 + 1).divide_exact(u**2 - 1)
    assert not exact
    assert (u**2 + u).square_variable(0) == u**4 + u**2


@pytest.mark.parametrize("call, needle", [
    (lambda: validate.real_array("t", [0.0, np.nan]), "t[1]=nan: must be finite"),
    (lambda: validate.real_array("d", 0.0, positive=True), "d=0.0: must be > 0"),
    (lambda: validate.real_array("p", True), "p=True"),
    (lambda: validate.mp_real("d", "abc"), "d='abc'"),
    (lambda: validate.rational("d", "x/2"), "d='x/2'"),
    (lambda: validate.odd_p(4, (1, 3), "why"), "p=4: must be an odd positive integer (why)"),
    (lambda: validate.odd_p(5, (1, 3), "why"), "outside the certified range"),
])
def test_validation_messages_name_field_value_and_reason(call, needle):
    with pytest.raises(ValueError) as info:
        call()
    assert needle in str(info.value)


def test_rational_of_floats_and_mpf_is_exact():
    assert validate.rational("d", 0.1) == Fraction(0.1)
    assert validate.rational("d", mpmath.mpf("0.5")) == Fraction(1, 2)
    assert validate.odd_p(3.0, (1, 3), "") == 3
