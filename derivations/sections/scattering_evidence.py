"""The numeric certificates of Theorem 5.4 that need no other result (paper section 5.1, ``ss``, ``gam_0``).

``derivations/sections/scattering.py`` derives the scattering angle and records these checks; a cold
build computes them in worker processes while the symbolic derivations run (``PREFETCH``), so they live
here, in a module that imports neither SymPy nor the symbolic core (a worker starts in about 0.2 s):

* "enclosed grid": the ss solution enclosed in ball arithmetic on the grid p in {0.5, 1, 2, 2.5, 3, 7/3}
  x d in {0.5, 2, 50}, and the lemma gam_0 (``scattering_balls.grid``): certificates;
* "fast rotation": the column d = 0.05 (|omega| up to 70), where an enclosure to the grid's tolerance
  costs about 5 s per point (30 s for the column, twice the whole default build): the mpmath
  route of ``poisson_taylor.ss_through`` (Frobenius series at t = +-oo, Taylor steps in between),
  labelled evidence, about 1.1 s for the six points at 36 digits.

Both follow the build option ``ball_checks`` (issue 43): "default" runs one p of each kind (non-integer 0.5,
odd 1, even 2), the grid's 9 enclosed points (``scattering_balls.GRIDS``) and 3 fast-rotation points at 24
digits to 1e-18 (``COLUMNS``); "full" (``build_formulas.py --ball-checks full``; ``tests/test_scattering_tiers.py``
in every CI run, without a build) every p, the column at 36 digits to 1e-30.  The claims say which ran.
"""
from __future__ import annotations

from dataclasses import dataclass
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


@dataclass(frozen=True)
class Column:
    """The fast-rotation points (p, d) of the evidence, its working digits and the claimed agreement 10^-digits."""

    p: tuple
    d: tuple
    dps: int
    digits: int


# "default": one p of each kind at 24 digits, to 1e-18 (the enclosed grid's tolerance); "full": the six p at 36, to 1e-30
COLUMNS = {"default": Column(("0.5", "1", "2"), GRID_D, 24, 18), "full": Column(GRID_P, GRID_D, GRID_DPS, GRID_DIGITS)}


def closed_form_half_cos(p_value, d_value):
    """cos(Delta psi/2) = |cos(pi p/2)| / cosh(pi p/(2d)) in mpmath (current precision)."""
    return abs(mpmath.cospi(p_value / 2)) / mpmath.cosh(mpmath.pi * p_value / (2 * d_value))


def fast_rotation_certificate(log: CertificateLog, tier: str = "full") -> Certificate:
    """G1(0) and cos(Delta psi) of the ss solution against the closed form on the d = 0.05 column (``COLUMNS[tier]``;
    "full" reads the module's ``GRID_*`` when called, as ``bench/bench_enclosure.py`` sets them)."""
    column = COLUMNS[tier] if tier != "full" else Column(GRID_P, GRID_D, GRID_DPS, GRID_DIGITS)
    worst_g0 = worst_cos = mpmath.mpf(0)
    with stopwatch() as elapsed, mpmath.workdps(column.dps):
        for ps in column.p:
            for ds in column.d:
                pv, dv = mpmath.mpf(Fraction(ps).numerator) / Fraction(ps).denominator, mpmath.mpf(ds)
                a = pv / dv
                u, v = [a, mpmath.mpf(0)], [mpmath.mpf(0), -a * mpmath.sqrt(dv**2 + 1)]
                g0, along = ss_through(u, v, column.dps)
                closed_g0 = -mpmath.cospi(pv / 2) / mpmath.cosh(mpmath.pi * pv / (2 * dv))
                worst_g0 = max(worst_g0, abs(g0[0] - closed_g0))
                worst_cos = max(worst_cos, abs(-along - (2 * closed_form_half_cos(pv, dv) ** 2 - 1)))
    points = len(column.p) * len(column.d)
    ok = max(worst_g0, worst_cos) <= mpmath.mpf(10) ** (-column.digits)
    detail = (f"{points} points: $p$ in {', '.join(column.p)}, $d$ in {', '.join(column.d)}; "
              f"largest differences from the closed forms ${mpmath.nstr(worst_g0, 3)}$ for $G1(0)$, "
              f"${mpmath.nstr(worst_cos, 3)}$ for $cos(Deltapsi)$")
    which = ("the full ball checks" if tier == "full" else
             f"the default ball checks; the full ones run $p$ in {', '.join(GRID_P)} at {GRID_DPS} digits to $1e-{GRID_DIGITS}$")
    return log.record(Certificate(
        "the solution with $to(gamma, -e1)$ as $to(t, -oo)$, integrated from $t = -oo$ to $+oo$, gives $G1(0) = -cos(pi p/2)/cosh(pi p/(2d))$ and "
        f"$cos(Deltapsi) = -G1(oo) = 2 cos(pi p/2)^2/cosh(pi p/(2 d))^2 - 1$ (to $1e-{column.digits}$; {points} points: "
        f"$p$ in {', '.join(column.p)}, $d = {', '.join(column.d)}$: {which})", "Theorem 5.4",
        f"Frobenius series at $t = pm(oo)$ and Taylor steps in mpmath at {column.dps} digits (evidence, not proof: "
        "ball enclosures of this column cost 16 seconds even at 10 digits, more than a whole cold build; $d = 0.5$, $2$, $50$ are "
        "enclosed)",
        Outcome.PASS if ok else Outcome.FAIL, elapsed[0], points, detail))


def numeric_certificates(item: tuple) -> list:
    """The numeric certificates of Theorem 5.4 that need no other result, recorded in a private log and
    handed over (a top-level function: the build starts it in a worker process with the build,
    ``PREFETCH``); ``item = (name, tier)``: "enclosed grid" (the ball enclosures and the lemma gam_0,
    ``scattering_balls``) or "fast rotation" (the d = 0.05 column, evidence), for the ball checks ``tier``
    ("default" or "full")."""
    name, tier = item
    private = CertificateLog()
    {"enclosed grid": scattering_balls.grid, "fast rotation": fast_rotation_certificate}[name](private, tier)
    return private.handed_over()
