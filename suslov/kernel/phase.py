"""Exact argument reductions: the phase (p/d) t, the angle variable th, and pi p/2.

* :func:`theta`: ``th = 2 arctan(e^-t)`` in (0, pi), so that ``tanh t = cos th`` and
  ``sech t = sin th`` without overflow for any t.
* :func:`phase_cos_sin`: cos and sin of (p/d) t in double-double arithmetic (then one tangent of
  the half angle gives both).  The plain
  product carries the rounding of p/d and of the product, an absolute phase error of
  about ``1e-16 (p/d)|t|``.  Here p/d = q + r/d with r = p - q d exact (Dekker's two-product),
  q t = h + l exactly, and the reduction modulo 2 pi subtracts k (C1 + C2 + C3) with
  C1, C2 of 30 significant bits, so k C1 and k C2 are exact for ``|k| < 2^23`` (Cody and
  Waite).  Valid for ``|phase| <`` :data:`PHASE_LIMIT` ``= 2^23 * 2 pi`` (5.3e7); callers warn or
  switch to mpmath beyond.
* :func:`half_pi_parts`: ``|sin(pi p/2)|``, ``|cos(pi p/2)|`` with p reduced modulo 2 exactly
  (``r = |p - 2 round(p/2)|`` is exact in floating point); near an odd integer the cosine is
  sin(pi (1 - r)/2), whose argument 1 - r is exact for r >= 1/2 (Sterbenz), so p within
  1e-12 of an integer keeps full relative accuracy.
"""
from __future__ import annotations

import numpy as np

__all__ = ["theta", "two_prod", "split_quotient", "reduce_scalar", "phase_cos_sin", "half_pi_parts", "PHASE_LIMIT"]

# 2 pi = _C1 + _C2 + _C3 (Cody and Waite's three-part constant)
_C1, _C2, _C3 = 6.283185303211212, 3.9683743166540886e-09, 2.068073192717642e-18
_SPLIT = 134217729.0  # 2^27 + 1 (Dekker's splitting)
PHASE_LIMIT = 2.0**23 * 6.283185307179586


def theta(t):
    """th = 2 arctan(e^-t) in (0, pi): tanh t = cos th, sech t = sin th (no overflow).

    >>> float(theta(0.0)) == np.pi / 2
    True
    """
    t = np.asarray(t, dtype=float)
    with np.errstate(over="ignore", under="ignore"):
        e = 2.0 * np.arctan(np.exp(-np.abs(t)))
    return np.where(t >= 0, e, np.pi - e)


def two_prod(a, b):
    """(h, l) with h + l = a * b exactly (Dekker; no FMA needed)."""
    h = a * b
    ta = _SPLIT * a
    a1 = ta - (ta - a)
    a2 = a - a1
    tb = _SPLIT * b
    b1 = tb - (tb - b)
    b2 = b - b1
    return h, ((a1 * b1 - h) + a1 * b2 + a2 * b1) + a2 * b2


def split_quotient(p, d):
    """(q, rd) with p/d = q + rd up to ~u^2 p/d: q = fl(p/d), r = p - q d from Dekker's exact q d (p - qd_h is
    exact by Sterbenz's lemma), rd = fl(fl(r)/d)."""
    q = p / d
    qd_h, qd_l = two_prod(q, d)
    return q, ((p - qd_h) - qd_l) / d


def phase_cos_sin(p, d, t):
    """cos and sin of (p/d) t (arrays broadcast), accurate to ~1e-16 absolute for ``|phase| < PHASE_LIMIT``."""
    t = np.asarray(t, dtype=float)
    p = np.asarray(p, dtype=float)
    d = np.asarray(d, dtype=float)
    q, rd = split_quotient(p, d)
    if q.ndim == 0 and d.ndim == 0:
        return _cos_sin_reduced(reduce_scalar(float(q), float(rd), t))
    h, low = two_prod(q, t)
    low = low + rd * t
    k = np.round(h / _C1)
    reduced = ((h - k * _C1) - k * _C2) + (low - k * _C3)
    return _cos_sin_reduced(reduced)


def _cos_sin_reduced(angle: np.ndarray):
    """cos and sin of an angle in [-pi, pi] from one tangent of the half angle, u = tan(angle/2):
    cos = (1 - u^2)/(1 + u^2), sin = 2u/(1 + u^2), absolute error a few ulps (u is finite: pi/2 is
    not a float); one transcendental call instead of two.  Overwrites ``angle``."""
    angle *= 0.5
    u = np.tan(angle, out=angle)
    u2 = u * u
    inverse = u2 + 1.0
    np.reciprocal(inverse, out=inverse)
    np.subtract(1.0, u2, out=u2)
    u2 *= inverse
    u *= 2.0
    u *= inverse
    return u2, u


def reduce_scalar(q: float, rd: float, t: np.ndarray) -> np.ndarray:
    """The phase (q + rd) t reduced to about [-pi, pi] for scalar p, d (q split once, in-place array operations:
    fewer passes): h + low = q t exactly (Dekker), low += rd t, k = rint(h/C1), then ((h - k C1) - k C2) +
    (low - k C3).  The operation sequence analysed by ``derivations.proofs.basis_proof``."""
    tq = _SPLIT * q
    q1 = tq - (tq - q)
    q2 = q - q1
    h = q * t
    b1 = np.multiply(t, _SPLIT)
    b1 -= np.subtract(b1, t)
    b2 = np.subtract(t, b1)
    low = np.multiply(b1, q1)
    low -= h
    low += q1 * b2
    low += q2 * b1
    b2 *= q2
    low += b2
    low += rd * t
    k = np.multiply(h, 1.0 / _C1)
    np.rint(k, out=k)
    h -= k * _C1
    h -= k * _C2
    k *= _C3
    low -= k
    h += low
    return h


def half_pi_parts(p):
    """``(|sin(pi p/2)|, |cos(pi p/2)|)`` in float64 with p reduced modulo 2 exactly."""
    p = np.asarray(p, dtype=float)
    r = np.abs(p - 2.0 * np.round(p / 2.0))
    s = np.sin(0.5 * np.pi * r)
    c = np.where(r >= 0.5, np.sin(0.5 * np.pi * (1.0 - r)), np.cos(0.5 * np.pi * r))
    return s, c
