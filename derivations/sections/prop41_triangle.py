"""Proposition 4.1 (section 4), the proof's last step: "one can check that I11^2 - (J2 - J3)^2 > 0".

The proof takes I23^2 as the first display's root with sign -,

    I23^2 = I22/(2 Delta) (p^2 + 2 I33 Delta - p s),   s = sqrt(p^2 + 4 I33 Delta),  Delta = I11 - I22,

and J2, J3 as the eigenvalues of the lower 2x2 block, so (J2 - J3)^2 = (I22 - I33)^2 + 4 I23^2 (the
discriminant of y^2 - (I22 + I33) y + I22 I33 - I23^2).  Then, exactly,

    I11^2 - (J2 - J3)^2 = A + B s,   A = -(T + 2 I22 p^2/Delta),  B = 2 I22 p/Delta,
    T = (I22 + I33)^2 - I11^2,

and Delta^2 (B^2 s^2 - A^2) = Delta (4 I22 p^2 (I11^2 - (I22 - I33)^2) - Delta T^2).  Under the proof's
assumptions (I11 > I22 > 0, I33 + I22 > I11, p > 0) A < 0 < B, so A + B s > 0 iff B^2 s^2 > A^2:

    I11^2 - (J2 - J3)^2 > 0   iff   4 I22 p^2 (I11^2 - (I22 - I33)^2) > (I11 - I22) ((I22 + I33)^2 - I11^2)^2.

It fails for I11 = 11/10, I22 = 1, I33 = 2, p = 1 (s = 3/sqrt 5, I23^2 = 7 - 3 sqrt 5): there
I11^2 - (J2 - J3)^2 = -2779/100 + 12 sqrt 5 < 0 (exact sign decision in Q(sqrt 5)).  The
proposition stays true: under the corrected eq:necc1 the build certifies example bodies for every p
(``physical_bodies.body_rows``).

Method: exact zero tests in Q(I11,I22,I33,p)[s]/(s^2 - p^2 - 4 I33 Delta) and Q(I11,I22,I33,p)
(``derivations.core.exact``), and an exact sign decision of a + b sqrt(r) with rational a, b, r.
"""
from __future__ import annotations

from fractions import Fraction

import sympy as sp

from derivations.core.certificates import Certificate, CertificateLog, Outcome, stopwatch
from derivations.core.errata import Erratum, erratum
from derivations.core.exact import certify_zero
from derivations.core.paper import PROP41_TRIANGLE
from derivations.core.symbols import I11, I22, I33, p

DELTA = I11 - I22
T_GAP = (I22 + I33) ** 2 - I11**2          # > 0 by the proof's I33 + I22 > I11
CONDITION = 4 * I22 * p**2 * (I11**2 - (I22 - I33) ** 2) - DELTA * T_GAP**2   # > 0 iff the step holds
COUNTEREXAMPLE = {"I11": Fraction(11, 10), "I22": Fraction(1), "I33": Fraction(2), "p": Fraction(1)}
CONDITION_LATEX = (r"I_{11}^2-(J_2-J_3)^2>0\iff 4I_{22}p^2\big(I_{11}^2-(I_{22}-I_{33})^2\big)>"
                   r"(I_{11}-I_{22})\big((I_{22}+I_{33})^2-I_{11}^2\big)^2")


def split_parts():
    """A and B of I11^2 - (J2 - J3)^2 = A + B s (the proof's root with sign -)."""
    return -(T_GAP + 2 * I22 * p**2 / DELTA), 2 * I22 * p / DELTA


def sign_of_surd(a: Fraction, b: Fraction, r: Fraction) -> int:
    """Sign of a + b sqrt(r) for rationals a, b and r >= 0, decided exactly (no floats)."""
    if r < 0:
        raise ValueError(f"r = {r}: the square root must be real (r >= 0)")
    if b == 0 or r == 0:
        return (a > 0) - (a < 0)
    if a == 0 or (a > 0) == (b > 0):
        return 1 if b > 0 else -1
    # opposite signs: compare a^2 with b^2 r
    gap = a * a - b * b * r
    if gap == 0:
        return 0
    return (1 if a > 0 else -1) if gap > 0 else (1 if b > 0 else -1)


def triangle_gap_parts(values: dict) -> tuple[Fraction, Fraction, Fraction]:
    """(a, b, r) with I11^2 - (J2 - J3)^2 = a + b sqrt(r) at rational I11, I22, I33, p (root with sign -)."""
    i11, i22, i33, pv = (Fraction(values[k]) for k in ("I11", "I22", "I33", "p"))
    delta = i11 - i22
    if delta <= 0 or i22 <= 0 or pv <= 0:
        raise ValueError(f"{values}: the proof assumes I11 > I22 > 0 and p > 0")
    gap = (i22 + i33) ** 2 - i11**2
    return -(gap + 2 * i22 * pv**2 / delta), 2 * i22 * pv / delta, pv**2 + 4 * i33 * delta


def condition_value(values: dict) -> Fraction:
    """4 I22 p^2 (I11^2 - (I22 - I33)^2) - (I11 - I22) ((I22 + I33)^2 - I11^2)^2 at rational data."""
    i11, i22, i33, pv = (Fraction(values[k]) for k in ("I11", "I22", "I33", "p"))
    return 4 * i22 * pv**2 * (i11**2 - (i22 - i33) ** 2) - (i11 - i22) * ((i22 + i33) ** 2 - i11**2) ** 2


def triangle_errata(log: CertificateLog, root: sp.Symbol, domain, field_domain, printed_root) -> Erratum:
    """Certificates and the errata row for the proof's "I11^2 - (J2 - J3)^2 > 0"."""
    label = "Proposition 4.1"
    a_part, b_part = split_parts()
    spread = (I22 - I33) ** 2 + 4 * printed_root     # (J2 - J3)^2, printed_root = the I23^2 with sign -
    c_split = certify_zero(
        log, "for the proof's $I23^2$ with the minus sign, $I11^2 - (J2 - J3)^2 = A + B s$ with "
        "$A = -(T + 2 I22 p^2/(I11 - I22))$, $B = 2 I22 p/(I11 - I22)$, $T = (I22 + I33)^2 - I11^2$, "
        "$(J2 - J3)^2 = (I22 - I33)^2 + 4 I23^2$", label,
        (I11**2 - spread) - (a_part + b_part * root), domain)
    c_condition = certify_zero(
        log, "$(I11 - I22)^2 (B^2 s^2 - A^2) = (I11 - I22) (4 I22 p^2 (I11^2 - (I22 - I33)^2) - (I11 - I22) T^2)$; "
        "with $A < 0$ and $B > 0$ ($I11 > I22$, $I22 > 0$, $I33 + I22 > I11$, $p > 0$), $A + B s > 0$ if and only if "
        "the bracket is positive", label,
        DELTA**2 * (b_part**2 * (p**2 + 4 * I33 * DELTA) - a_part**2) - DELTA * CONDITION, field_domain)
    with stopwatch() as elapsed:
        a, b, r = triangle_gap_parts(COUNTEREXAMPLE)
        sign = sign_of_surd(a, b, r)
        bracket = condition_value(COUNTEREXAMPLE)
    c_counter = log.record(Certificate(
        "$I11 = 11/10$, $I22 = 1$, $I33 = 2$, $p = 1$, root with the minus sign: $I11^2 - (J2 - J3)^2 > 0$", label,
        "exact sign decision of $a + b sqrt(r)$ with rational $a$, $b$, $r$ (the rational comparison of $a^2$ with "
        "$b^2 r$)",
        Outcome.PASS if sign > 0 else Outcome.FAIL, elapsed[0], 1,
        f"$I11^2 - (J2 - J3)^2 = {a} + {b} sqrt({r})$ has sign ${sign}$ ($a^2 = {a * a}$, $b^2 r = {b * b * r}$); "
        f"the condition's bracket is ${bracket}$",
        expected=Outcome.FAIL))
    return erratum(
        PROP41_TRIANGLE, "corrected", CONDITION_LATEX,
        "false in general: for $I11 = 11/10$, $I22 = 1$, $I33 = 2$, $p = 1$ the proof's root with the minus sign gives "
        "$I23^2 = 7 - 3 sqrt(5)$ and $I11^2 - (J2 - J3)^2 = -2779/100 + 12 sqrt(5)$, which is negative; under the "
        "proof's assumptions it holds exactly when the stated condition does. The proposition stays true (certified "
        "example bodies)",
        c_counter, c_split, c_condition)
