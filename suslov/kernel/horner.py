"""Stable evaluation of homogeneous polynomials in (omega1, omega2) (first integrals, section 6.2).

``P(w1, w2) = sum_k a[k] w1^(n-k) w2^k`` is evaluated as ``s^n P(w1/s, w2/s)`` with
``s = max(|w1|, |w2|)`` and Horner's rule in the ratio of modulus <= 1 (in w2/w1 where
``|w1| >= |w2|``, in w1/w2 elsewhere): every power stays bounded, so no intermediate
overflow and no growth of rounding errors with n beyond Horner's usual n u bound.
"""
from __future__ import annotations

import numpy as np

__all__ = ["horner_homogeneous", "scaled_unit"]


def scaled_unit(w1, w2):
    """``(s, u1, u2)`` with ``s = max(|w1|, |w2|)`` (1 where both vanish) and ``u = w / s``."""
    s = np.maximum(np.abs(w1), np.abs(w2))
    safe = np.where(s > 0, s, 1.0)
    return s, w1 / safe, w2 / safe


def horner_homogeneous(a, u1, u2):
    """``sum a[k] u1^(n-k) u2^k`` for ``max(|u1|, |u2|) = 1`` (or 0), Horner in the smaller ratio.

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


def combination(coefficients: np.ndarray, w1: np.ndarray, w2: np.ndarray, g: np.ndarray,
                block: int = 8192) -> np.ndarray:
    """``sum_i g_i P_i(w1, w2) / s^n`` for homogeneous P_i of odd degree n, ``s = max(|w1|, |w2|)``.

    ``coefficients`` is (m, n+1) (row i: a_ik of w1^(n-k) w2^k), ``g`` is (m, N), ``w1``, ``w2``
    are (N,).  The combination c_k = sum_i a_ik g_i is formed first (one matrix product),
    then one Horner pass in the ratio r of modulus <= 1: c_k r^k where ``|w1| >= |w2|``, the
    reversed c_(n-k) r^k elsewhere; the factor u_max^n = sign^n (u_max = +-1 exactly, n odd)
    is a sign.  Points with w1 = w2 = 0 give 0.

    >>> float(combination(np.array([[1.0, 0.0, 0.0, 2.0]]), np.array([1.0]), np.array([0.5]), np.array([[1.0]]))[0])
    1.25
    """
    n = coefficients.shape[1] - 1
    if n % 2 == 0:
        raise ValueError("combination: the degree must be odd (the sign of u_max^n)")
    N = w1.size
    out = np.empty(N)
    for start in range(0, N, block):
        a, b = w1[start:start + block], w2[start:start + block]
        first = np.abs(a) >= np.abs(b)
        big = np.where(first, a, b)
        safe = np.where(big == 0, 1.0, big)
        r = np.where(first, b, a) / safe
        # c_k = ((a_0k g_0 + a_1k g_1) + a_2k g_2) ...: elementwise, in this one order, not a BLAS product,
        # whose summation order and FMA use depend on the CPU OpenBLAS detects (the build's bit-for-bit
        # check of first_integral against its analysed sequence failed on an AMD EPYC for that reason)
        gb = g[:, start:start + block]
        c = np.multiply.outer(coefficients[0], gb[0])   # (n+1, N)
        for i in range(1, coefficients.shape[0]):
            c += np.multiply.outer(coefficients[i], gb[i])
        c = np.where(first, c, c[::-1])
        h = c[n].copy()
        for k in range(n - 1, -1, -1):
            h *= r
            h += c[k]
        out[start:start + block] = np.where(big == 0, 0.0, h * np.sign(big))
    return out
