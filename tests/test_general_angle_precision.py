"""Issue 44 "Precision that keeps its promise": the general scattering angle of huge and tiny entries.

``general_scattering_angle_mp(1e200, 1, 1, 1, dps=30)`` returned 2.00564027... for 2.03507241...: the angle
depends on ``Y = Im w_-`` modulo 2 (|Y| = 1e100 here), and 45 working digits leave nothing of pi Y/2 mod 2.  The
float route returned the same wrong value silently, the ball route a ball of width 0.25 at 30 digits and
``[+/- 6.29]`` for ``I11 = I22 = "1/3"``.  Required: the ``_mp`` value agrees with the true angle to the digits it
claims (or a ValueError states the digits it would need), the ball carries the bits asked, and the float route
refuses (ValueError) where its bound ``1e-13 (1 + |Y|)`` says nothing, or returns a value within it.

References, never the code under test: the closed form of the generated module's docstring written out in
mpmath at 400 and 800 digits,

    cos^2(Delta psi/2) = [cosh(pi U) |tau|^2 - Re(tau^2)] / (2 sinh^2(pi U)),
    tau = 2 cos(pi kappa),  kappa = (i/2) w_-,  w_-^2 = (u - i v).(u - i v),  U = |u|,

with u, v of omega = u tanh t + v sech t (eq:o12) written out here from the entries (D = I11 I23^2 + I13^2 I22,
r = sqrt(I11 I22)): u = (-I11 I22 I23, I11 I13 I22)/D, v = (I13 I22 r, I11 I23 r)/D -- checked against the
generated ``_omega_general`` (the certified model:011, not the invariants the code under test evaluates).  Each
reference is used only where its 400- and 800-digit values agree to 1e-200 (the 800-digit one then has
hundreds of digits to spare).  Entries are taken exactly: ints, Fractions and decimal strings as the rationals
they are, floats as their binary values.
"""
import functools
import re
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from flint import arb

import suslov as sf

FLOAT_BODIES = {   # floats: the bodies are their binary values
    "issue_1e200": (1e200, 1.0, 1.0, 1.0),                       # |Y| = 1e100, U = 1.41: mp30 gave 2.0056 for 2.0351
    "1e250": (1e250, 1.0, 1.0, 1.0),
    "1e300": (1e300, 1.0, 1.0, 1.0),                             # |Y| = 1e150
    "I22_1e300": (1.0, 1e300, 1.0, -1.0),
    "tiny_1e-200": (1e-200, 1.0, 1e-200, 1e-200),                # |Y| = 1e100 from entries of 1e-200
    "mixed_1e-200": (1.0, 1e-200, -3e-200, 1e-200),
    "1e100": (1e100, 1.0, 1.0, 1.0),                             # |Y| = 1e50: no underflow in float64
}
EXACT_BODIES = {
    "decimal_issue": ("1e200", 1, 1, 1),                          # the decimal 10^200: 2.0056..., not the float's
    "decimal_1e200": ("1e200", "1", "1", "3"),
    "decimal_1e-200": ("1e-200", 1, "1e-200", "1e-200"),
    "decimal_mixed_1e-200": (1, "1e-200", "-3e-200", "1e-200"),
    "ints_10**200+1": (10**200 + 1, 10**200, 1, 1),            # I11 - I22 = 1: equal at 45 digits
    "strings_10**200+1": (str(10**200 + 1), str(10**200), "1", "1"),
    "ints_10**100": (10**100, 10**100 - 1, 10**99, 3),          # hypergeometric_form's case (Y = 3e-148)
    "fractions_10**300": (Fraction(10**300), Fraction(1, 3), Fraction(1, 7), Fraction(-2, 3)),   # |Y| = 8.7e149
    "thirds": ("1/3", "1/3", "3/10", "-1/2"),                    # I11 = I22 inexact in binary: the ball was [+/- 6.29]
}
BODIES = {**FLOAT_BODIES, **EXACT_BODIES}


def entries(body, dps: int) -> list:
    """The entries in mpmath at ``dps`` digits, each rounded once from its exact rational value."""
    return [mpmath.mpf(q.numerator) / q.denominator for q in map(Fraction, body)]


def u_v(body, dps: int) -> tuple:
    """u, v of omega = u tanh t + v sech t (eq:o12, branch r = +sqrt(I11 I22)), written out here."""
    with mpmath.workdps(dps):
        I11, I22, I13, I23 = entries(body, dps)
        D, r = I11 * I23**2 + I13**2 * I22, mpmath.sqrt(I11 * I22)
        return (-I11 * I22 * I23 / D, I11 * I13 * I22 / D), (I13 * I22 * r / D, I11 * I23 * r / D)


def closed_form(body, dps: int) -> tuple:
    """(Delta psi, |Y|, U) from the docstring's definitions at ``dps`` digits."""
    u, v = u_v(body, dps)
    with mpmath.workdps(dps):
        U = mpmath.sqrt(u[0] ** 2 + u[1] ** 2)
        w_minus = mpmath.sqrt(sum((x - 1j * y) ** 2 for x, y in zip(u, v)))
        kappa = 0.5j * w_minus
        tau = 2 * mpmath.cos(mpmath.pi * kappa)
        cos2 = (mpmath.cosh(mpmath.pi * U) * abs(tau) ** 2 - (tau * tau).real) / (2 * mpmath.sinh(mpmath.pi * U) ** 2)
        return 2 * mpmath.acos(mpmath.sqrt(cos2)), abs(w_minus.imag), U


@functools.cache
def reference(body) -> tuple:
    """(angle, |Y|, U, error) at 800 digits, after checking that 400 digits agree with it to 1e-200 (relative).

    ``error`` bounds that of the 800-digit angle: the 400-digit one lost as many digits as it differs by, the
    800-digit one the same number of its 800 (ten times that, for margin)."""
    low, (high, Y, U) = closed_form(body, 400)[0], closed_form(body, 800)
    with mpmath.workdps(800):
        difference = abs(high - low)
        assert difference <= mpmath.mpf(10) ** -200 * high, (body, mpmath.nstr(difference, 5))
        error = difference * mpmath.mpf(10) ** -390 + mpmath.mpf(10) ** -790 * high
    return high, Y, U, error


class _Probe:
    """An mpmath number context whose (tanh t, sech t) are fixed: omega = u tanh t + v sech t is linear in them."""

    def __init__(self, tanh, sech):
        self.pair = (mpmath.mpf(tanh), mpmath.mpf(sech))

    def tanh_sech(self, t):
        return self.pair


@pytest.mark.parametrize("name", ["issue_1e200", "mixed_1e-200", "ints_10**200+1", "fractions_10**300"])
def test_u_v_written_here_are_the_certified_model(name):
    body, omega = BODIES[name], sf.active_formulas()._omega_general
    u, v = u_v(body, 400)
    with mpmath.workdps(400):
        values = entries(body, 400)
        r = mpmath.sqrt(values[0] * values[1])
        for mine, model in ((u, omega(_Probe(1, 0), None, *values, r)), (v, omega(_Probe(0, 1), None, *values, r))):
            for x, y in zip(mine, model):
                assert abs(x - y) <= mpmath.mpf(10) ** -390 * (abs(y) + abs(x)), name


def test_the_bodies_are_hard():
    """The issue's body and its kind: |Y| from 1e50 to 1e150 with U about 1, where the phase moves the angle."""
    for name in ("issue_1e200", "1e300", "tiny_1e-200", "decimal_issue", "decimal_1e200", "fractions_10**300"):
        _, Y, U, _ = reference(BODIES[name])
        assert Y > 1e49 and 0.1 < U < 10, name
    assert mpmath.nstr(reference(FLOAT_BODIES["issue_1e200"])[0], 9) == "2.03507242"   # dps 400, 2000-bit ball
    assert mpmath.nstr(reference(EXACT_BODIES["decimal_issue"])[0], 9) == "2.00564027"  # what mp30 gave for both


# ---------------------------------------------------------------- the mpmath twin


@pytest.mark.parametrize("dps", [15, 30, 60])
@pytest.mark.parametrize("name", BODIES)
def test_mp_agrees_with_the_reference_to_the_digits_it_claims(name, dps):
    body = BODIES[name]
    value = sf.general_scattering_angle_mp(*body, dps=dps)
    ref, _, _, ref_error = reference(body)
    assert value.dps == dps
    with mpmath.workdps(850):
        error = abs(mpmath.mpf(value) - ref)
        assert error <= mpmath.mpf(10) ** (1 - dps) * ref + ref_error, (name, dps, repr(value), mpmath.nstr(ref, dps + 5))


def test_mp_follows_mpmath_dps_for_the_issue_body():
    body = FLOAT_BODIES["issue_1e200"]
    with mpmath.workdps(40):
        value = sf.general_scattering_angle_mp(*body)
    assert value.dps == 40
    with mpmath.workdps(850):
        assert abs(mpmath.mpf(value) - reference(body)[0]) <= mpmath.mpf(10) ** -39 * 3


def test_ints_strings_and_fractions_are_one_body():
    ints = EXACT_BODIES["ints_10**200+1"]
    same = [sf.general_scattering_angle_mp(*b, dps=50) for b in
            (ints, EXACT_BODIES["strings_10**200+1"], tuple(Fraction(x) for x in ints), (str(10**200 + 1), "1e200", 1, "1.0"))]
    assert all(mpmath.mpf(x) == mpmath.mpf(same[0]) for x in same)
    decimal = EXACT_BODIES["decimal_issue"]
    assert sf.general_scattering_angle_mp(10**200, 1, 1, 1, dps=40) == sf.general_scattering_angle_mp(*decimal, dps=40)
    assert abs(sf.general_scattering_angle_mp(*decimal, dps=40) - sf.general_scattering_angle_mp(1e200, 1, 1, 1)) > 0.02


def test_mp_refuses_stating_the_digits_it_would_need(monkeypatch):
    """Beyond the working precision a route may use, a ValueError says how many digits the body needs."""
    from suslov.runtime import general_angle

    monkeypatch.setattr(general_angle, "MAX_EXTRA_BITS", 128)
    with pytest.raises(ValueError, match=r"needs about (\d+) working digits") as caught:
        sf.general_scattering_angle_mp(*FLOAT_BODIES["issue_1e200"], dps=30)
    needed = int(re.search(r"needs about (\d+) working digits", str(caught.value)).group(1))
    assert 130 <= needed <= 200 and "I11" in str(caught.value) and "|Y|" in str(caught.value)   # 30 + log10(1e100)
    with pytest.raises(ValueError, match=r"needs about \d+ working digits"):
        sf.general_scattering_angle_ball(*FLOAT_BODIES["1e300"], prec=100)
    # a body without a large phase needs no more than it asks
    assert abs(sf.general_scattering_angle_mp(1.25, 1, 0.3, -0.5, dps=30) - 2.9591441765003285) < 1e-15


# ---------------------------------------------------------------- balls


def ball_parts(x: arb) -> tuple:
    """(midpoint, radius) of a ball as exact mpf (read from arb's mantissa and exponent, not through float64)."""
    return tuple(mpmath.ldexp(mpmath.mpf(int(m)), int(e)) for m, e in (x.mid().man_exp(), x.rad().man_exp()))


@pytest.mark.parametrize("prec", [53, 200, 1000])
@pytest.mark.parametrize("name", BODIES)
def test_ball_contains_the_reference_and_carries_the_bits_asked(name, prec):
    body = BODIES[name]
    ball = sf.general_scattering_angle_ball(*body, prec=prec)
    ref, _, _, ref_error = reference(body)
    assert ball.is_finite(), name
    with mpmath.workdps(850):
        mid, rad = ball_parts(ball)
        assert abs(mid - ref) <= rad + ref_error, (name, prec, str(ball))
        assert rad <= mpmath.ldexp(ref, -(prec - 4)), (name, prec, str(ball))


def test_ball_by_digits_for_the_issue_body():
    body = FLOAT_BODIES["issue_1e200"]
    ball = sf.general_scattering_angle_ball(*body, dps=30)   # was [2.09 +/- 0.126]
    with mpmath.workdps(850):
        mid, rad = ball_parts(ball)
        assert rad < mpmath.mpf(10) ** -29 and abs(mid - reference(body)[0]) <= rad


# ---------------------------------------------------------------- the float route


@pytest.mark.parametrize("name", FLOAT_BODIES)
def test_float_route_refuses_where_its_bound_says_nothing(name):
    body = FLOAT_BODIES[name]
    Y = reference(body)[1]
    assert Y > 1e13                                  # 1e-13 (1 + |Y|) > 1 radian
    with pytest.raises(ValueError) as caught:
        sf.general_scattering_angle(*body)
    message = str(caught.value)
    assert "|Y|" in message and "general_scattering_angle_mp" in message and "outside the proven" in message
    assert "I11=" in message and "I23=" in message


def test_float_route_refusal_names_the_index():
    with pytest.raises(ValueError, match=r"at index \[1\]"):
        sf.general_scattering_angle([1.25, 1e200], 1.0, [0.3, 1.0], [-0.5, 1.0])


UNDERFLOW_BODIES = [   # the scaled invariants underflow (c2 = I11^3 I22^3/D^2 to 0): the float route gave 0.0
    (2.6048453048523657e+297, 7.268916814295063e+154, 8.483463728877399e-205, 2.3705045316004557e-09),
    (4.334196898863601e+211, 5.929453580914631e+66, -6.469820960641964e-94, -1.4660007679370422e-237),
    (3.292852354645562e+107, 4.18083830972588e-14, -4.31148337841677e-216, -2.970860273616703e-124),
    (10.0**100, 10.0**100 * (1 - 2.0**-52), 1e99, 3.0),
    (1e200, 3e-200, 1.0, 1e-100),                 # |Y| = 1.7e100 but an angle of 4.3e-100: the phase moves it < 1e-13
]


@pytest.mark.parametrize("body", UNDERFLOW_BODIES)
def test_float_route_elsewhere_within_its_bound(body):
    angle, Y, _, _ = reference(body)
    got = sf.general_scattering_angle(*body)
    assert np.isfinite(got)
    assert abs(got - float(angle)) <= 1e-13 * (1 + (float(Y) if Y <= 1e13 else 0.0)) * min(1.0, float(angle))
