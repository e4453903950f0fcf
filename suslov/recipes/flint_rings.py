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
"""
from __future__ import annotations

import flint

INTEGRAL_CTX = flint.fmpz_mpoly_ctx.get(("d", "w1", "w2", "g1", "g2", "g3"), "lex")
BASIS_CTX = flint.fmpq_mpoly_ctx.get(("x", "d", "i"), "lex")


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


class FlintBasisRing:
    """Q[x, d, i]/(i^2 + 1): the ring of ``derivations.sections.meromorphic``."""

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


INTEGRAL_RING = FlintIntegralRing()
BASIS_RING = FlintBasisRing()
