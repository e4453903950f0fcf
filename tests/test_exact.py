"""The exact zero test: identities pass, non-identities fail, extensions cover both roots."""
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from derivations.core.certificates import CertificateLog, CertificationFailure, Outcome
from derivations.core.differential import S, T, hyperbolic_ring
from derivations.core.exact import (
    Domain,
    Extension,
    certify_zero,
    is_identically_zero,
    normal_form,
)

x, y, d, c = sp.symbols("x y d c")
C_EXT = Extension(c, d**2 + 1, "c = sqrt(d^2+1)")
QD = Domain("Q(d)[c]", (C_EXT,))
PLAIN = Domain("Q(x, y)")


def test_rational_identity_and_non_identity():
    assert is_identically_zero((x**2 - y**2) / (x - y) - (x + y), PLAIN)
    assert not is_identically_zero((x**2 - y**2) / (x - y) - (x - y), PLAIN)


def test_extension_relation_is_used_for_both_roots():
    # c^2 - d^2 - 1 = 0 holds for c = +sqrt and c = -sqrt alike
    assert is_identically_zero(c**4 - (d**2 + 1) ** 2, QD)
    assert is_identically_zero((c - d) * (c + d) - 1, QD)
    # odd in c: not an identity (it would need a chosen root)
    assert not is_identically_zero(c**3 - (d**2 + 1), QD)


def test_imaginary_unit_is_an_extension():
    assert is_identically_zero(sp.I**2 + 1, PLAIN)
    assert not is_identically_zero(sp.I * x - x, PLAIN)


def test_tanh_sech_ring_derivatives():
    ring = hyperbolic_ring("Q[T][S]")
    # d/dt tanh = sech^2 = 1 - tanh^2 and the relation reduces S^2
    assert is_identically_zero(ring.d_dt(T) - (1 - T**2), ring.domain)
    # d/dt (S^2 + T^2) = 0
    assert is_identically_zero(ring.d_dt(S**2 + T**2), ring.domain)
    assert not is_identically_zero(ring.d_dt(S) - S * T, ring.domain)


def test_functions_are_rejected_not_passed():
    log = CertificateLog()
    cert = certify_zero(log, "tanh identity", "test", sp.tanh(x) - sp.tanh(x) + sp.sin(x), PLAIN,
                        expect=Outcome.UNKNOWN)
    assert cert.outcome is Outcome.UNKNOWN


def test_fractional_powers_are_unknown_not_dropped():
    """sqrt(x) - 1 once passed: the polynomial reader took int(1/2) = 0 as the exponent."""
    log = CertificateLog()
    for expr in (sp.sqrt(x) - 1, x ** sp.Rational(3, 2) - x, 1 / sp.sqrt(x + y) - 1):
        cert = certify_zero(log, "a fractional power", "test", expr, PLAIN, expect=Outcome.UNKNOWN)
        assert cert.outcome is Outcome.UNKNOWN and "not a polynomial" in cert.detail


def test_unexpected_outcome_raises_and_names_the_claim():
    log = CertificateLog()
    try:
        certify_zero(log, "x equals y", "eq:test", x - y, PLAIN)
    except CertificationFailure as failure:
        assert "x equals y" in str(failure) and "eq:test" in str(failure)
    else:
        raise AssertionError("a false claim passed")


def test_vanishing_denominator_is_unknown():
    log = CertificateLog()
    cert = certify_zero(log, "0/0", "test", sp.Mul(x, sp.Pow(c**2 - d**2 - 1, -1), evaluate=False), QD,
                        expect=Outcome.UNKNOWN)
    assert cert.outcome is Outcome.UNKNOWN


small = st.integers(min_value=-5, max_value=5)


@settings(max_examples=40, deadline=None)
@given(st.lists(small, min_size=3, max_size=3), st.lists(small, min_size=3, max_size=3), small)
def test_products_expand_to_identities_and_perturbations_fail(a, b, k):
    """(sum a_i x^i)(sum b_j c^j) expanded equals the product; adding k*x*c breaks it unless k == 0."""
    f = sum(ai * x**i for i, ai in enumerate(a))
    g = sum(bj * c**j for j, bj in enumerate(b))
    product = sp.expand(f * g)
    assert is_identically_zero(product - f * g, QD)
    assert is_identically_zero(product - f * g + k * x * c, QD) == (k == 0)


def test_normal_form_counts_terms():
    form = normal_form(x**2 + 2 * x * y + y**2 - (x + y) ** 2, PLAIN)
    assert form.is_zero and form.terms_tested >= 1


def test_cancelled_is_sympy_cancel():
    """cancelled() skips SymPy's gcds only where the canonical test says zero; the object equals sympy.cancel's."""
    import sympy as sp

    from derivations.core.exact import Domain, cancelled

    x, y = sp.symbols("x y")
    for expr in ((x**2 - y**2) / (x - y) - x - y,              # zero
                 (x**2 - y**2) / (x - y) - x,                  # y, after a gcd
                 (x + sp.I * y) / (x**2 + y**2) - 1 / (x - sp.I * y),   # zero over Q(i)
                 1 / (x + 1) + 1 / (x - 1)):
        assert sp.srepr(cancelled(expr, Domain("Q(x,y)[i]"))) == sp.srepr(sp.cancel(expr))
