"""Arguments of the closed-form scattering angle of any body, in float64, mpmath and ball arithmetic.

The general case in closed form (``derivations.sections.gauss`` and ``general_angle``): with
``s = sinh t`` the Poisson equations are Gauss's equation, and the scattering angle of *any* body is

    cos^2(Delta psi/2) = [cosh(pi U) |tau|^2 - Re(tau^2)] / (2 sinh^2(pi U)),  tau = 2 cos(pi kappa),

``kappa = (i/2) w_-``, ``w_-^2 = a + i b = (u - i v).(u - i v)``, ``U^2 = u.u``.  The generated module's
emitted ``_general_angle(ctx, h, g, s, c)`` evaluates it in a form without cancellation or overflow;
this module computes its four arguments from the emitted invariants ``(U^2, a, b, c2)`` of the body
(``_gauss_invariants``; ``c2 = (u x v)_3^2``):

* ``w_- = X + i Y`` by the stable complex square root: ``X^2 = (|w^2| + a)/2`` when ``a >= 0`` (then
  ``Y = b/(2X)``), else ``Y^2 = (|w^2| - a)/2`` (then ``X = |b|/(2|Y|)``), so no difference of nearly
  equal numbers; only ``|Y|`` is needed (the angle is even in Y).
  (float64: ``suslov.runtime.general_angle`` scales first, so nothing overflows.)
* the gap ``U - X = 2 c2 / ((U^2 + |v|^2 + |w^2|) (U + X))``, from
  ``(U^2 + |v|^2)^2 - |w^2|^2 = 4 U^2 v2^2 = 4 c2`` (certified by the build): positive for every body
  (``c2 = I11^3 I22^3 / D^2 > 0``), computed without cancellation even where the angle is small.
* ``h = pi U/2``, ``g = pi (U - X)/2``, ``s = |sin(pi Y/2)|``, ``c = |cos(pi Y/2)|`` (in float64 with
  Y reduced modulo 2 exactly: ``suslov.kernel.phase.half_pi_parts``).

``U^2 + |v|^2 = 2 U^2 - a >= U^2`` (``a <= U^2``), so that sum loses nothing either.
:func:`gauss_parameters` forms Gauss's A, B, C (``suslov.validated.hypergeometric_form``) from the exact
invariants the same way, the cancelling differences in integers.  No SymPy, no ``generated`` import
(the kernel layer).
"""
from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
from flint import acb, arb

__all__ = ["arb_arguments", "arb_arguments_and_phase", "arb_root", "float_lengths", "gauss_parameters", "mp_arguments"]


def float_lengths(U2, a, b, c2) -> tuple:
    """(U, U - X, |Y|) in float64 (arrays broadcast) from the invariants of the bodies; the caller
    scales them (they are lengths: degree -1 in (I13, I23)) and forms h, g, s, c."""
    U2, a, b, c2 = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (U2, a, b, c2)))
    b = np.abs(b)
    modulus = np.hypot(a, b)
    positive = a >= 0
    with np.errstate(divide="ignore", invalid="ignore"):
        big = np.sqrt(0.5 * (modulus + np.abs(a)))          # X when a >= 0, |Y| otherwise
        small = np.where(big > 0, 0.5 * b / big, 0.0)       # the other one, from X |Y| = |b|/2
    X = np.where(positive, big, small)
    Y = np.where(positive, small, big)
    U = np.sqrt(U2)
    gap = 2.0 * c2 / ((2.0 * U2 - a + modulus) * (U + X))
    return U, gap, Y


def _complex_root_parts(a, b, sqrt):
    b = abs(b)
    modulus = sqrt(a * a + b * b)
    big = sqrt((modulus + abs(a)) / 2)
    small = b / (2 * big) if big != 0 else 0 * b
    return (big, small, modulus) if a >= 0 else (small, big, modulus)


def mp_arguments(U2, a, b, c2) -> tuple:
    """(h, g, s, c) in mpmath at the working precision (mpf inputs)."""
    X, Y, modulus = _complex_root_parts(a, b, mpmath.sqrt)
    U = mpmath.sqrt(U2)
    gap = 2 * c2 / ((2 * U2 - a + modulus) * (U + X))
    return mpmath.pi * U / 2, mpmath.pi * gap / 2, abs(mpmath.sinpi(Y / 2)), abs(mpmath.cospi(Y / 2))


def arb_arguments(U2: arb, a: arb, b: arb, c2: arb) -> tuple:
    """(h, g, s, c) as balls (precision ``flint.ctx.prec``) containing the exact values at the ball inputs."""
    return arb_arguments_and_phase(U2, a, b, c2)[:4]


def arb_arguments_and_phase(U2: arb, a: arb, b: arb, c2: arb) -> tuple:
    """(h, g, s, c, |Y|) as balls: :func:`arb_arguments` and the ball of ``|Y|`` it took s and c from (its radius
    says how far the working precision is from resolving the phase pi Y/2 modulo 2)."""
    X, Y = arb_root(a, b)
    modulus = (a * a + b * b).sqrt()
    U = U2.sqrt()
    gap = 2 * c2 / ((2 * U2 - a + modulus) * (U + X))
    half = abs(Y) / 2
    return arb.pi() * U / 2, arb.pi() * gap / 2, abs(half.sin_pi()), abs(half.cos_pi()), abs(Y)


def arb_root(a: arb, b: arb) -> tuple:
    """(X, Y) with (X + i Y)^2 = a + i b and X >= 0, as balls, off the branch cut of acb's sqrt (b = 0 with
    a < 0 is the case I13 = 0, where a complex ball about the negative axis would cover both roots)."""
    modulus = (a * a + b * b).sqrt()
    if a < 0:
        size = ((modulus - a) / 2).sqrt()
        return abs(b) / (2 * size), (-size if b < 0 else size)
    if a.is_zero() and b.is_zero():
        return arb(0), arb(0)
    X = ((modulus + a) / 2).sqrt()
    return X, b / (2 * X)


def _quotient(numerator: int, denominator: int) -> arb:
    """``numerator/denominator`` (integers, denominator > 0) as a ball at ``flint.ctx.prec``: ``arb(int)`` is
    exact whatever its size, so the only rounding is the division's (relative, at any magnitude)."""
    return arb(numerator) / denominator


def gauss_parameters(U2: Fraction, a: Fraction, q: Fraction, R: Fraction) -> tuple:
    """``(A, B, C, kappa, mu, iU)`` of Gauss's equation (:func:`suslov.validated.hypergeometric_form`) as
    complex balls at ``flint.ctx.prec``, from the exact invariants ``U^2``, ``a = Re w_-^2`` and
    ``Im w_-^2 = b = q sqrt(R)`` (:func:`suslov.kernel.kimura.exact_invariants`).

    With ``w_- = X + iY`` (``X >= 0``, :func:`arb_root`), ``kappa = (i/2) w_- = (-Y + iX)/2``,
    ``mu = (i/2) conj(w_-) = (Y + iX)/2`` and ``kappa + mu = iX``:

    * ``A = (2 + kappa + mu + iU)/2 = 1 + i (U + X)/2`` (a sum of non-negative numbers);
    * ``B = (kappa + mu - iU)/2 = -i (U - X)/2``, the gap ``U - X = 2 c2 / ((2U^2 - a + |w^2|)(U + X))``
      with ``4 c2 = 4 U^2 (U^2 - a) - q^2 R`` (``(U^2 + |v|^2)^2 - |w^2|^2 = 4 c2``, certified: gauss) formed
      exactly in integers: no difference of nearly equal balls;
    * ``C = 1 + kappa = 1 - Y/2 + iX/2``; for ``Y > 0``, ``1 - Y/2 = (8 + a - |w^2|) / (4 (2 + Y))`` (from
      ``Y^2 = (|w^2| - a)/2``) and, when ``8 + a > 0``, ``8 + a - |w^2| = (64 + 16 a - q^2 R) / (8 + a + |w^2|)``
      with the numerator exact: ``Re C`` keeps its relative accuracy near ``Y = 2`` too (0 exactly when it is).

    Every rational enters as one rounded quotient of exact integers, so every part has a relative error of
    a few units of ``ctx.prec`` whatever the size of the entries (10^100 or 10^-100 alike).
    """
    nU, dU = U2.numerator, U2.denominator
    na, da = a.numerator, a.denominator
    nq, dq = q.numerator, q.denominator
    bn, bd = nq * nq * R.numerator, dq * dq * R.denominator          # b^2 = q^2 R = bn/bd
    U2b, ab = _quotient(nU, dU), _quotient(na, da)
    b = _quotient(nq, dq) * _quotient(R.numerator, R.denominator).sqrt()
    modulus = _quotient(na * na * bd + bn * da * da, da * da * bd).sqrt()    # |w^2| = sqrt(a^2 + q^2 R)
    X, Y = arb_root(ab, b)
    U = U2b.sqrt()
    c4n = 4 * nU * (nU * da - na * dU) * bd - bn * dU * dU * da            # 4 c2 = c4n / (dU^2 da bd)
    if c4n <= 0:
        raise ArithmeticError(f"4 c2 = {Fraction(c4n, dU * dU * da * bd)} <= 0: not the invariants of a body "
                              "(c2 = (u x v)_3^2 > 0 for every body)")
    gap = _quotient(c4n, 2 * dU * dU * da * bd) / ((2 * U2b - ab + modulus) * (U + X))
    if nq > 0 or (nq == 0 and na < 0):          # Y > 0 (arb_root: Y has the sign of b; Y >= 0 when b = 0)
        shifted = 8 * da + na                    # 8 + a = shifted/da
        if shifted > 0:
            difference = _quotient((64 * da + 16 * na) * bd - bn * da, da * bd) / (_quotient(shifted, da) + modulus)
        else:
            difference = _quotient(shifted, da) - modulus
        real_c = difference / (4 * (2 + Y))
    else:
        real_c = 1 - Y / 2
    kappa, mu, iU = acb(-Y, X) / 2, acb(Y, X) / 2, acb(0, U)
    return acb(1, (U + X) / 2), acb(0, -gap / 2), acb(real_c, X / 2), kappa, mu, iU
