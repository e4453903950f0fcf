"""The ring of the meromorphic derivation: Q[x, d, i]/(i^2 + 1) and the basis record (sections 5.1, 6.1).

Shared by :mod:`derivations.sections.meromorphic` (the certificates per odd p) and
:mod:`derivations.sections.meromorphic_printed` (the comparisons with the paper's printed forms), so that
neither imports the other.  Numerators live in python-flint ``fmpq_mpoly`` over (x, d, i) reduced
modulo i^2 + 1; the operators are the shared recipe's (``suslov.recipes.basis``) in this ring.
``eq:genhipprep`` (the third-order equation) appears as :func:`third_order_residual`.

The certificates' zero tests (:func:`third_order_holds`, and ``poisson_hold`` in
:mod:`derivations.sections.meromorphic`) compute the same residuals in coordinates: a numerator
``P = P0 + i P1`` (P0, P1 in Q[x, d]) as the pair ``(P0, P1)`` (:func:`split_i`), ``DD`` on the pair
(:func:`DD_split`: i times P is ``(-P1, P0)``, so no product raises the degree in i and no division by
``i^2 + 1`` is needed), the common factor ``(d^2+1) p^3`` of the third-order residual left out
(Q(i)[x, d] is an integral domain and the factor is not zero), and each identity ``A + B = C``
tested as the equality of the two sides of each coordinate (no difference formed).  Exact, the same
zero/non-zero answer; measured at p = 201 (one core, ``bench/results/basis_construct.md``): third order
1.6 s -> 1.1 s, the six Poisson equations 1.9 s -> 1.1 s (the first Poisson equation of the complex
solution reuses the third order's first derivative ``DD(N)``, the same polynomial).  The arithmetic
itself is not cheaper per term (``fmpz_mpoly`` in (x, j = i d) was measured too: the same time for the
tests, plus 0.8 s to convert); the gain is the operations not done.
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
ZERO = CTX.constant(0)
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
    """``poly`` at ``x = value`` (``subs``: the polynomial ``compose`` returns, in half the time)."""
    return poly.subs({"x": value})


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


def split_i(poly) -> tuple:
    """``(P0, P1)`` with ``poly = P0 + i P1``, P0 and P1 free of i (``poly`` of degree <= 1 in i)."""
    if poly.degrees()[2] <= 0:
        return poly, ZERO
    if poly.degrees()[2] > 1:
        raise ArithmeticError("split_i: a numerator of degree > 1 in i (not reduced modulo i^2 + 1)")
    return poly.subs({"i": 0}), poly.derivative("i")


def DD_split(parts: tuple, p: int, rate: int, q: int | None = None) -> tuple:
    """:func:`DD` on ``(N0, N1)`` (N = N0 + i N1): the pair of its real and imaginary coordinates.

    ``DD(N) = d (x (1+x^2) N' - 2 q x^2 N) + rate i p (1+x^2) N`` and ``i N = -N1 + i N0``.
    """
    q = p if q is None else q
    slope, level = D * X * (1 + X**2), 2 * q * D * X**2

    def base(part):
        return part if part.is_zero() else slope * part.derivative("x") - level * part

    N0, N1 = parts
    base0, base1 = base(N0), base(N1)
    if not rate:
        return base0, base1
    w = rate * p * (1 + X**2)
    return base0 - w * N1, base1 + w * N0


def third_order_holds(N, p: int, rate: int, first: tuple | None = None, parts: tuple | None = None) -> bool:
    """``third_order_residual(N, p, rate).is_zero()``, computed in coordinates (see the module docstring).

    The residual is ``(d^2+1) p^3 (u G3 + c2 G2 + c1 G1 - c0 G0)``; the bracket is tested, coordinate by
    coordinate, as ``u G3 + c2 G2 + c1 G1 == c0 G0``.  ``first``: ``DD_split(split_i(N), p, rate)`` when the
    caller has it already, ``parts`` likewise ``split_i(N)``.
    """
    G0 = split_i(N) if parts is None else parts
    G1 = DD_split(G0, p, rate, p) if first is None else first
    G2 = DD_split(G1, p, rate, p + 1)
    G3 = DD_split(G2, p, rate, p + 2)
    e = D**2 + 1
    u = X**2 - 1
    v = 1 + X**2
    c2 = D * (2 * u**2 - 4 * X**2)
    c1 = u * ((D**2 + p * p) * u**2 + 4 * p * p * e * X**2)
    c0 = 4 * p**2 * e * D * X**2 * v**2
    return all(u * g3 + c2 * g2 + c1 * g1 == c0 * g0 for g0, g1, g2, g3 in zip(G0, G1, G2, G3))


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


