"""sigma = -1 for every odd p, certified before any basis beyond the kept ones is built (``meromorphic_sigma.sigma_certificate``).

The module is emitted with ``_BASIS_SIGMA`` before the round trip certifies the bases of p > 15 on its own core, so
sigma comes from a general certificate: the recipe's ``complete`` run with p and d symbolic on ``g1 = x P(x^2)``
gives ``V3(0) = -i V2(0)``.  Checked here against what does not share that code path: the numerators of
``construct(p)`` in python-flint at x = 0 for several p (and ``F(0)``, ``Fhat(0)``, which make ``V2(0)`` non-zero),
and the certificate must fail on inputs that do not satisfy its identities (the conjugate solution, whose sigma is
+1, and a value changed by hand).
"""
import pytest
import sympy as sp

from derivations.core.certificates import CertificateLog, CertificationFailure, Outcome
from derivations.sections import meromorphic, meromorphic_sigma
from derivations.sections.meromorphic_ring import RING, D, I, at_x, red
from suslov.recipes import basis as recipe


def test_sigma_certificate_passes_and_says_minus_one():
    cert = meromorphic.sigma_certificate(CertificateLog(derivation="meromorphic"))
    assert cert.outcome is Outcome.PASS and cert.label == "asymp"
    assert "sigma = -1" in cert.claim and str(cert.detail) == "2 identities, 5 terms reduced to 0"
    assert meromorphic.SIGMA == -1


@pytest.mark.parametrize("p", [1, 5, 9, 17])
def test_the_values_at_zero_are_those_of_the_constructed_basis(p):
    """Independent route: the numerators of construct(p) (python-flint, d symbolic) at x = 0."""
    real, cplx = meromorphic.construct(p)
    F, Fhat = recipe.hypergeometric_polynomials(p, RING)
    F0, Fhat0 = at_x(F, 0), at_x(Fhat, 0)
    V2, V3 = at_x(cplx.M[1], 0), at_x(cplx.M[2], 0)
    assert red(V3 + I * V2).is_zero()                                   # V3(0) = -i V2(0): sigma = -1
    assert red(V2 - I * p * (D + I * p) * F0 * Fhat0).is_zero()          # V2(0) = i p (d + i p) P(0)
    # V2(0) is not zero: F(0) = prod_j ((3+2j)^2 d^2 + p^2) and Fhat(0) = -(d + i p) F(0)
    product = 1 + 0 * D
    for j in range((p - 1) // 2):
        product *= (3 + 2 * j) ** 2 * D**2 + p * p
    assert F0 == product and red(Fhat0 + (D + I * p) * F0).is_zero() and not V2.is_zero()


def test_sigma_certificate_fails_on_the_conjugate_solution():
    """e^{-i(p/d)t}: the recipe's complete with rate -1 gives V3(0) = +i V2(0) (sigma = +1); the identities fail."""
    x, p, d, P0, i = sp.symbols("x p d P0 i")
    S = sp.Function("S")
    solution = recipe.complete(x * (P0 + x**2 * S(x)), p, -1, meromorphic_sigma._JetRing(x, d, i))
    V2, V3 = (sp.expand(m.subs(x, 0)) for m in solution.M[1:])
    assert sp.expand((V3 - i * V2).subs(i, sp.I)) == 0                  # sigma = +1 there, by hand
    with pytest.raises(CertificationFailure):
        meromorphic.sigma_certificate(CertificateLog(), (V2, V3, p, d, i, P0))


def test_sigma_certificate_fails_on_a_changed_value():
    V2, V3, p, d, i, P0 = meromorphic.sigma_values()
    assert sp.expand(V3 - p * P0 * (d + i * p)) == 0                    # V3(0) = p P(0) (d + i p), by hand
    for values in ((V2, -V3, p, d, i, P0), (V2 + P0 * p, V3, p, d, i, P0)):
        with pytest.raises(CertificationFailure):
            meromorphic.sigma_certificate(CertificateLog(), values)
