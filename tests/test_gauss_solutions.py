"""Every body's Poisson solutions from Gauss's 2F1 (issue 37), against an independent integration in t.

From ``hypergeometric_form`` (A, B, C; z = (1 + i s)/2, s = sinh t) two solutions of the spinor lift are
built with mpmath's ``hyp2f1``: ``psi1 = z^(kappa/2) (1-z)^(mu/2) F(A, B; C; z)`` and the second exponent at
z = 0, ``z^(-kappa/2) (1-z)^(mu/2) F(A-C+1, B-C+1; 2-C; z)``, with ``psi2 = (psi1' - a psi1)/b``.  The
transfer ``M = Psi(s1) Psi(s0)^-1`` acts on S(gamma) by conjugation; the rotated vector must be what
SciPy's DOP853 gives for ``dgamma/dt = gamma x (u tanh t + v sech t)`` from t0 = asinh(s0) to t1, with u, v
from the generated module's certified omega (``omega_coefficients``).  Nothing here is the code that
computes the angle or the exponents' certificates.
"""
import math

import mpmath
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from suslov.validated import hypergeometric_form, omega_coefficients


def _frame(body):
    u, v = omega_coefficients(*body)
    u, v = np.array([float(x.mid()) for x in u]), np.array([float(x.mid()) for x in v])
    U = math.hypot(*u)
    e1 = u / U
    e2 = np.array([-e1[1], e1[0]])
    return U, float(v @ e1), float(v @ e2), u, v


def _spinor(w):
    i = mpmath.mpc(0, 1)
    return -i / 2 * mpmath.matrix([[w[0], w[1] - i * w[2]], [w[1] + i * w[2], -w[0]]])


def _vector(S):
    i = mpmath.mpc(0, 1)
    return [2 * i * S[0, 0], i * (S[0, 1] + S[1, 0]), S[1, 0] - S[0, 1]]


def _fundamental(form, U, v1, v2, s):
    A, B, C = (mpmath.mpc(float(x.real.mid()), float(x.imag.mid())) for x in (form.A, form.B, form.C))
    kappa, mu = (mpmath.mpc(float(x.real.mid()), float(x.imag.mid())) for x in form.gauss_exponent_differences[:2])
    i = mpmath.mpc(0, 1)

    def y(k, s_):
        z = (1 + i * s_) / 2
        if k == 0:
            return z ** (kappa / 2) * (1 - z) ** (mu / 2) * mpmath.hyp2f1(A, B, C, z)
        return z ** (-kappa / 2) * (1 - z) ** (mu / 2) * mpmath.hyp2f1(A - C + 1, B - C + 1, 2 - C, z)

    a = i / 2 * (U * s + v1) / (1 + s * s)
    b = i / 2 * v2 / (1 + s * s)
    columns = []
    for k in (0, 1):
        value = y(k, s)
        columns.append((value, (mpmath.diff(lambda x: y(k, x), s) - a * value) / b))
    return mpmath.matrix([[columns[0][0], columns[1][0]], [columns[0][1], columns[1][1]]])


@pytest.mark.parametrize("body", [("5/4", "1", "3/10", "-1/2"), ("1", "2", "1/3", "1/5"), ("2", "1", "0", "-2/5"),
                                  ("3", "1", "-1", "1/4")])
def test_hypergeometric_solutions_are_poisson_solutions(body):
    form = hypergeometric_form(*body, prec=120)
    U, v1, v2, u, v = _frame(body)
    s0, s1 = -1.0, 1.5
    with mpmath.workdps(30):
        M = _fundamental(form, U, v1, v2, mpmath.mpf(s1)) * _fundamental(form, U, v1, v2, mpmath.mpf(s0)) ** -1
        gamma0 = [mpmath.mpf(x) for x in (0.36, -0.48, 0.8)]      # in the frame u = (U, 0, 0)
        gamma1 = [complex(x) for x in _vector(M * _spinor(gamma0) * M ** -1)]
    assert max(abs(x.imag) for x in gamma1) < 1e-12            # a real rotation, as the Poisson flow is

    # the independent route: SciPy in t, in the same rotated frame
    def rhs(t, g):
        w = np.array([U * math.tanh(t) + v1 / math.cosh(t), v2 / math.cosh(t), 0.0])
        return np.cross(g, w)

    sol = solve_ivp(rhs, (math.asinh(s0), math.asinh(s1)), [0.36, -0.48, 0.8], method="DOP853", rtol=1e-12, atol=1e-13)
    assert np.allclose([x.real for x in gamma1], sol.y[:, -1], atol=1e-9), (gamma1, sol.y[:, -1])
    # and the rotated frame is the paper's omega: u -> (U, 0), v -> (v1, v2)
    assert math.isclose(float(np.hypot(*v)), math.hypot(v1, v2), rel_tol=1e-12)
