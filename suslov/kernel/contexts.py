"""Number contexts: one emitted formula, evaluated in float64, in mpmath, in ball arithmetic, or symbolically.

The build prints each closed form once, as a function ``f(ctx, ...)`` that takes its
elementary functions from ``ctx`` (the shape of mpmath's ``ctx_fp``/``ctx_mp``).  This
module provides the two run-time contexts; the build's round-trip certificate passes a
third, symbolic context (``derivations.output.roundtrip``) to the *same emitted function* and
compares the result with the certified expression exactly.

``exp`` and ``expm1`` serve the general scattering angle, whose emitted form has only
exponentials of non-positive arguments (no overflow).  ``FLOAT.sech`` is ``2 e^-|t| / (1 + e^-2|t|)``, which cannot overflow; ``MP`` uses
mpmath at the caller's working precision.
"""
from __future__ import annotations

import mpmath
import numpy as np
from flint import arb

__all__ = ["FloatContext", "MpContext", "ArbContext", "FLOAT", "MP", "ARB"]


class FloatContext:
    """float64 building blocks on NumPy arrays (broadcasting)."""

    @staticmethod
    def tanh(t):
        return np.tanh(t)

    @staticmethod
    def sech(t):
        with np.errstate(under="ignore"):
            e = np.exp(-np.abs(t))
            return 2.0 * e / (1.0 + e * e)

    @staticmethod
    def tanh_sech(t):
        """(tanh t, sech t), both to full relative accuracy, no overflow for any t.

        With ``a = |t|``, ``e = exp(-a)`` and ``m = expm1(-a) = e - 1`` (each accurate to an ulp):
        sech t = 2e/(1 + e^2) and tanh a = (1 - e)(1 + e)/(1 + e^2) = -m (1 + e)/(1 + e^2);
        no subtraction of nearly equal numbers anywhere (1 - e is m itself).  In-place
        array operations: cheaper than ``np.tanh`` plus a separate sech.
        """
        with np.errstate(under="ignore"):
            t = np.asarray(t, dtype=float)
            a = np.empty_like(t)
            np.abs(t, out=a)
            np.negative(a, out=a)
            e = np.exp(a, out=np.empty_like(t))
            m = np.expm1(a, out=a)
            inverse = np.multiply(e, e, out=np.empty_like(t))
            inverse += 1.0
            np.reciprocal(inverse, out=inverse)
            tanh = np.add(e, 1.0, out=np.empty_like(t))
            tanh *= m
            tanh *= inverse
            np.negative(tanh, out=tanh)
            np.copysign(tanh, t, out=tanh)
            e *= 2.0
            e *= inverse
            return tanh, e

    @staticmethod
    def sqrt(x):
        return np.sqrt(x)

    @staticmethod
    def atan2(y, x):
        return np.arctan2(y, x)

    @staticmethod
    def exp(x):
        with np.errstate(under="ignore"):
            return np.exp(x)

    @staticmethod
    def expm1(x):
        return np.expm1(x)

    @staticmethod
    def hypot(x, y):
        return np.hypot(x, y)


class MpContext:
    """mpmath building blocks (precision set by the caller's ``workdps``)."""

    tanh = staticmethod(mpmath.tanh)
    sech = staticmethod(mpmath.sech)

    @staticmethod
    def tanh_sech(t):
        return mpmath.tanh(t), mpmath.sech(t)

    sqrt = staticmethod(mpmath.sqrt)
    atan2 = staticmethod(mpmath.atan2)
    exp = staticmethod(mpmath.exp)
    expm1 = staticmethod(mpmath.expm1)
    hypot = staticmethod(mpmath.hypot)


class ArbContext:
    """python-flint ball arithmetic (``arb``, precision ``flint.ctx.prec``): every value is an
    enclosure, so an emitted formula evaluated here gives a ball that contains the exact value
    of the certified expression at the (ball) arguments."""

    @staticmethod
    def tanh(t):
        return arb(t).tanh()

    @staticmethod
    def sech(t):
        return arb(t).sech()

    @staticmethod
    def tanh_sech(t):
        t = arb(t)
        return t.tanh(), t.sech()

    @staticmethod
    def sqrt(x):
        """Square root of the non-negative part of the ball.  Every square root an emitted formula takes is
        of a quantity that is >= 0 on its domain (a sum of squares, a product of positive entries), but a
        ball of it can dip below 0 (``x*x`` of a ball about 0 is not known to be a square): the exact value
        lies in [0, upper], whose square root is enclosed; a ball entirely below 0 still gives NaN."""
        x = arb(x)
        if x.lower() < 0 and not x.upper() < 0:
            return arb(0).union(x.upper().sqrt())
        return x.sqrt()

    @staticmethod
    def atan2(y, x):
        return arb.atan2(arb(y), arb(x))

    @staticmethod
    def exp(x):
        return arb(x).exp()

    @staticmethod
    def expm1(x):
        return arb(x).expm1()

    @staticmethod
    def hypot(x, y):
        x, y = arb(x), arb(y)
        return (x * x + y * y).sqrt()


FLOAT = FloatContext()
MP = MpContext()
ARB = ArbContext()
