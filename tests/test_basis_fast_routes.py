"""The fast exact routes of the meromorphic basis (issue: the exact basis at large p) return what the plain ones do.

* ``FlintBasisRing.mul_red`` (Kronecker substitution in x and j = i d), ``red`` (no division when already
  reduced), ``divide_exact`` (exact division first), ``square_x`` (``inflate``): the same polynomials as
  the plain adapter below (a copy of the adapter before them), so the recipe builds the same objects;
* a ring without ``mul_red`` (the module's ball ring) gets ``red(A * B)``, its arithmetic unchanged;
* ``third_order_holds`` and ``poisson_hold`` (in coordinates) answer as the residuals' zero tests do, and
  a perturbed numerator is caught by both routes, with the certificate's size the residual's;
* ``numerators_digest``: the bytes hashed are those of the plain implementation below.
"""
import hashlib
import random
from array import array
from itertools import chain

import flint
import pytest

from derivations.core.certificates import CertificateLog, Outcome
from derivations.core.recipe_rings import BASIS_CTX, BASIS_RING
from derivations.sections import meromorphic
from derivations.sections.meromorphic_ring import (
    DD_split,
    split_i,
    third_order_holds,
    third_order_residual,
)
from suslov.recipes import basis as recipe
from suslov.recipes.flint_rings import kronecker_mul_red

X, D, I = BASIS_CTX.gens()


class PlainRing:
    """The exact basis ring as it was before the fast routes (divisions with remainder, compose, no mul_red)."""

    def __init__(self):
        self.x, self.d, self.i = BASIS_CTX.gens()
        self._i2 = self.i**2 + 1

    def red(self, P):
        return divmod(P, self._i2)[1]

    @staticmethod
    def dx(P):
        return P.derivative("x")

    @staticmethod
    def divide_exact(P, Q):
        quotient, remainder = divmod(P, Q)
        return quotient, remainder.is_zero()

    def square_x(self, P):
        return P.compose(self.x**2, self.d, self.i)

    @staticmethod
    def rational(n: int, q: int):
        return BASIS_CTX.constant(flint.fmpq(n, q))


def plain_digest(real_M, complex_M) -> str:
    """numerators_digest as first written (one string per numerator and per denominator list)."""
    digest = hashlib.sha256()
    for poly in list(real_M) + list(complex_M):
        digest.update(array("q", [len(poly), *chain.from_iterable(poly.monoms())]).tobytes())
        coefficients = poly.coeffs()
        digest.update(",".join([c.p.str(16) for c in coefficients]).encode())
        digest.update(b"/")
        digest.update(",".join([c.q.str(16) for c in coefficients]).encode())
        digest.update(b";")
    return digest.hexdigest()


def random_poly(rng, terms: int, parity=None, rational=False, big=80):
    """A polynomial in (x, d, i) of degree <= 1 in i; ``parity``: that of deg_d + deg_i for every monomial."""
    out = {}
    for _ in range(terms):
        a, b, e = rng.randrange(12), rng.randrange(15), rng.randrange(2)
        if parity is not None and (b + e) % 2 != parity:
            b += 1
        numerator = rng.randint(-(2**big), 2**big)
        out[(a, b, e)] = flint.fmpq(numerator, rng.choice([1, 3, 2**70 + 1])) if rational else numerator
    return BASIS_CTX.from_dict({k: v for k, v in out.items() if v})


@pytest.mark.parametrize("seed", range(12))
def test_kronecker_product_is_the_reduced_product(seed):
    rng = random.Random(seed)
    for parity_a in (0, 1):
        for parity_b in (0, 1):
            A = random_poly(rng, rng.choice([1, 5, 200]), parity_a, rational=seed % 3 == 0)
            B = random_poly(rng, rng.choice([1, 7, 300]), parity_b, rational=seed % 4 == 0)
            expected = BASIS_RING.red(A * B)
            assert kronecker_mul_red(A, B) == expected
            assert BASIS_RING.mul_red(A, B) == expected


def test_mixed_parity_unreduced_and_small_factors_take_the_plain_route():
    rng = random.Random(7)
    A = random_poly(rng, 300)            # both parities
    B = random_poly(rng, 300, 1)
    assert kronecker_mul_red(A, B) is None
    assert BASIS_RING.mul_red(A, B) == BASIS_RING.red(A * B)
    unreduced = random_poly(rng, 300, 0) + I**2 * D**2 * X   # i^2 would be read as 1: refused
    assert kronecker_mul_red(unreduced, B) is None
    assert BASIS_RING.mul_red(unreduced, B) == BASIS_RING.red(unreduced * B)
    zero = BASIS_CTX.constant(0)
    assert BASIS_RING.mul_red(zero, B) == zero and BASIS_RING.mul_red(X + I, D) == BASIS_RING.red((X + I) * D)


def test_the_ring_primitives_agree_with_the_plain_ones():
    plain = PlainRing()
    rng = random.Random(3)
    P = random_poly(rng, 400)
    Q = P * I + D * P                  # degree 2 in i
    for poly in (P, Q, BASIS_CTX.constant(0), BASIS_CTX.constant(5)):
        assert BASIS_RING.red(poly) == plain.red(poly)
        assert BASIS_RING.square_x(poly) == plain.square_x(poly)
    for divisor in (X, X**2 - 1):
        assert BASIS_RING.divide_exact(P * divisor, divisor) == plain.divide_exact(P * divisor, divisor)
        assert BASIS_RING.divide_exact(P * divisor + 1, divisor) == plain.divide_exact(P * divisor + 1, divisor)
        assert BASIS_RING.divide_exact(P * divisor + 1, divisor)[1] is False


@pytest.mark.parametrize("p", [1, 3, 7, 21, 33])
def test_construct_gives_the_objects_of_the_plain_ring(p):
    """21 and 33: F * Fhat above the packing threshold."""
    fast, plain = recipe.construct(p, BASIS_RING), recipe.construct(p, PlainRing())
    for a, b in zip(fast, plain):
        assert a.divisions_exact and b.divisions_exact
        assert all(m.monoms() == n.monoms() and m.coeffs() == n.coeffs() for m, n in zip(a.M, b.M))


def test_a_ring_without_mul_red_gets_red_of_the_product():
    calls = []

    class Ring(PlainRing):
        def red(self, P):
            calls.append(len(P))
            return super().red(P)

    F, Fhat = recipe.hypergeometric_polynomials(5, PlainRing())
    assert recipe.mul_red(F, Fhat, Ring()) == PlainRing().red(F * Fhat)
    assert calls == [len(F * Fhat)]


@pytest.fixture(scope="module")
def basis13():
    return recipe.construct(13, BASIS_RING)


def perturbed(sol, index, delta):
    M = list(sol.M)
    M[index] = M[index] + delta
    return recipe.Solution(sol.p, sol.rate, M)


def test_third_order_in_coordinates_answers_as_the_residual(basis13):
    _, cplx = basis13
    N = cplx.M[0]
    for candidate, rate in ((N, 1), (N, -1), (N + X**3, 1), (N + I * D * X, 1), (N + 7 * D**40 * X**5, 1)):
        expected = third_order_residual(candidate, 13, rate).is_zero()
        assert third_order_holds(candidate, 13, rate) is expected
        assert third_order_holds(candidate, 13, rate, DD_split(split_i(candidate), 13, rate)) is expected
    assert third_order_holds(N, 13, 1) and not third_order_holds(N + X**3, 13, 1)


@pytest.mark.parametrize("index", [0, 1, 2])
@pytest.mark.parametrize("delta", [X**3, I * D, 5 * X**26 * D**3])
def test_poisson_in_coordinates_answers_as_the_residuals(basis13, index, delta):
    for sol in basis13:
        assert meromorphic.poisson_hold(sol)
        bad = perturbed(sol, index, delta)
        assert all(r.is_zero() for r in meromorphic.poisson_residuals(bad)) is False
        assert meromorphic.poisson_hold(bad) is False


def test_a_perturbed_numerator_fails_its_certificates_with_the_residual_size(monkeypatch):
    p = 17
    real, cplx = recipe.construct(p, BASIS_RING)
    bad_cplx = perturbed(cplx, 0, X**5 * D)
    monkeypatch.setattr(meromorphic, "construct", lambda q: (real, bad_cplx))
    log = CertificateLog(derivation="meromorphic")
    with pytest.raises(meromorphic.CertificationFailure):
        meromorphic.certify_p(log, p)
    third = log.certificates[-1]
    assert third.label == "F_23_pol" and third.outcome is Outcome.FAIL
    assert third.work == len(third_order_residual(bad_cplx.M[0], p, 1)) > 0


@pytest.mark.parametrize("seed", range(6))
def test_digest_hashes_the_bytes_of_the_plain_implementation(seed):
    rng = random.Random(seed)
    polys = [random_poly(rng, rng.choice([0, 1, 30, 5000]), rational=rng.random() < 0.4, big=rng.choice([10, 3000]))
             for _ in range(6)]
    assert meromorphic.numerators_digest(polys[:3], polys[3:]) == plain_digest(polys[:3], polys[3:])


def test_digest_of_a_basis_is_the_plain_one(basis13):
    real, cplx = basis13
    assert meromorphic.numerators_digest(real.M, cplx.M) == plain_digest(real.M, cplx.M)
