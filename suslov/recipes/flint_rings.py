"""Exact ring adapters for the shared recipes of ``suslov.recipes``: python-flint polynomials, symbolic d.

The recipes (``suslov/recipes/integrals.py``, ``suslov/recipes/basis.py``) are written
once with ring operations; here they run on python-flint polynomials with ``d`` as a
variable, so what the build certifies is the recipe itself, for every p, and the
generated module runs the same function on numbers (``suslov/recipes/rings.py``).  The formula catalog
(``suslov.catalog_families``) runs them here too, at run time, to write a family's formula for a p the
tree's build certified (python-flint is part of the core install; no SymPy needed to run them).

* :data:`INTEGRAL_RING`: ``Z[d, w1, w2, g1, g2, g3]`` (``fmpz_mpoly``), fraction-free;
* :data:`BASIS_RING`: ``Q[x, d, i]/(i^2+1)`` (``fmpq_mpoly``, normal form of degree <= 1
  in i after every product that can raise it).

Fast exact primitives of :class:`FlintBasisRing` (the recipe's objects are unchanged: every route
below returns the polynomial the plain one returns, and python-flint's normal form makes the
objects identical, term by term):

* ``mul_red(A, B)`` = ``red(A * B)`` for the large products, by Kronecker substitution
  (:func:`kronecker_mul_red`): in ``Q[x, d, i]/(i^2+1)`` the monomials with ``deg_d + deg_i`` even
  are the polynomials in x and ``j = i d`` (``j^2 = -d^2``), every numerator of the recipe has one
  such parity (``F`` even, ``Fhat`` odd: ``d Fhat`` is even), so ``F * (d Fhat)`` is one product of
  polynomials in (x, j), packed into univariate ``fmpz_poly`` (``x^a j^m -> z^(a S + m)``), whose
  FFT multiplication replaces flint's multivariate product: no terms with i^2 to form and reduce,
  and an output of the size of the result.  Measured at p = 201 (two 20k-term factors, coefficients
  of 1.7k bits, one core): 2.7 s -> 1.3 s (the univariate product 0.97 s; packing, unpacking
  and ``from_dict`` 0.3 s; ``bench/results/basis_construct.md``).  An earlier variant split each
  factor by its power of i and formed the complex product with three products (Karatsuba): 1.7 s.
  Small products keep the plain route (:data:`KRONECKER_MIN_WORK`), and so does a factor of mixed
  parity or of degree > 1 in i.
* ``red(P)`` returns ``P`` itself when it is already of degree <= 1 in i (the division by
  ``i^2 + 1`` would return the same polynomial; 40-60 ms per 80k-term numerator at p = 201);
* ``divide_exact(P, Q)`` tries flint's exact division first (``P / Q``: 2-3x faster than the
  division with remainder, measured 30 ms against 60-100 ms at p = 201) and falls back to
  ``divmod`` when it is not exact (the quotient then is the one ``divmod`` returns, as before);
* ``square_x(P)`` by ``inflate`` (x -> x^2 on the exponents: 14 ms against 63 ms for ``compose``);
* ``exact = True`` and ``mul_i(P)`` = ``red(i * P)`` as ``i P0 - P1`` for ``P = P0 + i P1`` (no i^2 term formed
  and divided out: 60 ms against 100 ms at p = 201): the recipe's exact routes (``suslov/recipes/basis.py``);
* ``mul_red(F, F)``, a square, packs once and lets flint square (0.57 s against 0.90 s for a product of two at
  p = 201); the product is unpacked row by row (one power of x at a time: no ``divmod`` per coefficient).
"""
from __future__ import annotations

from math import lcm

import flint
from flint.utils.flint_exceptions import DomainError

INTEGRAL_CTX = flint.fmpz_mpoly_ctx.get(("d", "w1", "w2", "g1", "g2", "g3"), "lex")
BASIS_CTX = flint.fmpq_mpoly_ctx.get(("x", "d", "i"), "lex")

# len(A) * len(B) from which mul_red packs.  Measured: F * Fhat (x, d and i) gains from ~250k term pairs on
# (p = 31), a product of two numerators' values at x = 0 (d and i only) from ~10k on (p = 51: 0.7 ms either
# way; p = 201: 168 ms -> 10 ms); below 40k term pairs either route takes one or two milliseconds
KRONECKER_MIN_WORK = 40_000


class FlintIntegralRing:
    """Z[d, w1, w2, ...]: the ring of ``derivations.sections.first_integrals``."""

    def __init__(self):
        self.d, self.w1, self.w2 = INTEGRAL_CTX.gens()[:3]
        self.one = INTEGRAL_CTX.constant(1)

    @staticmethod
    def constant(n):
        return INTEGRAL_CTX.constant(n)

    @staticmethod
    def dw1(P):
        return P.derivative("w1")

    @staticmethod
    def dw2(P):
        return P.derivative("w2")

    def divide_w1(self, P):
        quotient, remainder = divmod(P, self.w1)
        return quotient, remainder.is_zero()


def _parity(P):
    """The parity of ``deg_d + deg_i`` shared by all the monomials of ``P``, or None when they differ."""
    parities = {(ed + ei) & 1 for _, ed, ei in P.monoms()}
    return parities.pop() if len(parities) == 1 else None


def _packed(P, parity: int, stride: int):
    """``(den, fmpz_poly)``: ``den d^parity P`` as a polynomial in x and ``j = i d``, packed ``x^a j^m -> z^(a stride + m)``.

    A monomial ``x^a d^b i^e`` with ``b + e + parity`` even is ``(-1)^(m//2) x^a j^m / d^parity``, ``m = b + parity``
    (``j^m = i^m d^m`` and ``i^m = (-1)^(m//2) i^(m mod 2)``, ``e = m mod 2``)."""
    monoms, coefficients = P.monoms(), P.coeffs()
    den = 1
    for c in coefficients:
        if c.q != 1:
            den = lcm(den, int(c.q))
    dense = [0] * ((P.degrees()[0] + 1) * stride)
    for (ex, ed, _), c in zip(monoms, coefficients):
        m = ed + parity
        value = c.p if den == 1 else (c * den).p
        dense[ex * stride + m] = -value if m & 2 else value
    return den, flint.fmpz_poly(dense)


def kronecker_mul_red(A, B, ctx=BASIS_CTX):
    """``A * B`` reduced modulo i^2 + 1 by one univariate integer product, or None when the route does not apply.

    It applies when each factor has one parity of ``deg_d + deg_i`` over all its monomials (``F``, ``Fhat`` and
    every numerator of the basis, its values at x = 0 included; none has more than one).  Then ``d^s A`` (s its
    parity) lies in ``Z[x, j]``, ``j = i d`` (``i^2 = -1`` becomes ``j^2 = -d^2``: the quotient ring is a
    polynomial ring in x and j), the product of the two is one product of polynomials in (x, j), packed by
    Kronecker substitution ``x^a j^m -> z^(a S + m)`` with ``S`` above the product's j-degree (so no two
    monomials share an exponent), and each ``x^a j^m`` of it is ``(-1)^(m//2) x^a i^(m mod 2) d^m``, divided by
    ``d^(s_A + s_B)`` (exactly: every monomial of ``d^(s_A + s_B) A B`` has at least that power of d).
    Denominators are cleared first and divided out at the end.  Factors of degree > 1 in i (not reduced) are
    refused (None) too: the packing reads i^e off the parity.
    """
    if A.degrees()[2] > 1 or B.degrees()[2] > 1:
        return None
    parity_a, parity_b = _parity(A), _parity(B)
    if parity_a is None or parity_b is None:
        return None
    stride = A.degrees()[1] + parity_a + B.degrees()[1] + parity_b + 1
    den_a, packed_a = _packed(A, parity_a, stride)
    # a square packed once: flint squares when both factors are one object (0.57 s against 0.90 s at p = 201)
    den_b, packed_b = (den_a, packed_a) if B is A else _packed(B, parity_b, stride)
    shift = parity_a + parity_b
    terms = {}
    coefficients = (packed_a * packed_b).coeffs()
    for ex in range(-(-len(coefficients) // stride)):   # by rows of one power of x: no divmod per coefficient
        for m, c in enumerate(coefficients[ex * stride:(ex + 1) * stride]):
            if c:
                terms[(ex, m - shift, m & 1)] = -c if m & 2 else c
    product = ctx.from_dict(terms)
    den = den_a * den_b
    return product if den == 1 else product / den


class FlintBasisRing:
    """Q[x, d, i]/(i^2 + 1): the ring of ``derivations.sections.meromorphic``."""

    def __init__(self):
        self.x, self.d, self.i = BASIS_CTX.gens()
        self._i2 = self.i**2 + 1

    def red(self, P):
        if P.degrees()[2] <= 1:
            return P                  # already the normal form (what the division would return)
        return divmod(P, self._i2)[1]

    exact = True    # the recipe may regroup its operations (suslov/recipes/basis.py): the same polynomials

    def mul_i(self, P):
        """``red(i * P)``: for P = P0 + i P1 (reduced), ``i P0 - P1``, with no i^2 term formed and divided out."""
        if P.degrees()[2] > 1:
            return self.red(self.i * P)
        return self.i * P.subs({"i": 0}) - P.derivative("i")   # 60 ms against 100 ms at p = 201 (80k terms)

    def mul_red(self, A, B):
        """``red(A * B)``, packed (:func:`kronecker_mul_red`) when both are large, reduced and of one parity each."""
        if len(A) * len(B) >= KRONECKER_MIN_WORK:
            product = kronecker_mul_red(A, B, BASIS_CTX)
            if product is not None:
                return product
        return self.red(A * B)

    @staticmethod
    def dx(P):
        return P.derivative("x")

    @staticmethod
    def divide_exact(P, Q):
        try:
            return P / Q, True
        except DomainError:
            quotient, remainder = divmod(P, Q)
            return quotient, remainder.is_zero()

    @staticmethod
    def square_x(P):
        return P.inflate([2, 1, 1])

    @staticmethod
    def rational(n: int, q: int):
        return BASIS_CTX.constant(flint.fmpq(n, q))


INTEGRAL_RING = FlintIntegralRing()
BASIS_RING = FlintBasisRing()
