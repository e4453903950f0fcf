"""Polynomial first integrals F3 = P1 g1 + P2 g2 + P3 g3 for odd p (Theorem 6.2).

Labels: ``eq:p1``, ``eq:p23``, ``eq:partial``, ``pol_sol``, ``eq:liniowiec``,
and the printed p = 1 integral of section 6.3.

Construction (derived, then certified per odd p)
------------------------------------------------
Along ``eq:sysfin`` (+ sign) the time derivative of a function of omega is
``(d/p) w2 L``, with ``L P = w2/(d^2+1) dP/dw1 - w1 dP/dw2``.  Collecting the
coefficients of g1, g2, g3 in dF3/dt gives ``eq:partial``, whence

    P3 = -(d/p) L P1,        P2 = (w2/w1) (P1 - (d/p) L P3)

(the printed ``eq:p23`` has ``+`` in P3: a sign misprint; its ``eq:partial`` is
right).  ``P1 = w1 Q``, ``Q = F1^((p-1)/2) F(z)``, ``F1 = (d^2+1) w1^2 + w2^2``,
``z = w2^2/F1`` and ``F(z) = 3F2(1/2, (1+p)/2, (1-p)/2; beta1, beta2; z)`` with
``beta1,2 = (d -+ i p)/(2d)`` and the rising factorial ``(a)_k = a(a+1)...(a+k-1)``
(the paper defines it with one factor too many).  Its coefficients are

    c_j = binom(2j, j) / 4^j * prod_{m<j} ((2m+1)^2 - p^2) d^2 / ((2m+1)^2 d^2 + p^2),

which differs from the printed ``pol_sol`` in the sign (-1)^j and in the
denominators ``(2m+1)^2 d^2 + p^2`` (printed: ``(2m+1) d^2 + p^2``).
Normalisation: P1 = w1 Q with c_0 = 1, so P1 = w1 F1^((p-1)/2) + ...; the
leading coefficient is what comes out, not rescaled.

Certification at scale (docs/design.md: measure, do not guess)
---------------------------------------------------------
Everything is cleared of denominators and tested in
``Z[d, w1, w2, g1, g2, g3]`` with python-flint's ``fmpz_mpoly``:
``Den = prod_{m<J} ((2m+1)^2 d^2 + p^2)`` (``J = (p-1)/2``), ``K = p (d^2+1)``,

    P1 = P1~/Den,  P3 = M3/(K Den),  P2 = M2/(K^2 Den),
    G  = K^2 Den F3 = K^2 P1~ g1 + M2 g2 + K M3 g3,

and ``K dG/dt`` (vector field scaled by K, so integral) must be the zero
polynomial.  ``Q~ = Den Q`` is built by a Horner-type recursion
``R_{k+1} = q_k F1 R_k + e_{k+1} d^(2k+2) w2^(2k+2)``, ``q_k = (2k+1)^2 d^2 + p^2``,
``e_j = binom(2j,j) prod_{m<j}((2m+1)^2-p^2)/4^j`` (an integer), so no rational
arithmetic at all; the cost grows like p^3 to p^4 (``bench/``).
P2 is a polynomial iff ``w1`` divides ``K^2 P1~ - d L~ M3`` exactly (checked by
exact division); F3 is functionally independent of F1, F2 because the minor
``det d(F1, F2, F3)/d(w1, g1, g2) = 2 dF1/dw1 (g1 P2 - g2 P1)`` is a non-zero
polynomial.
"""
from __future__ import annotations

import functools
from math import comb

import flint
import symengine as se
import sympy as sp

from derivations.core import paper
from derivations.core.certificates import (
    Certificate,
    CertificateLog,
    Outcome,
    stopwatch,
)
from derivations.core.common_denominator import NotAPolynomial, polynomial
from derivations.core.errata import erratum
from derivations.core.exact import Domain, certify_polys_zero, certify_zero
from derivations.core.statement import Statement, ring
from derivations.core.flint_factor import factor_univariate
from derivations.core.recipe_rings import INTEGRAL_CTX as CTX
from derivations.core.recipe_rings import INTEGRAL_RING
from derivations.core.result import DerivationResult
from derivations.core.symbols import d, g1, g2, g3, p, w1, w2
from derivations.core.typeset import latex
from suslov.recipes.integrals import IntegralNumerators, integral_numerators

NAME = "first_integrals"
TITLE = "Polynomial first integrals $P_1,P_2,P_3$ for odd $p$ (section 6.2)"
REQUIRES = ("special_case",)

D_, W1, W2, G1, G2, G3 = CTX.gens()
FLINT_DOMAIN = "Z[d,w1,w2,g1,g2,g3] (fraction-free, `python-flint` `fmpz_mpoly`)"
WRITE_OUT_MAX = 7  # P1, P2, P3 written out in the LaTeX for p <= 7


def check_odd(p_value: int) -> int:
    if isinstance(p_value, bool) or not isinstance(p_value, int) or p_value < 1 or p_value % 2 == 0:
        raise ValueError(f"p={p_value!r}: the polynomial integral exists for odd positive integers p only")
    return p_value


def hypergeometric_coefficient(j: int, p_value: int, d_value):
    """c_j of F(z) for a given d (exact for a SymPy/Fraction d)."""
    value = sp.Rational(comb(2 * j, j), 4**j)
    for m in range(j):
        value *= sp.Integer((2 * m + 1) ** 2 - p_value**2) * d_value**2 / ((2 * m + 1) ** 2 * d_value**2 + p_value**2)
    return value


class FractionFree(IntegralNumerators):
    """P1 = P1t/Den, P3 = M3/(K Den), P2 = M2/(K^2 Den) in Z[d, w1, w2] (the recipe's output)."""

    def scaled_integral(self):
        """G = K^2 Den F3."""
        return self.K**2 * self.P1t * G1 + self.M2 * G2 + self.K * self.M3 * G3

    def terms(self) -> int:
        return len(self.P1t) + len(self.M2) + len(self.M3)


def construct(p_value: int) -> tuple[FractionFree, bool]:
    """The fraction-free P1, P2, P3 from the shared recipe; the flag says whether w1 divided exactly."""
    numerators = integral_numerators(check_odd(p_value), INTEGRAL_RING)
    return FractionFree(**vars(numerators)), numerators.exact


_RATIONAL_CTX = flint.fmpq_mpoly_ctx.get(CTX.names(), "lex")
_INDEX = {str(x): k for k, x in enumerate((d, w1, w2, g1, g2, g3))}


def _integer_polynomial(expr) -> object:
    """``expr``, a polynomial over Z once its denominators cancel, as an element of ``CTX``.

    symengine's products keep one exponent per base, so K times a right-hand side over K's own factors
    cancels as it is multiplied; SymPy's ``cancel`` runs only where a denominator is left."""
    try:
        poly = polynomial(se.expand(se.sympify(expr)), _RATIONAL_CTX, _INDEX)
    except NotAPolynomial:
        try:
            poly = polynomial(se.expand(se.sympify(sp.cancel(expr))), _RATIONAL_CTX, _INDEX)
        except NotAPolynomial as error:
            raise ArithmeticError(f"not a polynomial over Z: {expr} ({error})") from error
    if any(c.q != 1 for c in poly.coeffs()):
        raise ArithmeticError(f"not a polynomial over Z: {expr}")
    return CTX.from_dict({tuple(int(e) for e in m): int(c.p) for m, c in zip(poly.monoms(), poly.coeffs())})


def scaled_field(field_pd: dict, p_value: int) -> dict:
    """K times the derived eq:sysfin field and the Poisson field, in Z[d, w, g]."""
    K = p_value * (d**2 + 1)
    poisson = {g1: -w2 * g3, g2: w1 * g3, g3: w2 * g1 - w1 * g2}
    return {str(var): _integer_polynomial(K * rhs.subs(p, p_value))
            for var, rhs in list(field_pd.items()) + list(poisson.items())}


_FLINT_NAME = {"omega1": "w1", "omega2": "w2", "gamma1": "g1", "gamma2": "g2", "gamma3": "g3"}


def scaled_time_derivative(G, field: dict):
    """K dG/dt along the scaled field."""
    total = CTX.constant(0)
    for var, rhs in field.items():
        total += G.derivative(_FLINT_NAME[var]) * rhs
    return total


def certify_p(log: CertificateLog, p_value: int, field_pd: dict) -> tuple[FractionFree, list[Certificate]]:
    """Construct and certify the integral for one odd p."""
    with stopwatch() as elapsed:
        ff, divisible = construct(p_value)
        G = ff.scaled_integral()
        dG = scaled_time_derivative(G, scaled_field(field_pd, p_value))
        vanishes = dG.is_zero()
    cert_int = log.record(Certificate(
        f"$p = {p_value}$: $deriv(F3, t) = 0$ on eq:sysfin + Poisson ($F3 = P1 g1 + P2 g2 + P3 g3$, $P1 = w1 Q$)",
        "eq:liniowiec", Statement("exact zero test in ", ring(FLINT_DOMAIN)), Outcome.PASS if vanishes else Outcome.FAIL,
        elapsed[0], len(G), f"$G$ ($F3$ times $K^2$ and the common denominator of $P1$) has {len(G)} terms; $K deriv(G, t)$ has {len(dG)} terms"))
    cert_poly = log.record(Certificate(
        f"$p = {p_value}$: $P2$ is a polynomial ($w1$ divides $K^2 Ptilde_1 - d Ltilde M3$ exactly); $P3$ is one by construction",
        "eq:p23", Statement("exact division in ", ring(FLINT_DOMAIN)), Outcome.PASS if divisible else Outcome.FAIL,
        0.0, ff.terms(), "remainder of the division by $w1$ is 0" if divisible else "non-zero remainder"))
    with stopwatch() as elapsed:
        # det d(F1,F2,F3)/d(w1,g1,g2) = 2 dF1/dw1 (g1 P2 - g2 P1) up to the positive factor K^2 Den
        minor = 2 * (2 * (D_**2 + 1) * W1) * (G1 * ff.M2 - G2 * ff.K**2 * ff.P1t)
        independent = not minor.is_zero()
    cert_ind = log.record(Certificate(
        f"$p = {p_value}$: $F3$ is functionally independent of $F1$ and $F2$ (a Jacobian minor of order 3 is a non-zero polynomial)",
        "Theorem 6.2", Statement("non-zero test in ", ring(FLINT_DOMAIN)), Outcome.PASS if independent else Outcome.FAIL,
        elapsed[0], len(minor), f"minor $d(F1,F2,F3)/d(w1,g1,g2)$ has {len(minor)} terms"))
    return ff, [cert_int, cert_poly, cert_ind]


def to_sympy(poly) -> sp.Expr:
    names = [sp.Symbol("d"), w1, w2, g1, g2, g3]
    return sp.Add(*(int(c) * sp.Mul(*(v**e for v, e in zip(names, m))) for m, c in poly.to_dict().items()))


def _univariate_d(poly) -> list:
    """The coefficients (constant first) of an element of Z[d, w, g] that involves d only."""
    coefficients = {}
    for exponents, c in poly.to_dict().items():
        if any(exponents[1:]):
            raise ValueError("expected a polynomial in d alone")
        coefficients[exponents[0]] = int(c)
    return [coefficients.get(k, 0) for k in range(max(coefficients, default=0) + 1)]


def _coefficient_groups(ff: FractionFree) -> list[tuple[dict, list]]:
    """For P1, P2, P3: ({(a, b): coefficients in d of w1^a w2^b in the numerator}, the denominator's), from the
    fraction-free polynomials (P1 = P1t/Den, P2 = M2/(K^2 Den), P3 = M3/(K Den)); lists are constant first."""
    den, K = ff.Den, ff.K
    out = []
    for numerator, denominator in ((ff.P1t, den), (ff.M2, K**2 * den), (ff.M3, K * den)):
        groups = {}
        for (e_d, e_w1, e_w2, *rest), c in numerator.to_dict().items():
            if any(rest):
                raise ValueError("P1, P2, P3 do not involve gamma")
            groups.setdefault((e_w1, e_w2), {})[e_d] = int(c)
        out.append(({k: [cs.get(j, 0) for j in range(max(cs) + 1)] for k, cs in groups.items()},
                    _univariate_d(denominator)))
    return out


def rational_forms(ff: FractionFree) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """P1, P2, P3 as SymPy expressions (for small p: LaTeX and cross-checks).

    Each is ``sum_(a,b) factor(c_ab(d)) w1^a w2^b`` with the coefficients of Q(d) in factored form, the
    expression ``collect(expand(P), [w1, w2], factor)`` gives; the factorisations are FLINT's
    (:mod:`derivations.core.flint_factor`), 1.5 s of SymPy's ``factor`` fewer per build."""
    return tuple(sp.Add(*(factor_univariate(coefficients, den_coefficients, d) * w1**a * w2**b
                          for (a, b), coefficients in groups.items()))
                 for groups, den_coefficients in _coefficient_groups(ff))


def rational_polys(ff: FractionFree) -> list[sp.Poly]:
    """P1, P2, P3 as Polys over QQ(d), the same objects as ``_poly`` of :func:`rational_forms`, built from
    their coefficients instead of parsed from an expression (0.4 s of SymPy fewer per build)."""
    field = sp.QQ.frac_field(d)

    def element(coefficients: list):
        return field.from_sympy(sp.Add(*(c * d**j for j, c in enumerate(coefficients) if c)))

    polys = []
    for groups, den_coefficients in _coefficient_groups(ff):
        den = element(den_coefficients)
        terms = {(a, b, 0, 0, 0): element(coefficients) / den for (a, b), coefficients in groups.items()}
        polys.append(sp.Poly.from_dict(terms, w1, w2, g1, g2, g3, domain=field))
    return polys


QD_FIELD = "Q(d)[w1,w2,g1,g2,g3] (SymPy `Poly` over the field $Q(d)$)"


@functools.lru_cache(maxsize=256)   # the same constants (w1, w2, 1/(d^2+1), gamma, signs) are asked for again and again
def _poly(expr) -> sp.Poly:
    return sp.Poly(expr, w1, w2, g1, g2, g3, domain=sp.QQ.frac_field(d))


def sympy_integral(p_value: int, coefficients, p3_sign: int = -1) -> list[sp.Poly]:
    """P1, P2, P3 by arithmetic in the rational-function field (small p only).

    ``coefficients(j)`` gives c_j; ``p3_sign = -1`` is the derived
    P3 = -(d/p) L P1, ``+1`` the printed eq:p23.
    """
    F1 = _poly((d**2 + 1) * w1**2 + w2**2)
    J = (p_value - 1) // 2
    Q = sum((_poly(coefficients(j) * w2 ** (2 * j)) * F1 ** (J - j) for j in range(J + 1)), _poly(0))
    W1_, W2_ = _poly(w1), _poly(w2)
    k = _poly(d / p_value)

    def L(P):
        return W2_ * P.diff(w1) * _poly(1 / (d**2 + 1)) - W1_ * P.diff(w2)

    P1 = W1_ * Q
    P3 = _poly(p3_sign) * k * L(P1)
    P2, remainder = (W2_ * (P1 - k * L(P3))).div(W1_)
    if not remainder.is_zero:
        raise ArithmeticError(f"p = {p_value}: w1 does not divide the numerator of P2")
    return [P1, P2, P3]


def printed_pol_sol_coefficient(j: int, p_value: int):
    """c_j as printed in pol_sol (transcribed)."""
    value = sp.Integer(1)
    for m in range(1, j + 1):
        value *= sp.Rational(2 * m - 1, 2 * m)
    for m in range(j):
        value *= (p_value**2 - (2 * m + 1) ** 2) * d**2 / ((2 * m + 1) * d**2 + p_value**2)
    return value


def lie_residual(P: list, field: dict) -> sp.Poly:
    """dF3/dt for F3 = P1 g1 + P2 g2 + P3 g3 along eq:sysfin + Poisson, as a Poly over QQ(d)."""
    G = [_poly(g) for g in (g1, g2, g3)]
    F3 = P[0] * G[0] + P[1] * G[1] + P[2] * G[2]
    full = {w1: field[w1], w2: field[w2], g1: -w2 * g3, g2: w1 * g3, g3: w2 * g1 - w1 * g2}
    return sum((F3.diff(v) * _poly(rhs) for v, rhs in full.items()), _poly(0))


# the conditions of every formula of this section (the catalog and the documents print them)
HYPOTHESES = (r"$I_{13}=0$, with $p$, $d$ of section 4: $I_{11}=I_{22}(d^2+1)$, $I_{23}=-I_{22}d/p$", "$d>0$")
P_NAMES = sp.symbols("P1:4")


def catalog_form(polys) -> sp.Tuple:
    """``(Eq(P1, ...), Eq(P2, ...), Eq(P3, ...))`` of :func:`rational_forms`' P1, P2, P3 (the formula catalog)."""
    return sp.Tuple(*[sp.Eq(name, P, evaluate=False) for name, P in zip(P_NAMES, polys)])


def recipe_expr() -> sp.Tuple:
    """The construction for every odd p as SymPy: P1 = w1 F1^((p-1)/2) F(w2^2/F1) with F1 and the (derived) series
    F of eq:pol_sol written out, P3 = -(d/p) L P1, P2 = (w2/w1)(P1 - (d/p) L P3) for the unknowns P1(w1, w2), ...

    The series is :func:`hypergeometric_coefficient`'s c_j, ``(2j-1)!!/(2j)!! = binom(2j, j)/4^j`` (a finite
    ``Sum``: SymPy's ``hyper`` does not read back from ``srepr``)."""
    j, k = sp.symbols("j m", integer=True, nonnegative=True)
    F1 = (d**2 + 1) * w1**2 + w2**2
    coefficient = (sp.factorial2(2 * j - 1) / sp.factorial2(2 * j)
                   * sp.Product(((2 * k + 1) ** 2 - p**2) * d**2 / ((2 * k + 1) ** 2 * d**2 + p**2), (k, 0, j - 1)))
    series = sp.Sum(coefficient * (w2**2 / F1) ** j, (j, 0, (p - 1) / 2))
    P1, P2, P3 = (sp.Function(name.name)(w1, w2) for name in P_NAMES)

    def L(P):
        return w2 / (d**2 + 1) * sp.Derivative(P, w1) - w1 * sp.Derivative(P, w2)

    return sp.Tuple(sp.Eq(P1, w1 * F1 ** ((p - 1) / 2) * series, evaluate=False),
                    sp.Eq(P3, -d / p * L(P1), evaluate=False),
                    sp.Eq(P2, w2 / w1 * (P1 - d / p * L(P3)), evaluate=False))


def _latex_lines(name: str, P: sp.Expr) -> str:
    """``name = term_1 + term_2 ...`` with one monomial in (w1, w2) per aligned line."""
    # P comes from rational_forms: one term per monomial in (w1, w2), its coefficient already factored
    # (a number times a sum, alone, is distributed by Add: such pieces are gathered and factored again)
    pieces = {}
    for term in sp.Add.make_args(P):
        coefficient, monomial = term.as_independent(w1, w2, as_Add=False)
        pieces.setdefault((sp.degree(monomial, w1), sp.degree(monomial, w2)), []).append(coefficient)
    terms = {k: v[0] if len(v) == 1 else sp.factor(sp.Add(*v)) for k, v in pieces.items()}
    lines = []
    for (a, b), coefficient in sorted(terms.items(), reverse=True):
        term = latex(coefficient) if (a, b) == (0, 0) else latex(coefficient * w1**a * w2**b)
        lines.append(term if not lines or term.startswith("-") else "+" + term)
    return f"{name}={{}}&" + r"\\&".join(lines)


def run(log: CertificateLog, options, special_result) -> DerivationResult:
    result = DerivationResult(NAME)
    field_pd = special_result.exports["field"]
    QD = Domain("Q(d)[omega, gamma]")
    rows, forms, proofs, objects = [], {}, {}, {}
    refuted = {"p23": [], "pol_sol": []}
    for p_value in log.per_p("first integrals", options.odd_p_values()):
        field = {k: v.subs(p, p_value) for k, v in field_pd.items()}
        ff, certs = certify_p(log, p_value, field_pd)
        objects[p_value] = ff
        proofs[p_value] = certs[0]
        row = {"p": p_value, "degree": p_value, "terms": [len(ff.P1t), len(ff.M2), len(ff.M3)],
               "certificates": [c.key for c in certs]}
        if p_value <= WRITE_OUT_MAX:
            derived = rational_forms(ff)
            forms[p_value] = derived
            with stopwatch() as built:
                cross = sympy_integral(p_value, lambda j: hypergeometric_coefficient(j, p_value, d))
                diffs = [a - b for a, b in zip(rational_polys(ff), cross)]
            c_cross = certify_polys_zero(log, f"$p = {p_value}$: fraction-free $P1, P2, P3$ equal the rational-function "
                                         "route", "eq:p23", diffs, QD_FIELD, seconds=built[0])
            row["certificates"].append(c_cross.key)
            with stopwatch() as built:
                printed_sign = sympy_integral(p_value, lambda j: hypergeometric_coefficient(j, p_value, d), p3_sign=1)
                residual = lie_residual(printed_sign, field)
            refuted["p23"].append(certify_polys_zero(
                log, f"$p = {p_value}$: printed eq:p23 (the plus sign, $P3 = (d/p) L P1$, and $P2$ from it) gives a first integral",
                paper.P23.label, [residual], QD_FIELD, expect=Outcome.FAIL, seconds=built[0]))
            if p_value >= 3:
                with stopwatch() as built:
                    printed_q = sympy_integral(p_value, lambda j: printed_pol_sol_coefficient(j, p_value))
                    residual = lie_residual(printed_q, field)
                refuted["pol_sol"].append(certify_polys_zero(
                    log, f"$p = {p_value}$: the printed pol_sol coefficients give a first integral",
                    paper.POL_SOL.label, [residual], QD_FIELD, expect=Outcome.FAIL, seconds=built[0]))
        rows.append(row)

    if 1 in forms:
        P = forms[1]
        c_p1 = certify_zero(log, "printed $p = 1$ integral equals $d$ times the derived $F3$", paper.P1_INTEGRAL.label,
                            paper.P1_INTEGRAL_F3 - d * (P[0] * g1 + P[1] * g2 + P[2] * g3), QD)
        result.errata.append(erratum(paper.P1_INTEGRAL, "confirmed",
                                     r"F_3=\omega_1\gamma_1+\frac{\omega_2\gamma_2-d\,\omega_2\gamma_3}{d^2+1}",
                                     "equal up to the constant factor $d$ (normalisation $P1 = w1 Q$)", c_p1))
    if refuted["p23"]:
        result.errata.append(erratum(
            paper.P23, "corrected", r"P_3=-\frac{d}{p}\Big(\frac{\omega_2}{d^2+1}\frac{\partial P_1}{\partial\omega_1}"
            r"-\omega_1\frac{\partial P_1}{\partial\omega_2}\Big)",
            "the printed + sign in $P3$ contradicts the paper's own eq:partial; with it $deriv(F3, t) != 0$",
            *refuted["p23"], proofs[min(proofs)]))
    if refuted["pol_sol"]:
        result.errata.append(erratum(
            paper.POL_SOL, "corrected",
            r"\mathcal F_1(z)=\sum_{j=0}^{(p-1)/2}\frac{(2j-1)!!}{(2j)!!}\prod_{m=0}^{j-1}"
            r"\frac{((2m+1)^2-p^2)\,d^2}{(2m+1)^2d^2+p^2}\,z^j",
            "sign $(-1)^j$ missing and denominators $(2m+1)d^2+p^2$ instead of $(2m+1)^2 d^2+p^2$; the printed "
            "Pochhammer symbol $RisingFactorial(a, k)$ has the $k + 1$ factors $a + m$, $m$ from $0$ to $k$: one factor too "
            "many (the coefficients above use the $k$ factors, $m$ from $0$ to $k - 1$)", *refuted["pol_sol"], proofs[3]))

    # the SymPy forms of the written-out P{p} (formula catalog); the catalog's family for every certified p is
    # written at run time from the same certified recipe (suslov.catalog_families), not stored
    family = {p_value: catalog_form(polys) for p_value, polys in forms.items()}
    for p_value, polys in sorted(forms.items()):
        result.formula(f"P{p_value}", "eq:p1, eq:p23", f"$p={p_value}$ (one monomial per line)",
                       r"\begin{aligned}" + r"\\".join(_latex_lines(f"P_{i + 1}", P) for i, P in enumerate(polys))
                       + r"\end{aligned}", proofs[p_value], expr=family[p_value],
                       hypotheses=[*HYPOTHESES, f"$p={p_value}$"])
    result.formula("recipe", "eq:p1, eq:p23", "Construction for every odd $p$",
                   r"P_1=\omega_1F_1^{\frac{p-1}{2}}\mathcal F_1\Big(\frac{\omega_2^2}{F_1}\Big),\quad "
                   r"P_3=-\frac{d}{p}LP_1,\quad P_2=\frac{\omega_2}{\omega_1}\Big(P_1-\frac{d}{p}LP_3\Big),\quad "
                   r"L=\frac{\omega_2}{d^2+1}\partial_{\omega_1}-\omega_1\partial_{\omega_2},\quad "
                   r"F_1=(d^2+1)\omega_1^2+\omega_2^2,\quad "
                   r"\mathcal F_1(z)=\sum_{j=0}^{(p-1)/2}\frac{(2j-1)!!}{(2j)!!}\prod_{m=0}^{j-1}"
                   r"\frac{((2m+1)^2-p^2)\,d^2}{(2m+1)^2d^2+p^2}\,z^j",
                   *proofs.values(), expr=recipe_expr(), hypotheses=[*HYPOTHESES, "$p$ a positive odd integer"])
    result.exports.update(rows=rows, objects=objects,
                          catalog_family_certificates={row["p"]: list(row["certificates"]) for row in rows})
    return result
