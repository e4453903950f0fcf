"""The scattering angle of every body in closed form, in float64, mpmath and ball arithmetic.

``invariants`` is the generated module's emitted ``_gauss_invariants(ctx, I11, I22, I13, I23)`` and
``emitted`` its ``_general_angle(ctx, h, g, s, c)`` (certified: ``derivations/sections/gauss.py`` and
``general_angle.py``); the arguments between them come from :mod:`suslov.kernel.gauss_angle`.  Here:
validation, broadcasting and the scaling that keeps float64 finite for every finite body.

Scaling (float64 only).  The invariants ``(U^2, a, b, c2)`` are homogeneous of degree 0 in the four
entries and, in ``(I13, I23)`` alone, of degree -2 (``c2``: -4).  So the entries are first divided by
their largest modulus, then ``(I13, I23)`` by theirs (``lam``); the lengths ``U``, ``X``, ``Y`` and
the gap computed there are divided by ``lam`` afterwards: a body next to the equilibrium
(``|I13|, |I23| ~ 1e-200``) gives a finite angle instead of an overflow.

Precision that keeps its promise (issue 44).  The angle depends on ``Y = Im w_-`` modulo 2 (``s, c`` are
``|sin|, |cos|`` of ``pi Y/2``), so an absolute error of the angle below ``10^-n`` needs ``Y`` to
``n + log10|Y|`` digits: ``(1e200, 1, 1, 1)`` has ``|Y| = 1e100``, and at the 45 working digits of ``dps=30``
the mp twin returned 2.0056... for 2.0350... (the float route, through its mpmath repair, alike and silently).

* ``_mp`` and ``_ball``: the entries are read exactly (``suslov.kernel.validate.rational``) and multiplied by
  their common denominator (the invariants are homogeneous of degree 0), so the cancelling differences of the
  invariants (``I11 - I22``, ``I13^2 I22 - I11 I23^2``) start from exact integers whatever the exponent spread
  of the entries (``"1/3", "1/3"`` gave the ball ``[+/- 6.29]``).  The closed form is evaluated in ball
  arithmetic at the working precision (first ``prec + 30`` bits, or ``dps + 15`` digits); while the ball of the
  angle carries fewer relative bits than asked, the working precision grows by what is missing plus ``log2`` of
  the radii of ``|Y|``, ``h`` and ``g`` that are not below 1/4 (the phase needs ``log2 |Y|`` more bits than the
  angle, the exponentials ``log2 h``), and at least by half.  Beyond :data:`MAX_EXTRA_BITS` bits more than asked
  a ``ValueError`` states the working digits the body needs.  The mp twin evaluates the emitted formula in
  mpmath at the precision the ball found sufficient and returns that value only when it lies within the ball
  (widened by 2^-8 of the last digit claimed); ``dps`` digits are then correct up to the rounding of the last.
  Balls of non-zero radius given as entries are evaluated once, at ``prec + 30`` bits (their width is theirs).
* float64 (its bits on the proven domain unchanged: ``derivations/proofs/general_angle_proof.py``):

  - where the docstring's forward bound ``1e-13 (1 + |Y|)`` exceeds one radian (``|Y| > 1e13``) the float64
    phase says nothing.  Where, in addition, the phase moves the angle by more than ``1e-13`` (the angles at
    ``s = 0`` and ``s = 1`` differ by more: ``cos^2(Delta psi/2)`` is linear in ``s^2``; next to the equilibrium
    ``sech h`` removes the phase and the result stands) a ``ValueError`` names the body, ``|Y|``, why it is outside
    the proven domain and the mp twin.  Inside the proven domain this never happens: ``|Y|^2/U^2 <= |I11 - I22|
    D/(I11 I22) <= 2^41`` (scaled entries, ``D <= 2``), so ``|Y| < 1.5e6 U``, and the phase moves the angle by at
    most ``pi sech h`` (``cos^2(Delta psi/2) = cosh^2 x/cosh^2 h - s^2 (sinh^2 h - sinh^2 x)/(sinh^2 h cosh^2 h)``,
    ``x = pi X/2``), below 1e-13 beyond ``h = 32``: where it matters, ``|Y| < 3.1e7``.
  - outside the proven domain's ``I11, I22 >= 2^-20`` times the largest entry, the scaled invariants can
    underflow (``c2 = I11^3 I22^3/D^2`` to 0: the angle 0 for pi), so each such body gets the phase rule and its
    value is checked against the ball of the closed form (60 bits): kept when within ``1e-13 (1 + |Y|)``
    (relative below an angle of 1; without the Y term when ``|Y| > 1e13``), else replaced by the ball's value
    (one ball evaluation per such body, about 0.2 ms).  Next to the equilibrium (``pi U/2 > 7e13``, entries in
    the domain) the float64 values were exact against 120-bit balls on 1500 sampled bodies: not checked.
  - entries whose float64 evaluation has no finite value get the phase rule too; the composition in mpmath at
    ``finite.REPAIR_DPS`` digits (what ``finite.repair`` returned) is kept when within 2^-56 of the 60-bit ball,
    else the ball's value is taken.
"""
from __future__ import annotations

import math
from fractions import Fraction

import flint
import mpmath
import numpy as np
from flint import arb

from suslov.kernel import finite, gauss_angle, phase, validate
from suslov.kernel.contexts import ARB, FLOAT, MP
from suslov.kernel.display import Ball, MPValue
from suslov.kernel.enclosure import to_arb
from suslov.kernel.scalars import like_ufunc
from suslov.kernel.validate import ball_prec, mp_dps, mp_real, rational, real_array

__all__ = ["MAX_EXTRA_BITS", "general_scattering_angle", "general_scattering_angle_ball", "general_scattering_angle_mp"]

_HUGE = 1e300   # h and g beyond this change no digit of the angle (e^-2h underflows long before)
NAMES = ("I11", "I22", "I13", "I23")
_Y_LIMIT = 1e13        # |Y| beyond which the docstring's forward bound 1e-13 (1 + |Y|) exceeds one radian
_PHASE_TOL = 1e-13     # a phase that moves the angle by less than this leaves the float64 result standing
_FLOOR, _H_LIMIT = 2.0**-20, 7e13   # the proven float64 domain (general_angle_proof): scaled I11, I22, h = pi U/2
_REPAIR_BITS = 60      # a repaired float64 value is kept when within the ball of this many bits
MAX_EXTRA_BITS = 65_536   # the _mp and _ball routes work at most this many bits beyond the precision asked
_LOG2_10 = math.log2(10)


def _equilibrium(both_zero) -> None:
    both_zero = np.asarray(both_zero)
    if np.any(both_zero):
        index = tuple(int(i) for i in np.argwhere(both_zero)[0]) if both_zero.ndim else ()
        where = f" at index {list(index)}" if index else ""
        raise ValueError(f"I13=0 and I23=0{where}: the constraint axis is a principal axis; every motion is an "
                         "equilibrium (no scattering)")


@like_ufunc
def general_scattering_angle(invariants, emitted, I11, I22, I13, I23) -> np.ndarray | np.float64:
    I11, I22 = real_array("I11", I11, positive=True), real_array("I22", I22, positive=True)
    I13, I23 = real_array("I13", I13), real_array("I23", I23)
    I11, I22, I13, I23 = np.broadcast_arrays(I11, I22, I13, I23)
    _equilibrium((I13 == 0) & (I23 == 0))
    given = (I11, I22, I13, I23)
    size = np.maximum(np.maximum(I11, I22), np.maximum(np.abs(I13), np.abs(I23)))
    I11, I22, I13, I23 = I11 / size, I22 / size, I13 / size, I23 / size
    lam = np.maximum(np.abs(I13), np.abs(I23))
    # lam = 0 (I13/size and I23/size both below float64's range: 0/0) and Y/lam beyond float64 (lam subnormal) give
    # NaN here, silently: those bodies are evaluated again in mpmath below
    with np.errstate(under="ignore", invalid="ignore"):
        U2, a, b, c2 = invariants(FLOAT, I11, I22, I13 / lam, I23 / lam)
    with np.errstate(divide="ignore", invalid="ignore"):   # the same NaN, without a RuntimeWarning
        U, gap, Y = gauss_angle.float_lengths(U2, a, b, c2)
    with np.errstate(over="ignore"):   # lengths scale like 1/lam
        h, g, Y = np.minimum(0.5 * np.pi * U / lam, _HUGE), np.minimum(0.5 * np.pi * gap / lam, _HUGE), Y / lam
    with np.errstate(invalid="ignore"):
        s, c = phase.half_pi_parts(Y)
    with np.errstate(under="ignore", over="ignore", invalid="ignore"):
        angle = np.asarray(emitted(FLOAT, h, g, s, c), dtype=float)
    # outside the proven domain's I11, I22 >= 2^-20 (scaled), each value is checked against the ball of the closed
    # form; where float64 has no value (entries spanning more than its range: I11/size underflows to 0), the
    # formula again in mpmath at finite.REPAIR_DPS (as finite.repair evaluates it), checked alike
    missing = ~np.isfinite(angle)
    checked = missing | ~((I11 >= _FLOOR) & (I22 >= _FLOOR))
    if checked.any():
        for index in (tuple(int(i) for i in row) for row in np.argwhere(checked)):
            body = tuple(float(x[index]) for x in given)
            if missing[index]:
                with mpmath.workdps(finite.REPAIR_DPS):
                    value = _again(invariants, emitted, *(mpmath.mpf(x) for x in body))
                    angle[index] = float(_certified_float(invariants, emitted, body, value, index))
            else:
                angle[index] = float(_certified_float(invariants, emitted, body, angle[index], index))
    # nothing is left non-finite: the angle lies in [0, pi]; finite.repair stays the contract's last check
    (angle,) = finite.repair("general_scattering_angle", (angle,), NAMES, given, lambda *body: (
        _certified_float(invariants, emitted, tuple(float(x) for x in body), _again(invariants, emitted, *body), None),))
    return angle


def _again(invariants, emitted, *body):
    """The composition in mpmath at the current precision (mpf entries), as finite.repair evaluated it."""
    return emitted(MP, *gauss_angle.mp_arguments(*invariants(MP, *body)))


def _phase_error(body, index, Y: str, spread, small, far) -> ValueError:
    """The float64 route's refusal of a body whose phase pi Y/2 (mod 2) it cannot resolve and which matters."""
    where = f" at index {list(index)}" if index else ""
    outside = [f"{n} < 2^-20 times the largest entry" for n in small] + (["pi U/2 > 7e13"] if far else [])
    domain = f"outside the proven float64 domain ({', '.join(outside)}): " if outside else ""
    shown = ", ".join(f"{n}={x!r}" for n, x in zip(NAMES, body))
    return ValueError(f"general_scattering_angle({shown}){where}: {domain}|Y| = |Im w_-| = {Y}, so the phase "
                      f"pi Y/2 (mod 2) is beyond float64 (its bound 1e-13 (1 + |Y|) says nothing) and moves the angle "
                      f"by up to {spread:.2g}; general_scattering_angle_mp evaluates it with the digits it needs")


def _certified_float(invariants, emitted, body: tuple, candidate, index):
    """A float64 route's value (a float, or the repair's mpf) for one body outside the proven domain: the phase
    rule (ValueError), then ``candidate`` when within ``1e-13 (1 + |Y|)`` (relative below an angle of 1; without
    the Y term when ``|Y| > 1e13``, where the phase moves the angle by less than ``_PHASE_TOL``) of the ball of
    the closed form, else the ball's midpoint (``_REPAIR_BITS`` relative bits).  The float64 entries are exact."""
    entries = _integer_body(tuple(rational(n, x) for n, x in zip(NAMES, body)))
    with flint.ctx.workprec(_REPAIR_BITS + 30):
        first = _ball_and_radii(invariants, emitted, entries, _REPAIR_BITS + 30)
        _, Y, h, g = first
        magnitude = float(Y.mid())
        if magnitude > _Y_LIMIT:
            spread = float(abs(emitted(ARB, h, g, arb(1), arb(0)) - emitted(ARB, h, g, arb(0), arb(1))).mid())
            if not spread <= _PHASE_TOL:
                size = max(abs(x) for x in body)
                raise _phase_error(body, index or (), Y.mid().str(3, radius=False), spread,
                                   [n for n, x in zip(NAMES, body[:2]) if not x / size >= _FLOOR],
                                   not float(h.mid()) <= _H_LIMIT)
            magnitude = 0.0
    describe = "general_scattering_angle(" + ", ".join(f"{n}={x!r}" for n, x in zip(NAMES, body)) + ")"
    ball = _certified_ball(invariants, emitted, entries, _REPAIR_BITS, _REPAIR_BITS + 30, lambda: describe,
                           first=first)
    exact = float(ball.mid())
    if isinstance(candidate, mpmath.mpf):      # the repair's 30 digits: kept when float64 cannot tell them apart
        tolerance = 2.0**-56 * abs(exact)
    else:
        tolerance = 1e-13 * (1 + magnitude) * min(1.0, exact)
    if mpmath.isfinite(candidate) and abs(float(candidate) - exact) <= tolerance:
        return candidate
    return _to_mpf(ball.mid()) if isinstance(candidate, mpmath.mpf) else exact


def general_scattering_angle_mp(invariants, emitted, I11, I22, I13, I23, dps=None):
    dps = mp_dps(dps)
    given = (I11, I22, I13, I23)
    with mpmath.workdps(dps + 15):
        I11, I22 = mp_real("I11", I11, positive=True), mp_real("I22", I22, positive=True)
        I13, I23 = mp_real("I13", I13), mp_real("I23", I23)
        _equilibrium(I13 == 0 and I23 == 0)
    entries = _integer_body(tuple(rational(n, x) for n, x in zip(NAMES, given)))
    target = math.ceil(dps * _LOG2_10) + 8
    start = math.ceil((dps + 15) * _LOG2_10)

    def describe() -> str:
        return f"general_scattering_angle_mp({_shown_body(given)}, dps={dps})"

    def in_mpmath(bits):
        with mpmath.workprec(max(x.bit_length() for x in entries) + 1):
            exact = tuple(mpmath.mpf(x) for x in entries)      # exact: the working precision rounds what follows
        with mpmath.workprec(bits):
            return emitted(MP, *gauss_angle.mp_arguments(*invariants(MP, *exact)))

    out = _certified_mp(invariants, emitted, entries, target, start, in_mpmath, describe)
    with mpmath.workdps(dps):
        return MPValue(+out, dps)


def general_scattering_angle_ball(invariants, emitted, I11, I22, I13, I23, dps=None, prec=None) -> Ball:
    prec = ball_prec(dps, prec)
    given = (I11, I22, I13, I23)
    with flint.ctx.workprec(prec + 30):
        I11, I22, I13, I23 = balls = tuple(to_arb(n, x) for n, x in zip(NAMES, given))
        for name, x in (("I11", I11), ("I22", I22)):
            if not x > 0:
                raise ValueError(f"{name}={x}: must be positive")
        if I13.is_zero() and I23.is_zero():
            _equilibrium(True)
        if any(isinstance(x, arb) and not x.is_exact() for x in given):   # balls given: their width is theirs
            return Ball(emitted(ARB, *gauss_angle.arb_arguments(*invariants(ARB, *balls))))
    exact = tuple(_to_fraction(n, x) if isinstance(x, arb) else rational(n, x) for n, x in zip(NAMES, given))
    return Ball(_certified_ball(invariants, emitted, _integer_body(exact), prec, prec + 30,
                                lambda: f"general_scattering_angle_ball({_shown_body(given)}, prec={prec})"))


# ---------------------------------------------------------------- working precision that grows with the body


def _integer_body(exact: tuple) -> tuple:
    """The four exact entries times their common denominator (and over the gcd of the numerators): integers in
    the same ratios, so the degree-0 invariants are those of the body and every difference starts exact."""
    common = 1
    for q in exact:
        common = common * q.denominator // math.gcd(common, q.denominator)
    numbers = [q.numerator * (common // q.denominator) for q in exact]
    divisor = 0
    for n in numbers:
        divisor = math.gcd(divisor, n)
    return tuple(n // divisor for n in numbers)


def _ball_and_radii(invariants, emitted, entries: tuple, bits: int) -> tuple:
    """(angle, |Y|, h, g) as balls at ``bits`` from the exact integer entries."""
    with flint.ctx.workprec(bits):
        h, g, s, c, Y = gauss_angle.arb_arguments_and_phase(*invariants(ARB, *(arb(x) for x in entries)))
        return emitted(ARB, h, g, s, c), Y, h, g


def _more_bits(angle: arb, target: int, radii) -> int | None:
    """Bits to add to reach ``target`` relative bits: the shortfall of the angle, plus log2 of every radius of
    |Y|, h, g at or above 1/4 (there the angle's ball no longer shrinks with the working precision: a phase or an
    exponential not resolved at all); None when nothing is finite to go by."""
    more = 0
    for x in radii:
        if not x.is_finite():
            return None
        rad = x.rad()
        if rad >= 0.25:
            mantissa, exponent = rad.man_exp()
            more += int(mantissa).bit_length() + int(exponent) + 2      # log2(rad) + 2, rounded up
    accuracy = angle.rel_accuracy_bits() if angle.is_finite() else -(10**9)
    return more + max(0, target - max(accuracy, 0))


def _certified_ball(invariants, emitted, entries, target: int, start: int, describe, check=None, first=None) -> arb:
    """The ball of the angle with at least ``target`` relative bits (``check(bits, ball)`` may ask for more),
    the working precision growing from ``start`` (``first``: the balls already evaluated there); ValueError
    beyond ``target + 30 + MAX_EXTRA_BITS``."""
    bits, limit = start, target + 30 + MAX_EXTRA_BITS
    while True:
        angle, Y, h, g = first or _ball_and_radii(invariants, emitted, entries, bits)
        first = None
        if angle.is_finite() and angle.rel_accuracy_bits() >= target and (check is None or check(bits, angle)):
            return angle
        more = _more_bits(angle, target, (Y, h, g))
        following = max(bits + (more or 0) + 32, bits + bits // 2)
        if following > limit:
            need = f"about {math.ceil((bits + more + 32) / _LOG2_10)}" if more is not None else \
                f"more than {math.ceil(bits / _LOG2_10)}"
            raise ValueError(f"{describe()}: this body needs {need} working digits (|Y| = |Im w_-| ~ "
                             f"{_magnitude(Y)}: the phase pi Y/2 (mod 2) needs log10|Y| digits beyond those asked; "
                             f"h = pi U/2 ~ {_magnitude(h)}), beyond the {math.floor(limit / _LOG2_10)} digits "
                             f"this route works with ({MAX_EXTRA_BITS} bits beyond the precision asked)")
        bits = following


def _certified_mp(invariants, emitted, entries, target: int, start: int, in_mpmath, describe):
    """The mpmath value at the working precision the ball found sufficient, returned only within that ball."""
    found = {}

    def agrees(bits, ball) -> bool:
        value = in_mpmath(bits)
        found["value"] = value
        return mpmath.isfinite(value) and _within(value, ball, target)

    _certified_ball(invariants, emitted, entries, target, start, describe, agrees)
    return found["value"]


def _within(value, ball: arb, bits: int) -> bool:
    """``value`` (an mpf) within ``ball`` widened by ``2^-bits`` relative."""
    with flint.ctx.workprec(max(flint.ctx.prec, bits + 20)):
        return bool(abs(_to_arb(value) - ball.mid()) <= ball.rad() + abs(ball.mid()) * arb(2) ** -bits)


def _to_arb(value) -> arb:
    """An mpf as the exact ball of its binary value (never rounded through the global mpmath precision)."""
    sign, mantissa, exponent, _ = value._mpf_
    return arb((-int(mantissa) if sign else int(mantissa), int(exponent)))


def _to_mpf(x: arb):
    """An exact arb as an mpf, rounded to the current mpmath precision."""
    mantissa, exponent = x.man_exp()
    return mpmath.mpf((int(mantissa), int(exponent)))


def _to_fraction(name: str, x: arb) -> Fraction:
    """An exact ball given as an entry, exactly (its size checked like any exact input: through an exact mpf)."""
    mantissa, exponent = (int(v) for v in x.mid().man_exp())
    with mpmath.workprec(max(mantissa.bit_length(), 1) + 1):
        return rational(name, mpmath.mpf((mantissa, exponent)))


def _magnitude(x: arb) -> str:
    if not x.is_finite():
        return "?"
    upper = abs(x).upper()
    if upper.is_zero():
        return "0"
    with flint.ctx.workprec(64):
        decades = float((upper.log() / arb(10).log()).mid())
    return f"1e{round(decades)}"


def _shown_body(given) -> str:
    show = getattr(validate, "shown", repr)     # abbreviates 6000-digit entries
    return ", ".join(f"{n}={show(x)}" for n, x in zip(NAMES, given))
