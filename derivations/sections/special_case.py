"""The special case I13 = 0 in the variables p, d (paper section 4).

Labels: ``omegas``, ``eq:sysfin``, ``eq:ccalki``, ``eq:necc2``, ``eq:cpr``,
``eq:am2`` (residue of A(t), section 3.2), ``eq:necc1`` (parameter map).

Method
------
The general solution of ``derivations.sections.model`` is specialised, not re-typed:
with ``I13 = 0`` its coefficients are ``b = c1 = 0``, ``a = -I22/I23`` and
``c2/2 = r/I23``.  Writing ``c^2 = I11/I22 = d^2 + 1`` and ``a = p/d`` forces

    I11 = I22 (d^2 + 1),   I23 = -I22 d / p,   r = I22 c,

and under this substitution the derived Euler equations become exactly
``eq:sysfin`` with the ``+`` sign (``I22`` cancels) and the solution becomes
``omega1 = (p/d) tanh t``, ``omega2 = -(p/d) c sech t``.  Certificates live in
``Q(p, d)[c][T][S]/(c^2 - d^2 - 1, S^2 + T^2 - 1)``: both branches of
``c = +-sqrt(d^2+1)`` at once.

Residue of ``A(t)`` (``eq:at``) at ``t0 = i pi/2``: with ``x = e^t``,
``tanh t = (x^2-1)/(x^2+1)`` and ``sech t = 2x/(x^2+1)``, and
``Res_t f = Res_{x=i} f(x)/x``, a rational residue at a simple pole computed
exactly as ``N(i)/D'(i)``.  (``sympy.residue(tanh(t), t, I*pi/2)`` returns 0 in
SymPy 1.14, which is wrong; the value is 1.  The second route, ``eps A(i pi/2 + eps) -> A0``, is an
exact Laurent expansion: ``_laurent_limit``.)
"""
from __future__ import annotations

import symengine as se
import sympy as sp

from derivations.core import flint_factor, paper
from derivations.core.certificates import CertificateLog, Outcome
from derivations.core.differential import (
    S,
    T,
    hyperbolic_ring,
    lie_derivative,
    ode_residuals,
    t,
)
from derivations.core.emit import Emitted
from derivations.core.errata import erratum
from derivations.core.exact import Domain, Extension, certify_zero
from derivations.core.exp_substitution import certify_ode_in_exp
from derivations.core.result import DerivationResult
from derivations.core.symbols import I11, I13, I22, I23, I33, c, d, from_symengine, p, r, w1, w2, x
from derivations.core.typeset import latex
from derivations.sections import model

NAME = "special_case"
TITLE = "The case $I_{13}=0$ in the variables $p$, $d$ (section 4)"
REQUIRES = ("model",)

C_EXT = Extension(c, d**2 + 1, "c = +-sqrt(d^2+1)")
PD_DOMAIN = Domain("Q(p,d)[c]/(c^2-d^2-1)", (C_EXT,))
PD_FIELD = Domain("Q(p,d,I22)[omega, gamma]")
PD_RING = hyperbolic_ring("Q(p,d)[c][T][S]/(c^2-d^2-1, S^2+T^2-1)", C_EXT)
I_DOMAIN = Domain("Q(I11,I22,I23)")

SUBSTITUTION = {I13: 0, I11: I22 * (d**2 + 1), I23: -I22 * d / p, r: I22 * c}
lam = sp.Symbol("lambda")  # eigenvalue variable
# hypotheses of the formulas in p, d (printed with them, attached to their catalog entries)
CASE = "$I_{13}=0$"
D_POSITIVE = "$d>0$"
P_REAL = "$p$ real, $p\\ne0$"
SOLUTION = r"$\omega(t)=\big(\tfrac pd\tanh t,\,-\tfrac pdc\operatorname{sech}t\big)$, $c^2=d^2+1$"


def _expanded_det(matrix: sp.Matrix) -> sp.Expr:
    """``sympy.expand(matrix.det())`` for a matrix of Laurent monomials in d, c, lambda and i (the per-p A0 -
    lambda I) through symengine: a sum of monomials, which SymPy writes one way only, so the same
    expression (tests/test_special_case_det.py: p <= 101), about 6x faster."""
    return from_symengine(se.expand(se.Matrix(matrix).det()), d, c, p)


def residue_at_i_pi_half(expr: sp.Expr) -> sp.Expr:
    """Residue at ``t = i pi/2`` of a rational expression in ``T, S``."""
    in_x = sp.together(expr.subs({T: (x**2 - 1) / (x**2 + 1), S: 2 * x / (x**2 + 1)}) / x)
    num, den = sp.fraction(in_x)
    if sp.expand(den.subs(x, sp.I)) != 0:
        return sp.Integer(0)
    slope = sp.expand(sp.diff(den, x).subs(x, sp.I))
    if slope == 0:
        raise ValueError("pole at t = i pi/2 is not simple")
    return sp.expand(num.subs(x, sp.I) / slope)


def _laurent_limit(log: CertificateLog, A: sp.Matrix, A0: sp.Matrix):
    """eps A(i pi/2 + eps) = A0 + O(eps^2), exactly (was a 60-digit mpmath spot check).

    With y = e^eps, e^(i pi/2 + eps) = i y: tanh(i pi/2 + eps) = coth eps and sech(i pi/2 + eps) =
    -i csch eps (identities in Q(y)(i)); eps coth eps = 1 + eps^2/3 + O(eps^4) and eps csch eps =
    1 - eps^2/6 + O(eps^4) (their Laurent series, Bernoulli numbers, by SymPy's series); A is linear
    and homogeneous in (T, S), so eps A(i pi/2 + eps) = A(eps coth eps, -i eps csch eps) ->
    A(1, -i), which equals A0."""
    y, eps, lam_ = sp.symbols("y eps lambda_h")
    z = sp.I * y
    identities = [(z**2 - 1) / (z**2 + 1) - (y**2 + 1) / (y**2 - 1), 2 * z / (z**2 + 1) + sp.I * 2 * y / (y**2 - 1)]
    identities += [sp.series(eps * sp.coth(eps), eps, 0, 4).removeO() - (1 + eps**2 / 3),
                   sp.series(eps * sp.csch(eps), eps, 0, 4).removeO() - (1 - eps**2 / 6)]
    identities += list(A.subs({T: lam_ * T, S: lam_ * S}, simultaneous=True) - lam_ * A)
    identities += list(A.subs({T: 1, S: -sp.I}, simultaneous=True) - A0)
    return certify_zero(
        log, "$eps A(i pi/2 + eps)$ tends to $A0$: $tanh(i pi/2 + eps) = coth(eps)$, "
             "$sech(i pi/2 + eps) = -i csch(eps)$ ($y = exp(eps)$), $eps coth(eps) = 1 + eps^2/3 + O(eps^4)$, "
             "$eps csch(eps) = 1 - eps^2/6 + O(eps^4)$ (exact Laurent series), $A$ linear and homogeneous in "
             "$(tanh, sech)$ and $A(1, -i) = A0$", paper.AM2.label,
        identities, Domain("Q(p,d,y,eps,lam)[c]/(c^2-d^2-1)", (C_EXT,)))


def poisson_matrix(omega1, omega2) -> sp.Matrix:
    """A(t) of ``eq:at``: gamma' = A gamma."""
    return sp.Matrix([[0, 0, -omega2], [0, 0, omega1], [omega2, -omega1, 0]])


def positive_branch(expr):
    """``expr`` with ``c = +sqrt(d^2 + 1)``, the branch the documents print."""
    return expr.subs(c, sp.sqrt(d**2 + 1))


def _limits(solution: dict) -> dict:
    return {s: [solution[v].subs({T: s, S: 0}) for v in (w1, w2)] for s in (1, -1)}


def run(log: CertificateLog, options, model_result) -> DerivationResult:
    result = DerivationResult(NAME)
    field = model_result.exports["field"]
    poisson = model_result.exports["poisson"]
    general = model_result.exports["solution"]
    coeff = model_result.exports["coefficients"]

    # 1. the coefficients with I13 = 0, and the parametrisation by p, d
    zero13 = {name: flint_factor.factor(value.subs(I13, 0)) for name, value in coeff.items()}
    c_coef = certify_zero(log, "with $I13 = 0$: $b = c1 = 0$, $a = -I22/I23$, $c2/2 = r/I23$", "eq:necc2",
                          [zero13["b"], zero13["c1/2"], zero13["a"] + I22 / I23, zero13["c2/2"] - r / I23],
                          model.WITH_R)
    c_c2 = certify_zero(log, "under $a = p/d$, $c^2 = d^2+1$: $c2 = -2 c a$ (branch $r = I22 c$)", "eq:necc2",
                        (2 * zero13["c2/2"]).subs(SUBSTITUTION) + 2 * c * p / d, PD_DOMAIN)
    a_val = zero13["a"]
    p_squared = I22 * (I11 - I22) / I23**2
    c_p2 = certify_zero(log, "$p^2 = a^2 d^2 = I22 (I11 - I22)/I23^2$ with $d^2 = (I11 - I22)/I22$", "eq:necc1",
                        a_val**2 * (I11 - I22) / I22 - p_squared, I_DOMAIN)
    det_one = {I33: model.I33_FROM_DET.subs(I13, 0)}
    necc1 = paper.NECC1_P2.subs(det_one)
    c_necc1 = certify_zero(log, "printed eq:necc1 ($I13 = 0$, $det(I) = 1$) equals the derived $p^2$", "eq:necc1",
                           necc1 - p_squared, I_DOMAIN, expect=Outcome.FAIL)
    c_necc1_scale = certify_zero(log, "derived $p^2 = (I11 I22)^2$ times the printed eq:necc1 left-hand side", "eq:necc1",
                                 p_squared - (I11 * I22) ** 2 * necc1, I_DOMAIN)
    result.formula("pmap", "eq:necc1, eq:cpr", "Parameters from the inertia tensor ($I_{13}=0$)",
                   r"c^2=\frac{I_{11}}{I_{22}}=d^2+1,\quad p=a\,d=-\frac{I_{22}\,d}{I_{23}},\quad "
                   r"p^2=\frac{I_{22}(I_{11}-I_{22})}{I_{23}^2}", c_coef, c_c2, c_p2,
                   expr=sp.Tuple(sp.Eq(c**2, I11 / I22, evaluate=False), sp.Eq(c**2, d**2 + 1, evaluate=False),
                                 sp.Eq(p, sp.Symbol("a") * d, evaluate=False), sp.Eq(p, a_val * d, evaluate=False),
                                 sp.Eq(p**2, p_squared, evaluate=False)),
                   hypotheses=[CASE, model.FRAME, "$I_{11}>I_{22}>0$", D_POSITIVE,
                               "$a$ the coefficient of $\\tanh t$ in $\\omega_1(t)$ of the general solution"])
    result.errata.append(erratum(
        paper.NECC1, "corrected", r"p^2=\frac{I_{22}(I_{11}-I_{22})}{I_{23}^2}"
        r"=\frac{I_{11}I_{22}(I_{11}-I_{22})}{I_{11}I_{22}I_{33}-1}\ (\det\mathbb I=1)",
        "the printed value is $p^2$ of the printed gen12, whose time runs $-I11 I22$ times faster; "
        "for the equations derived from 3.25 the parameter gains the factor $(I11 I22)^2$ "
        "(the Kovalevskaya side of Theorem 3.2 is re-derived separately)",
        c_necc1, c_necc1_scale))

    a_printed = paper.OMEGAS_A.subs(det_one)
    c_a_pr = certify_zero(log, "printed omegas: $a = (I22 I33 - I23^2)/I23$ equals the derived a", "omegas",
                          a_printed - a_val, I_DOMAIN, expect=Outcome.FAIL)
    c_a_scale = certify_zero(log, "derived $a = -(I11 I22)$ times the printed $a$ ($det(I) = 1$)", "omegas",
                             a_val + I11 * I22 * a_printed, I_DOMAIN)

    # 2. the equations in p, d
    sysfin = {v: flint_factor.factor(field[v].subs(SUBSTITUTION)) for v in (w1, w2)}
    c_sys = certify_zero(log, "derived Euler equations with $I13 = 0$ become eq:sysfin with the + sign",
                         paper.SYSFIN.label, [sysfin[v] - paper.printed_sysfin(1)[v] for v in (w1, w2)], PD_FIELD)
    c_sys_minus = certify_zero(log, "eq:sysfin with the - sign is the derived system", paper.SYSFIN.label,
                               [sysfin[v] - paper.printed_sysfin(-1)[v] for v in (w1, w2)], PD_FIELD,
                               expect=Outcome.FAIL)
    F1 = paper.CCALKI_F1
    c_f1 = certify_zero(log, "$F1 = (d^2+1) w1^2 + w2^2$ is conserved by eq:sysfin (+)", paper.CCALKI.label,
                        lie_derivative(F1, paper.printed_sysfin(1)), PD_FIELD)
    c_f1_minus = certify_zero(log, "$F1$ is conserved by eq:sysfin with the - sign", paper.CCALKI.label,
                              lie_derivative(F1, paper.printed_sysfin(-1)), PD_FIELD, expect=Outcome.FAIL)
    c_f2 = certify_zero(log, "$F2 = inner(gamma, gamma)$ is conserved by the Poisson equations", paper.CCALKI.label,
                        lie_derivative(paper.CCALKI_F2, poisson), PD_FIELD)
    c_energy = certify_zero(log, "$I11 w1^2 + I22 w2^2 = I22 F1$ under the substitution", paper.CCALKI.label,
                            (I11 * w1**2 + I22 * w2**2).subs(SUBSTITUTION) - I22 * F1, PD_FIELD)
    result.formula("sysfin", "eq:sysfin", "Euler equations for $I_{13}=0$",
                   r"\dot\omega_1=" + latex(sysfin[w1]) + r",\quad\dot\omega_2=" + latex(sysfin[w2]),
                   c_sys, expr=sp.Tuple(model.ode(w1, sysfin[w1]), model.ode(w2, sysfin[w2])),
                   hypotheses=[CASE, D_POSITIVE, P_REAL])
    # the printer orders F1's terms omega1^2 (d^2+1) + omega2^2: kept as the paper's TeX
    result.formula("ccalki", "eq:ccalki", "First integrals",
                   r"F_1=(d^2+1)\omega_1^2+\omega_2^2,\quad F_2=\gamma_1^2+\gamma_2^2+\gamma_3^2", c_f1, c_f2,
                   c_energy, expr=sp.Tuple(sp.Eq(sp.Symbol("F1"), F1, evaluate=False),
                                           sp.Eq(sp.Symbol("F2"), paper.CCALKI_F2, evaluate=False)),
                   hypotheses=[CASE, D_POSITIVE, P_REAL])
    result.errata.append(erratum(
        paper.SYSFIN, "corrected", r"\dot\omega_1=+" + latex(sysfin[w1]) + r",\ \dot\omega_2=" + latex(sysfin[w2]),
        "the sign is not a free choice: only + follows from the Euler equations, and with - the "
        "energy $F1$ of eq:ccalki is not conserved", c_sys, c_sys_minus, c_f1_minus))

    # 3. the solution omega(t) in p, d
    solution = {v: sp.expand(general[v].subs(SUBSTITUTION)) for v in (w1, w2)}
    c_sol = certify_zero(log, "$omega1 = (p/d) tanh t$, $omega2 = -(p/d) c sech t$ solve eq:sysfin, both branches of $c$",
                         "omegas", ode_residuals(PD_RING, solution, sysfin), PD_RING.domain)
    # second exact route (was an mpmath.diff spot check): rational in x = e^t, d/dt = x d/dx
    numeric_certs = [certify_ode_in_exp(
        log, "$omega(t)$ solves eq:sysfin, both branches of $c$, "
             "in $x = exp(t)$ ($tanh(t) = (x^2 - 1)/(x^2 + 1)$, $sech(t) = 2 x/(x^2 + 1)$, and $d/dt$ is $x$ times $d/dx$)", "omegas",
        [solution[w1], solution[w2]], [sysfin[w1], sysfin[w2]], [w1, w2], "Q(p,d)(x)[c]/(c^2-d^2-1)", (C_EXT,))]
    c_form = certify_zero(log, "printed omegas form $w1 = a tanh t$, $w2 = -a c sech t$ with $a = p/d$", "omegas",
                          [solution[w1] - (p / d) * T, solution[w2] + (p / d) * c * S], PD_RING.domain)
    result.formula("omegas", "omegas", "Angular velocity ($a=p/d$, $c=\\sqrt{d^2+1}$)",
                   r"\omega_1(t)=\frac{p}{d}\tanh t,\quad \omega_2(t)=-\frac{p\sqrt{d^2+1}}{d}\operatorname{sech}t",
                   c_sol, *numeric_certs, c_form,
                   expr=sp.Tuple(*[sp.Eq(model.of_t(v), model.of_tanh_sech(positive_branch(solution[v])), evaluate=False)
                                   for v in (w1, w2)]),
                   hypotheses=[CASE, D_POSITIVE, P_REAL, "rate $A=1$, $t_0=0$",
                               "$c=\\sqrt{d^2+1}$ (with $-c$ it is a solution too)"])
    result.errata.append(erratum(
        paper.OMEGAS, "corrected", r"\omega_1=a\tanh t,\ \omega_2=-ac\,\mathrm{sech}\,t,\ a=-\frac{I_{22}}{I_{23}}",
        "the form is confirmed; the printed $a = (I22 I33 - I23^2)/I23 = 1/(I11 I23)$ ($det(I) = 1$) is the value "
        "for the printed gen12, $-1/(I11 I22)$ times the derived one", c_form, c_a_pr, c_a_scale))

    level = sp.expand(F1.subs(solution, simultaneous=True))
    c_level = certify_zero(log, "$F1 = a^2 c^2 = p^2 (d^2+1)/d^2$ on $omega(t)$", "eq:ccalki",
                           level - p**2 * (d**2 + 1) / d**2, PD_RING.domain)
    result.formula("level", "eq:ccalki", "Energy level of the normalised solution",
                   r"F_1=a^2c^2=\frac{p^2(d^2+1)}{d^2}", c_level,
                   expr=sp.Tuple(sp.Eq(sp.Symbol("F1"), sp.Symbol("a")**2 * c**2, evaluate=False),
                                 sp.Eq(sp.Symbol("F1"), p**2 * (d**2 + 1) / d**2, evaluate=False)),
                   hypotheses=[CASE, D_POSITIVE, P_REAL, SOLUTION, "$a=p/d$", "$c^2=d^2+1$"])
    result.errata.append(erratum(paper.F1_VALUE_SENTENCE, "not comparable", r"F_1=a^2c^2=\frac{p^2(d^2+1)}{d^2}",
                                 "the printed sentence breaks off after '$F1 = a^2 c^2$ ='; completed by derivation",
                                 c_level))

    limits = _limits(solution)
    c_lim = certify_zero(log, "$to(omega(t), (pm(p/d), 0))$ as $to(t, pm(oo))$ ($to(tanh(t), pm(1))$, $to(sech(t), 0)$)", "omegas",
                         [limits[1][0] - p / d, limits[1][1], limits[-1][0] + p / d, limits[-1][1]], PD_DOMAIN)
    c_lim_text = certify_zero(log, "text: the limit angular velocity is $mp a$ as $to(t, pm(oo))$", "omegas (text)",
                              [limits[1][0] + p / d, limits[-1][0] - p / d], PD_DOMAIN, expect=Outcome.FAIL)
    result.formula("limits", "omegas", "Limit steady rotations about $(1,0,0)$",
                   r"\lim_{t\to\pm\infty}\omega(t)=\left(\pm\frac{p}{d},\,0\right)", c_lim,
                   expr=sp.Tuple(*[sp.Eq(sp.Limit(model.of_t(v), t, sign * sp.oo), limits[sign][k], evaluate=False)
                                   for sign in (1, -1) for k, v in enumerate((w1, w2))]),
                   hypotheses=[CASE, D_POSITIVE, P_REAL, SOLUTION])
    result.errata.append(erratum(paper.LIMIT_TEXT, "corrected",
                                 r"t\to\pm\infty:\ \omega_1\to\pm a",
                                 "the text's $mp a$ contradicts the formula omegas ($omega1 = a tanh t$)",
                                 c_lim, c_lim_text))

    # 4. residue of A(t) at t = i pi/2
    A = poisson_matrix(solution[w1], solution[w2])
    A0 = A.applyfunc(residue_at_i_pi_half)
    c_am2 = certify_zero(log, "residue of $A(t)$ at $t = i pi/2$ is eq:am2", paper.AM2.label,
                         list(A0 - paper.AM2_MATRIX), PD_DOMAIN)
    c_res_num = _laurent_limit(log, A, A0)
    lam_poly = sp.expand((A0 - lam * sp.eye(3)).det())
    c_char = certify_zero(log, "$det(A0 - lam) = -(lam^3 - p^2 lam)$: eigenvalues $0$, $pm(p)$", "eq:ro",
                          lam_poly + lam**3 - p**2 * lam, PD_DOMAIN)
    A0_shown, characteristic = sp.ImmutableMatrix(positive_branch(A0)), flint_factor.factor(-lam**3 + p**2 * lam)
    result.formula("A0", "eq:am2, eq:ro", "Residue of $A(t)$ at $t_0=i\\pi/2$ and its eigenvalues",
                   [("A_0", A0_shown), (r"\det(A_0-\lambda)", characteristic)], c_am2, c_res_num, c_char,
                   expr=sp.Tuple(sp.Eq(model.named_matrix("A0", 3, 3), A0_shown, evaluate=False),
                                 sp.Eq(sp.Symbol("charA0"), characteristic, evaluate=False)),
                   hypotheses=[CASE, D_POSITIVE, P_REAL, SOLUTION + ", branch $c=\\sqrt{d^2+1}$"])
    result.errata.append(erratum(paper.AM2, "confirmed", paper.AM2.latex, "derived as an exact residue",
                                 c_am2, c_res_num))

    # 5. per-p table: the residue eigenvalues for each integer p <= pmax
    per_p = []
    for p_value in options.p_values():
        cert = certify_zero(log, f"$p = {p_value}$: $det(A0 - lam) = -lam (lam - {p_value})(lam + {p_value})$",
                            "eq:ro", _expanded_det(A0.subs(p, p_value) - lam * sp.eye(3))
                            + lam * (lam - p_value) * (lam + p_value), Domain("Q(d)[c]/(c^2-d^2-1)", (C_EXT,)))
        per_p.append({"p": p_value, "parity": "odd" if p_value % 2 else "even",
                      "eigenvalues": f"0, {p_value}, -{p_value}", "level": latex(p_value**2 * (d**2 + 1) / d**2),
                      "rate": latex(sp.Integer(p_value) / d), "certificate": cert.key})

    # 5. the inverse map (I11, I22, I23) -> (p, d), emitted for special_case_parameters
    p_of_inertia = -I22 * d / I23
    c_inverse = certify_zero(log, "$d^2 = I11/I22 - 1$ and $p = -I22 d/I23$ invert the substitution $I11 = I22 (d^2+1)$, "
                             "$I23 = -I22 d/p$", "eq:necc1", [(I11 / I22 - 1).subs(SUBSTITUTION) - d**2,
                                                           p_of_inertia.subs(SUBSTITUTION) - p], Domain("Q(p,d,I22)"))
    tanh_t, sech_t = sp.tanh(t), sp.sech(t)
    emit = [Emitted("omega", (t, p, d), ((T, tanh_t), (S, sech_t), (c, sp.sqrt(d**2 + 1))),
                    (solution[w1], solution[w2]), (c_sol.key, c_form.key),
                    "omega(t) for I13 = 0 (omegas), branch c = +sqrt(d^2+1).", (T, S)),
            Emitted("special_parameters", (I11, I22, I23), ((d, sp.sqrt(I11 / I22 - 1)),), (p_of_inertia, d),
                    (c_inverse.key,), "(p, d) of a body with I13 = 0 (eq:necc1, corrected).")]
    result.exports.update(solution=solution, field=sysfin, A0=A0, per_p=per_p, emit=emit,
                          p_of_inertia=-I22 * sp.Symbol("d") / I23,
                          substitution=SUBSTITUTION)
    return result
