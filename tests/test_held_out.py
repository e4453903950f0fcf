"""Held-out inputs (issue 44): a table of (input, expected outcome) over the public surfaces.

Each row is an input a careful user or an attacker gave the library in the issue's review, with the outcome it
must have: a value, checked against an independent reference computed here (mpmath at high working precision,
straight from the closed forms' definitions, none of the project's evaluation code), a verdict, or an exception of
the documented type naming the field.  The table is data; one test walks it, so adding an input is adding a row.
"""
from __future__ import annotations

import math

import mpmath
import pytest
from flint import arb

from generated import suslov_formulas as gf
from suslov import validated

# ----------------------------------------------------------------- independent references (mpmath, definitions)


def _mp(x):
    """x (int, float, decimal or "n/m" string) as an mpf at the current precision, exactly as written."""
    from fractions import Fraction

    q = Fraction(x)   # a float is its binary value, a string the decimal or ratio it spells
    return mpmath.mpf(q.numerator) / q.denominator


def theorem52(p, d, dps):
    """Theorem 5.4 (corrected): cos(Delta psi/2) = |cos(pi p/2)| / cosh(pi p/(2 d))."""
    with mpmath.workdps(dps):
        p, d = _mp(p), _mp(d)
        return 2 * mpmath.acos(abs(mpmath.cos(mpmath.pi * p / 2)) / mpmath.cosh(mpmath.pi * p / (2 * d)))


def general_angle(I11, I22, I13, I23, dps):
    """cos^2(Delta psi/2) = (cosh(pi U)|tau|^2 - Re tau^2)/(2 sinh^2(pi U)), tau = 2 cos(pi kappa), kappa = (i/2) w_-,
    w_-^2 = (u - i v).(u - i v), U = |u|, for omega = u tanh t + v sech t of the body (eq:o12 normalised)."""
    with mpmath.workdps(dps):
        I11, I22, I13, I23 = (_mp(x) for x in (I11, I22, I13, I23))
        D = I13**2 * I22 + I23**2 * I11
        r = mpmath.sqrt(I11 * I22)
        u = (-I11 * I22 * I23 / D, I11 * I22 * I13 / D)
        v = (I22 * I13 * r / D, I11 * I23 * r / D)
        U = mpmath.sqrt(u[0] ** 2 + u[1] ** 2)
        w2 = sum((a - 1j * b) ** 2 for a, b in zip(u, v))
        tau = 2 * mpmath.cos(mpmath.pi * 0.5j * mpmath.sqrt(w2))
        cos2 = (mpmath.cosh(mpmath.pi * U) * abs(tau) ** 2 - mpmath.re(tau**2)) / (2 * mpmath.sinh(mpmath.pi * U) ** 2)
        return 2 * mpmath.acos(mpmath.sqrt(cos2))


def _scene_verdict(p, d, effect):
    import suslov

    result = suslov.simulate({"body": {"p": p, "d": d}, "motion": {"time": [-1, 1], "samples": 3},
                              "effects": {"compute": [effect]}})
    return result.results[effect]


# ----------------------------------------------------------------- the table: (id, call, expected)

VALUES = [   # (id, call, reference, relative tolerance)
    ("general_mp_huge_I11", lambda: gf.general_scattering_angle_mp(1e200, 1, 1, 1, dps=30),
     lambda: general_angle(1e200, 1, 1, 1, 400), 1e-28),
    ("general_mp_body", lambda: gf.general_scattering_angle_mp("5/4", 1, "3/10", "-1/2", dps=40),
     lambda: general_angle("5/4", 1, "3/10", "-1/2", 200), 1e-38),
    ("theorem52_mp_decimals", lambda: gf.scattering_angle_mp("2.5", "0.7", dps=40),
     lambda: theorem52("2.5", "0.7", 200), 1e-38),
    ("theorem52_mp_huge_even_p", lambda: gf.scattering_angle_mp(10**1000, 1, dps=20),
     lambda: theorem52(10**1000, 1, 2100), 1e-18),
    ("theorem52_float", lambda: gf.scattering_angle(2.0, 1.0), lambda: theorem52(2, 1, 50), 1e-14),
]

VERDICTS = [   # (id, call, expected)
    ("galois_p3", lambda: validated.galois_group(2, 1, 0, "-1/3").group, "reducible"),
    ("galois_decimal_not_a_third", lambda: validated.galois_group(2, 1, 0, "-0.3333333333333333").group, "SO(3,C)"),
    ("scene_galois_p3", lambda: _scene_verdict(3, 1.0, "galois_group")["verdict"], "reducible"),
    ("scene_galois_p1", lambda: _scene_verdict(1, 0.5, "galois_group")["verdict"], "reducible"),
    ("scene_galois_p2", lambda: _scene_verdict(2, 1.0, "galois_group")["verdict"], "SO(3,C)"),
    ("poles_p1000_decimal", lambda: validated.local_behaviour(2, 1, 0, "-1e-3").kind, "logarithmic"),
    ("poles_p101", lambda: validated.local_behaviour(2, 1, 0, "-1/101").kind, "meromorphic"),
    ("hypergeometric_huge_exact_finite",
     lambda: all(math.isfinite(float(x)) for x in (
         validated.hypergeometric_form(10**100, 10**100 - 1, 10**99, 3).C.real.mid(),
         validated.hypergeometric_form(10**100, 10**100 - 1, 10**99, 3).C.imag.mid())), True),
]

ENCLOSES_PI = [   # (id, call returning an arb): must contain pi exactly (odd p: Delta psi = pi)
    ("enclosure_p3", lambda: validated.scattering_angle_enclosure(2, 1, 0, "-1/3", dps=30).angle),
    ("scene_enclosure_p5", lambda: arb(_scene_verdict(5, 1.0, "scattering_angle_enclosure")["ball"])),
]

REFUSED = [   # (id, call, exception type, text the message must contain)
    ("huge_exponent_before_work", lambda: validated.galois_group("5/4", 1, "1e10000000", "-1/2"), ValueError, "I13"),
    ("monodromy_huge_exponent", lambda: validated.monodromy("5/4", 1, "1e10000000", "-1/2", max_seconds=10),
     ValueError, "I13"),
    ("zero_denominator", lambda: validated.galois_group("1/0", 1, 0, 1), ValueError, "I11"),
    ("infinite_entry", lambda: validated.galois_group("inf", 1, 0, 1), ValueError, "I11"),
    ("float_route_outside_its_domain", lambda: gf.general_scattering_angle(1e200, 1, 1, 1), ValueError,
     "outside the proven float64 domain"),
    ("nan_p", lambda: gf.scattering_angle(float("nan"), 1), ValueError, "p=nan"),
    ("even_p_first_integral", lambda: gf.first_integral(2, 1.0, 1, 1, 1, 0, 0), ValueError, "p=2"),
    ("even_p_basis", lambda: gf.gamma_basis(0.0, 2, 1.0), ValueError, "p=2"),
    ("equilibrium_angle", lambda: gf.general_scattering_angle(2, 1, 0, 0), ValueError, "I13=0 and I23=0"),
    ("equilibrium_poles", lambda: validated.local_behaviour(2, 1, 0, 0), ValueError, "I13=0 and I23=0"),
    ("ball_precision_unbounded", lambda: gf.general_scattering_angle_ball("5/4", 1, "3/10", "-1/2", prec=10**9),
     ValueError, "prec"),
]


@pytest.mark.parametrize("ident, call, reference, tolerance", VALUES, ids=[r[0] for r in VALUES])
def test_values_against_independent_references(ident, call, reference, tolerance):
    got, want = call(), reference()
    with mpmath.workdps(60):
        assert abs(mpmath.mpf(got) - want) <= tolerance * abs(want), f"{ident}: {got} vs {want}"


@pytest.mark.parametrize("ident, call, expected", VERDICTS, ids=[r[0] for r in VERDICTS])
def test_verdicts(ident, call, expected):
    assert call() == expected, ident


@pytest.mark.parametrize("ident, call", ENCLOSES_PI, ids=[r[0] for r in ENCLOSES_PI])
def test_enclosures_contain_pi_exactly(ident, call):
    from flint import ctx

    ball = call()
    with ctx.workprec(400):
        assert ball.contains(arb.pi()), f"{ident}: {ball} excludes pi"


@pytest.mark.parametrize("ident, call, error, text", REFUSED, ids=[r[0] for r in REFUSED])
def test_refusals_name_the_field(ident, call, error, text):
    with pytest.raises(error, match=None) as caught:
        call()
    assert text in str(caught.value), f"{ident}: {caught.value}"
