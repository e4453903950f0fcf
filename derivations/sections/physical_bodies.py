"""Proposition 4.1 (section 4): physical bodies with I13 = 0 for every p, and its proof's errata.

The proposition claims, for every p > 0, a positive-definite inertia tensor with I13 = 0
whose eigenvalues satisfy the triangle inequalities and which satisfies eq:necc1.

* **The proof's displays.**  Its first display solves eq:necc1 as a quadratic in I23^2,

      I23^2 = I22/(2 Delta) (p^2 + 2 I33 Delta +- p sqrt(p^2 + 4 I33 Delta)),  Delta = I11 - I22;

  its roots have sum I22 (p^2/Delta + 2 I33) and product (I22 I33)^2, i.e. they solve
  ``Delta (I22 I33 - I23^2)^2 = p^2 I22 I23^2``.  With det I = I11 (I22 I33 - I23^2) = 1 this
  is the *printed* eq:necc1, ``(I11 - I22)/(I11 I22 (I11 I22 I33 - 1)) = p^2`` (certified:
  the roots solve it).  The derived condition (special_case, eq:necc1 corrected) is
  ``p^2 = I22 (I11 - I22)/I23^2``: scale-invariant and *linear* in I23^2, with the single
  root I23^2 = I22 Delta/p^2, which does not solve the proof's quadratic (certified, refuted).
  The second display, ``I22 I33 - I23^2 = I22/(2 Delta) (-p^2 + p sqrt(p^2 + 2 I33 Delta))``,
  has 2 I33 under the square root where the first display's minus root gives 4 I33
  (refuted as printed, certified with 4 I33).

* **The proposition itself holds** under the corrected condition: for each p the rational
  tensor ``[[5/4, 0, 0], [0, 1, 1/(2p)], [0, 1/(2p), 1]]`` is positive definite, its eigenvalues
  satisfy the triangle inequalities, and I22 (I11 - I22)/I23^2 = p^2 (exact rational arithmetic);
  in general I22 I33 - I23^2 = I22 (p^2 I33 - Delta)/p^2 > 0 whenever p^2 I33 > Delta, which
  the proof's own assumption I33 + I22 > I11 gives for every p >= 1 (exact identity).

* **The proof's last step**, I11^2 - (J2 - J3)^2 > 0, is false in general; its exact condition and a
  certified counterexample are in ``prop41_triangle``.
"""
from __future__ import annotations

from fractions import Fraction

import sympy as sp

from derivations.core.certificates import (
    Certificate,
    CertificateLog,
    Outcome,
    stopwatch,
)
from derivations.core.errata import erratum
from derivations.core.exact import Domain, Extension, certify_zero
from derivations.core.paper import PROP41
from derivations.core.symbols import I11, I22, I23, I33, p
from derivations.sections.prop41_triangle import triangle_errata

ROOT = sp.Symbol("s")          # s = sqrt(p^2 + 4 I33 (I11 - I22))
DELTA = I11 - I22
QUADRATIC_DOMAIN = Domain("Q(I11,I22,I33,p)[s]/(s^2 - p^2 - 4 I33 (I11 - I22))",
                          (Extension(ROOT, p**2 + 4 * I33 * DELTA, "s = sqrt(p^2 + 4 I33 (I11-I22))"),))
PRINTED_ROOT = sp.Symbol("u")  # u = sqrt(p^2 + 2 I33 (I11 - I22)), the second display's root
BOTH_ROOTS_DOMAIN = QUADRATIC_DOMAIN.with_extensions(
    "Q(I11,I22,I33,p)[s,u]/(s^2 - p^2 - 4 I33 (I11 - I22), u^2 - p^2 - 2 I33 (I11 - I22))",
    Extension(PRINTED_ROOT, p**2 + 2 * I33 * DELTA, "u = sqrt(p^2 + 2 I33 (I11-I22))"))
FIELD_DOMAIN = Domain("Q(I11,I22,I33,p)", ())

DERIVED_LATEX = (r"I_{23}^2=\frac{I_{22}(I_{11}-I_{22})}{p^2}\ \text{(linear, one root)},\ "
                 r"I_{22}I_{33}-I_{23}^2=\frac{I_{22}\big(p^2I_{33}-(I_{11}-I_{22})\big)}{p^2}")


def printed_roots(sign: int) -> sp.Expr:
    """The first display's I23^2 (sign of the square root)."""
    return I22 / (2 * DELTA) * (p**2 + 2 * I33 * DELTA + sign * p * ROOT)


def physical_body(p_value: int) -> dict:
    """A rational inertia tensor with I13 = 0 and p^2 = I22 (I11 - I22)/I23^2."""
    return {"I11": Fraction(5, 4), "I22": Fraction(1), "I33": Fraction(1), "I23": Fraction(1, 2 * p_value),
            "I13": Fraction(0)}


def check_body(I: dict, p_value: int) -> tuple[bool, str]:
    minors = [I["I11"], I["I11"] * I["I22"], I["I11"] * (I["I22"] * I["I33"] - I["I23"] ** 2)]
    positive = all(m > 0 for m in minors)
    meromorphic = I["I22"] * (I["I11"] - I["I22"]) / I["I23"] ** 2 == p_value**2
    spread = (I["I22"] - I["I33"]) ** 2 + 4 * I["I23"] ** 2  # (J2 - J3)^2
    triangle = I["I11"] < I["I22"] + I["I33"] and spread < I["I11"] ** 2
    ok = positive and meromorphic and triangle
    return ok, (f"leading minors {', '.join(str(m) for m in minors)} positive; $p^2 = {p_value**2}$; "
                f"$I11 < J2 + J3$ with $J2 + J3 = {I['I22'] + I['I33']}$; $(J2-J3)^2 = {spread}$, below $I11^2 = {I['I11'] ** 2}$")


def body_rows(log: CertificateLog, p_values) -> list[dict]:
    """One certified example body per p (Proposition 4.1 under the corrected condition)."""
    rows = []
    for p_value in p_values:
        body = physical_body(p_value)
        with stopwatch() as elapsed:
            ok, detail = check_body(body, p_value)
        cert = log.record(Certificate(
            f"$p = {p_value}$: the inertia tensor $I$ with rows $(5/4, 0, 0)$, $(0, 1, 1/(2 p))$, $(0, 1/(2 p), 1)$ is positive definite, its eigenvalues satisfy "
            "the triangle inequalities, and $I22 (I11-I22)/I23^2 = p^2$", "Proposition 4.1",
            "exact rational arithmetic", Outcome.PASS if ok else Outcome.FAIL, elapsed[0], 3, detail))
        det = body["I11"] * (body["I22"] * body["I33"] - body["I23"] ** 2)
        rows.append({"p": p_value, "I23": str(body["I23"]), "det": str(det), "certificate": cert.key})
    return rows


def proof_errata(log: CertificateLog, result) -> None:
    """Certificates and the errata row for the displays in the proof of Proposition 4.1."""
    label = "Proposition 4.1"
    printed_quadratic = [DELTA * (I22 * I33 - x) ** 2 - p**2 * I22 * x for x in (printed_roots(1), printed_roots(-1))]
    c_quadratic = certify_zero(
        log, "the proof's $I23^2$ (both signs) solve $(I11-I22)(I22 I33 - I23^2)^2 = p^2 I22 I23^2$, i.e. the printed "
        "eq:necc1 with $det(I) = I11 (I22 I33 - I23^2) = 1$", label, printed_quadratic, QUADRATIC_DOMAIN)
    c_printed_det1 = certify_zero(
        log, "with $det(I) = 1$ the printed eq:necc1 reads $(I11-I22)/(I11^2 I22 I23^2) = p^2$ ($I11 I22 I33 - 1 = I11 I23^2$)",
        label, (I11 * I22 * I33 - 1 - I11 * I23**2).subs(I33, (1 / I11 + I23**2) / I22), FIELD_DOMAIN)
    corrected_root = I22 * DELTA / p**2
    c_not_corrected = certify_zero(
        log, "the root $I23^2 = I22 (I11-I22)/p^2$ of the corrected eq:necc1 solves the proof's quadratic", label,
        DELTA * (I22 * I33 - corrected_root) ** 2 - p**2 * I22 * corrected_root, FIELD_DOMAIN, expect=Outcome.FAIL)
    second_printed = I22 / (2 * DELTA) * (-p**2 + p * PRINTED_ROOT)
    second_fixed = I22 / (2 * DELTA) * (-p**2 + p * ROOT)
    minus_root = printed_roots(-1)
    c_second = certify_zero(
        log, "second display as printed ($2 I33$ under the root) equals $I22 I33 - I23^2$ for the root with sign -",
        label, (I22 * I33 - minus_root) - second_printed, BOTH_ROOTS_DOMAIN, expect=Outcome.FAIL)
    c_second_fixed = certify_zero(
        log, "second display with $4 I33$ under the root equals $I22 I33 - I23^2$ for the root with sign -", label,
        (I22 * I33 - minus_root) - second_fixed, QUADRATIC_DOMAIN)
    c_linear = certify_zero(
        log, "corrected eq:necc1 $(p^2 = I22 (I11-I22)/I23^2)$: $I22 I33 - I23^2 = I22 (p^2 I33 - (I11-I22))/p^2$", label,
        (I22 * I33 - corrected_root) - I22 * (p**2 * I33 - DELTA) / p**2, FIELD_DOMAIN)
    result.errata.append(erratum(
        PROP41, "corrected", DERIVED_LATEX,
        "the proof's quadratic in $I23^2$ is the uncorrected eq:necc1 ($det(I) = 1$); under the corrected condition it "
        "is linear with one positive root, and $I22 I33 - I23^2 > 0$ iff $p^2 I33 > I11 - I22$ (true for $p >= 1$ under "
        "the proof's $I33 + I22 > I11$). The second display has $2 I33$ under the root where the first gives $4 I33$. "
        "The proposition holds: certified example bodies for every $p$ in the monodromy section",
        c_quadratic, c_printed_det1, c_not_corrected, c_second, c_second_fixed, c_linear))
    result.errata.append(triangle_errata(log, ROOT, QUADRATIC_DOMAIN, FIELD_DOMAIN, minus_root))
