"""Hard cases that must stay numerically stable (issue 6).

Each case: the generated float64 function against its mpmath twin at 50 digits (an
independent evaluation path: mpmath arithmetic, no shared float code), with the
tolerance stated, and no NaN, no inf, no overflow/invalid/divide warning.  The
inputs are binary floats, passed unchanged to the twin, so both evaluate the same
number.  The scattering angle's hard cases (tiny angles, p within 1e-12 of an
integer, small d) are in tests/test_scattering.py; integrators started on the limit
axis in tests/test_scenes.py.
"""
import warnings

import mpmath
import numpy as np
import pytest

from generated.suslov_formulas import (
    BASIS_PS,
    INTEGRAL_PS,
    first_integral,
    first_integral_coefficients,
    first_integral_mp,
    gamma_basis,
    gamma_basis_mp,
    omega,
    omega_mp,
)

PMAX_BASIS = max(BASIS_PS)


def clean(fn, *args):
    """Call fn with every floating-point warning turned into an error; check the result is finite."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with np.errstate(over="raise", invalid="raise", divide="raise"):
            out = fn(*args)
    assert np.all(np.isfinite(np.asarray(out, dtype=float)))
    return out


def mp_basis(t, p, d):
    return np.array(gamma_basis_mp(t, p, d, 50).tolist(), dtype=float)


@pytest.mark.parametrize("t", [-1e4, -3e3, -750.0, 750.0, 3e3, 1e4])
@pytest.mark.parametrize("p,d", [(1, 0.5), (3, 1e-3), (7, 1e3)])
def test_omega_large_t(t, p, d):
    """|t| up to 1e4: omega1 relative 1e-15; omega2 = O(e^-|t|) underflows, absolute 1e-300."""
    w1, w2 = clean(omega, t, p, d)
    r1, r2 = omega_mp(t, p, d, 50)
    assert abs(float(w1) - float(r1)) <= 1e-15 * abs(float(r1))
    assert abs(float(w2) - float(r2)) <= 1e-300


@pytest.mark.parametrize("t", [-1e4, -2e3, -40.0, 40.0, 2e3, 1e4])
@pytest.mark.parametrize("p,d", [(1, 0.5), (3, 0.3), (5, 1e-3), (PMAX_BASIS, 1.7)])
def test_gamma_basis_large_t(t, p, d):
    """|t| up to 1e4 (phase (p/d) t up to 5e7): absolute 2e-13, thanks to the double-double phase."""
    got = clean(gamma_basis, t, p, d)
    assert np.max(np.abs(got - mp_basis(t, p, d))) <= 2e-13


@pytest.mark.parametrize("t", [0.0, 1e-300, -1e-300, 1e-8, -1e-8, 1e-3, -1e-3])
def test_largest_p_near_zero_and_removable_singularity(t):
    """Largest generated odd p at and near t = 0 (alternating sums; printed forms have 0/0 there): 1e-13."""
    for d in (0.05, 1.0, 20.0):
        got = clean(gamma_basis, t, PMAX_BASIS, d)
        assert np.max(np.abs(got - mp_basis(t, PMAX_BASIS, d))) <= 1e-13
        assert np.max(np.abs(got @ got.T - np.eye(3))) <= 1e-13


@pytest.mark.parametrize("d", [1e-3, 3e-3, 1e2, 1e3])
@pytest.mark.parametrize("p", [1, 3, 9])
def test_small_and_large_d(p, d):
    """d from 1e-3 (p/d = 9000: fast rotation) to 1e3: gamma_basis absolute 2e-13, omega relative 1e-15."""
    t = np.array([-25.0, -2.0, -0.1, 0.0, 0.3, 4.0, 25.0])
    got = clean(gamma_basis, t, p, d)
    for i, ti in enumerate(t):
        assert np.max(np.abs(got[i] - mp_basis(ti, p, d))) <= 2e-13
    w1, w2 = clean(omega, t, p, d)
    for i, ti in enumerate(t):
        r1, r2 = omega_mp(ti, p, d, 50)
        assert abs(w1[i] - float(r1)) <= 1e-15 * max(abs(float(r1)), abs(float(r2)))
        assert abs(w2[i] - float(r2)) <= 1e-15 * max(abs(float(r1)), abs(float(r2)))


def _scale(p, d, w1, w2):
    """Natural size of F3: sum of |coefficient| |w|^p |gamma| (gamma unit); exact coefficients."""
    coeffs = first_integral_coefficients(p, d)
    m = max(abs(w1), abs(w2))
    return sum(float(abs(c)) for P in coeffs.values() for c in P) * m**p


@pytest.mark.parametrize("p", [INTEGRAL_PS[0], 7, max(INTEGRAL_PS)])
@pytest.mark.parametrize("size", [1.0, 1e3, 1e8])
def test_first_integral_large_omega(p, size):
    """Large |omega| and large p: |F - F_ref| <= 1e-14 x scale, scale = sum |coeff| |omega|^p (rational d)."""
    d = 0.5
    rng = np.random.default_rng(p)
    for _ in range(5):
        w = rng.normal(size=2) * size
        g = rng.normal(size=3)
        g /= np.linalg.norm(g)
        got = clean(first_integral, p, d, w[0], w[1], *g)
        ref = first_integral_mp(p, d, w[0], w[1], *g, dps=50)
        assert abs(float(got) - float(ref)) <= 1e-14 * _scale(p, d, *w)


@pytest.mark.parametrize("t", [-1e4, -500.0, 0.0, 500.0, 1e4])
def test_first_integral_along_solution_large_t(t):
    """F3 on the certified solution at |t| up to 1e4 equals its value at t = 0 (relative 1e-12)."""
    p, d = 5, 0.5
    w1, w2 = omega(np.array([0.0, t]), p, d)
    B = gamma_basis(np.array([0.0, t]), p, d)
    for row in range(3):
        f = [clean(first_integral, p, d, w1[k], w2[k], *B[k, row]) for k in range(2)]
        assert abs(float(f[1]) - float(f[0])) <= 1e-12 * _scale(p, d, p / d * np.sqrt(d * d + 1), 0.0)
