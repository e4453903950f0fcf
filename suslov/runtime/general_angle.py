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
"""
from __future__ import annotations

import flint
import mpmath
import numpy as np

from suslov.kernel import finite, gauss_angle, phase
from suslov.kernel.contexts import ARB, FLOAT, MP
from suslov.kernel.display import Ball, MPValue
from suslov.kernel.enclosure import to_arb
from suslov.kernel.validate import ball_prec, mp_dps, mp_real, real_array

__all__ = ["general_scattering_angle", "general_scattering_angle_mp", "general_scattering_angle_ball"]

_HUGE = 1e300   # h and g beyond this change no digit of the angle (e^-2h underflows long before)
NAMES = ("I11", "I22", "I13", "I23")


def _equilibrium(both_zero) -> None:
    both_zero = np.asarray(both_zero)
    if np.any(both_zero):
        index = tuple(int(i) for i in np.argwhere(both_zero)[0]) if both_zero.ndim else ()
        where = f" at index {list(index)}" if index else ""
        raise ValueError(f"I13=0 and I23=0{where}: the constraint axis is a principal axis; every motion is an "
                         "equilibrium (no scattering)")


def general_scattering_angle(invariants, emitted, I11, I22, I13, I23) -> np.ndarray:
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
    U, gap, Y = gauss_angle.float_lengths(U2, a, b, c2)
    with np.errstate(over="ignore"):   # lengths scale like 1/lam
        h, g, Y = np.minimum(0.5 * np.pi * U / lam, _HUGE), np.minimum(0.5 * np.pi * gap / lam, _HUGE), Y / lam
    with np.errstate(invalid="ignore"):
        s, c = phase.half_pi_parts(Y)
    with np.errstate(under="ignore", over="ignore", invalid="ignore"):
        angle = np.asarray(emitted(FLOAT, h, g, s, c), dtype=float)
    # entries spanning more than float64's range (I11/size underflows to 0): those again in mpmath
    (angle,) = finite.repair("general_scattering_angle", (angle,), NAMES, given,
                             lambda *body: (emitted(MP, *gauss_angle.mp_arguments(*invariants(MP, *body))),))
    return angle


def general_scattering_angle_mp(invariants, emitted, I11, I22, I13, I23, dps=None):
    dps = mp_dps(dps)
    with mpmath.workdps(dps + 15):
        I11, I22 = mp_real("I11", I11, positive=True), mp_real("I22", I22, positive=True)
        I13, I23 = mp_real("I13", I13), mp_real("I23", I23)
        _equilibrium(I13 == 0 and I23 == 0)
        out = emitted(MP, *gauss_angle.mp_arguments(*invariants(MP, I11, I22, I13, I23)))
    with mpmath.workdps(dps):
        return MPValue(+out, dps)


def general_scattering_angle_ball(invariants, emitted, I11, I22, I13, I23, dps=None, prec=None) -> Ball:
    prec = ball_prec(dps, prec)
    with flint.ctx.workprec(prec + 30):
        I11, I22, I13, I23 = (to_arb(n, x) for n, x in zip(NAMES, (I11, I22, I13, I23)))
        for name, x in (("I11", I11), ("I22", I22)):
            if not x > 0:
                raise ValueError(f"{name}={x}: must be positive")
        if I13.is_zero() and I23.is_zero():
            _equilibrium(True)
        return Ball(emitted(ARB, *gauss_angle.arb_arguments(*invariants(ARB, I11, I22, I13, I23))))
