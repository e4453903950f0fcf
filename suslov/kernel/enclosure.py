"""Validated integration of the Poisson equations: rigorous enclosures of the ss solution and its angle.

Paper: eq:whole (``gamma' = gamma x omega``), eq:o12 (the general solution omega(t) of any body
with I12 = 0, a = e3), the boundary condition ``ss`` and the angle of Theorem 5.4 (section 5.1),
here for *any* body (I13 != 0 included): the independent route beside the closed form of every body
(``derivations/sections/general_angle.py`` checks one against the other).  No SymPy and no
``generated`` import: the build (``derivations/sections/scattering.py``) and the run time (``suslov.validated``)
both call :func:`ss_angle_enclosure` with the coefficients u, v of omega.  Everything is python-flint
ball arithmetic (``arb``); every number returned is an interval that contains the exact value.

Set-up (rate-1 time s; another energy only rescales time, which changes neither the path of gamma
nor the angle).  ``omega(s) = u tanh s + v sech s`` (u, v: pairs of balls), ``n = u/|u|``.  The ss solution has
``gamma(-oo) = -n``; the angle between the limit rotation axes is ``Delta psi = arccos(-<gamma(+oo), n>)``
(for I13 = 0 this is ``cos Delta psi = -gamma1(+oo)``, the definition of Theorem 5.4).

The enclosure, in three rigorous pieces:

1. **Limit series at -oo** (``x = e^s``, ``|x| < 1``).  ``tanh s = (x^2-1)/(x^2+1)`` and ``sech s = 2x/(x^2+1)``
   make ``x dgamma/dx = gamma x omega(x)`` with ``omega(x) = sum w_j x^j``, ``w_0 = -u``,
   ``w_2m = 2 (-1)^(m+1) u``, ``w_(2m+1) = 2 (-1)^m v``.  The ss solution is the exponent-0 series
   ``gamma = sum y_k x^k``, ``y_0 = -n``, ``(k - C(w_0)) y_k = sum_(j=1..k) C(w_j) y_(k-j)`` with
   ``C(w) y = y x w``.  C(w_0) is real skew-symmetric, so ``||(k - C(w_0))^-1|| <= 1/k``, and
   ``||C(w_j)|| <= W = 2 max(|u|, |v|)``: by induction ``||y_k|| <= b_k`` with ``b_0 = 1``,
   ``b_k = (W/k) (b_0 + ... + b_(k-1))``, i.e. ``b_(k+1) = b_k (k + W)/(k + 1)``: the ratios tend to 1
   (from above when W > 1, from below when W < 1), so the remainder after order N at x is at most
   ``sqrt(3) b_(N+1) x^(N+1) / (1 - q x)``, ``q = max(1, (N + 1 + W)/(N + 2))`` (when q x < 1;
   :func:`_majorant_tail`).
2. **Taylor steps** from s0 = -S to s1 = +S (step h, centre c).  The Taylor coefficients of tanh and
   sech at c come from ``arb_series`` (exp of a series), those of gamma from Picard iteration on
   series (pass n fixes coefficient n and runs on series of n + 1 terms).  Truncation after order N: on
   the closed square ``|Re tau|, |Im tau| <= rho`` (rho <= 1, corners at distance sqrt 2 < pi/2 from
   c, so tanh and sech are analytic there) ``|omega_i| <= |u_i| max|tanh| + |v_i| max|sech|`` (acb enclosures on a grid
   of sub-boxes), hence ``||A|| <= M = sqrt(2 (W1^2 + W2^2))`` (Frobenius norm of the cross-product
   matrix), Grönwall along rays gives ``||gamma(c + tau)|| <= Y e^{M rho}`` and Cauchy's estimate
   ``||gamma_k|| <= sqrt(3) Y e^{M rho} rho^-k``, so the remainder at ``|tau| <= h`` is at most
   ``sqrt(3) Y e^{M rho} (h/rho)^{N+1} / (1 - h/rho)``; h is halved where this exceeds the budget.
   **No wrapping effect**: the step is applied to the *midpoint* (an exact vector) and the accumulated
   error is carried as one Euclidean radius delta.  For real s the transition matrix is a rotation
   (the system matrix is real skew-symmetric), so an error of norm delta stays of norm delta; each
   step adds the Euclidean norm of its ball radii and its truncation bound.
3. **Limit series at +oo** (x = e^-s).  The solution g with ``g(+oo) = n`` is the exponent-0 series of
   ``x dg/dx = g x (-omega(x))`` (same recurrence and bound, ``omega(x) = u (1-x^2)/(1+x^2) + v 2x/(1+x^2)``).
   Two solutions keep their inner product (the flow is a rotation), so
   ``<gamma(+oo), n> = <gamma(s1), g(s1)>``: no integration to +oo.  The angle is
   ``cos Delta psi = -<gamma(s1), g(s1)>`` and ``sin Delta psi = |gamma(s1) x g(s1)|`` (the cross
   product of two solutions is a solution: its norm is kept too), each widened by ``delta |g|``; the
   angle is the arctangent of whichever quotient of the two is bounded, so next to 0 and pi (odd p)
   it keeps the width of the data (arccos alone halves the digits there), clipped to [0, pi]
   (``|gamma| = |g| = 1`` exactly).

References for the method: Cauchy majorants for linear ODEs with analytic coefficients as in
M. Mezzarobba, arXiv:1607.01967 (here in their simplest form: a bound of the coefficient matrix on a
disc, Grönwall and Cauchy's estimate); F. Johansson, arXiv:1606.06977 for ball arithmetic.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

from flint import acb, arb, arb_mat, arb_series, ctx

from .display import Ball
from .reprs import enclosure_html, enclosure_latex
from .validate import rational

__all__ = ["AngleEnclosure", "EnclosureTooCostly", "DIGITS_RANGE", "MAX_SECONDS", "to_arb", "ss_angle_enclosure"]

_UNIT = arb(0, 1)  # the ball [-1, 1]: x + _UNIT * r widens x by r (r an exact upper bound) without rounding
RHO = 1.0          # half-width of the square on which tanh, sech are bounded (corners at sqrt 2 < pi/2)
GRID = 4           # sub-boxes per side for those bounds


@dataclass(frozen=True)
class AngleEnclosure:
    """The scattering angle as a ball, with how it was obtained."""

    angle: arb                 # contains Delta psi (a Ball: its repr shows the digits the radius supports)
    cos_angle: arb             # contains cos Delta psi = -<gamma(+oo), n>
    window: tuple              # (s0, s1): rate-1 times where the tails take over
    steps: int
    order: int
    prec: int                  # working precision in bits
    error_budget: dict         # Euclidean error pieces: tail_minus, steps (rounding + truncation), tail_plus
    gamma_at_zero: tuple       # balls containing gamma(0) of the ss solution (s = 0: tanh s = 0)
    gamma_at_start: tuple      # balls containing gamma(-S) (limit series with its remainder bound)

    @property
    def width(self) -> float:
        return 2.0 * float(self.angle.rad())

    def _repr_latex_(self) -> str:   # notebooks: the ball with the digits its radius supports (suslov.kernel.reprs)
        return enclosure_latex(self)

    def _repr_html_(self) -> str:
        return enclosure_html(self)


def to_arb(name: str, value) -> arb:
    """A ball for a number: exact input (an int or NumPy integer, a Fraction, a decimal or ``a/b`` string, an mpf)
    as one quotient rounded at the working precision, its size checked first (``MAX_ENTRY_BITS`` of
    :mod:`suslov.kernel.validate`: ``"1e100000000"`` is refused before any integer is built); a float or NumPy
    floating scalar as the binary number it is; an arb as it is, when finite.

    Anything else (complex, None, a list, a bool, a NaN or infinite ball) is a ``ValueError`` naming the field,
    like every input error of the public functions."""
    if isinstance(value, arb):
        if not value.is_finite():
            raise ValueError(f"{name}={value}: must be finite")
        return value
    exact = rational(name, value, accepted="a real int, Fraction, decimal or 'a/b' string, float or arb")
    return arb(exact.numerator) / exact.denominator


def _norm_upper(values) -> arb:
    """An upper bound of the Euclidean norm of a vector of balls (an exact arb)."""
    return arb(sum((abs(x).abs_upper() ** 2 for x in values), arb(0)).sqrt().abs_upper())


def _disc_bound(c: arb, u, v) -> arb:
    """``M >= ||A(c + tau)||_2`` on the square ``|Re tau|, |Im tau| <= RHO`` (ball enclosures on sub-boxes)."""
    tanh_max = sech_max = arb(0)
    half = arb(RHO) / GRID
    for i in range(GRID):
        for j in range(GRID):
            box = acb(c + arb(-RHO + (2 * i + 1) * RHO / GRID, half), arb(-RHO + (2 * j + 1) * RHO / GRID, half))
            tanh_max = tanh_max.max(abs(box.tanh()).abs_upper())
            sech_max = sech_max.max(abs(box.sech()).abs_upper())
    w = [abs(u[k]).abs_upper() * tanh_max + abs(v[k]).abs_upper() * sech_max for k in (0, 1)]
    return arb((2 * (w[0] ** 2 + w[1] ** 2)).sqrt().abs_upper())


class _Clock:
    """Elapsed time against ``max_seconds``, with progress reports (see :func:`ss_angle_enclosure`)."""

    def __init__(self, max_seconds, progress, length: float):
        if max_seconds is not None and not (isinstance(max_seconds, (int, float)) and max_seconds > 0):
            raise ValueError(f"max_seconds={max_seconds!r}: must be a positive number of seconds (or None)")
        self.max_seconds, self.progress, self.length = max_seconds, progress, length
        self.start = self.last = time.perf_counter()

    def check(self, done: float) -> None:
        now = time.perf_counter()
        elapsed, fraction = now - self.start, done / self.length
        total = elapsed / fraction if fraction > 0.02 else None   # no estimate before 2% of the window
        if self.progress is not None and now - self.last >= 1.0:
            self.last = now
            self.progress(fraction, elapsed, total)
        if self.max_seconds is not None and elapsed > self.max_seconds:
            estimate = f"; estimated total {total:.0f} s" if total else ""
            raise EnclosureTooCostly(
                f"enclosure stopped after {elapsed:.0f} s (max_seconds={self.max_seconds:g}) at {100 * fraction:.0f}% "
                f"of the integration window{estimate}: |omega| is large for this body (step sizes shrink like "
                "1/|omega|) or digits is high; raise max_seconds or lower digits")


def _tanh_sech_series(c: arb, length: int) -> tuple:
    """Taylor series of tanh and sech at c (overflow-free form for either sign of c)."""
    sign = 1 if c >= 0 else -1
    x = arb_series([c, 1], prec=length)
    q = (-2 * sign * x).exp()                        # e^{-2|x|}-like, small for large |c|
    tanh = sign * (1 - q) / (1 + q)
    sech = 2 * (-sign * x).exp() / (1 + q)
    return tanh, sech


def _truncation(Y: arb, M: arb, h: arb, order: int) -> arb:
    """sqrt(3) Y e^{M rho} (h/rho)^{N+1} / (1 - h/rho) with the best rho in [2h, RHO] (see the module docstring)."""
    rho = min(arb(RHO), max(2 * h, arb(order + 1) / M))
    ratio = h / rho
    return (arb(3).sqrt() * Y * (M * rho).exp() * ratio ** (order + 1) / (1 - ratio)).abs_upper()


def _step(y, c: arb, h: arb, u, v, order: int) -> list:
    """The Taylor polynomial of order N of gamma at c (gamma(c) = y, exact midpoints), evaluated at c + h."""
    length = order + 1
    tanh, sech = _tanh_sech_series(c, length)
    w1, w2 = u[0] * tanh + v[0] * sech, u[1] * tanh + v[1] * sech
    # Picard: pass n fixes coefficient n, so it only needs series of n + 1 terms (the products of
    # shorter series are a third of the work of full-length ones; the balls are the same bits for
    # the build's orders, where arb_poly_mullow computes each coefficient on its own)
    g = [arb_series([y[k]], prec=1) for k in range(3)]
    for n in range(1, length):
        rhs = (-g[2] * w2, g[2] * w1, g[0] * w2 - g[1] * w1)   # gamma x (w1, w2, 0), n terms
        g = [arb_series([y[k]], prec=n + 1) + rhs[k].integral() for k in range(3)]
    values = []
    for k in range(3):
        total = arb(0)
        for coefficient in reversed(g[k].coeffs()[:length]):
            total = total * h + coefficient
        values.append(total)
    return values


def _limit_series(u, v, n, side: int, x: arb, budget: arb, clock=None, done: float = 0.0) -> tuple:
    """The exponent-0 solution at s = side * oo, evaluated at ``x = e^(-|s|)``: (balls, remainder bound).

    side = -1: gamma with gamma(-oo) = -n; side = +1: g with g(+oo) = n (module docstring, 1 and 3).
    Terms are added until the remainder bound is below ``budget``.
    """
    W = 2 * max(_norm_upper(u), _norm_upper(v))
    sign = 1 if side < 0 else -1                   # x dgamma/dx = gamma x (sign omega(x))

    def w(j):                                      # coefficient j of sign * omega(x)
        if j == 0:
            return tuple(sign * side * k for k in u)         # -u on both sides
        if j % 2 == 0:
            factor = 2 * (-1) ** (j // 2 + 1) * (-side)      # tanh: -1 + 2x^2 - ... (side -1), 1 - 2x^2 + ... (+1)
            return tuple(sign * factor * k for k in u)
        return tuple(sign * 2 * (-1) ** (j // 2) * k for k in v)

    def cross(y, ww):
        return (-y[2] * ww[1], y[2] * ww[0], y[0] * ww[1] - y[1] * ww[0])

    w0 = w(0)
    first = [side * k for k in n]                  # -n at -oo, +n at +oo
    coefficients, total, power = [first], list(first), arb(1)
    bound_sum, b, k = arb(1), arb(1), 0
    while True:
        k += 1
        if clock is not None:
            clock.check(done)
        rhs = [arb(0)] * 3
        for j in range(1, k + 1):
            term = cross(coefficients[k - j], w(j))
            rhs = [rhs[i] + term[i] for i in range(3)]
        system = arb_mat([[k, 0, w0[1]], [0, k, -w0[0]], [-w0[1], w0[0], k]])   # k - C(w0)
        yk = system.solve(arb_mat([[value] for value in rhs]))
        coefficients.append([yk[i, 0] for i in range(3)])
        power *= x
        total = [total[i] + coefficients[-1][i] * power for i in range(3)]
        b = W * bound_sum / k                      # b_k, and b_(k+1) = b_k (k + W)/(k + 1)
        bound_sum += b
        remainder = _majorant_tail(b, k, W, power, x)
        if remainder is not None and (remainder < budget or k > 4000):
            return total, remainder


def _majorant_tail(b: arb, k: int, W: arb, power: arb, x: arb) -> arb | None:
    """``sqrt(3) sum_(m > k) b_m x^m`` bounded from ``b = b_k`` and ``power = x^k`` (None when it diverges).

    ``b_(m+1)/b_m = (m + W)/(m + 1)``: decreasing towards 1 when W > 1, increasing towards 1 when
    W < 1, so every ratio after k is at most ``q = max(1, (k + 1 + W)/(k + 2))`` and the tail is at
    most ``sqrt(3) b_(k+1) x^(k+1) / (1 - q x)`` (a geometric series, when q x < 1).
    """
    following = b * (k + W) / (k + 1)
    q = max(arb(1), (k + 1 + W) / (k + 2))
    if not q * x < 1:
        return None
    return (arb(3).sqrt() * following * power * x / (1 - q * x)).abs_upper()


def _angle_from_both(cos_angle: arb, sin_angle: arb) -> arb:
    """Delta psi in [0, pi] from balls containing its cosine and its (non-negative) sine.

    Next to Delta psi = 0 or pi the cosine alone loses half the digits (arccos has infinite slope
    at +-1: a cosine known to r gives the angle to sqrt(2 r)); the arctangent of sin/cos or cos/sin,
    whichever quotient is bounded, keeps the width of the data.  Intersected with the
    cosine-only enclosure (both contain the angle)."""
    from_cosine = _angle_from_cosine(cos_angle)
    if not sin_angle > 0 and not (cos_angle < 0 or cos_angle > 0):
        return from_cosine
    if cos_angle < 0 and abs(cos_angle) >= sin_angle:
        angle = arb.pi() - (sin_angle / -cos_angle).atan()
    elif cos_angle > 0 and cos_angle >= sin_angle:
        angle = (sin_angle / cos_angle).atan()
    elif sin_angle > 0:
        angle = arb.pi() / 2 - (cos_angle / sin_angle).atan()
    else:
        return from_cosine
    return angle.intersection(from_cosine)


def _angle_from_cosine(cos_angle: arb) -> arb:
    """arccos on [-1, 1] as an arctangent of sin/cos (finite slope at cos = +-1 from inside), in [0, pi]."""
    sine = (1 - cos_angle**2).nonnegative_part().sqrt()        # 1 - c^2 >= 0 exactly
    if cos_angle < 0:
        angle = arb.pi() - (sine / -cos_angle).atan()
    elif cos_angle > 0:
        angle = (sine / cos_angle).atan()
    else:
        angle = arb.atan2(sine, cos_angle)
    return angle.intersection(arb.pi() / 2 + arb(0, 1) * arb.pi() / 2)


class EnclosureTooCostly(RuntimeError):
    """The enclosure would take longer than its ``max_seconds`` (the message says how far it got)."""


DIGITS_RANGE = (1, 300)   # 300 digits: about 1 minute for an ordinary body on one core (bench_enclosure)
MAX_SECONDS = 120.0       # default time limit of the run-time entry points


def ss_angle_enclosure(u, v, digits: float = 30, prec: int | None = None, step: float = 0.25,
                       series_start: float = 1.5, max_seconds: float | None = None,
                       progress=None) -> AngleEnclosure:
    """Enclosure of the ss scattering angle for omega(s) = u tanh s + v sech s (u, v pairs of balls).

    ``digits``: the absolute error aimed at, 10**-digits (sets the window, the order and, unless
    given, the precision); at most ``DIGITS_RANGE[1]``.  The returned ball is rigorous whatever the
    settings; a too low ``prec`` only makes it wider, and so do u, v computed at a lower precision
    than ``prec`` (they are balls: their radii propagate).

    The cost grows with ``|omega|`` (the step shrinks where omega turns fast: like p^2 as I23 -> 0 for
    I13 = 0) and with digits.  ``max_seconds``: stop with :class:`EnclosureTooCostly` once the
    integration has run that long, saying how far it got and the estimated total (extrapolated from
    the fraction of the window done); ``progress(fraction, seconds, estimated_total)`` is called at
    most once a second.
    """
    if isinstance(digits, bool) or not isinstance(digits, (int, float)) or not (
            DIGITS_RANGE[0] <= digits <= DIGITS_RANGE[1]):
        raise ValueError(f"digits={digits!r}: must be a number of digits in [{DIGITS_RANGE[0]}, {DIGITS_RANGE[1]}]")
    if not 0.5 <= series_start <= 3:
        raise ValueError(f"series_start={series_start!r}: must be in [0.5, 3] (the series converge for |x| < 1)")
    if not 0 < step <= 0.5:
        raise ValueError(f"step={step!r}: must be in (0, 0.5] (tanh, sech have poles pi/2 off the real axis)")
    saved_cap = ctx.cap                                # workprec restores the precision, not the cap
    try:
        with ctx.workprec(int(prec if prec is not None else 3.33 * digits + 40)):
            u = tuple(arb(x) for x in u)
            v = tuple(arb(x) for x in v)
            nu = (u[0] ** 2 + u[1] ** 2).sqrt()
            if not nu > 0:
                raise ValueError("u = 0: no limit rotation (omega does not tend to a non-zero equilibrium)")
            n = (u[0] / nu, u[1] / nu, arb(0))
            target = arb(10) ** (-digits)
            S = arb(series_start)
            if not S.is_exact():
                raise ValueError(f"series_start={series_start!r}: must be a binary fraction (0.5, 1.5, 2.25, ...)")
            order = math.ceil(1.5 * digits) + 10
            ctx.cap = order + 2                            # arb_series truncates at ctx.cap terms
            clock = _Clock(max_seconds, progress, 2 * float(S))
            y, tail_minus = _limit_series(u, v, n, -1, (-S).exp(), target / 3, clock)
            delta = _norm_upper([arb(0, b.rad()) for b in y]) + tail_minus
            at_start = tuple(b + _UNIT * tail_minus for b in y)
            y = [b.mid() for b in y]
            per_unit_time = target / 3 / (2 * S)          # step budget: truncation <= this times h
            step_error = arb(0)
            c, steps = -S, 0
            while c < S:
                clock.check(float(c + S))
                # h = step / 2^m keeps every c an exact dyadic number: c lands on s = 0 (gamma(0) reported)
                # and on S exactly
                h = arb(step)
                while (c < 0 and c + h > 0) or c + h > S:
                    h = h / 2
                M = _disc_bound(c, u, v)
                Y = _norm_upper(y)
                truncation = _truncation(Y, M, h, order)
                while truncation > per_unit_time * h:     # adapt the step where omega turns fast
                    h = h / 2
                    if h < 1e-9:
                        raise ArithmeticError(f"step below 1e-9 at s = {c}: |omega| too large for {digits} digits "
                                              f"at {ctx.prec} bits")
                    truncation = _truncation(Y, M, h, order)
                balls = _step(y, c, h, u, v, order)
                step_error += _norm_upper([arb(0, b.rad()) for b in balls]) + truncation
                y = [b.mid() for b in balls]
                c, steps = c + h, steps + 1
                if c == 0:
                    at_zero = tuple(arb(x) + _UNIT * (delta + step_error).abs_upper() for x in y)
            delta += step_error
            g, tail_plus = _limit_series(u, v, n, +1, (-S).exp(), target / 3, clock, 2 * float(S))
            g = [b + _UNIT * tail_plus for b in g]
            along = sum((y[k] * g[k] for k in range(3)), arb(0))
            along = along + _UNIT * (delta * (1 + tail_plus)).abs_upper()    # |<e, g>| <= |e| |g|
            cos_angle = (-along).intersection(arb(0, 1))
            # sin Delta psi = |y x g| (y, g unit solutions at angle pi - Delta psi); |e x g| <= |e| |g|
            cross = (y[1] * g[2] - y[2] * g[1], y[2] * g[0] - y[0] * g[2], y[0] * g[1] - y[1] * g[0])
            norm = sum((k * k for k in cross), arb(0)).nonnegative_part().sqrt()
            sin_angle = (norm + _UNIT * (delta * (1 + tail_plus)).abs_upper()).intersection(arb(0.5, 0.5))
            angle = _angle_from_both(cos_angle, sin_angle)
            s0, s1 = -float(S), float(S)
            return AngleEnclosure(Ball(angle), Ball(cos_angle), (s0, s1), steps, order, ctx.prec,
                                  {"tail_minus": float(tail_minus.abs_upper()), "steps": float(step_error.abs_upper()),
                                   "tail_plus": float(tail_plus.abs_upper())}, at_zero, at_start)
    finally:
        ctx.cap = saved_cap


