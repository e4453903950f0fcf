"""Stable evaluation of homogeneous polynomials in (omega1, omega2) (first integrals, section 6.2).

``P(w1, w2) = sum_k a[k] w1^(n-k) w2^k`` is evaluated as ``s^n P(w1/s, w2/s)`` with
``s = max(|w1|, |w2|)`` and Horner's rule in the ratio of modulus <= 1 (in w2/w1 where
|w1| >= |w2|, in w1/w2 elsewhere): every power stays bounded, so no intermediate
overflow and no growth of rounding errors with n beyond Horner's usual n u bound.
"""
from __future__ import annotations

import numpy as np

__all__ = ["horner_homogeneous", "scaled_unit"]


def scaled_unit(w1, w2):
    """(s, u1, u2) with s = max(|w1|, |w2|) (1 where both vanish) and u = w / s."""
    s = np.maximum(np.abs(w1), np.abs(w2))
    safe = np.where(s > 0, s, 1.0)
    return s, w1 / safe, w2 / safe


def horner_homogeneous(a, u1, u2):
    """sum a[k] u1^(n-k) u2^k for max(|u1|, |u2|) = 1 (or 0), Horner in the smaller ratio.

    >>> float(horner_homogeneous([1.0, 2.0, 3.0], np.float64(1.0), np.float64(0.5)))  # 1 + 2*0.5 + 3*0.25
    2.75
    """
    n = len(a) - 1
    a = np.asarray(a, dtype=float)
    first = np.abs(u1) >= np.abs(u2)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(first, u2 / np.where(first, u1, 1.0), u1 / np.where(first, 1.0, u2))
    h_first = np.zeros_like(r)
    h_second = np.zeros_like(r)
    for k in range(n, -1, -1):
        h_first = h_first * r + a[k]
        h_second = h_second * r + a[n - k]
    return np.where(first, h_first * u1**n, h_second * u2**n)
