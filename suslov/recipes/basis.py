"""Recipe: numerators of the orthonormal basis of Poisson solutions for odd p (sections 5.1, 6.1).

Labels: ``pol_sol``, ``abc``, ``poly_F``, ``F_23_splitted``, ``F_23_pol``, ``gam1``,
``gam2``, ``gam3`` (Theorem 6.1, corrected), ``eq:gam3``, ``asymp``.

With ``x = e^t`` every solution is ``e^{i r t} N(x)/(1+x^2)^p`` with a polynomial
numerator of degree <= 2p (r = 0 or r = p/d).  Components are kept in the *c-free*
scaling ``(g1, c g2, c g3)``, ``c = sqrt(d^2+1)``, where the Poisson equations with
``omega = ((p/d) tanh t, -(p/d) c sech t)`` have rational coefficients.

* gamma^(1): ``g1 = tanh t F1(sech^2 t)``, numerator
  ``N1 = (x^2 - 1) sum_j e_j d^(2j) Den1_j 4^j x^(2j) (1+x^2)^(p-1-2j)``
  (``Den1_j = prod_{j<=m<J} ((2m+1)^2 d^2 + p^2)``: denominators of c_j cleared).
* the complex solution: ``g1 = e^{+i(p/d)t} x P(x^2)/(1+x^2)^p``, ``P = F Fhat`` with
  ``F = 2F1(a+, b; c+; -y)``, ``a+ = (2-p)/2 + ip/(2d)``, ``b = (1-p)/2``,
  ``c+ = 3/2 + ip/(2d)`` and ``Fhat = [d(p-1)y - d - ip] F - 2d y(y+1) F'``, denominators
  ``prod_j ((3+2j)^2 d^2 + p^2)`` cleared.
* the other components from ``eq:gam3`` in exact form: ``g3~ = D g1 (1+x^2)/(2 a x)`` and
  ``g2~ = (c w2 g1 - D g3~)/w1`` with ``D = x d/dx``; the divisions by ``x`` and by
  ``x^2 - 1`` (zero at t = 0, the removable singularity of the printed ``eq:gam3``) are
  exact polynomial divisions (the build certifies that they are).

The result is ``(2p^2 N1, M2, p M3)`` over ``2p^2 (1+x^2)^p`` for each solution.  The
build certifies, for every odd p in range, the Poisson equations, orthonormality and the
limits of these numerators; the module normalises them by their own values at x = 0
(certified to be the right normalisation) and evaluates them as trigonometric polynomials.

Ring adapter: elements ``x``, ``d``, ``i``; ``dx(P)``; ``red(P)`` (normal form modulo
i^2 + 1, the identity for numeric complex coefficients); ``divide_exact(P, Q) ->
(quotient, exact)`` for Q monic in x; ``square_x(P)`` (x -> x^2); ``rational(n, q)``; optionally
``mul_red(A, B)``, a faster route to ``red(A * B)`` (:func:`mul_red`).  The exact ring of the build
(``suslov.recipes.flint_rings.FlintBasisRing``) provides it for ``F * Fhat``, the largest product of
the recipe (Kronecker substitution: 2.7 s -> 1.3 s at p = 201, the same polynomial;
``bench/bench_basis_construct.py``); a ring
without it (the ball ring of the module, ``suslov.recipes.rings.AcbBasisRing``) runs
``red(F * Fhat)`` exactly as before, so its arithmetic, and every float the module returns, is
unchanged.

Exact routes: a ring that declares ``exact = True`` (its arithmetic is exact, so a regrouped computation gives
the same element; it then provides ``mul_i(P) = red(i * P)`` too) gets the same polynomials in fewer
operations; any other ring (the ball ring) runs the operations as written above, in the same order, so its
balls, and the module's floats, are those of before.  Why: the round trip builds the exact basis of every odd
p > 15 once (``derivations.output.roundtrip.per_p_checks``), the largest part of a pmax-201 build.

* ``gamma1_numerator``: the sum ``sum_j e_j U^j W^(J-j) Den1_j`` (``U = 4 d^2 y``, ``W = (1+y)^2``, y = x^2)
  as the recurrence ``Q_(k+1) = Q_k W B_k + e_(k+1) U^(k+1)`` (J products by a 6-term polynomial, coefficients
  growing with k), not a tail product and a power of (1+x^2) formed afresh for each j;
* ``hypergeometric_polynomials``: the J + 1 terms of F summed in pairs (each copied log2 J times, not once per
  later term); ``Fhat`` and ``DD`` form ``i F`` reduced (``mul_i``), with no i^2 terms to divide out;
* ``construct``: ``F Fhat = L S - d y (y+1) S'`` with ``S = F^2`` and ``L = d(p-1)y - d - ip`` (from
  ``Fhat = L F - 2 d y(y+1) F'``): one square (flint squares a packed polynomial in 0.57 s against 0.90 s for
  the product of two at p = 201) and three linear passes.

Measured at p = 201 (shared 2-core AMD EPYC, one process, loaded machine): the construction 3.27 s -> 2.68 s
(``gamma1_numerator`` 0.69 -> 0.33, ``hypergeometric_polynomials`` 0.30 -> 0.13, ``F Fhat`` 1.26 -> 1.08,
the complex solution's ``complete`` 1.04 -> 0.62); the same polynomials, term by term, for every odd p <= 61
and p = 101, 151, 201 (``tests/test_basis_fast_paths.py`` at small p; ``bench/bench_basis_roundtrip.py``).  In
the round trip's ``per_p_checks`` (fresh processes, medians of 4): the construction 2.77 -> 2.46 s at p = 201,
1.13 -> 1.06 s at p = 151, 0.35 -> 0.30 s at p = 101 (``bench/results/basis_roundtrip.md``).
"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from math import factorial

from .integrals import e_coefficient

__all__ = ["DD", "Solution", "complete", "construct", "exact", "gamma1_numerator", "hypergeometric_polynomials", "mul_red"]


@dataclass
class Solution:
    """c-free numerators (M1, M2~, M3~) over 2p^2 (1+x^2)^p; rate r = 0 or p/d (1)."""

    p: int
    rate: int
    M: list
    divisions_exact: bool = True


def exact(ring) -> bool:
    """Whether ``ring`` declares exact arithmetic (``exact = True``, with ``mul_i``): the recipe then regroups some
    sums and products (the same elements, fewer operations: the module docstring); a ball ring computes the
    operations as written."""
    return getattr(ring, "exact", False)


def DD(N, p: int, rate: int, ring, q: int | None = None):
    """d * numerator of D(e^{i r t} N/(1+x^2)^q) over (1+x^2)^(q+1), r = rate p/d, q = p by default."""
    q = p if q is None else q
    X, D = ring.x, ring.d
    if exact(ring):
        # i N formed reduced (no i^2 terms to divide out), the d x (1+x^2) factor as one product
        base = (D * X * (1 + X**2)) * ring.dx(N) - (2 * q * D * X**2) * N
        return base + (rate * p * (1 + X**2)) * ring.mul_i(N) if rate else base
    base = D * (X * ring.dx(N) * (1 + X**2) - 2 * q * X**2 * N)
    return ring.red(base + rate * ring.i * p * N * (1 + X**2)) if rate else base


def mul_red(A, B, ring):
    """``ring.red(A * B)``, by the ring's own ``mul_red`` when it has one (the same element, computed faster)."""
    fast = getattr(ring, "mul_red", None)
    return ring.red(A * B) if fast is None else fast(A, B)


def gamma1_numerator(p: int, ring):
    """(x^2-1) sum_j e_j d^(2j) Den1_j 4^j x^(2j) (1+x^2)^(p-1-2j)."""
    X, D = ring.x, ring.d
    J = (p - 1) // 2
    if exact(ring):
        # with U = 4 d^2 y, W = (1+y)^2, B_m = (2m+1)^2 d^2 + p^2 (y = x^2: p - 1 - 2j = 2(J - j)) the sum is Q_J of
        # Q_0 = e_0, Q_(k+1) = Q_k W B_k + e_(k+1) U^(k+1): J products by a 6-term polynomial instead of a tail and a
        # power of (1+x^2) formed afresh for every j
        total, power = e_coefficient(0, p) + 0 * X, 1 + 0 * X
        U, W = 4 * D**2 * X, (1 + X) ** 2
        for k in range(J):
            power = power * U
            total = total * (W * ((2 * k + 1) ** 2 * D**2 + p * p)) + e_coefficient(k + 1, p) * power
        return (X**2 - 1) * ring.square_x(total)
    total = 0 * X
    for j in range(J + 1):
        tail = 1
        for m in range(j, J):
            tail = tail * ((2 * m + 1) ** 2 * D**2 + p * p)
        total = total + e_coefficient(j, p) * D ** (2 * j) * tail * 4**j * X ** (2 * j) * (1 + X**2) ** (p - 1 - 2 * j)
    return (X**2 - 1) * total


def _rising_over_factorial(b: Fraction, k: int) -> Fraction:
    """(b)_k / k! with (b)_k = b (b+1) ... (b+k-1)."""
    value = Fraction(1)
    for j in range(k):
        value *= b + j
    return value / factorial(k)


def hypergeometric_polynomials(p: int, ring):
    """Den2 F(-y) and Den2 Fhat as polynomials in y (written in the variable x).

    The coefficient of y^k is (b)_k/k! (-1)^k prod_{j<k} A_j prod_{k<=j<J} B_j with
    A_j = ((2-p+2j) d + ip)((3+2j) d - ip) and B_j = (3+2j)^2 d^2 + p^2: the prefix products of
    A and the suffix products of B are formed once (2J products, each reduced modulo i^2 + 1),
    not afresh for every k (J^2/2 products, with the powers of i left to grow: 2x at p = 201).
    """
    Y, D, I = ring.x, ring.d, ring.i
    J = (p - 1) // 2
    prefix = [1 + 0 * Y]                      # prefix[k] = prod_{j<k} A_j
    for j in range(J):
        prefix.append(ring.red(prefix[-1] * (((2 - p + 2 * j) * D + I * p) * ((3 + 2 * j) * D - I * p))))
    suffix = [1 + 0 * Y]                      # suffix[J-k] = prod_{k<=j<J} B_j
    for j in range(J - 1, -1, -1):
        suffix.append(suffix[-1] * ((3 + 2 * j) ** 2 * D**2 + p * p))
    F = 0 * Y
    terms = []
    for k in range(J + 1):
        rising = _rising_over_factorial(Fraction(1 - p, 2), k)
        coefficient = ring.rational(rising.numerator, rising.denominator) * prefix[k] * suffix[J - k]
        term = ring.red(coefficient * (-1) ** k * Y**k)
        if exact(ring):
            terms.append(term)
        else:
            F = F + term
    if exact(ring):
        # summed in pairs: each term is copied log2(J) times, not once per later term; i F reduced as formed
        F = _pairwise_sum(terms)
        return F, (D * (p - 1) * Y - D) * F - p * ring.mul_i(F) - 2 * D * Y * (Y + 1) * ring.dx(F)
    F = ring.red(F)
    Fhat = ring.red((D * (p - 1) * Y - D - I * p) * F - 2 * D * Y * (Y + 1) * ring.dx(F))
    return F, Fhat


def _pairwise_sum(terms: list):
    while len(terms) > 1:
        terms = [terms[n] + terms[n + 1] if n + 1 < len(terms) else terms[n] for n in range(0, len(terms), 2)]
    return terms[0]


def complete(N1, p: int, rate: int, ring) -> Solution:
    """Components 2, 3 from the first by eq:gam3 (exact divisions by x and x^2 - 1)."""
    X, D = ring.x, ring.d
    M3, exact3 = ring.divide_exact(DD(N1, p, rate, ring), X)
    numerator2 = ring.red(-4 * p * p * (D**2 + 1) * X * N1 - DD(M3, p, rate, ring))
    M2, exact2 = ring.divide_exact(numerator2, X**2 - 1)
    return Solution(p, rate, [2 * p * p * N1, M2, p * M3], exact3 and exact2)


def construct(p: int, ring) -> tuple[Solution, Solution]:
    """(real solution gamma^(1), complex solution e^{i(p/d)t} V) for odd ``p``."""
    if isinstance(p, bool) or not isinstance(p, int) or p < 1 or p % 2 == 0:
        raise ValueError(f"p={p!r}: the meromorphic basis exists for odd positive integers p only")
    real = complete(gamma1_numerator(p, ring), p, 0, ring)
    F, Fhat = hypergeometric_polynomials(p, ring)
    if exact(ring):
        # Fhat = L F - 2 d y(y+1) F' with L = d(p-1)y - d - ip, so F Fhat = L S - d y(y+1) S' with S = F^2: a square
        # (cheaper than a product of two factors) and three linear passes
        X, D = ring.x, ring.d
        S = mul_red(F, F, ring)
        product = (D * (p - 1) * X - D) * S - p * ring.mul_i(S) - D * X * (X + 1) * ring.dx(S)
    else:
        product = mul_red(F, Fhat, ring)
    V1 = ring.red(ring.x * ring.square_x(product))
    return real, complete(V1, p, 1, ring)
