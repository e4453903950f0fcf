"""Reduction of the Poisson equations (I13 = 0) to a 3F2 equation (paper section 5.1).

Labels: ``eq:genhipprep``, ``a'ss``, ``t->z``, ``eq:gamma_1``, ``eq:genhip``,
``eq:3F2``, ``eq:param``, ``eq:ghyp`` (Pochhammer symbol).  Symbolic p and d.

Method
------
1. *Third-order equation for gamma1.*  Along the vector field X of eq:sysfin
   (+ sign, from ``special_case``) and the Poisson equations, the four linear
   forms ``X^k gamma1`` (k = 0..3) in ``gamma`` are linearly dependent; the
   printed coefficients ``a'ss`` are certified by the exact identity
   ``a0 X^3 g1 + a1 X^2 g1 + a2 X g1 + a3 g1 = 0`` in ``Q(p,d)[omega,gamma]``.
2. *Change of variable* ``z = d^2 w2^2/((d^2+1) p^2) = sech^2 t``: in the
   tanh/sech ring, ``gamma1 = F(z(t))`` gives by the chain rule
   ``a0 z'^3 F''' + (...) F'' + (...) F' + a3 F``; the ratios to the leading
   coefficient are certified equal to the printed ``b1, b2, b3`` at ``z = S^2``.
3. *Substitution* ``gamma1 = w u`` with ``w^2 = z - 1`` (an extension,
   ``w' = w/(2(z-1))``): the operator becomes ``w`` times a third-order operator
   in ``u``, certified proportional to the printed ``eq:genhip`` in ``Q(p,d)(z)``.
4. *Identification* with the canonical 3F2 operator ``eq:3F2`` at the
   parameters ``eq:param``: exact in ``Q(p,d)(i)(z)``.

The Pochhammer symbol of ``eq:ghyp`` is printed as ``a(a+1)...(a+k)``; the
series solves ``eq:3F2`` only with ``(a)_k = a(a+1)...(a+k-1)``, which the
certificate for p = 3 shows (the printed definition's series fails).
"""
from __future__ import annotations

import sympy as sp

from derivations.core import flint_factor, paper
from derivations.core.certificates import CertificateLog, Outcome
from derivations.core.differential import S, lie_derivative, t
from derivations.core.errata import erratum
from derivations.core.exact import Domain, certify_zero
from derivations.core.result import DerivationResult
from derivations.core.symbols import d, g1, g2, g3, p, w1, w2
from derivations.core.typeset import latex
from derivations.sections.model import of_t
from derivations.sections.special_case import CASE, D_POSITIVE, P_REAL, PD_RING, SOLUTION

NAME = "hypergeometric"
TITLE = "Reduction to the generalised hypergeometric equation (section 5.1)"
REQUIRES = ("special_case",)

z = sp.Symbol("z")
u0, u1, u2, u3 = sp.symbols("u0:4")  # u and its z-derivatives (jet variables)
HYPOTHESES = [CASE, D_POSITIVE, P_REAL]
F0, F1_, F2_, F3_ = sp.symbols("F0:4")
w = sp.Symbol("w")  # w**2 = z - 1

PQ = Domain("Q(p,d)[omega,gamma]")
QZ = Domain("Q(p,d)(z)[u]")
QZ_W = Domain("Q(p,d)(z)[w]/(w^2-z+1)", (paper_w := None) or ())


def genhip_coefficients():
    """Printed eq:genhip: m3 u''' + m2 u'' + m1 u' + m0 u."""
    return [sp.Rational(1, 8) * (p**2 - 1), sp.Rational(1, 4) * (1 + p**2 / d**2) + sp.Rational(1, 4) * (p**2 - 13) * z,
            sp.Rational(1, 2) * (4 - 9 * z) * z, z**2 * (1 - z)]


def canonical_3f2(alphas, betas):
    """eq:3F2 coefficients [m0, m1, m2, m3]."""
    a1, a2, a3 = alphas
    b1, b2 = betas
    return [-a1 * a2 * a3, b1 * b2 - (1 + a1 + a2 + a3 + a1 * a2 + a2 * a3 + a3 * a1) * z,
            z * (1 + b1 + b2 - (3 + a1 + a2 + a3) * z), z**2 * (1 - z)]


PARAM = ((sp.Rational(1, 2), (1 + p) / 2, (1 - p) / 2), ((d - sp.I * p) / (2 * d), (d + sp.I * p) / (2 * d)))


def pochhammer(a, k, printed=False):
    """(a)_k = a (a+1) ... (a+k-1); the printed definition has one more factor."""
    return sp.Mul(*[a + j for j in range(k + (1 if printed else 0))])


def series_3f2(alphas, betas, p_value, printed=False):
    """Terminating 3F2 (alpha3 = (1-p)/2) with the given Pochhammer convention."""
    top = (1 - p_value) // 2
    terms = []
    for k in range(-top + 1):
        num = sp.Mul(*[pochhammer(a.subs(p, p_value), k, printed) for a in alphas])
        den = sp.Mul(*[pochhammer(b.subs(p, p_value), k, printed) for b in betas]) * sp.factorial(k)
        terms.append(num / den * z**k)
    return sp.Add(*terms)


def linear_operator(coefficients, f, x) -> sp.Expr:
    """``sum_k coefficients[k] f^(k)``: the left-hand side of a linear equation in the catalog's form."""
    return sp.Add(*[m * sp.Derivative(f, (x, k)) if k else m * f for k, m in enumerate(coefficients)])


def apply_z_operator(coefficients, f):
    return sum(m * sp.diff(f, z, k) for k, m in enumerate(coefficients))


def run(log: CertificateLog, options, special_result) -> DerivationResult:
    result = DerivationResult(NAME)
    field = dict(special_result.exports["field"])
    field.update({g1: -w2 * g3, g2: w1 * g3, g3: w2 * g1 - w1 * g2})

    # 1. third-order equation for gamma1
    jets = [g1]
    for _ in range(3):
        jets.append(sp.expand(lie_derivative(jets[-1], field)))
    a0 = (d**2 + 1) * p**2 * w1
    a1 = d * p * (2 * (d**2 + 1) * w1**2 - w2**2)
    a2 = (d**2 + 1) * w1 * ((d**2 + p**2) * w1**2 + p**2 * w2**2)
    a3 = -d * p * w2**2 * ((d**2 + 1) * w1**2 + w2**2)
    c_prep = certify_zero(log, "$gamma1$ solves $a0 deriv(g1, t, 3) + a1 deriv(g1, t, 2) + a2 deriv(g1, t) + a3 g1 = 0$ "
                          "on every solution of eq:sysfin + Poisson (printed a'ss)", "eq:genhipprep",
                          a0 * jets[3] + a1 * jets[2] + a2 * jets[1] + a3 * jets[0], PQ)
    result.formula("genhipprep", "eq:genhipprep, a'ss", "Third-order equation for $\\gamma_1$",
                   [r"a_0\dddot\gamma_1+a_1\ddot\gamma_1+a_2\dot\gamma_1+a_3\gamma_1=0,\quad "
                    + r",\quad ".join(f"a_{i}={latex(flint_factor.factor(v))}" for i, v in enumerate((a0, a1))) + ",",
                    *[f"a_{i}={latex(flint_factor.factor(v))}" + ("," if i == 2 else "") for i, v in enumerate((a2, a3), 2)]],
                   c_prep, expr=sp.Tuple(
                       sp.Eq(linear_operator([sp.Symbol(f"a{3 - k}") for k in range(4)], sp.Function("gamma1")(t), t), 0,
                             evaluate=False),
                       *[sp.Eq(sp.Symbol(f"a{i}"), of_t(flint_factor.factor(v)), evaluate=False)
                         for i, v in enumerate((a0, a1, a2, a3))]),
                   hypotheses=HYPOTHESES + [r"$(\omega,\gamma)(t)$ any solution of the Euler and Poisson equations"])
    result.errata.append(erratum(paper.GENHIPPREP, "confirmed", paper.GENHIPPREP.latex,
                                 "certified as an identity along the flow", c_prep))

    # 2. z = d^2 w2^2 / ((d^2+1) p^2) = sech^2 t on omega(t); chain rule
    solution = special_result.exports["solution"]
    z_of_w = d**2 * w2**2 / ((d**2 + 1) * p**2)
    c_z = certify_zero(log, "$z = d^2 w2^2/((d^2+1) p^2)$ equals $sech(t)^2$ on $omega(t)$", "t->z",
                       z_of_w.subs(solution, simultaneous=True) - S**2, PD_RING.domain)
    zt = [S**2]
    for _ in range(3):
        zt.append(sp.expand(PD_RING.d_dt(zt[-1])))
    zz = S**2
    printed_zdot = [-2 * d * zz * solution[w1] / p,
                    2 * zz * (2 * p**2 + 2 * d**2 * p**2 - 3 * (1 + d**2) * p**2 * zz) / ((d**2 + 1) * p**2),
                    -8 * d * zz * (p**2 + d**2 * p**2 - 3 * (d**2 + 1) * p**2 * zz) * solution[w1] / ((d**2 + 1) * p**3)]
    c_zdots = certify_zero(log, "printed $deriv(z, t)$, $deriv(z, t, 2)$, $deriv(z, t, 3)$ along $omega(t)$", "t->z",
                           [zt[k + 1] - printed_zdot[k] for k in range(3)], PD_RING.domain)
    # gamma1(t) = F(z(t)): derivatives in terms of F0..F3 = F, F', F'', F'''
    g_t = [F0, zt[1] * F1_, zt[2] * F1_ + zt[1] ** 2 * F2_, zt[3] * F1_ + 3 * zt[1] * zt[2] * F2_ + zt[1] ** 3 * F3_]
    on_sol = {k: v.subs(solution, simultaneous=True) for k, v in (("a0", a0), ("a1", a1), ("a2", a2), ("a3", a3))}
    operator = sp.expand(on_sol["a0"] * g_t[3] + on_sol["a1"] * g_t[2] + on_sol["a2"] * g_t[1] + on_sol["a3"] * g_t[0])
    coeff = [operator.coeff(f) for f in (F0, F1_, F2_, F3_)]
    b_printed = {
        1: 2 / z + 1 / (z - 1),
        2: (-p**2 * (z - 1) + d**2 * (1 + z * (-6 - p**2 * (z - 1) + 4 * z))) / (4 * d**2 * (z - 1) ** 2 * z**2),
        3: (d**2 + 1) * p**2 / (8 * d**2 * (z - 1) ** 2 * z**2),
    }
    c_b = certify_zero(log, "in $z = sech(t)^2$ the equation is $deriv(g, z, 3) + b1 deriv(g, z, 2) + b2 deriv(g, z) + b3 g = 0$ "
                       "with the printed $b1$, $b2$, $b3$",
                       "eq:gamma_1", [coeff[3 - k] / coeff[3] - b_printed[k].subs(z, S**2) for k in (1, 2, 3)],
                       PD_RING.domain)
    result.formula("gamma_1", "eq:gamma_1, t->z", "Equation in $z=4/(e^t+e^{-t})^2=\\operatorname{sech}^2t$",
                   [r"\gamma_1'''+b_1\gamma_1''+b_2\gamma_1'+b_3\gamma_1=0,\quad b_1=" + latex(b_printed[1]) + ",",
                    r"b_2=" + latex(flint_factor.factor(b_printed[2])) + ",", r"b_3=" + latex(b_printed[3])],
                   c_z, c_zdots, c_b,
                   expr=sp.Tuple(
                       sp.Eq(linear_operator(sp.symbols("b3 b2 b1") + (1,), sp.Function("gamma1")(z), z), 0, evaluate=False),
                       *[sp.Eq(sp.Symbol(f"b{k}"), value, evaluate=False)
                         for k, value in ((1, b_printed[1]), (2, flint_factor.factor(b_printed[2])), (3, b_printed[3]))]),
                   hypotheses=HYPOTHESES + [SOLUTION, r"$z=\operatorname{sech}^2t$"])

    # 3. gamma1 = w u, w^2 = z - 1
    r_k = [sp.Integer(1)]  # w^(k) = w r_k
    for _ in range(3):
        r_k.append(sp.together(sp.diff(r_k[-1], z) + r_k[-1] / (2 * (z - 1))))
    us = [u0, u1, u2, u3]
    # derivatives of w u divided by w (Leibniz)
    wu = [sp.Add(*(sp.binomial(n, k) * r_k[k] * us[n - k] for k in range(n + 1))) for n in range(4)]
    reduced = sp.expand(wu[3] + b_printed[1] * wu[2] + b_printed[2] * wu[1] + b_printed[3] * wu[0])
    e = [reduced.coeff(v) for v in us]
    m = genhip_coefficients()
    c_genhip = certify_zero(log, "$gamma1 = sqrt(z-1) u$ turns eq:gamma_1 into eq:genhip (ratios to the leading coefficient)",
                            "eq:genhip", [e[k] / e[3] - m[k] / m[3] for k in range(3)], QZ)
    result.formula("genhip", "eq:genhip", "Equation for $u=\\gamma_1/\\sqrt{z-1}$",
                   r"z^2(1-z)u'''+\tfrac12(4-9z)zu''+\Big[\tfrac14\Big(1+\frac{p^2}{d^2}\Big)+\tfrac14(p^2-13)z\Big]u'"
                   r"+\tfrac18(p^2-1)u=0", c_genhip,
                   expr=sp.Eq(linear_operator(m, sp.Function("u")(z), z), 0, evaluate=False),
                   hypotheses=HYPOTHESES + [r"$\gamma_1(z)$ a solution of the equation in $z$ above"])

    # 4. identification with 3F2
    canon = canonical_3f2(*PARAM)
    c_param = certify_zero(log, "eq:genhip is the generalised hypergeometric equation eq:3F2 with the parameters eq:param", "eq:param",
                           [canon[k] - m[k] for k in range(4)], QZ)
    result.formula("param", "eq:3F2, eq:param", "Parameters of the $_3F_2$",
                   r"\alpha=\Big(\tfrac12,\tfrac{1+p}{2},\tfrac{1-p}{2}\Big),\quad\beta=\Big(\frac{d-ip}{2d},\frac{d+ip}{2d}\Big)",
                   # alpha1..3, beta1, beta2 as in eq:3F2 (a symbol "beta" would read back as sympy.beta)
                   c_param, expr=sp.Tuple(*[sp.Eq(sp.Symbol(f"{name}{k}"), value, evaluate=False)
                                            for name, values in (("alpha", PARAM[0]), ("beta", PARAM[1]))
                                            for k, value in enumerate(values, 1)]),
                   hypotheses=HYPOTHESES)
    for item in (paper.GAMMA_1, paper.GENHIP, paper.PARAM):
        result.errata.append(erratum(item, "confirmed", item.latex, "certified exactly (symbolic $p$, $d$)",
                                     {"eq:gamma_1": c_b, "eq:genhip": c_genhip, "eq:param": c_param}[item.label]))

    # Pochhammer: the series solves eq:3F2 only with (a)_k = a...(a+k-1) (checked at p = 3)
    good = series_3f2(*PARAM, 3)
    bad = series_3f2(*PARAM, 3, printed=True)
    m3 = [v.subs(p, 3) for v in m]
    c_poch = certify_zero(log, "$p = 3$: the generalised hypergeometric series with the Pochhammer symbol "
                          "$RisingFactorial(a, k)$ of $k$ factors $a$, ..., $a + k - 1$ solves eq:genhip", "eq:ghyp",
                          apply_z_operator(m3, good), QZ)
    c_poch_bad = certify_zero(log, "$p = 3$: the generalised hypergeometric series with the printed Pochhammer symbol of $k + 1$ "
                              "factors $a$, ..., $a + k$ solves eq:genhip",
                              "eq:ghyp", apply_z_operator(m3, bad), QZ, expect=Outcome.FAIL)
    result.errata.append(erratum(paper.POCHHAMMER, "corrected", r"(a)_k=a(a+1)\cdots(a+k-1),\ (a)_0=1",
                                 "the printed definition has one factor too many", c_poch, c_poch_bad))
    result.exports.update(genhip=m, b=b_printed)
    return result
