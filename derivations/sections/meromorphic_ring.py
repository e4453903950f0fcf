"""The ring of the meromorphic derivation: Q[x, d, i]/(i^2 + 1) and the basis record (sections 5.1, 6.1).

Shared by :mod:`derivations.sections.meromorphic` (the certificates per odd p) and
:mod:`derivations.sections.meromorphic_printed` (the comparisons with the paper's printed forms), so that
neither imports the other.  Numerators live in python-flint ``fmpq_mpoly`` over (x, d, i) reduced
modulo i^2 + 1; the operators are the shared recipe's (``suslov.recipes.basis``) in this ring.
``eq:genhipprep`` (the third-order equation) appears as :func:`third_order_residual`.
"""
from __future__ import annotations

from dataclasses import dataclass

import flint

from derivations.core.recipe_rings import BASIS_CTX as CTX
from derivations.core.recipe_rings import BASIS_RING
from suslov.recipes import basis as recipe
from suslov.recipes.basis import Solution

RING = BASIS_RING
X, D, I = CTX.gens()
ONE = CTX.constant(1)
I2 = I**2 + 1
DOMAIN = "Q[x,d,i]/(i^2+1) (`python-flint` `fmpq_mpoly`; numerators over $(1+x^2)^p$)"
ZCTX = flint.fmpq_mpoly_ctx.get(("z", "d"), "lex")
ZV, ZD = ZCTX.gens()


def red(poly):
    """Normal form modulo i^2 + 1 (i-degree <= 1)."""
    return divmod(poly, I2)[1]


def conj(poly):
    return red(poly.compose(X, D, -I))


def at_x(poly, value: int):
    return poly.compose(CTX.constant(value), D, I)


def DD(N, p: int, rate: int, q: int | None = None):
    """d * numerator of D(e^{i r t} N/(1+x^2)^q) over (1+x^2)^(q+1) (the recipe's operator)."""
    return recipe.DD(N, p, rate, RING, q)


def third_order_residual(N, p: int, rate: int):
    """d^4 (1+x^2)^(p+4) times eq:genhipprep applied to g1 = e^{i rate (p/d) t} N/(1+x^2)^p.

    With w1 = (p/d)(x^2-1)/(1+x^2) and w2^2 = 4 p^2 (d^2+1) x^2/(d^2 (1+x^2)^2) the
    coefficients a'ss become the polynomial factors below (derived by hand from
    a'ss and checked by the certificates of ``derivations.sections.hypergeometric``).
    """
    G0 = N
    G1 = DD(G0, p, rate, p)
    G2 = DD(G1, p, rate, p + 1)
    G3 = DD(G2, p, rate, p + 2)
    e = D**2 + 1
    u = X**2 - 1
    v = 1 + X**2
    return red(e * p**3 * u * G3 + D * p**3 * e * (2 * u**2 - 4 * X**2) * G2
               + e * p**3 * u * ((D**2 + p * p) * u**2 + 4 * p * p * e * X**2) * G1
               - 4 * p**5 * e**2 * D * X**2 * v**2 * G0)


def gamma1_numerator(p: int):
    return recipe.gamma1_numerator(p, RING)


def hypergeometric_polynomials(p: int):
    return recipe.hypergeometric_polynomials(p, RING)


def in_y_squared(poly):
    """poly(y) -> poly(x^2)."""
    return RING.square_x(poly)



@dataclass
class Basis:
    p: int
    real: Solution
    complex_: Solution
    k: object            # V2 numerator at x = 0 (complex constant in Q(d)(i))
    scale_real: object   # the numerators of gamma^(1) are over scale_real (1+x^2)^p
    sigma: int           # V3(0) = i sigma V2(0)
    certificates: list


