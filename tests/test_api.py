"""The public API as a new user meets it: broadcasting, integral floats, mp twins, exports, frames.

Expected values come from independent routes: the mpmath twins (a second number context),
the closed forms typed here from the paper's notation, and integration-free identities
(orthonormality, the certified inverse map of eq:necc1).
"""
import warnings

import mpmath
import numpy as np
import pytest

import suslov
from generated import suslov_formulas as sf


def test_omega_broadcasts_over_p_and_d():
    t = np.array([[-1.0], [0.5]])
    d = np.array([0.5, 1.0, 2.0])
    w1, w2 = sf.omega(t, 3, d)
    assert w1.shape == (2, 3)
    for i in range(2):
        for j in range(3):
            e1, e2 = sf.omega_mp(float(t[i, 0]), 3, float(d[j]))
            assert abs(w1[i, j] - float(e1)) <= 1e-15 * 3 / d[j] * np.sqrt(d[j] ** 2 + 1)
    w1p, _ = sf.omega(0.3, np.array([1.0, -2.0]), 0.5)
    assert np.allclose(w1p, np.array([1.0, -2.0]) / 0.5 * np.tanh(0.3), rtol=1e-15)


def test_gamma_basis_broadcasts_over_d_and_accepts_integral_float_p():
    t = np.array([-0.7, 0.0, 1.3])
    d = np.array([0.5, 2.0, 0.5])
    B = sf.gamma_basis(t, 3.0, d)
    for i in range(3):
        ref = sf.gamma_basis(t[i], 3, d[i])
        assert np.allclose(B[i], ref, rtol=0, atol=1e-15)
        M = sf.gamma_basis_mp(float(t[i]), 3, float(d[i]), dps=30)
        assert max(abs(B[i][r][c] - float(M[r, c])) for r in range(3) for c in range(3)) < 1e-13


def test_first_integral_broadcasts_over_d():
    d = np.array([0.5, 1.5])
    w1, w2 = sf.omega(0.2, 5, d)
    F = sf.first_integral(5, d, w1, w2, 1.0, 0.0, 0.0)
    for j in range(2):
        exact = sf.first_integral_mp(5, float(d[j]), float(w1[j]), float(w2[j]), 1, 0, 0)
        assert F[j] == pytest.approx(float(exact), rel=1e-13)


def test_gamma_basis_beyond_the_double_double_phase_range_keeps_its_digits():
    """|p t/d| = 1e12 > 5.3e7: the phase is reduced in mpmath, no silent loss (was 3e-6)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        B = sf.gamma_basis(1e3, 1, 1e-9)
    M = sf.gamma_basis_mp(1e3, 1, 1e-9, dps=40)
    assert max(abs(B[r][c] - float(M[r, c])) for r in range(3) for c in range(3)) < 1e-13


@pytest.mark.parametrize("call, needle", [
    (lambda: sf.gamma_basis_mp([0.1, 0.2], 3, "0.5"), "t=[0.1, 0.2]"),
    (lambda: sf.omega_mp("soon", 1, 1), "t='soon'"),
    (lambda: sf.scattering_angle_mp(1, "-1"), "d='-1'"),
    (lambda: sf.first_integral_mp(3, "0", 1, 1, 1, 0, 0), "d='0'"),
    (lambda: sf.omega_general_mp(0, 1, 1, 0, 0), "I13=0 and I23=0"),
])
def test_mp_twins_name_the_field(call, needle):
    with pytest.raises(ValueError) as info:
        call()
    assert needle in str(info.value)


def test_mp_twins_have_documentation_like_the_float_versions():
    for name in ("omega_mp", "omega_general_mp", "first_integral_mp", "gamma_basis_mp", "scattering_angle_mp"):
        doc = getattr(sf, name).__doc__
        assert doc and ">>>" in doc or name == "omega_general_mp", name
        assert "dps" in doc, name


def test_suslov_reexports_the_whole_public_api():
    for name in sf.__all__:
        assert getattr(suslov, name) is getattr(sf, name)
    assert set(sf.__all__) <= set(dir(suslov))
    with pytest.raises(AttributeError):
        suslov.no_such_function  # noqa: B018


@pytest.mark.parametrize("I23", [0.45, -0.45])
def test_special_case_parameters_chain_into_the_closed_forms(I23):
    """Both signs of I23 give p > 0 and a frame in which omega(t, p, d) is the body's motion."""
    I = np.array([[2.0, 0.0, 0.0], [0.0, 1.0, I23], [0.0, I23, 1.5]])
    p, d, R = sf.special_case_parameters(I)
    M = I / np.linalg.det(I) ** (1 / 3)
    I11, I22 = M[0, 0], M[1, 1]
    # the inverse of eq:necc1's substitution, typed here: d^2 = I11/I22 - 1, p^2 = I22 (I11 - I22)/I23^2
    assert d == pytest.approx(np.sqrt(I11 / I22 - 1), rel=1e-12)
    assert p == pytest.approx(np.sqrt(I22 * (I11 - I22)) / abs(M[1, 2]), rel=1e-12)
    N = R.T @ M @ R
    assert N[1, 2] < 0 and abs(N[0, 2]) < 1e-12 and abs(N[0, 1]) < 1e-12
    ts = np.linspace(-2, 2, 5)
    w = np.array(sf.omega(ts, p, d))
    v = np.array(sf.omega_general(ts, N[0, 0], N[1, 1], N[0, 2], N[1, 2]))
    assert np.max(np.abs(w - v)) < 1e-12


def test_meromorphy_is_a_named_tuple():
    result = sf.meromorphy([[2.0, 0, 0], [0, 1.0, 0.5], [0, 0.5, 1.5]])
    case, p2, p, odd = result
    assert (case, result.case) == ("I13=0", "I13=0")
    assert p2 == pytest.approx(4.0) and p == pytest.approx(2.0) and odd is False


def test_omega_mp_accepts_exact_decimals():
    with mpmath.workdps(40):
        expected = 6 * mpmath.tanh(mpmath.mpf(1) / 10)
    assert abs(sf.omega_mp("0.1", 3, "0.5", dps=40)[0] - expected) < mpmath.mpf(10) ** -38
