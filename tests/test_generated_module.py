"""The generated module: values, stability, vectorisation, errors, invariants.

References are independent of the code under test: the mpmath twin at 50
digits (a second evaluation context), SciPy's DOP853 integrating the paper's
eq:sysfin / the unreduced constrained Euler equations, and the paper's own
energy value F1 = a^2 c^2.
"""
import subprocess
import sys
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from generated import suslov_formulas as sf


def rel_err(approx, exact):
    return abs(float(approx) - float(exact)) / max(abs(float(exact)), 1e-300)


@pytest.mark.parametrize("p, d", [(1, 0.5), (3, 0.5), (15, 2.0), (-4, 1.0), (2.5, 1e-3), (7, 1e3)])
def test_omega_matches_mpmath_twin_at_50_digits(p, d):
    ts = [-1e4, -700.0, -20.0, -1.0, -1e-8, 0.0, 0.3, 5.0, 711.0, 1e4]
    w1, w2 = sf.omega(np.array(ts), p, d)
    scale = abs(p) / d * np.sqrt(d * d + 1)
    for i, t in enumerate(ts):
        e1, e2 = sf.omega_mp(t, p, d, dps=50)
        # tolerance: a few ulps of the overall scale of omega (cancellation-free formulas)
        assert abs(w1[i] - float(e1)) <= 4e-16 * scale
        assert abs(w2[i] - float(e2)) <= 4e-16 * scale


def test_no_overflow_or_warning_for_huge_times():
    t = np.concatenate([np.linspace(-1e4, 1e4, 2001), [-1e300, 1e300]])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        w1, w2 = sf.omega(t, 3, 0.01)
    assert np.all(np.isfinite(w1)) and np.all(np.isfinite(w2))
    # limits: steady rotations (+-p/d, 0)
    assert w1[0] == -300.0 and w1[-1] == 300.0 and w2[-1] == 0.0


@pytest.mark.parametrize("shape", [(), (5,), (2, 3)])
def test_vectorised_shapes(shape):
    t = np.linspace(-2, 2, int(np.prod(shape)) or 1).reshape(shape)
    w1, w2 = sf.omega(t, 1, 1.0)
    assert w1.shape == shape and w2.shape == shape and w1.dtype == np.float64


def test_omega_solves_printed_sysfin_against_independent_integrator():
    p, d = 3.0, 0.5

    def sysfin(_, w):  # the paper's eq:sysfin with the + sign, typed here
        return [d / (p * (d * d + 1)) * w[1] ** 2, -d / p * w[0] * w[1]]

    w0 = [float(v) for v in sf.omega_mp(-3, p, d)]
    sol = solve_ivp(sysfin, (-3, 3), w0, method="DOP853", rtol=1e-12, atol=1e-12, dense_output=True)
    ts = np.linspace(-3, 3, 13)
    w1, w2 = sf.omega(ts, p, d)
    ref = sol.sol(ts)
    assert np.max(np.abs(ref[0] - w1)) < 1e-9 * p / d
    assert np.max(np.abs(ref[1] - w2)) < 1e-9 * p / d


@settings(max_examples=60, deadline=None)
@given(st.floats(-30, 30).filter(lambda v: abs(v) > 1e-3), st.floats(1e-3, 1e3), st.floats(-50, 50))
def test_energy_level_is_a2c2(p, d, t):
    """F1 = (d^2+1) w1^2 + w2^2 equals a^2 c^2 = p^2 (d^2+1)/d^2 (paper, after eq:ccalki)."""
    w1, w2 = sf.omega(t, p, d)
    level = (d * d + 1) * w1**2 + w2**2
    assert rel_err(level, p * p * (d * d + 1) / (d * d)) < 1e-13


def unreduced_rigid_body(I):
    """omega' from I omega' = I omega x omega + lambda a with a . omega' = 0 (numpy, no reduction)."""
    Iinv = np.linalg.inv(I)
    a = np.array([0.0, 0.0, 1.0])

    def rhs(_, w):
        torque = np.cross(I @ w, w)
        lam = -(a @ Iinv @ torque) / (a @ Iinv @ a)
        return Iinv @ (torque + lam * a)

    return rhs


@pytest.mark.parametrize("branch", [1, -1])
@pytest.mark.parametrize("tensor", [(2.0, 1.0, 0.3, 0.5), (1.2, 1.7, -0.4, 0.9), (3.0, 0.7, 0.8, -0.2)])
def test_omega_general_against_unreduced_constrained_euler(tensor, branch):
    I11, I22, I13, I23 = tensor
    I33 = (1 + I11 * I23**2 + I22 * I13**2) / (I11 * I22)  # det I = 1
    I = np.array([[I11, 0, I13], [0, I22, I23], [I13, I23, I33]])
    assert abs(np.linalg.det(I) - 1) < 1e-12
    w0 = [*map(float, sf.omega_general_mp(-2, *tensor, branch=branch)), 0.0]
    sol = solve_ivp(unreduced_rigid_body(I), (-2, 2), w0, method="DOP853", rtol=1e-12, atol=1e-13,
                    dense_output=True)
    ts = np.linspace(-2, 2, 9)
    w1, w2 = sf.omega_general(ts, *tensor, branch=branch)
    ref = sol.sol(ts)
    scale = np.max(np.abs(ref[:2]))
    assert np.max(np.abs(ref[0] - w1)) < 1e-8 * scale
    assert np.max(np.abs(ref[1] - w2)) < 1e-8 * scale
    assert np.max(np.abs(ref[2])) < 1e-9 * scale  # the constraint holds
    # energy I11 w1^2 + I22 w2^2 is conserved along the trajectory
    energy = I11 * w1**2 + I22 * w2**2
    assert np.ptp(energy) < 1e-12 * energy[0]


def test_omega_general_mp_twin_agrees():
    for t in (-5.0, 0.0, 0.7, 900.0):
        w = sf.omega_general(t, 2.0, 1.0, 0.3, 0.5)
        m = sf.omega_general_mp(t, 2.0, 1.0, 0.3, 0.5, dps=50)
        assert abs(float(w[0]) - float(m[0])) < 1e-15 * 3 and abs(float(w[1]) - float(m[1])) < 1e-15 * 3


@pytest.mark.parametrize("call, field", [
    (lambda: sf.omega(np.nan, 1, 1), "t"),
    (lambda: sf.omega([0.0, np.inf], 1, 1), "t[1]"),
    (lambda: sf.omega("soon", 1, 1), "t="),
    (lambda: sf.omega(0.0, 0, 1), "p=0"),
    (lambda: sf.omega(0.0, float("nan"), 1), "p=nan"),
    (lambda: sf.omega(0.0, 1, 0.0), "d=0.0"),
    (lambda: sf.omega(0.0, 1, -2), "d=-2"),
    (lambda: sf.omega(0.0, True, 1), "p=True"),
    (lambda: sf.omega_mp(0, 1, -1), "d="),
    (lambda: sf.omega_general(0.0, -1, 1, 0.1, 0.1), "I11=-1"),
    (lambda: sf.omega_general(0.0, 1, 1, 0, 0), "I13=0 and I23=0"),
    (lambda: sf.omega_general(0.0, 2, 1, 0.1, 0.1, branch=2), "branch=2"),
])
def test_bad_input_names_the_field(call, field):
    with pytest.raises(ValueError, match=None) as info:
        call()
    assert field in str(info.value)


def test_import_does_not_pull_in_sympy():
    code = "import sys, generated.suslov_formulas, suslov; print('sympy' in sys.modules, 'derivations' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["False", "False"]


def test_certificates_file_is_loadable_and_all_as_expected():
    doc = sf.load_certificates()
    assert doc["certificates"], "no certificates"
    assert all(c["outcome"] == c["expected"] for c in doc["certificates"])
    assert {"model", "special_case"} <= set(doc["derivations"])
