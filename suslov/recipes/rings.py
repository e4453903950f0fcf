"""Run-time ring adapters for the recipes: numeric d, exact (Fraction), mpmath or ball coefficients.

The build's adapters (python-flint, symbolic d) live in ``derivations/core/recipe_rings.py``;
these are the ones the generated module uses.  Each adapter provides exactly the
operations listed in the recipe's docstring.
"""
from __future__ import annotations

from suslov.kernel.sparse import Sparse

__all__ = ["IntegralRing", "AcbBasisRing", "homogeneous_coefficients"]


class IntegralRing:
    """Polynomials in (w1, w2) with coefficients in the number type of ``d`` (Fraction, python-flint fmpq or mpf)."""

    def __init__(self, d):
        self.d = d
        self.one = d ** 0
        self.w1, self.w2 = Sparse.gens(2)

    @staticmethod
    def constant(n):
        return Sparse(2, {(0, 0): n})

    @staticmethod
    def dw1(P):
        return P.derivative(0)

    @staticmethod
    def dw2(P):
        return P.derivative(1)

    @staticmethod
    def divide_w1(P):
        quotient = Sparse(2, {(a - 1, b): c for (a, b), c in P.terms.items() if a >= 1})
        return quotient, all(a >= 1 for a, _ in P.terms)


def homogeneous_coefficients(P, degree: int) -> list:
    """[a_0, ..., a_n]: P = sum a_k w1^(n-k) w2^k (P homogeneous of degree n)."""
    out = [0] * (degree + 1)
    for (a, b), c in P.terms.items():
        if a + b != degree:
            raise ValueError(f"not homogeneous of degree {degree}: monomial w1^{a} w2^{b}")
        out[b] = c
    return out


class AcbBasisRing:
    """Polynomials in x with python-flint ``acb`` ball coefficients (``acb_poly``) for a numeric d.

    Every coefficient the recipe produces is a ball that contains the exact value for this d,
    so the radius bounds the error rigorously: the module's float coefficients need no second
    run at a higher precision.  Precision: ``flint.ctx.prec`` (set by the caller).
    """

    def __init__(self, d):
        import flint

        self._flint = flint
        self.d = flint.arb(d)
        self.i = flint.acb(0, 1)
        self.x = flint.acb_poly([0, 1])

    @staticmethod
    def red(P):
        return P

    @staticmethod
    def dx(P):
        return P.derivative()

    @staticmethod
    def divide_exact(P, Q):
        quotient, remainder = divmod(P, Q)
        return quotient, all(0 in c for c in remainder.coeffs())

    def square_x(self, P):
        return P(self.x**2)

    def rational(self, n: int, q: int):
        return self._flint.arb(n) / q
