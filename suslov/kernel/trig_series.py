"""Trigonometric polynomials in th = 2 arctan(e^-t), evaluated without trigonometric calls.

With cos th = tanh t and sin th = sech t, the point z = e^{i th} = tanh t + i sech t is on
the unit circle, and ``sum_k alpha_k cos k th + beta_k sin k th = Re sum_k (alpha_k - i
beta_k) z^k``.  The powers z^k are formed by repeated complex multiplication (each step
adds about one rounding error of relative size u, since ``|z| = 1``: k u after k steps, not the
k^2 u of the three-term Chebyshev recurrence), stacked as a real matrix [Re z^k; Im z^k],
and all series are evaluated at once by one matrix product (BLAS).  Points are processed in
blocks so the power matrix stays in cache.
"""
from __future__ import annotations

import numpy as np

__all__ = ["evaluate"]

BLOCK = 8192


def evaluate(T: np.ndarray, S: np.ndarray, coefficients: np.ndarray, block: int = BLOCK) -> np.ndarray:
    """Values (m, n) of m series at n points; ``coefficients`` is (2(p+1), m): cos rows, then sin rows.

    >>> T, S = np.array([0.0]), np.array([1.0])   # th = pi/2
    >>> evaluate(T, S, np.array([[1.0], [0.0], [0.0], [1.0]]))   # 1 + sin th
    array([[2.]])
    """
    T, S = np.ravel(T), np.ravel(S)
    n, p = T.size, coefficients.shape[0] // 2 - 1
    out = np.empty((coefficients.shape[1], n))
    transposed = np.ascontiguousarray(coefficients.T)
    powers = np.empty((p + 1, min(block, max(n, 1))), dtype=complex)
    real = np.empty((2 * (p + 1), powers.shape[1]))
    for start in range(0, n, block):
        z = T[start:start + block] + 1j * S[start:start + block]
        m = z.size
        powers[0, :m] = 1.0
        for k in range(1, p + 1):
            np.multiply(powers[k - 1, :m], z, out=powers[k, :m])
        real[:p + 1, :m] = powers[:, :m].real
        real[p + 1:, :m] = powers[:, :m].imag
        np.matmul(transposed, real[:, :m], out=out[:, start:start + m])
    return out
