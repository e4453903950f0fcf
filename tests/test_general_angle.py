"""Closed-form scattering angle of any body (``general_scattering_angle`` and its twins).

References, never the code under test at its own precision: (1) the ball closed form at 1050 bits
(300 digits, the binary value of the float inputs) for the float64 evaluation; (2) the validated
integration of the ss solution (``scattering_angle_enclosure``, method "integration") and a direct
acb evaluation of cos^2(Delta psi/2) = [cosh(pi U)|tau|^2 - Re(tau^2)]/(2 sinh^2(pi U)) from
``omega_coefficients`` for the ball itself; (3) Theorem 5.4 (``scattering_angle(p, d)``) for I13 = 0.
Float bound: the docstring's absolute 1e-13 (1 + |Y|), |Y| = |Im w_-| (observed: below 0.006 of it).
"""
import inspect
import math

import mpmath
import numpy as np
import pytest
from flint import acb, arb, ctx

import suslov as sf
from suslov.validated import omega_coefficients, scattering_angle_enclosure



def abs_Y(body):
    """|Im w_-| from omega_coefficients: w_-^2 = (u - i v).(u - i v) (either root: the same |Im|)."""
    (u1, u2), (v1, v2) = omega_coefficients(*body)
    with mpmath.workdps(30):
        u1, u2, v1, v2 = (mpmath.mpf(float(x.mid())) for x in (u1, u2, v1, v2))
        return float(abs(mpmath.sqrt(mpmath.mpc(u1, -v1) ** 2 + mpmath.mpc(u2, -v2) ** 2).imag))


def reference(body):
    ball = sf.general_scattering_angle_ball(*body, prec=1050)
    assert ball.is_finite() and ball.rad() < 1e-120   # < 1e-290, but 1e-133 at |I13| ~ 1e-200 (lengths ~ 1e199)
    return ball


def error(got, ball) -> float:
    """Upper bound of |got - ball| for a float or an mpf (taken exactly: man 2^exp)."""
    with ctx.workprec(1100):
        sign, man, exp, _ = (got if isinstance(got, mpmath.mpf) else mpmath.mpf(float(got)))._mpf_
        return float((arb(-int(man) if sign else int(man)) * arb(2) ** int(exp) - ball).abs_upper())


HARD = {   # (I11, I22, I13, I23): exact binary values of these floats are the bodies
    "doc": (1.25, 1.0, 0.3, -0.5),
    "near_equilibrium_1e-3": (1.25, 1.0, 1e-3, -2e-3),
    "near_equilibrium_1e-8": (1.25, 1.0, 1e-8, -3e-8),
    "near_equilibrium_1e-200": (2.0, 1.0, 3e-200, 1e-200),
    "large_U_angle_2.89": (7191.272691764685, 0.07260755855427556, -0.02734281677854138, -1.1343288661753608e-06),
    "large_U_large_Y": (0.0010018081918170543, 3925.685607395666, 4.878772230910337e-06, 0.00290297072569972),
    # U ~ 1, |Y| = 4e5 and 8e4: the phase pi Y/2 carries Y's rounding (errors 8e-11, 4e-11: 0.002, 0.006 of the bound)
    "large_Y_I13_0": (114058996001.05945, 1.0, 0.0, -0.8651231531397169),
    "large_Y_small_I13": (40840057290.743965, 1.0, -0.0010797241443191382, -2.606082256370703),
    "small_U": (1.0, 1.001, 5.0, 7.0),
    "small_U_2": (1.0, 2.0, 50.0, -30.0),
    "I11<I22": (1.0, 2.5, 0.4, 0.7),
    "I11<I22_b": (0.3, 2.0, -0.2, 0.05),
    "I11=I22": (1.5, 1.5, 0.2, 0.3),
    "tiny_I23": (2.0, 1.0, 0.5, 1e-12),
    "near_0_I13_0": (2.0, 1.0, 0.0, 1e6),                 # p = 1e-6: angle 4.4e-6
    "near_0": (2.0, 1.0, 3e5, 1e6),
    "near_0_I11<I22": (1.0, 2.0, 5e4, -3e4),
    "near_pi_p=1+1e-12": (2.0, 1.0, 0.0, -1 / (1 + 1e-12)),
    "near_pi_p=3-1e-12": (2.0, 1.0, 0.0, -1 / (3 - 1e-12)),
    "near_pi_tiny_I13_1e-14": (2.0, 1.0, 1e-14, -1.0),
    "near_pi_tiny_I13_1e-9": (2.0, 1.0, 1e-9, -1.0),
    "mirror_near_odd": (1.0, 2.0, 1.0, 1e-10),            # I23 ~ 0, eq:lina's p ~ 1
}


@pytest.mark.parametrize("body", HARD.values(), ids=HARD.keys())
def test_float_against_300_digit_ball(body):
    ref, Y = reference(body), abs_Y(body)
    got = sf.general_scattering_angle(*body)
    assert np.isfinite(got) and 0 <= got <= np.pi
    assert error(got, ref) <= 1e-13 * (1 + Y)
    if float(ref) < 1e-3:   # the evaluation form has no cancellation: small angles keep relative accuracy
        assert error(got, ref) <= 1e-13 * float(ref)


@pytest.mark.parametrize("body", [HARD[k] for k in ("doc", "I11<I22", "near_equilibrium_1e-3", "small_U",
                                                     "large_U_angle_2.89", "near_0", "near_pi_tiny_I13_1e-9")])
def test_scaled_tensors_give_the_same_angle(body):
    ref, Y = reference(body), abs_Y(body)
    angle = sf.general_scattering_angle(*body)
    for scale in (1e-150, 1e150, 1e-300, 1e300):
        got = sf.general_scattering_angle(*(x * scale for x in body))
        assert np.isfinite(got) and error(got, ref) <= 1e-13 * (1 + Y), scale
    for k in (-1000, -500, 500, 1000):    # exact scalings: the same bits
        assert sf.general_scattering_angle(*(math.ldexp(x, k) for x in body)) == angle


def direct_formula(body, prec=400):
    """Delta psi from the defining formula in acb, from omega_coefficients (no invariants, no evaluation form)."""
    with ctx.workprec(prec):
        (u1, u2), (v1, v2) = omega_coefficients(*body)
        w = (acb(u1, -v1) ** 2 + acb(u2, -v2) ** 2).sqrt()
        U = (u1 * u1 + u2 * u2).sqrt()
        tau = 2 * (arb.pi() * acb(0, 1) * w / 2).cos()
        cos2 = ((arb.pi() * U).cosh() * abs(tau) ** 2 - (tau * tau).real) / (2 * (arb.pi() * U).sinh() ** 2)
        return 2 * cos2.sqrt().acos()


EXACT = [("5/4", 1, "3/10", "-1/2"), (1, "5/2", "2/5", "7/10"), (2, 1, "1/1000", "-1/3"), (1, "1001/1000", 5, 7)]


@pytest.mark.parametrize("body", EXACT)
def test_ball_against_validated_integration(body):
    kwargs = {"method": "integration"} if "method" in inspect.signature(scattering_angle_enclosure).parameters else {}
    integrated = scattering_angle_enclosure(*body, dps=30, **kwargs).angle
    ball = sf.general_scattering_angle_ball(*body, prec=200)
    direct = direct_formula(body)
    assert integrated.rad() < 1e-25 and ball.rad() < 1e-50 and direct.rad() < 1e-50
    assert integrated.overlaps(ball) and abs(float((integrated - ball).mid())) < 1e-25
    assert direct.overlaps(ball) and float((direct - ball).abs_upper()) < 1e-50


@pytest.mark.parametrize("body", [(2, 1, 0, -1), (2, 1, 0, "-1/3"), (1, 2, 1, 0)])
def test_ball_at_exactly_odd_p_encloses_pi(body):
    """Theorem 5.4: odd p gives pi (the float and mp twins do; the integration encloses pi for (2, 1, 0, -1))."""
    ball = sf.general_scattering_angle_ball(*body, prec=200)
    assert ball.is_finite() and ball.rad() < 1e-50 and ball.overlaps(arb.pi())


@pytest.mark.parametrize("p,d", [(1.0, 0.5), (3.0, 2.0), (5.0, 0.05), (2.0, 1.0), (4.0, 0.3), (0.7, 0.3),
                                 (2.5, 5.0), (1.3, 20.0), (1e-3, 1.0), (1 + 1e-12, 1.0), (6.0, 50.0)])
@pytest.mark.parametrize("sign", [1, -1])
def test_i13_zero_is_theorem_5_2(p, d, sign):
    I22 = 1.3
    I11 = I22 * (1 + d * d)
    I23 = -sign * I22 * d / p
    p_body = math.sqrt(I22 * (I11 - I22) / I23**2)     # the brief's map, from the float tensor
    d_body = math.sqrt((I11 - I22) / I22)
    got = sf.general_scattering_angle(I11, I22, 0.0, I23)
    assert abs(got - sf.scattering_angle(p_body, d_body)) <= 1e-14
    if p in (1.0, 3.0, 5.0):
        assert abs(got - np.pi) <= 1e-15


def test_mp_twin_honours_mp_dps_and_matches_the_ball():
    body = ("5/4", 1, "3/10", "-1/2")
    ball = sf.general_scattering_angle_ball(*body, prec=400)
    before = mpmath.mp.dps
    with mpmath.workdps(60):
        v60 = sf.general_scattering_angle_mp(*body)
    with mpmath.workdps(20):
        v20 = sf.general_scattering_angle_mp(*body)
        v40 = sf.general_scattering_angle_mp(*body, dps=40)
    assert mpmath.mp.dps == before and (v60.dps, v20.dps, v40.dps) == (60, 20, 40)
    for v, digits in ((v60, 58), (v20, 18), (v40, 38)):
        assert error(v, ball) < 10.0**-digits
    with mpmath.workdps(60):
        assert mpmath.mpf(v20) != v60              # rounded to 20 digits, not 60
    # decimal strings are exact: 3/10 is not the float 0.3
    with mpmath.workdps(50):
        float_body = sf.general_scattering_angle_mp(1.25, 1, 0.3, -0.5)
    assert abs(float_body - v60) > 1e-20


@pytest.mark.parametrize("name", ["near_equilibrium_1e-8", "large_U_large_Y", "small_U", "near_0",
                                  "near_pi_p=1+1e-12", "I11<I22_b"])
def test_mp_twin_matches_ball_on_hard_bodies(name):
    ref = reference(HARD[name])
    got = sf.general_scattering_angle_mp(*HARD[name], dps=50)
    assert error(got, ref) <= 1e-48 * float(ref)


BODY = dict(I11=1.25, I22=1.0, I13=0.3, I23=-0.5)
FUNCS = {"float": sf.general_scattering_angle, "mp": sf.general_scattering_angle_mp,
         "ball": sf.general_scattering_angle_ball}
BAD = [("I11", 0.0), ("I11", -1.0), ("I22", 0), ("I22", -2.0), ("I11", float("nan")), ("I13", float("nan")),
       ("I23", float("inf")), ("I22", -float("inf")), ("I13", "abc"), ("I23", 1 + 1j), ("I13", 0.3 + 0j)]


@pytest.mark.parametrize("func", FUNCS)
@pytest.mark.parametrize("field,value", BAD)
def test_bad_input_names_the_field(func, field, value):
    body = {**BODY, field: value}
    with pytest.raises(ValueError, match=field):
        FUNCS[func](**body)


@pytest.mark.parametrize("field", ["I11", "I13"])
def test_float_function_refuses_strings(field):
    with pytest.raises(ValueError, match=field):
        sf.general_scattering_angle(**{**BODY, field: "1.0"})


@pytest.mark.parametrize("func", FUNCS)
def test_equilibrium_is_refused(func):
    for zeros in [(0, 0), (0.0, -0.0)] + ([] if func == "float" else [("0", "0.0")]):
        with pytest.raises(ValueError, match="I13=0 and I23=0"):
            FUNCS[func](1.25, 1.0, *zeros)
    if func == "float":
        with pytest.raises(ValueError, match=r"I13=0 and I23=0 at index \[1\]"):
            FUNCS[func]([1.25, 1.3], 1.0, [0.3, 0.0], [0.5, 0.0])


def test_broadcasting_equals_scalar_calls():
    I11 = np.array([[1.25], [2.0], [0.5]])                # (3, 1)
    I13 = np.array([[0.3, -1e-3, 0.0, 5.0]])              # (1, 4)
    I23 = np.array([-0.5, 0.2, 0.7, 1e-8])                # (4,)
    got = sf.general_scattering_angle(I11, 1.0, I13, I23)
    assert got.shape == (3, 4) and np.all(np.isfinite(got))
    for i in range(3):
        for j in range(4):
            scalar = sf.general_scattering_angle(float(I11[i, 0]), 1.0, float(I13[0, j]), float(I23[j]))
            assert np.shape(scalar) == () and got[i, j] == scalar
    assert sf.general_scattering_angle([1.25, 2.0], 1.0, 0.3, -0.5).shape == (2,)
