"""Numbers that print the precision they carry (issue 26: printed precision hid computed precision).

A python-flint ball prints at the context's 15 digits whatever its radius (``[2.95914417650033 +/-
1.49e-15]`` for a ball of width 8.4e-30), and an mpf prints at mpmath's global 15 digits whatever
precision computed it.  :class:`Ball` (an ``arb``) and :class:`MPValue` (an ``mpf``) are the same
numbers with a ``repr`` that shows every digit the radius, or the working precision, supports;
arithmetic on them returns ordinary ``arb`` / ``mpf``.  To print more or fewer digits:
``ball.str(n, radius=True)`` and ``mpmath.nstr(value, n)``.

How many digits (issue 44: a 1000-bit ball raised ``OverflowError``, its radius 2.5e-309 being below
float64's normal range, and from 1100 bits printed 17 digits): :func:`ball_digits` reads the midpoint and
the radius in arb itself (``log10(|mid|/rad)`` in ball arithmetic; arb's exponents have no range limit),
never through float64.  The ball is printed with the digits up to and including the first one the radius
reaches, so the printed radius (the radius plus the rounding of the printed midpoint, rounded up by arb)
stays within a factor 1.5 of the ball's own radius; at most :data:`MAX_DIGITS` digits.
For JSON: :func:`ball_fields` gives the printed ball with its midpoint and radius as float64 numbers that
agree with it.
"""
from __future__ import annotations

import math

import mpmath
from flint import arb, ctx  # noqa: F401  (ctx: the working precision of exact balls)

__all__ = ["Ball", "MPValue", "ball_digits", "ball_text", "ball_fields", "radius_upper", "MAX_DIGITS"]

MAX_DIGITS = 100_000    # the most digits a Ball's repr prints (``ball.str(n)`` prints any other number)
_EXACT_DIGITS = 17      # the fewest digits of an exact ball (radius 0): float64's round-trip digits


def ball_digits(x: arb) -> int:
    """Significant digits of the midpoint that the radius supports, plus the first digit it reaches.

    ``floor(log10(|mid|/rad)) + 2``, computed in arb (no float64 range: radii such as 1e-900 are read
    from arb's exponents); 1 for a ball whose radius reaches its midpoint (it prints as ``[+/- r]``), for
    a zero midpoint and for a non-finite ball.  An exact ball (radius 0) shows every digit its midpoint
    needs to be told from its neighbours at its precision (at least 17).  At most :data:`MAX_DIGITS`.
    """
    if not x.is_finite():
        return 1
    mid, rad = x.mid(), x.rad()
    if mid.is_zero():
        return 1
    if rad.is_zero():
        # the exact midpoint's own mantissa (abs() would round it to the context's precision first: an exact
        # 20-digit integer raised "man_exp requires an exact value")
        mantissa, _ = mid.man_exp()
        bits = abs(int(mantissa)).bit_length()
        return min(MAX_DIGITS, max(_EXACT_DIGITS, math.ceil(bits * math.log10(2)) + 1))
    with ctx.workprec(64):
        decades = (abs(mid) / rad).log() / arb(10).log()   # log10(|mid|/rad) as a ball: its width is about 1e-17
    if not decades.is_finite():
        return 1
    return max(1, min(MAX_DIGITS, math.floor(float(decades.mid())) + 2))


def ball_text(x: arb) -> str:
    """``x`` printed with :func:`ball_digits` digits: ``[midpoint +/- radius]``, the radius arb's own upper
    bound of ``rad`` plus the rounding of the printed midpoint (within a factor 1.5 of ``x.rad()``)."""
    digits = ball_digits(x)
    # more=True: arb would otherwise drop the digit the radius reaches, printing a radius up to 13 times x.rad()
    return x.str(digits, radius=True, more=digits > 1)


def radius_upper(x: arb) -> float:
    """``x.rad()`` as a float64 rounded up (an upper bound: a radius below float64's range gives the
    smallest subnormal 5e-324, never 0; above it, inf)."""
    rad = x.rad()
    if rad.is_zero():
        return 0.0
    value = float(rad)
    if not math.isfinite(value):
        return math.inf
    if arb(value) < rad:
        value = math.nextafter(value, math.inf)
    return value


def ball_fields(x: arb) -> dict:
    """``{"ball": ball_text(x), "midpoint": float, "radius": radius_upper(x)}`` for a JSON record: the
    printed ball shows the digits its radius supports, so its ``+/-`` and ``radius`` agree (a ball printed
    with a fixed 25 digits showed ``+/- 1.05e-25`` beside ``radius: 2.0e-40``)."""
    return {"ball": ball_text(x), "midpoint": float(x.mid()), "radius": radius_upper(x)}


class Ball(arb):
    """An ``arb`` whose repr shows the digits its radius supports.

    >>> Ball(arb(2).sqrt())                 # doctest: +ELLIPSIS
    [1.41421356237309... +/- ...]
    """

    def __repr__(self) -> str:
        return ball_text(self)

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
