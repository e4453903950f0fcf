"""x = e^t substitution (issue 34): the exact routes that replaced the mpmath.diff spot checks refute seeded errors."""
import mpmath
import sympy as sp

from derivations.core.certificates import CertificateLog, Outcome
from derivations.core.differential import S, T
from derivations.core.exp_substitution import COS, SIN, X, certify_ode_in_exp, d_dt, in_exp
from derivations.sections import printed_examples as pe

y = sp.Symbol("y")


def test_tanh_solves_the_riccati_equation_and_a_wrong_field_is_refuted():
    log = CertificateLog(derivation="test")
    good = certify_ode_in_exp(log, "tanh' = 1 - tanh^2", "test", [T], [1 - y**2], [y], "Q(x)")
    bad = certify_ode_in_exp(log, "tanh' = 1 + tanh^2", "test", [T], [1 + y**2], [y], "Q(x)", expect=Outcome.FAIL)
    assert good.outcome is Outcome.PASS and bad.outcome is Outcome.FAIL


def test_substitution_agrees_with_mpmath():
    with mpmath.workdps(30):
        t = mpmath.mpf("0.37")
        value = sp.lambdify(X, in_exp(T * S + S**2))(mpmath.exp(t))
        assert abs(value - (mpmath.tanh(t) * mpmath.sech(t) + mpmath.sech(t) ** 2)) < 1e-28
        assert d_dt(COS, 3) == -3 * SIN and d_dt(SIN, 3) == 3 * COS


def test_printed_rows_with_a_seeded_sign_error_are_refuted():
    from derivations.core.exact import certify_zero

    log = CertificateLog(derivation="test")
    P = pe.printed_rows(1)
    assert certify_zero(log, "printed p = 1 rows solve eq:ps", "test", pe.poisson_residuals(P, 1),
                        pe.DOMAIN).outcome is Outcome.PASS
    P[1, 0] = -P[1, 0]
    assert certify_zero(log, "seeded", "test", pe.poisson_residuals(P, 1), pe.DOMAIN,
                        expect=Outcome.FAIL).outcome is Outcome.FAIL


def test_printed_rows_match_the_mpmath_transcription():
    from derivations.core import paper

    for p in (1, 3):
        P = pe.printed_rows(p)
        with mpmath.workdps(30):
            t, d = mpmath.mpf("0.41"), mpmath.mpf("0.8")
            values = {X: mpmath.exp(t), pe.d_: d, pe.c_: mpmath.sqrt(d * d + 1),
                      COS: mpmath.cos(p * t / d), SIN: mpmath.sin(p * t / d)}
            reference = paper.printed_example(p, t, d)
            for i in range(3):
                for j in range(3):
                    got = sp.lambdify(list(values), P[i, j], "mpmath")(*values.values())
                    assert abs(got - reference[i][j]) < 1e-25


def test_laurent_limit_refutes_a_wrong_residue():
    from derivations.core.symbols import c, d, p
    from derivations.sections.special_case import _laurent_limit, poisson_matrix

    log = CertificateLog(derivation="test")
    A = poisson_matrix(p / d * T, -p / d * c * S)
    A0 = sp.Matrix([[0, 0, -sp.I * p * c / d], [0, 0, p / d], [sp.I * p * c / d, -p / d, 0]])   # eq:am2
    assert _laurent_limit(log, A, A0).outcome is Outcome.PASS
    wrong = A0.copy()
    wrong[1, 2] = -wrong[1, 2]
    from derivations.core.certificates import CertificationFailure
    import pytest
    with pytest.raises(CertificationFailure):
        _laurent_limit(log, A, wrong)
