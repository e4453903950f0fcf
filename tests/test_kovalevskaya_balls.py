"""kovalevskaya_exponents' round-trip certificate (issue 34): ball enclosures of the eigenvalues of the certified
Kovalevskaya matrix K, not mpmath's QR at 30 digits.  It passes on the module, and fails when the exponents are
moved by 1e-8 (beyond the stated 1e-9); the fallback through the characteristic polynomial encloses the double
exponent -1 of a body with p = 2, where Arb cannot isolate the eigenvalues."""
import flint
import numpy as np
import pytest
import sympy as sp

from derivations.core.certificates import CertificateLog, CertificationFailure, Outcome
from derivations.core.options import BuildOptions
from derivations.core.symbols import I11, I13, I22, I23
from derivations.output import kovalevskaya_balls as kb
from derivations.output.pipeline import derive
from generated import suslov_formulas as sf


@pytest.fixture(scope="module")
def K():
    return derive(BuildOptions(jobs=1), ["model", "kovalevskaya"]).results["kovalevskaya"].exports["matrix"]


def test_the_certificate_passes(K):
    certificate = kb.check_kovalevskaya_exponents(CertificateLog(derivation="test"), sf, K)
    assert certificate.outcome is Outcome.PASS and certificate.work == 8


def test_moved_exponents_fail(K):
    class Moved:
        canonical_frame = staticmethod(sf.canonical_frame)

        @staticmethod
        def kovalevskaya_exponents(body):
            return sf.kovalevskaya_exponents(body) + 1e-8

    with pytest.raises(CertificationFailure):
        kb.check_kovalevskaya_exponents(CertificateLog(derivation="test"), Moved, K)


def test_double_exponent_through_the_characteristic_polynomial(K):
    # I13 = 0, p = 2 exactly in rationals: exponents -1, 1, 2, 1 + 2, 1 - 2 (= -1 twice)
    d = sp.Rational(1, 2)          # I22 = 1, I11 = I22 (d^2 + 1), I23 = -I22 d/p
    assert (d**2 + 1, -d / 2) == (sp.Rational(5, 4), sp.Rational(-1, 4))
    with flint.ctx.workprec(200):
        values = {I11: flint.acb(flint.fmpq(5, 4)), I22: flint.acb(1), I13: flint.acb(0),
                  I23: flint.acb(flint.fmpq(-1, 4)), sp.Symbol("r"): flint.acb(flint.fmpq(5, 4)).sqrt()}
        matrix = flint.acb_mat([[kb._acb_of(K[i, j], values) for j in range(5)] for i in range(5)])
        balls = kb._eigenvalue_balls(matrix)
        expected = sorted([-1, -1, 1, 2, 3])
        for want in expected:
            assert any(ball.contains(want) for ball in balls), (want, balls)
        assert sorted(np.round([float(b.real.mid()) for b in balls], 9)) == expected


def test_meromorphy_certificate_passes_and_fails_for_a_moved_p_squared(K):
    certificate = kb.check_meromorphy(CertificateLog(derivation="test"), sf, K)
    assert certificate.outcome is Outcome.PASS and certificate.work == 4

    class Moved:
        canonical_frame = staticmethod(sf.canonical_frame)
        kovalevskaya_exponents = staticmethod(sf.kovalevskaya_exponents)

        @staticmethod
        def meromorphy(body):
            result = sf.meromorphy(body)
            return type("M", (), {"p_squared": complex(result.p_squared) * (1 + 1e-11)})()

    with pytest.raises(CertificationFailure):
        kb.check_meromorphy(CertificateLog(derivation="test"), Moved, K)


def test_lambda_squared_ball_against_the_closed_form(K):
    # I13 = 0: Lambda^2 = p^2 = I22 (I11 - I22)/I23^2 at the canonical entries (eq:necc1's case), in exact rationals
    body = [[2.0, 0, 0], [0, 1.0, 0.5], [0, 0.5, 1.5]]
    from fractions import Fraction
    e11, e22, e13, e23 = (Fraction(float(v)) for v in sf.canonical_frame(body)[1])
    assert e13 == 0
    exact = e22 * (e11 - e22) / e23**2
    with flint.ctx.workprec(200):
        ball = kb.lambda_squared_ball(sf, body, K)
        assert ball.contains(flint.acb(flint.fmpq(exact.numerator, exact.denominator)))
        assert ball.rad() < 1e-40


def test_meromorphy_cases_certificate_passes_and_fails_for_a_wrong_decision(K):
    certificate = kb.check_meromorphy_cases(CertificateLog(derivation="test"), sf, K)
    assert certificate.outcome is Outcome.PASS and certificate.work == 9

    class Loose:                      # oddness with a tolerance of 0.6: p = 2.5 and 0.5 "odd"
        canonical_frame = staticmethod(sf.canonical_frame)
        kovalevskaya_exponents = staticmethod(sf.kovalevskaya_exponents)

        @staticmethod
        def meromorphy(body):
            result = sf.meromorphy(body)
            odd = 2 * round((result.p - 1) / 2) + 1 if result.p is not None else None   # the nearest odd integer
            loose = odd is not None and abs(result.p - odd) <= 0.6
            return result._replace(odd=loose)

    with pytest.raises(CertificationFailure):
        kb.check_meromorphy_cases(CertificateLog(derivation="test"), Loose, K)


def test_a_decision_at_its_tolerance_edge_is_not_clear(K):
    # p = 3: distance ~1e-16 against tol * p = 3e-9, clear; p = 3 + 3e-9 sits on the edge tol * p (within 1e-12)
    d, I22 = 0.5, 1.3
    for p, clear_expected in ((3.0, True), (3.0 + 3e-9, False)):
        I23 = -I22 * d / p
        body = [[I22 * (d * d + 1), 0, 0], [0, I22, I23], [0, I23, I22 * (d / p) ** 2 + 1.0]]
        with flint.ctx.workprec(200):
            clear = kb._exact_decision(sf, body, K, 1e-9)[3]
        assert clear is clear_expected, p
