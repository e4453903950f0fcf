"""Rigorous enclosures (issue 16): validated angles, ball certificates, float functions inside their bounds.

Independent routes for the expected values: ``derivations.sections.poisson_taylor.ss_through`` (mpmath at 50
digits: a different implementation of series + Taylor steps, no balls), the closed form of
Theorem 5.4, exact rational evaluation of the first integrals (Fractions), and the simulator's
DOP853 integration with its error estimate.
"""
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from flint import arb, ctx

from derivations.core.balls import certify_enclosure, decide
from derivations.core.certificates import CertificateLog, Outcome
from derivations.sections.poisson_taylor import ss_through
from derivations.sections.scattering_balls import omega_pd
from generated import suslov_formulas as sf
from suslov.kernel.contexts import MP
from suslov.kernel.enclosure import ss_angle_enclosure, to_arb
from suslov.validated import omega_coefficients, scattering_angle_enclosure

BODIES = [("5/4", "1", "3/10", "-1/2"), ("2", "1", "-7/10", "1/5"), ("3/2", "1", "1/4", "0"), ("5/4", "1", "0", "-1/4")]


def mp_coefficients(I11, I22, I13, I23):
    """u, v from the emitted omega in mpmath (probe values of tanh, sech), for the independent route."""
    class Probe:
        def __init__(self, pair):
            self.pair = pair

        def tanh_sech(self, t):
            return self.pair

        sqrt = staticmethod(mpmath.sqrt)

    args = [mpmath.mpf(Fraction(x).numerator) / Fraction(x).denominator for x in (I11, I22, I13, I23)]
    r = mpmath.sqrt(args[0] * args[1])
    u = sf._omega_general(Probe((1, 0)), None, *args, r)
    v = sf._omega_general(Probe((0, 1)), None, *args, r)
    return list(u), list(v)


@pytest.mark.parametrize("body", BODIES, ids=lambda b: ",".join(b))
def test_enclosure_contains_an_independent_50_digit_value(body):
    enclosure = scattering_angle_enclosure(*body, dps=30, method="integration")
    assert enclosure.width < 1e-25
    with mpmath.workdps(60):
        u, v = mp_coefficients(*body)
        _, along = ss_through(u, v, 50)
        reference = mpmath.acos(-along)
        with ctx.workprec(200):
            ball = arb(mpmath.nstr(reference, 55))
            assert enclosure.angle.overlaps(ball)
            assert abs(enclosure.angle.mid() - ball) < 1e-28


def test_special_body_contains_the_closed_form():
    """I13 = 0 with I22 (I11 - I22)/I23^2 = p^2: the enclosure contains scattering_angle_ball(p, d)."""
    I11, I22, I23 = Fraction(5, 4), Fraction(1), Fraction(-1, 4)       # p^2 = 4, p = 2, d = 1/2
    p, d = sf._special_parameters(MP, *(mpmath.mpf(x.numerator) / x.denominator for x in (I11, I22, I23)))
    assert abs(p - 2) < 1e-30 and abs(d - mpmath.mpf(1) / 2) < 1e-30
    enclosure = scattering_angle_enclosure(I11, I22, 0, I23, dps=30, method="integration")
    closed = sf.scattering_angle_ball(2, Fraction(1, 2), prec=200)
    assert enclosure.angle.overlaps(closed) and enclosure.width < 1e-25


def test_general_body_agrees_with_the_simulators_integration():
    from suslov.simulator.body import make_body
    from suslov.simulator.integrate import numeric_angle

    tensor = np.array([[2.0, 0.1, 0.2], [0.1, 1.0, -0.3], [0.2, -0.3, 1.5]])
    body = make_body(tensor=tensor)
    angle, error, _ = numeric_angle(body)
    I11, I22, I13, I23 = body.entries
    enclosure = scattering_angle_enclosure(I11, I22, I13, I23, dps=15, method="integration")   # floats: their binary values
    assert abs(angle - float(enclosure.angle.mid())) <= error + enclosure.width + 1e-12


def test_odd_p_gives_pi_inside_the_ball():
    with ctx.workprec(150):   # u, v are balls: made at the working precision, or they carry 53-bit radii
        u, v = omega_pd(arb(3), arb(1) / 2)
    enclosure = ss_angle_enclosure(u, v, digits=30)
    assert enclosure.angle.contains(arb.pi()) or enclosure.angle.overlaps(arb.pi())
    assert enclosure.cos_angle.overlaps(arb(-1)) and float(enclosure.cos_angle.rad()) < 1e-28


def test_wrong_claim_is_refuted_not_unknown():
    log = CertificateLog(derivation="test")
    u, v = omega_pd(arb(5) / 2, arb(7) / 10)

    def off_by_1e_10(prec):
        e = ss_angle_enclosure(u, v, digits=20, prec=prec)
        return [e.angle - sf.scattering_angle_ball("2.5", "0.7", prec=prec) - arb("1e-10")]

    cert = certify_enclosure(log, "angle equals the closed form plus 1e-10", "test", off_by_1e_10, arb("1e-15"),
                             prec=110, expect=Outcome.FAIL)
    assert cert.outcome is Outcome.FAIL


def test_too_low_precision_is_unknown_not_pass():
    log = CertificateLog(derivation="test")

    def closed_minus_itself(prec):           # exactly zero, but a 20-bit ball cannot show |.| <= 1e-30
        ball = sf.scattering_angle_ball("2.5", "0.7", prec=prec)
        return [ball - sf.scattering_angle_ball("2.5", "0.7", prec=prec)]

    cert = certify_enclosure(log, "a zero at 20 bits", "test", closed_minus_itself, arb("1e-30"), prec=20,
                             doublings=0, expect=Outcome.UNKNOWN)
    assert cert.outcome is Outcome.UNKNOWN
    assert decide(arb(0, 1e-40), arb("1e-30")) is Outcome.PASS
    assert decide(arb(1, 1e-3), arb("1e-30")) is Outcome.FAIL


@pytest.mark.parametrize("p,d", [(2.5, 0.7), (1.0, 0.5), (3.0 + 1e-12, 0.2), (0.3, 20.0), (2.0, 0.05), (7.0 - 1e-13, 1.3),
                                 (1e-6, 2.0), (40.5, 3.0)])
def test_float_angle_inside_the_ball_widened_by_its_bound(p, d):
    """scattering_angle (float64) lies in the ball of the same closed form widened by relative 1e-13."""
    ball = sf.scattering_angle_ball(p, d, prec=128)           # floats: exact binary values, as the float path sees
    value = float(sf.scattering_angle(p, d))
    bound = 1e-13 * abs(float(ball.mid())) + float(ball.rad())
    assert abs(value - float(ball.mid())) <= bound


@pytest.mark.parametrize("p", [1, 3, 7, 15])
def test_float_first_integral_inside_its_bound(p):
    """first_integral (float64) against the exact value at the same binary inputs (Fractions), within the
    docstring's bound 2e-15 (p+1) s^p sum_i |gamma_i| sum_k |a_ik|."""
    rng = np.random.default_rng(16 + p)
    d = 0.5
    coefficients = sf.first_integral_coefficients(p, d)
    for _ in range(20):
        w1, w2 = rng.normal(size=2)
        g = rng.normal(size=3)
        g /= np.linalg.norm(g)
        value = float(sf.first_integral(p, d, w1, w2, *g))
        W1, W2, G = Fraction(w1), Fraction(w2), [Fraction(x) for x in g]
        exact = sum(G[i] * sum(a * W1 ** (p - k) * W2 ** k for k, a in enumerate(coefficients[f"P{i + 1}"]))
                    for i in range(3))
        s = max(abs(w1), abs(w2))
        bound = 2e-15 * (p + 1) * s**p * sum(abs(x) for x in g) * max(
            sum(abs(float(a)) for a in coefficients[f"P{i + 1}"]) for i in range(3))
        assert abs(value - float(exact)) <= bound


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="I11"):
        scattering_angle_enclosure(0, 1, "0.3", "0.5")
    with pytest.raises(ValueError, match="principal axis"):
        scattering_angle_enclosure(2, 1, 0, 0)
    with pytest.raises(ValueError, match="digits"):
        ss_angle_enclosure(*omega_pd(arb(1), arb(1)), digits=0)
    with pytest.raises(ValueError, match="not a decimal"):
        to_arb("I13", "0.3x")
    with pytest.raises(ValueError, match="prec"):
        sf.scattering_angle_ball(2, 1, prec=3)
    with pytest.raises(ValueError, match="d="):
        sf.scattering_angle_ball(2, 0)
    u, v = omega_coefficients("5/4", 1, "3/10", "-1/2")
    assert all(x.is_finite() for x in (*u, *v))


def gamma_basis_ball(t, p, d, bits=256):
    """Balls containing the rows of the certified basis at (t, p, d): the shared recipe on python-flint
    balls (AcbBasisRing), its Fourier form, and the trigonometric series and phase evaluated in arb at the
    exact binary t and d (gamma_basis_mp's formula, no float step anywhere)."""
    from flint import acb

    from suslov.kernel import fourier
    from suslov.recipes.rings import AcbBasisRing

    with ctx.workprec(bits):
        ring = AcbBasisRing(d)
        c = (ring.d**2 + 1).sqrt()
        real, cplx = sf._basis_core(p, ring)
        real_lists = [m.coeffs() for m in real.M]
        complex_lists = [m.coeffs() for m in cplx.M]
        s, k = -real_lists[0][0], complex_lists[1][0]
        rows = [[v / (f * s) for v in comp] for comp, f in zip(real_lists, (1, c, c))]
        rows += [[f * v / k for v in comp] for comp, f in zip(complex_lists, (c, 1, 1))]
        alpha, beta = fourier.to_fourier_acb(rows, p)
        T = to_arb("t", t)
        theta = 2 * (-T).exp().atan()
        phase = p * T / to_arb("d", d)
        cphi, sphi = phase.cos(), phase.sin()

        def series(index):
            return sum((alpha[index, j] * (j * theta).cos() + beta[index, j] * (j * theta).sin()
                        for j in range(p + 1)), acb(0))

        sigma = sf._BASIS_SIGMA[p]
        out = [[None] * 3 for _ in range(3)]
        for j in range(3):
            out[0][j] = series(j).real
            z = series(3 + j)
            out[1][j] = cphi * z.real - sphi * z.imag
            out[2][j] = -sigma * (sphi * z.real + cphi * z.imag)
        return out


@pytest.mark.parametrize("t,p,d", [(0.3, 1, 0.5), (-7.25, 3, 0.5), (2.0, 5, 1.7), (40.0, 7, 0.05), (-1e3, 3, 2.0),
                                   (0.0, 15, 0.2), (123.456, 9, 3.0)])
def test_float_gamma_basis_inside_the_ball_widened_by_its_bound(t, p, d):
    """gamma_basis (float64) inside the ball of the certified basis widened by the docstring's (proven) bound
    1e-14 (p+1)^1.5."""
    balls = gamma_basis_ball(t, p, d)
    value = sf.gamma_basis(t, p, d)
    bound = 1e-14 * (p + 1) ** 1.5
    for i in range(3):
        for j in range(3):
            assert float(balls[i][j].rad()) < 1e-30
            assert abs(float(value[i, j]) - float(balls[i][j].mid())) <= bound, (i, j)


def theorem_52_angle(p, d, dps=60):
    """Delta psi in [0, pi] from Theorem 5.4 in mpmath, cos(Delta psi/2) = cos(pi p/2)/cosh(pi p/(2d)) (independent route)."""
    with mpmath.workdps(dps):
        p, d = mpmath.mpf(p), mpmath.mpf(d)
        angle = 2 * mpmath.acos(mpmath.cos(mpmath.pi * p / 2) / mpmath.cosh(mpmath.pi * p / (2 * d)))
        return 2 * mpmath.pi - angle if angle > mpmath.pi else angle


@pytest.mark.parametrize("I23,p", [("-1/3", 3), ("-1/2", 2), ("-100", "0.01")], ids=["pi", "between", "near0"])
def test_integration_keeps_the_width_of_the_data_at_pi_and_next_to_0(I23, p):
    """I11 = 2, I22 = 1 (d = 1), I13 = 0: p = 1/|I23|; at odd p Delta psi = pi exactly (issue 34)."""
    enclosure = scattering_angle_enclosure("2", "1", "0", I23, dps=30, method="integration")
    assert enclosure.width < 1e-28
    reference = theorem_52_angle(p, 1)
    with mpmath.workdps(60):
        middle = mpmath.mpf(arb(enclosure.angle).mid().str(45, radius=False))
        assert abs(middle - reference) <= float(enclosure.angle.rad()) + mpmath.mpf(10) ** -44


@pytest.mark.parametrize("angle", ["0", "1e-20", "1", "2.5", "pi - 1e-20", "pi"])
def test_angle_from_cosine_and_sine_keeps_the_radius(angle):
    from suslov.kernel.enclosure import _angle_from_both

    with mpmath.workdps(80):
        exact = mpmath.pi - mpmath.mpf("1e-20") if angle == "pi - 1e-20" else (
            +mpmath.pi if angle == "pi" else mpmath.mpf(angle))
        cos_s, sin_s, exact_s = (mpmath.nstr(x, 70) for x in (mpmath.cos(exact), mpmath.sin(exact), exact))
    with ctx.workprec(200):
        radius = arb("1e-40")
        cos_ball = (arb(cos_s) + arb(0, 1) * radius).intersection(arb(0, 1))
        sin_ball = (arb(sin_s) + arb(0, 1) * radius).intersection(arb(0.5, 0.5))
        enclosed = _angle_from_both(cos_ball, sin_ball)
        assert enclosed.overlaps(arb(exact_s))
        assert float(enclosed.rad()) < 1e-38        # the cosine alone would give about 1e-20 at 0 and pi
