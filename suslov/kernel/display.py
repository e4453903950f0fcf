"""Numbers that print the precision they carry (issue 26: printed precision hid computed precision).

A python-flint ball prints at the context's 15 digits whatever its radius (``[2.95914417650033 +/-
1.49e-15]`` for a ball of width 8.4e-30), and an mpf prints at mpmath's global 15 digits whatever
precision computed it.  :class:`Ball` (an ``arb``) and :class:`MPValue` (an ``mpf``) are the same
numbers with a ``repr`` that shows every digit the radius, or the working precision, supports;
arithmetic on them returns ordinary ``arb`` / ``mpf``.  To print more or fewer digits:
``ball.str(n, radius=True)`` and ``mpmath.nstr(value, n)``.
"""
from __future__ import annotations

import math

import mpmath
from flint import arb, ctx  # noqa: F401  (ctx: the working precision of exact balls)

__all__ = ["Ball", "MPValue", "ball_digits"]


def ball_digits(x: arb) -> int:
    """Significant digits of the midpoint that the radius supports (at least 1, at most the precision's)."""
    mid, rad = abs(float(x.mid())), float(x.rad())
    if rad == 0 or mid == 0 or not math.isfinite(mid):
        return max(17, int(ctx.prec / 3.32))   # an exact ball: the digits of the working precision
    return max(1, min(100_000, math.floor(math.log10(mid / rad)) + 1))


class Ball(arb):
    """An ``arb`` whose repr shows the digits its radius supports.

    >>> Ball(arb(2).sqrt())
    [1.414213562373095 +/- ...]
    """

    def __repr__(self) -> str:
        return self.str(ball_digits(self), radius=True)

    __str__ = __repr__


class MPValue(mpmath.mpf):
    """An ``mpf`` computed at ``dps`` digits whose repr shows those digits (``mpmath.nstr(v, n)`` for others)."""

    __slots__ = ("dps",)

    def __new__(cls, value, dps: int):
        self = object.__new__(cls)
        self._mpf_ = value._mpf_ if isinstance(value, mpmath.mpf) else mpmath.mpf(value)._mpf_
        self.dps = dps
        return self

    def __repr__(self) -> str:
        return mpmath.libmp.to_str(self._mpf_, self.dps, strip_zeros=False)

    __str__ = __repr__
