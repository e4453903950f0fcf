"""The proven mixed bound of general_scattering_angle (issue 34; derivations/proofs/general_angle_proof.py).

Each stage's claim is checked on held-out bodies against mpmath at 50 digits, an independent route:

* stage 2: the float angle is within the proven bound of the exact formula evaluated (in mpmath) at the float
  arguments h~, g~, Y~ the run time computed;
* stage 1: those arguments are within the proven relative bounds of the exact h, g, Y of the scaled float body
  (invariants and lengths in mpmath).

A seeded change to one run-time operation is rejected by the bit-for-bit check that ties the proof to the code.
"""
import math

import mpmath
import numpy as np
import pytest
from flint import ctx

import suslov as sf
from conftest import mutated_function
from derivations.proofs import general_angle_proof as proof
from derivations.proofs.float_bounds import U
from suslov.kernel import gauss_angle, phase
from suslov.kernel.contexts import FLOAT, MP

FORMULAS = sf.active_formulas()


@pytest.fixture(scope="module")
def bounds():
    result = proof.prove(FORMULAS)
    return {key: float(value.upper()) for key, value in result.items() if key in ("h", "g", "Y", "Y absolute", "angle")}


def held_out_bodies():
    rng = np.random.default_rng(99)
    bodies = [(2.0, 1.0, 0.0, -1.0), (3.0, 3.0, 0.4, -0.2), (1.0, 0.5, 1e-7, 0.3), (0.9, 1.0, 0.25, 1e-300),
              (5.0, 2.0, 1e-9, 2e-9), (1.0, 1 - 2**-40, 0.6, -0.8)]
    for _ in range(40):
        I11, I22 = (float(v) for v in 10 ** rng.uniform(-5, 1, 2))
        I13, I23 = (float(v) for v in rng.uniform(-1, 1, 2) * 10 ** rng.uniform(-8, 1))
        bodies.append((I11, I22, I13, I23))
    return bodies


def float_arguments(I11, I22, I13, I23):
    """The run time's scaled entries and (h~, g~, Y~, lam) for one body (as suslov.runtime.general_angle)."""
    size = max(I11, I22, abs(I13), abs(I23))
    I11, I22, I13, I23 = (np.float64(v) / size for v in (I11, I22, I13, I23))
    lam = max(abs(I13), abs(I23))
    entries = (I11, I22, I13 / lam, I23 / lam)
    U_, gap, Y = gauss_angle.float_lengths(*FORMULAS._gauss_invariants(FLOAT, *entries))
    return entries, lam, (float(0.5 * np.pi * U_ / lam), float(0.5 * np.pi * gap / lam), float(Y / lam))


@pytest.mark.parametrize("body", held_out_bodies())
def test_stage2_the_float_angle_is_the_exact_formula_at_the_float_arguments(bounds, body):
    _, _, (h, g, Y) = float_arguments(*body)
    value = float(FORMULAS.general_scattering_angle(*body))
    with mpmath.workdps(50):
        s, c = abs(mpmath.sinpi(mpmath.mpf(Y) / 2)), abs(mpmath.cospi(mpmath.mpf(Y) / 2))
        exact = FORMULAS._general_angle(MP, mpmath.mpf(h), mpmath.mpf(g), s, c)
        assert abs(value - exact) <= bounds["angle"], (body, float(abs(value - exact)) / 2**-53)


@pytest.mark.parametrize("body", held_out_bodies())
def test_stage1_the_float_arguments_are_within_the_proven_relative_bounds(bounds, body):
    entries, lam, (h, g, Y) = float_arguments(*body)
    with mpmath.workdps(50):
        exact = gauss_angle.mp_arguments(*FORMULAS._gauss_invariants(MP, *(mpmath.mpf(float(e)) for e in entries)))
        h_exact, g_exact = exact[0] / mpmath.mpf(float(lam)), exact[1] / mpmath.mpf(float(lam))
        U2, a, b, c2 = FORMULAS._gauss_invariants(MP, *(mpmath.mpf(float(e)) for e in entries))
        Y_exact = abs(mpmath.sqrt(mpmath.mpc(a, b)).imag) / mpmath.mpf(float(lam))
        assert abs(h - h_exact) <= bounds["h"] * h_exact
        assert abs(g - g_exact) <= bounds["g"] * g_exact
        assert abs(Y - Y_exact) <= bounds["Y"] * Y_exact + bounds["Y absolute"]


def test_the_proven_bounds_are_those_stated(bounds):
    assert bounds["angle"] <= proof.STATED_U * 2**-53
    assert max(bounds["h"], bounds["g"], bounds["Y"]) <= proof.STATED_RHO_U * 2**-53


@pytest.mark.parametrize("module, name, old, new", [
    (gauss_angle, "float_lengths", "gap = 2.0 * c2 / ((2.0 * U2 - a + modulus) * (U + X))",
     "gap = 2.0 * c2 / ((2.0 * U2 + (modulus - a)) * (U + X))"),                          # a reordered sum
    (gauss_angle, "float_lengths", "gap = 2.0 * c2 / ((2.0 * U2 - a + modulus) * (U + X))",
     "gap = 2.0 * c2 / (2.0 * U2 - a + modulus) / (U + X)"),                              # a reordered quotient
    (phase, "half_pi_parts", "np.sin(0.5 * np.pi * (1.0 - r))", "np.cos(0.5 * np.pi * r)"),  # the other branch
])
def test_a_seeded_change_to_one_operation_is_rejected(monkeypatch, module, name, old, new):
    assert proof.same_operations(FORMULAS)[0]
    monkeypatch.setattr(module, name, mutated_function(module, name, old, new))
    assert not proof.same_operations(FORMULAS)[0]


def test_the_relative_rule_of_expm1_holds_at_sampled_points():
    """float_bounds.expm1's relative rule: |expm1(x (1 + t)) - expm1(x)| <= r e^(max(x,0)(1+r) + |x| r) |expm1(x)|."""
    from flint import arb

    from derivations.proofs.float_bounds import FE, LIBM_REL, expm1

    rng = np.random.default_rng(5)
    with ctx.workprec(128):
        for x in list(rng.uniform(-40, 3, 30)) + [-1e-9, 1e-9, 0.0]:
            r = 1e-10
            bound = expm1(FE(arb(float(x)), 0, r, 0))
            with mpmath.workdps(40):
                exact = mpmath.expm1(mpmath.mpf(float(x)))
                for t in (-r, r):
                    moved = mpmath.expm1(mpmath.mpf(float(x)) * (1 + mpmath.mpf(t)))
                    rho = (1 + bound.r) / (1 + LIBM_REL) - 1      # the propagated part, without the call's rounding
                    allowed = mpmath.mpf(rho.upper().str(30, radius=False)) * abs(exact)
                    assert abs(moved - exact) <= allowed + 1e-300, x
    assert math.isfinite(float(U))
