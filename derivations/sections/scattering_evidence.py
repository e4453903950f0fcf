"""The numeric certificates of Theorem 5.4 that need no other result (paper section 5.1, ``ss``, ``gam_0``).

``derivations/sections/scattering.py`` derives the scattering angle and records these checks; a cold
build computes them in worker processes while the symbolic derivations run (``PREFETCH``), so they live
here, in a module that imports neither SymPy nor the symbolic core (a worker starts in about 0.2 s):

* "enclosed grid": the ss solution enclosed in ball arithmetic on the grid p in {0.5, 1, 2, 2.5, 3, 7/3}
  x d in {0.5, 2, 50}, and the lemma gam_0 (``scattering_balls.grid``): certificates;
* "fast rotation": the column d = 0.05 (|omega| up to 70), where an enclosure to the grid's tolerance
  costs about 5 s per point (30 s for the column, twice the whole default build): the 36-digit mpmath
  route of ``poisson_taylor.ss_through`` (Frobenius series at t = +-oo, Taylor steps in between),
  labelled evidence, about 1.1 s.
"""
from __future__ import annotations

from fractions import Fraction

import mpmath

from derivations.core.certificates import Certificate, CertificateLog, Outcome, stopwatch
from derivations.sections import scattering_balls
from derivations.sections.poisson_taylor import ss_through

# Grid of the integration check: non-integer, odd and even p; small and large d.
GRID_P = ("0.5", "1", "2", "2.5", "3", "7/3")
GRID_D = ("0.05",)   # fast rotation (|omega| up to 70): evidence; d = 0.5, 2, 50 are enclosed (scattering_balls)
GRID_DPS = 36
GRID_DIGITS = 30


def closed_form_half_cos(p_value, d_value):
    """cos(Delta psi/2) = |cos(pi p/2)| / cosh(pi p/(2d)) in mpmath (current precision)."""
    return abs(mpmath.cospi(p_value / 2)) / mpmath.cosh(mpmath.pi * p_value / (2 * d_value))


def fast_rotation_certificate(log: CertificateLog) -> Certificate:
    """G1(0) and cos(Delta psi) of the ss solution against the closed form on the d = 0.05 column, 36 digits."""
    worst_g0 = worst_cos = mpmath.mpf(0)
    with stopwatch() as elapsed, mpmath.workdps(GRID_DPS):
        for ps in GRID_P:
            for ds in GRID_D:
                pv, dv = mpmath.mpf(Fraction(ps).numerator) / Fraction(ps).denominator, mpmath.mpf(ds)
                a = pv / dv
                u, v = [a, mpmath.mpf(0)], [mpmath.mpf(0), -a * mpmath.sqrt(dv**2 + 1)]
                g0, along = ss_through(u, v, GRID_DPS)
                closed_g0 = -mpmath.cospi(pv / 2) / mpmath.cosh(mpmath.pi * pv / (2 * dv))
                worst_g0 = max(worst_g0, abs(g0[0] - closed_g0))
                worst_cos = max(worst_cos, abs(-along - (2 * closed_form_half_cos(pv, dv) ** 2 - 1)))
    points = len(GRID_P) * len(GRID_D)
    ok = max(worst_g0, worst_cos) <= mpmath.mpf(10) ** (-GRID_DIGITS)
    detail = (f"{points} points: $p$ in {', '.join(GRID_P)}, $d$ in {', '.join(GRID_D)}; "
              f"largest differences from the closed forms ${mpmath.nstr(worst_g0, 3)}$ for $G1(0)$, "
              f"${mpmath.nstr(worst_cos, 3)}$ for $cos(Deltapsi)$")
    return log.record(Certificate(
        "the solution with $to(gamma, -e1)$ as $to(t, -oo)$, integrated from $t = -oo$ to $+oo$, gives $G1(0) = -cos(pi p/2)/cosh(pi p/(2d))$ and "
        "$cos(Deltapsi) = -G1(oo) = 2 cos(pi p/2)^2/cosh(pi p/(2 d))^2 - 1$ (to $1e-30$)", "Theorem 5.4",
        f"Frobenius series at $t = pm(oo)$ and Taylor steps in mpmath at {GRID_DPS} digits (evidence, not proof: "
        "ball enclosures of this column cost 16 seconds even at 10 digits, 40 percent of a cold build; $d = 0.5$, $2$, $50$ are "
        "enclosed)",
        Outcome.PASS if ok else Outcome.FAIL, elapsed[0], points, detail))


def numeric_certificates(name: str) -> list:
    """The numeric certificates of Theorem 5.4 that need no other result, recorded in a private log and
    handed over (a top-level function: the build starts it in a worker process with the build,
    ``PREFETCH``): "enclosed grid" (the ball enclosures and the lemma gam_0, ``scattering_balls``) or
    "fast rotation" (the d = 0.05 column, 36-digit evidence)."""
    private = CertificateLog()
    {"enclosed grid": scattering_balls.grid, "fast rotation": fast_rotation_certificate}[name](private)
    return private.handed_over()
