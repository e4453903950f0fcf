"""Recipe: the polynomial first integral F3 = P1 g1 + P2 g2 + P3 g3 for odd p (Theorem 6.2).

Labels: ``eq:p1``, ``eq:p23``, ``eq:partial``, ``pol_sol``.  Along ``eq:sysfin`` the time
derivative of a function of omega is ``(d/p) w2 L`` with ``L = w2/(d^2+1) d/dw1 - w1 d/dw2``;
collecting the coefficients of g1, g2, g3 in dF3/dt gives ``eq:partial``, whence

    P3 = -(d/p) L P1,        P2 = (w2/w1) (P1 - (d/p) L P3),

with ``P1 = w1 F1^((p-1)/2) F(w2^2/F1)``, ``F1 = (d^2+1) w1^2 + w2^2`` and ``F`` the
terminating 3F2(1/2, (1+p)/2, (1-p)/2; (d-ip)/(2d), (d+ip)/(2d); z) with coefficients

    c_j = binom(2j, j)/4^j prod_{m<j} ((2m+1)^2 - p^2) d^2 / ((2m+1)^2 d^2 + p^2).

Fraction-free form (no division anywhere, so it runs in Z[d, w1, w2]):
``Den = prod_{m<J} q_m``, ``q_m = (2m+1)^2 d^2 + p^2``, ``K = p (d^2+1)``, ``J = (p-1)/2``,

    R_0 = e_0,  R_{k+1} = q_k F1 R_k + e_{k+1} d^(2k+2) w2^(2k+2),   P1~ = w1 R_J = Den P1,
    M3 = -d L~ P1~ = K Den P3,     M2 = w2 (K^2 P1~ - d L~ M3) / w1 = K^2 Den P2,

with ``L~ = (d^2+1) L`` and the integers ``e_j = binom(2j,j) prod_{m<j}((2m+1)^2-p^2)/4^j``.
The division by w1 is exact (certified by the build for every p in range).

Ring adapter (what ``ring`` must provide): elements ``d``, ``w1``, ``w2``, ``one`` (the
coefficient ring's 1); ``dw1(P)``,
``dw2(P)``; ``divide_w1(P) -> (quotient, exact: bool)``; ``constant(n)``.
"""
from __future__ import annotations

from dataclasses import dataclass
from math import comb

__all__ = ["e_coefficient", "IntegralNumerators", "integral_numerators"]


def e_coefficient(j: int, p: int) -> int:
    """``e_j = binom(2j,j) prod_{m<j}((2m+1)^2 - p^2) / 4^j`` (an integer for odd p).

    >>> [e_coefficient(j, 5) for j in range(3)]
    [1, -12, 144]
    """
    num = comb(2 * j, j)
    for m in range(j):
        num *= (2 * m + 1) ** 2 - p**2
    value, rest = divmod(num, 4**j)
    if rest:
        raise ArithmeticError(f"e_{j} for p = {p} is not an integer")
    return value


@dataclass
class IntegralNumerators:
    """P1 = P1t/Den, P3 = M3/(K Den), P2 = M2/(K^2 Den); ``exact``: w1 divided exactly."""

    p: int
    P1t: object
    M2: object
    M3: object
    K: object
    Den: object
    exact: bool


def integral_numerators(p: int, ring) -> IntegralNumerators:
    """The fraction-free numerators for odd ``p`` in ``ring`` (see the module docstring)."""
    if isinstance(p, bool) or not isinstance(p, int) or p < 1 or p % 2 == 0:
        raise ValueError(f"p={p!r}: the polynomial integral exists for odd positive integers p only")
    D, W1, W2 = ring.d, ring.w1, ring.w2
    e = D**2 + 1

    def L_scaled(P):
        return W2 * ring.dw1(P) - e * W1 * ring.dw2(P)

    J = (p - 1) // 2
    F1 = e * W1**2 + W2**2
    R = ring.constant(e_coefficient(0, p))
    Den = ring.one
    for k in range(J):
        q_k = (2 * k + 1) ** 2 * D**2 + p**2
        R = q_k * F1 * R + e_coefficient(k + 1, p) * D ** (2 * k + 2) * W2 ** (2 * k + 2)
        Den = Den * q_k
    P1t = W1 * R
    K = p * e
    M3 = -D * L_scaled(P1t)
    N = K**2 * P1t - D * L_scaled(M3)
    M2, exact = ring.divide_w1(W2 * N)
    return IntegralNumerators(p, P1t, M2, M3, K, Den, exact)
