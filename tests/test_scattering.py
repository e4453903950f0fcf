"""Scattering angle (Theorem 5.4, corrected): the generated function against independent routes.

References: (1) the closed form in mpmath at 50 digits (``scattering_angle_mp``) for the
float64 evaluation; (2) an independent 40-digit integration from t = -oo to +oo
(``derivations.sections.poisson_taylor``: Frobenius series at the ends, Taylor steps) for the formula
itself; (3) the full rigid body: a tensor with I13 = 0, integrated with SciPy from the
ss series start (``suslov.simulator.integrate``), for the map (p, d) <- I (corrected Theorem 5.4 p).
"""
import warnings

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from derivations.sections.poisson_taylor import ss_through
from generated.suslov_formulas import (
    scattering_angle,
    scattering_angle_mp,
    special_case_parameters,
)
from suslov.simulator.body import make_body
from suslov.simulator.integrate import numeric_angle


@pytest.mark.parametrize("p,d", [(0.7, 0.3), (2.0, 5.0), (4.0, 1.0), (1.3, 20.0)])
def test_formula_matches_40_digit_integration(p, d):
    with mpmath.workdps(40):
        a = mpmath.mpf(p) / mpmath.mpf(d)
        _, along = ss_through([a, mpmath.mpf(0)], [mpmath.mpf(0), -a * mpmath.sqrt(mpmath.mpf(d) ** 2 + 1)], 40)
        integrated = mpmath.acos(-along)
        assert abs(integrated - scattering_angle_mp(p, d, 40)) < mpmath.mpf(10) ** -25  # tolerance 1e-25 rad


@pytest.mark.parametrize("p", [1, 3, 5, 7, 101])
@pytest.mark.parametrize("d", [0.05, 0.5, 50.0])
def test_odd_p_gives_pi(p, d):
    assert scattering_angle(p, d) == pytest.approx(np.pi, abs=1e-15)


@settings(max_examples=200, deadline=None)
@given(st.floats(1e-6, 60.0), st.floats(1e-3, 1e3))
def test_float_matches_mp_twin(p, d):
    """Relative 1e-13 against the 50-digit twin, over the whole (p, d) box (tiny angles included)."""
    ref = scattering_angle_mp(p, d, 50)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = scattering_angle(p, d)
    assert np.isfinite(got) and 0 <= got <= np.pi
    assert abs(got - float(ref)) <= 1e-13 * float(ref) + 1e-300


@pytest.mark.parametrize("p", [2 + 1e-12, 2 - 1e-12, 4 + 3e-13, 1 + 1e-12, 3 - 1e-12, 1e-10])
@pytest.mark.parametrize("d", [1e-3, 1.0, 1e3])
def test_near_integers_and_tiny_angles(p, d):
    """Within 1e-12 of an integer and tiny angles: relative 1e-13 (mpmath 50 digits, exact decimal input)."""
    ref = float(scattering_angle_mp(p, d, 50))
    got = float(scattering_angle(p, d))
    assert abs(got - ref) <= 1e-13 * ref


def test_vectorised_broadcast_and_errors():
    out = scattering_angle(np.array([1.0, 2.0, 2.5]), np.array([[0.5], [2.0]]))
    assert out.shape == (2, 3)
    assert out[0, 1] == pytest.approx(float(scattering_angle_mp(2, 0.5)), rel=1e-14)
    with pytest.raises(ValueError, match="d"):
        scattering_angle(1.0, [1.0, -1.0])
    with pytest.raises(ValueError, match="p"):
        scattering_angle(np.nan, 1.0)


def test_rigid_body_with_i13_zero_uses_corrected_p():
    """A tensor with I13 = 0: numeric integration of its ss solution gives the closed-form angle at the
    corrected p = sqrt(I11 I22 (I11 - I22)/(I11 I22 I33 - 1)) (det I = 1), not the printed one."""
    I = np.array([[2.0, 0.0, 0.0], [0.0, 1.0, -0.45], [0.0, -0.45, 1.5]])
    body = make_body(I, energy=0.7)
    angle, error, _ = numeric_angle(body)
    p, d, _ = special_case_parameters(I)
    assert angle == pytest.approx(float(scattering_angle(p, d)), abs=max(1e-11, 10 * error))
    M = I / np.linalg.det(I) ** (1 / 3)
    I11, I22, I23, I33 = M[0, 0], M[1, 1], M[1, 2], M[2, 2]
    corrected = np.sqrt(I11 * I22 * (I11 - I22) / (I11 * I22 * I33 - 1))
    printed = np.sqrt((I11 - I22) / (I11 * I22 * (I11 * I22 * I33 - 1)))
    assert p == pytest.approx(corrected, rel=1e-12)
    assert abs(angle - float(scattering_angle(printed, d))) > 1e-3


def test_general_body_angle_does_not_depend_on_energy():
    I = [[2.0, 0.1, 0.2], [0.1, 1.0, -0.3], [0.2, -0.3, 1.5]]
    a1, e1, _ = numeric_angle(make_body(I, energy=0.3))
    a2, e2, _ = numeric_angle(make_body(I, energy=5.0))
    assert abs(a1 - a2) <= 10 * (e1 + e2) + 1e-12
