"""The scattering angle of Theorem 5.4 (corrected) in float64, mpmath and ball arithmetic.

``emitted`` is the generated module's ``_scattering_angle(ctx, x, s, c)`` with ``x = pi |p|/(2d)`` and
``s``, ``c`` = ``|sin|``, ``|cos|`` of ``pi p/2``; here the exact reduction of pi p/2
(``suslov.kernel.phase.half_pi_parts``: p within 1e-12 of an integer keeps full relative accuracy),
the precision handling of the twins, and results that print the digits they carry.
"""
from __future__ import annotations

import flint
import mpmath
import numpy as np

from suslov.kernel import phase
from suslov.kernel.contexts import ARB, FLOAT, MP
from suslov.kernel.display import Ball, MPValue
from suslov.kernel.enclosure import to_arb
from suslov.kernel.scalars import like_ufunc
from suslov.kernel.validate import ball_prec, mp_dps, mp_real, real_array

__all__ = ["scattering_angle", "scattering_angle_mp", "scattering_angle_ball"]


@like_ufunc
def scattering_angle(emitted, p, d) -> np.ndarray | np.float64:
    p, d = np.broadcast_arrays(real_array("p", p), real_array("d", d, positive=True))
    s, c = phase.half_pi_parts(p)
    # p and d beyond 2^1020 both divided by 4 (exactly), so that fl(pi |p|) and 2d overflow only where x does (at
    # p = d = 1e308 x was inf/inf = NaN, at p = 5e307, d = 1e308 it was 0); x beyond float64 is inf, silently:
    # sech x = 0 and tanh x = 1 there, the angle's limit
    quarter = np.where(np.maximum(np.abs(p), d) > 2.0**1020, 0.25, 1.0)
    with np.errstate(under="ignore", over="ignore"):
        x = np.pi * np.abs(p * quarter) / (2.0 * (d * quarter))
        return np.asarray(emitted(FLOAT, x, s, c), dtype=float)


def scattering_angle_mp(emitted, p, d, dps):
    dps = mp_dps(dps)
    with mpmath.workdps(dps + 10):
        p, d = mp_real("p", p), mp_real("d", d, positive=True)
        s, c = abs(mpmath.sinpi(p / 2)), abs(mpmath.cospi(p / 2))
        out = emitted(MP, mpmath.pi * abs(p) / (2 * d), s, c)
    with mpmath.workdps(dps):
        return MPValue(+out, dps)


def scattering_angle_ball(emitted, p, d, dps, prec) -> Ball:
    prec = ball_prec(dps, prec)
    with flint.ctx.workprec(prec + 20):
        p, d = to_arb("p", p), to_arb("d", d)
        if not d > 0:
            raise ValueError(f"d={d}: must be positive")
        s, c = abs((p / 2).sin_pi()), abs((p / 2).cos_pi())
        return Ball(emitted(ARB, flint.arb.pi() * abs(p) / (2 * d), s, c))
