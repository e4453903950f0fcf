"""Enclosure certificates for the scattering angle (paper section 5.1, Theorem 5.4, ``gam_0``).

The numeric claims of ``derivations/sections/scattering.py`` decided with balls (``derivations/core/balls.py``)
instead of spot checks:

* **Gamma-function value** (step 3 of the derivation): ``Gamma(b1) Gamma(b2) Gamma(1/2) /
  (Gamma(a1) Gamma(a2) Gamma(a3)) = cos(pi p/2)/cosh(pi p/(2d))`` at rational points, both sides in
  acb ball arithmetic (reciprocal Gamma, so odd p, where 1/Gamma((1-p)/2) = 0, is no special case).
* **The closed form against a rigorous integration**: for every (p, d) of the grid, the ss solution
  is enclosed by ``suslov.kernel.enclosure.ss_angle_enclosure`` (limit series with majorant
  remainders at both ends, Taylor steps with Cauchy bounds in between; no closed form used), and
  its G1(0) and cos(Delta psi) are compared with ``-cos(pi p/2)/cosh(pi p/(2d))`` and
  ``2 cos^2(pi p/2)/cosh^2(pi p/(2d)) - 1``.
* **The lemma gam_0**: at t = -S the enclosed ss solution's G1 against ``-sqrt(1-z) 3F2(1/2, (1+p)/2,
  (1-p)/2; 1/2 - ip/(2d), 1/2 + ip/(2d); z)``, z = sech^2 S, with Arb's rigorous 3F2.

A pass proves ``|difference| <= tolerance`` at every point; equality itself is the derivation's
(the reflection formulas, the lemma), which enclosures cannot prove.  The fast-rotation column
d = 0.05 of the grid (|omega| up to 70, about 5 s per point at this tolerance) stays an mpmath
spot check (``scattering_evidence``), labelled evidence.

Which points (issue 43): the build option ``ball_checks`` (``GRIDS``).  "default" encloses one p of each
kind (non-integer 0.5, odd 1, even 2) on every d, 9 points to the same 1e-18; "full"
(``build_formulas.py --ball-checks full``, and ``tests/test_scattering_tiers.py`` in every CI run, without a
build) all 18.  The claims name the points and the set that ran.
"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from flint import acb, arb

from derivations.core.balls import certify_enclosure
from derivations.core.certificates import Certificate, CertificateLog
from suslov.kernel.enclosure import ss_angle_enclosure

GAMMA_POINTS = (("1/3", "1/2"), ("5/2", "7/10"), ("2", "1"), ("37/10", "1/5"), ("1/10", "5"), ("3", "3"))
GRID_P = ("0.5", "1", "2", "2.5", "3", "7/3")    # the full grid (--ball-checks full)
GRID_D = ("0.5", "2", "50")
GRID_DIGITS = 20                 # enclosure target; the claims' tolerance is 1e-18
SERIES_START = 1.5               # t = -1.5: where the limit series hands over to the Taylor steps
TOLERANCE = "1e-18"


@dataclass(frozen=True)
class Grid:
    """The (p, d) points whose ss solution is enclosed, and the enclosures' digits and the claims' tolerance."""

    p: tuple
    d: tuple
    digits: int = GRID_DIGITS
    tolerance: str = TOLERANCE

    def points(self) -> list:
        return [(ps, ds) for ps in self.p for ds in self.d]


# "default": one p of each kind (non-integer, odd, even) on every d: 9 of the 18 points, the same tolerance (the
# closed form is derived exactly, steps 1-4 of scattering.py; the enclosures corroborate it); "full": the 18 points
# (build_formulas.py --ball-checks full; tests/test_scattering_tiers.py runs them without a build)
GRIDS = {"default": Grid(("0.5", "1", "2"), GRID_D), "full": Grid(GRID_P, GRID_D)}


def exact(text: str) -> arb:
    value = Fraction(text)
    return arb(value.numerator) / value.denominator


def closed_g0(p: arb, d: arb) -> arb:
    return -(p / 2).cos_pi() / (arb.pi() * p / (2 * d)).cosh()


def omega_pd(p: arb, d: arb) -> tuple:
    """u, v of omega = u tanh t + v sech t for I13 = 0 (omegas): u = (p/d, 0), v = (0, -c p/d)."""
    c = (d * d + 1).sqrt()
    return (p / d, arb(0)), (arb(0), -c * p / d)


def gamma_value(log: CertificateLog) -> Certificate:
    def quantities(prec: int) -> list:
        out = []
        for ps, ds in GAMMA_POINTS:
            p, d = exact(ps), exact(ds)
            half = arb(1) / 2
            b1, b2 = acb(half, -p / (2 * d)), acb(half, p / (2 * d))
            lead = (b1.gamma() * b2.gamma() * acb(half).gamma() * acb(half).rgamma()
                    * acb((1 + p) / 2).rgamma() * acb((1 - p) / 2).rgamma())
            target = (p / 2).cos_pi() / (arb.pi() * p / (2 * d)).cosh()
            out += [lead.real - target, lead.imag]
        return out

    return certify_enclosure(
        log, "$Gamma(b1) Gamma(b2) Gamma(-s)/(Gamma(a1) Gamma(a2) Gamma(a3)) = cos(pi p/2)/cosh(pi p/(2 d))$ to $1e-40$ at "
        f"$(p, d)$ = {', '.join(f'$({a}, {b})$' for a, b in GAMMA_POINTS)}", "Theorem 5.4", quantities, arb(10) ** -40,
        prec=160, what="`acb.gamma` and `acb.rgamma`")


def tier_words(tier: str) -> str:
    """Which set of the ball checks ran, for the claims (``tier``: ``BuildOptions.ball_checks``)."""
    return ("the full ball checks" if tier == "full" else
            f"the default ball checks; the full ones add $p$ in {', '.join(p for p in GRID_P if p not in GRIDS['default'].p)}")


def grid(log: CertificateLog, tier: str = "full") -> tuple[Certificate, Certificate]:
    """(closed form vs validated integration on the grid of ``GRIDS[tier]``, the lemma gam_0 at t = -S): two
    certificates whose claims name the points and the set of ball checks."""
    chosen = GRIDS[tier]
    enclosures = {}

    def integrate(prec: int) -> dict:
        for ps, ds in chosen.points():
            u, v = omega_pd(exact(ps), exact(ds))
            enclosures[ps, ds] = ss_angle_enclosure(u, v, digits=chosen.digits, prec=prec,
                                                     series_start=SERIES_START)
        return enclosures

    def against_closed_form(prec: int) -> list:
        out = []
        for (ps, ds), e in integrate(prec).items():
            p, d = exact(ps), exact(ds)
            g0 = closed_g0(p, d)
            out += [e.gamma_at_zero[0] - g0, e.cos_angle - (2 * g0 * g0 - 1)]
        return out

    points = (f"{len(chosen.points())} points: $p$ in {', '.join(chosen.p)}, $d$ in {', '.join(chosen.d)}: "
              + tier_words(tier))
    c_grid = certify_enclosure(
        log, f"the solution with $to(gamma, -e1)$ as $to(t, -oo)$, enclosed from $t = -oo$ to $+oo$, has $G1(0) = -cos(pi p/2)/cosh(pi p/(2d))$ and $cos(Deltapsi) "
        f"= 2 cos(pi p/2)^2/cosh(pi p/(2 d))^2 - 1$ to ${chosen.tolerance}$ ({points})", "Theorem 5.4", against_closed_form,
        arb(chosen.tolerance), prec=int(3.33 * chosen.digits + 40), doublings=1,
        what="validated integration (limit series with majorant remainders + Taylor steps with Cauchy bounds, "
             "`suslov.kernel.enclosure`) against the closed form")

    def lemma(prec: int) -> list:
        out = []
        for (ps, ds), e in enclosures.items():
            p, d = exact(ps), exact(ds)
            S = arb(e.window[1])
            z = S.sech() ** 2
            half = arb(1) / 2
            f = acb(z).hypgeom([half, (1 + p) / 2, (1 - p) / 2], [acb(half, -p / (2 * d)), acb(half, p / (2 * d))])
            printed = -(1 - z).sqrt() * f
            out += [e.gamma_at_start[0] - printed.real, printed.imag]
        return out

    c_lemma = certify_enclosure(
        log, "gam_0: the solution with $to(gamma, -e1)$ as $to(t, -oo)$ has $G1 = -sqrt(1-z) hyper((1/2, (1+p)/2, (1-p)/2), (1/2 - i p/(2 d), 1/2 + i p/(2 d)), z)$, "
        f"$z = sech(t)^2$, at $t = -{SERIES_START}$ to ${chosen.tolerance}$ ({points})", "gam_0", lemma,
        arb(chosen.tolerance), prec=int(3.33 * chosen.digits + 40), doublings=0,
        what="validated solution (limit series at $t = -oo$ with its remainder bound) against Arb's generalised "
             "hypergeometric function `acb.hypgeom`")
    return c_grid, c_lemma
