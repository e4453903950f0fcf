"""Rational functions of x = e^t as trigonometric polynomials in th = 2 arctan(e^-t).

With x = cot(th/2): x^m / (1+x^2)^p = cos^m(th/2) sin^(2p-m)(th/2), a trigonometric
polynomial of degree p in th (m + n = 2p even).  Writing cos and sin of th/2 through
e^{+-i th/2} and expanding both binomials gives its Fourier coefficients

    F_k = (-i)^n / 4^p * sum_{a+b=p-k} C(m, a) C(n, b) (-1)^b,   k = -p..p,  n = 2p - m,

real for even n (a cosine series) and imaginary for odd n (a sine series).  The integer
matrices are exact and cached per p; :func:`to_fourier` applies them to the coefficients
of a numerator at any precision (mpmath ``fsum``).  The basis of Poisson solutions is
evaluated in this form: its coefficients are bounded, there is no cancellation for
large p and no overflow for any t.
"""
from __future__ import annotations

from functools import lru_cache
from math import comb

import mpmath

__all__ = ["fourier_matrices", "to_fourier"]


@lru_cache(maxsize=None)
def fourier_matrices(p: int) -> tuple[tuple[tuple[int, ...], ...], tuple[tuple[int, ...], ...]]:
    """Integer (C, S): x^m/(1+x^2)^p = (sum_k C[m][k] cos k th + S[m][k] sin k th) / 4^p."""
    C = [[0] * (p + 1) for _ in range(2 * p + 1)]
    S = [[0] * (p + 1) for _ in range(2 * p + 1)]
    for m in range(2 * p + 1):
        n = 2 * p - m
        unit = (-1) ** (n // 2) if n % 2 == 0 else (-1) ** ((n + 1) // 2)  # (-i)^n = unit or unit * i
        for k in range(p + 1):
            total = sum(comb(m, a) * comb(n, p - k - a) * (-1) ** (p - k - a)
                        for a in range(max(0, p - k - n), min(m, p - k) + 1))
            weight = 1 if k == 0 else 2
            if n % 2 == 0:
                C[m][k] = weight * unit * total
            else:  # F_k = i unit total: weight Re(F_k e^{ik th}) = -weight unit total sin k th
                S[m][k] = -weight * unit * total
    return tuple(map(tuple, C)), tuple(map(tuple, S))


def to_fourier(numerator, p: int):
    """(cos coefficients, sin coefficients) of numerator(x)/(1+x^2)^p, k = 0..p (mpmath)."""
    C, S = fourier_matrices(p)
    scale = mpmath.mpf(4) ** p
    numerator = list(numerator) + [0] * (2 * p + 1 - len(numerator))
    alpha = [mpmath.fsum(numerator[m] * C[m][k] for m in range(2 * p + 1)) / scale for k in range(p + 1)]
    beta = [mpmath.fsum(numerator[m] * S[m][k] for m in range(2 * p + 1)) / scale for k in range(p + 1)]
    return alpha, beta
