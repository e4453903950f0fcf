"""The Euler-Poisson equations of the Suslov problem and their general solution.

Paper sections 1-2: ``3.25``, ``ep3.26``, ``gen12``, ``eq:whole``, ``eq:o12``,
``c's``, ``eq:enlev``.

Method
------
1. Inertia tensor with ``I12 = 0``; ``det I = 1`` fixes
   ``I33 = (1 + I11 I23^2 + I22 I13^2)/(I11 I22)``.
2. The reduced Euler equations are *solved for*, not transcribed:
   ``I omega' = I omega x omega + lambda a`` with ``a = e3``, ``omega3 = 0``,
   is a linear system for ``(omega1', omega2', lambda)``.  Result:
   ``omega1' = -m3 omega2 / I11``, ``omega2' = m3 omega1 / I22`` with
   ``m3 = I13 omega1 + I23 omega2``.  Only ``I11, I22, I13, I23`` appear
   (entries of I, not of its inverse; ``I33`` drops out).
3. Poisson equations from a space-fixed vector: ``R' = R hat(omega)`` and
   ``gamma = R^T e`` give ``gamma' = -hat(omega) gamma = gamma x omega``.
4. General solution by reduction: ``u = I13 w1 + I23 w2`` and
   ``v = I23 w1/I22 - I13 w2/I11`` satisfy ``u' = u v``,
   ``v' = -u^2/(I11 I22)``, solved (rate A = 1) by ``u = r sech t``,
   ``v = -tanh t`` with ``r^2 = I11 I22``; inverting the linear map gives
   ``omega(t)``.  The sign of ``r`` is the paper's ``+-``: certificates in
   ``Q(I)[r]/(r^2 - I11 I22)`` cover both signs at once.

Findings (errata): the printed ``ep3.26`` drops the factor
``1/<a, I^-1 a>`` and reverses the cross product; ``gen12`` inherits this and
equals the derived field times ``-(I^-1)_33 = -I11 I22`` (a reparametrisation
of time, ``tau = -I11 I22 t``); the printed ``eq:o12``/``c's`` solve the printed
``gen12`` (signs coupled) and are ``-1/(I11 I22)`` times the derived solution.
"""
from __future__ import annotations

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
from derivations.core.symbols import (
    I11,
    I13,
    I22,
    I23,
    I33,
    g1,
    g2,
    g3,
    gamma,
    lam,
    omega,
    r,
    w1,
    w2,
)
from derivations.core.typeset import latex

NAME = "model"
TITLE = "Euler-Poisson equations and their general solution (sections 1-2)"

R_EXT = Extension(r, I11 * I22, "r = +-sqrt(I11*I22)")
RATIONAL = Domain("Q(I11,I22,I13,I23)[omega, gamma]")
WITH_R = Domain("Q(I11,I22,I13,I23)[r]/(r^2-I11 I22)", (R_EXT,))
RING = hyperbolic_ring("Q(I11,I22,I13,I23)[r][T][S]/(r^2-I11 I22, S^2+T^2-1)", R_EXT)

I33_FROM_DET = (1 + I11 * I23**2 + I22 * I13**2) / (I11 * I22)
E3 = sp.Matrix([0, 0, 1])


# hypotheses of the formulas (printed with them, attached to their catalog entries)
FRAME = "$I_{12}=0$"
CONSTRAINT = "$a=e_3$, so $\\omega_3=0$"
POSITIVE = "$I_{11},I_{22}>0$"
NONZERO_D = "$D=I_{13}^2I_{22}+I_{23}^2I_{11}\\ne0$"
BRANCH_R = "$r=\\pm\\sqrt{I_{11}I_{22}}$ (either branch)"


def of_tanh_sech(expr) -> sp.Expr:
    """An expression in the generators T, S as a function of t: T = tanh t, S = sech t."""
    return sp.sympify(expr).subs({T: sp.tanh(t), S: sp.sech(t)})


def inertia_tensor(i33=I33) -> sp.Matrix:
    return sp.Matrix([[I11, 0, I13], [0, I22, I23], [I13, I23, i33]])


def hat(v: sp.Matrix) -> sp.Matrix:
    """The matrix of ``x -> v x x``."""
    return sp.Matrix([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def of_t(expr) -> sp.Expr:
    """``expr`` with the state symbols omega1, omega2, gamma1..3 as undefined functions of t: the catalog's
    form of a formula along a solution (``DerivedFormula.expr``)."""
    return sp.sympify(expr).xreplace({s: sp.Function(s.name)(t) for s in (w1, w2, g1, g2, g3)})


def ode(state: sp.Symbol, rhs) -> sp.Eq:
    """``d/dt state(t) = rhs`` in the catalog's form (functions of t on both sides)."""
    return sp.Eq(sp.Derivative(sp.Function(state.name)(t), t), of_t(rhs), evaluate=False)


def named_matrix(name: str, rows: int, cols: int) -> sp.ImmutableMatrix:
    """The matrix of symbols ``name11, name12, ...``: a named matrix on the left of a catalog equation
    (``Eq(Symbol(name), matrix)`` does not survive ``sympify(srepr(...))``: SymPy evaluates it to False)."""
    return sp.ImmutableMatrix(rows, cols, lambda i, j: sp.Symbol(f"{name}{i + 1}{j + 1}"))


def derive_euler_field() -> tuple[dict, sp.Expr]:
    """Solve ``I w' = I w x w + lambda e3`` (``w3 = 0``) for ``w1', w2', lambda``."""
    dw1, dw2 = sp.symbols("dw1 dw2")
    inertia = inertia_tensor()
    equations = inertia * sp.Matrix([dw1, dw2, 0]) - (inertia * omega).cross(omega) - lam * E3
    (solution,) = sp.linsolve(list(equations), [dw1, dw2, lam])
    field = {w1: flint_factor.factor(solution[0]), w2: flint_factor.factor(solution[1])}
    return field, flint_factor.factor(solution[2])


def derive_poisson_field() -> dict:
    """``gamma' = -hat(omega) gamma`` for a vector fixed in space."""
    rhs = -hat(omega) * gamma
    return {g1: rhs[0], g2: rhs[1], g3: rhs[2]}


def derive_general_solution() -> dict:
    """omega(T, S) from ``u = r S``, ``v = -T`` by inverting the linear map."""
    u_val, v_val = r * S, -T
    (sol,) = sp.linsolve(
        [I13 * w1 + I23 * w2 - u_val, I23 * w1 / I22 - I13 * w2 / I11 - v_val], [w1, w2]
    )
    return {w1: flint_factor.factor(sol[0]), w2: flint_factor.factor(sol[1])}


def run(log: CertificateLog, options) -> DerivationResult:
    result = DerivationResult(NAME)
    inertia = inertia_tensor()

    # 1. normalisation det I = 1
    c_det = certify_zero(log, "$det(I) = 1$ fixes $I33 = (1 + I11 I23^2 + I22 I13^2)/(I11 I22)$", "section 2",
                         inertia_tensor(I33_FROM_DET).det() - 1, RATIONAL)
    result.formula("i33", "section 2", "Normalisation $\\det\\mathbb I=1$",
                   sp.Eq(I33, I33_FROM_DET), c_det, hypotheses=[FRAME, r"$\det\mathbb I=1$", POSITIVE])

    # 2. reduced Euler equations, solved from 3.25
    field, multiplier = derive_euler_field()
    inertia_dot = inertia * sp.Matrix([field[w1], field[w2], 0])
    c_euler = certify_zero(log, "derived $deriv(omega, t)$, $lam$ satisfy $deriv(I omega, t) = cross(I omega, omega) + lam a$",
                           "3.25", inertia_dot - (inertia * omega).cross(omega) - multiplier * E3, RATIONAL)
    inverse_a = inertia.inv() * E3
    printed_lambda = -((inertia * omega).cross(omega)).dot(inverse_a) / E3.dot(inverse_a)
    c_lambda = certify_zero(log, "printed Lagrange multiplier $lam = -inner(cross(I w, w), Iinv a)/inner(a, Iinv a)$",
                            "3.25 (text)", multiplier - printed_lambda, RATIONAL)
    m3 = (inertia * omega).dot(E3)
    printed_ep = m3 * omega.cross(inverse_a)
    c_ep_printed = certify_zero(log, "printed ep3.26 $inner(I w, a) cross(w, Iinv a)$ gives $deriv(I w, t)$ (first two rows)",
                                paper.EP326.label, list((inertia_dot - printed_ep)[:2]), RATIONAL,
                                expect=Outcome.FAIL)
    corrected_ep = m3 / E3.dot(inverse_a) * inverse_a.cross(omega)
    c_ep_corrected = certify_zero(log, "corrected ep3.26 $inner(I w, a)/inner(a, Iinv a) cross(Iinv a, w)$ gives $deriv(I w, t)$",
                                  paper.EP326.label, list((inertia_dot - corrected_ep)[:2]), RATIONAL)
    result.errata.append(erratum(
        paper.EP326, "corrected",
        r"\frac{d}{dt}(\mathbb I\omega)=\frac{\langle\mathbb I\omega,a\rangle}{\langle a,\mathbb I^{-1}a\rangle}"
        r"\,\mathbb I^{-1}a\times\omega",
        "the printed form drops $1/inner(a, Iinv a)$ and reverses the cross product; it equals the true "
        "right-hand side times $-inner(a, Iinv a) = -I11 I22$ ($det(I) = 1$)",
        c_ep_printed, c_ep_corrected))

    c_gen12 = certify_zero(log, "printed gen12 equals the derived reduced Euler equations", paper.GEN12.label,
                           [paper.GEN12_FIELD[x] - field[x] for x in (w1, w2)], RATIONAL, expect=Outcome.FAIL)
    c_gen12_scale = certify_zero(log, "printed gen12 equals $-I11 I22$ times the derived field (time $tau = -I11 I22 t$)",
                                 paper.GEN12.label,
                                 [paper.GEN12_FIELD[x] + I11 * I22 * field[x] for x in (w1, w2)], RATIONAL)
    entries = sorted({str(s) for v in field.values() for s in v.free_symbols} - {"omega1", "omega2"})
    result.formula("euler", "gen12", "Reduced Euler equations (derived from 3.25)",
                   r"\dot\omega_1=" + latex(field[w1]) + r",\qquad \dot\omega_2=" + latex(field[w2]),
                   c_euler, c_gen12_scale, expr=sp.Tuple(ode(w1, field[w1]), ode(w2, field[w2])),
                   hypotheses=[FRAME, CONSTRAINT, POSITIVE])
    result.formula("lambda", "3.25", "Lagrange multiplier", sp.Eq(lam, multiplier), c_euler, c_lambda,
                   hypotheses=[FRAME, CONSTRAINT, POSITIVE])
    result.notes.append(
        "Entries of the inertia tensor that appear in the reduced Euler equations: "
        + ", ".join(f"${name}$" for name in entries) + " (entries of $I$ itself, not of its inverse; $I33$ does "
        "not appear, it only enters through $det(I) = 1$).")
    result.errata.append(erratum(
        paper.GEN12, "corrected",
        r"\dot\omega_1=" + latex(field[w1]) + r",\ \dot\omega_2=" + latex(field[w2]),
        "printed right-hand sides are the derived ones times $-I11 I22$, i.e. the printed system runs in "
        "the time $tau = -I11 I22 t$ (consistent with the printed ep3.26)",
        c_gen12, c_gen12_scale))

    # 3. Poisson equations
    poisson = derive_poisson_field()
    c_poisson = certify_zero(log, "$deriv(gamma, t) = cross(gamma, omega)$ (space-fixed $gamma$) is eq:whole",
                             paper.WHOLE.label, [poisson[x] - paper.WHOLE_FIELD[x] for x in (g1, g2, g3)],
                             RATIONAL)
    result.formula("poisson", "eq:whole", "Poisson equations",
                   r",\ ".join(r"\dot\gamma_%d=%s" % (i + 1, latex(poisson[x]))
                               for i, x in enumerate((g1, g2, g3))), c_poisson,
                   expr=sp.Tuple(*[ode(x, poisson[x]) for x in (g1, g2, g3)]),
                   hypotheses=[CONSTRAINT, r"$\gamma$ fixed in space: $\gamma=R^Te$, $\dot R=R\hat\omega$"])
    result.errata.append(erratum(paper.WHOLE, "confirmed", paper.WHOLE.latex,
                                 "derived from $deriv(R, t) = R omegahat$, $gamma = R^T e$", c_poisson))

    # 4. general solution by the (u, v) reduction
    u = I13 * w1 + I23 * w2
    v = I23 * w1 / I22 - I13 * w2 / I11
    c_uv = certify_zero(log, "$u = I13 w1 + I23 w2$, $v = I23 w1/I22 - I13 w2/I11$ obey $deriv(u, t) = u v$, $deriv(v, t) = -u^2/(I11 I22)$",
                        "derived", [lie_derivative(u, field) - u * v,
                                    lie_derivative(v, field) + u**2 / (I11 * I22)], RATIONAL)
    c_uv_sol = certify_zero(log, "$u = r sech t$, $v = -tanh t$ ($r^2 = I11 I22$) solve the $(u, v)$ system",
                            "derived", [RING.d_dt(r * S) - (r * S) * (-T),
                                        RING.d_dt(-T) + (r * S) ** 2 / (I11 * I22)], RING.domain)
    solution = derive_general_solution()
    c_sol = certify_zero(log, "derived $omega(t)$ solves the reduced Euler equations, both signs of $r$",
                         "eq:o12", ode_residuals(RING, solution, field), RING.domain)
    # second exact route (was an mpmath.diff spot check): x = e^t makes omega rational, d/dt = x d/dx
    numeric_certs = [certify_ode_in_exp(
        log, "derived $omega(t)$ solves the reduced Euler equations, both signs of $r$, "
             "in $x = exp(t)$ ($tanh(t) = (x^2 - 1)/(x^2 + 1)$, $sech(t) = 2 x/(x^2 + 1)$, and $d/dt$ is $x$ times $d/dx$)", "eq:o12",
        [solution[w1], solution[w2]], [field[w1], field[w2]], [w1, w2],
        "Q(I11,I22,I13,I23)(x)[r]/(r^2-I11 I22)", (R_EXT,))]
    D = I13**2 * I22 + I23**2 * I11
    coeff = {name: flint_factor.factor(sp.Poly(solution[x], T, S).coeff_monomial(m))
             for name, x, m in (("a", w1, T), ("c1/2", w1, S), ("b", w2, T), ("c2/2", w2, S))}
    c_line = certify_zero(log, "$omega(t)$ tends to the equilibrium line $I13 w1 + I23 w2 = 0$ as $to(t, pm(oo))$",
                          "eq:o12", [(I13 * solution[w1] + I23 * solution[w2]).subs({S: 0, T: s}) for s in (1, -1)],
                          WITH_R)
    result.formula("o12", "eq:o12, c's", "General solution (rate $A=1$), $r=\\pm\\sqrt{I_{11}I_{22}}$",
                   [(r"\omega_%d" % (k + 1), of_tanh_sech(solution[w])) for k, w in enumerate((w1, w2))],
                   c_uv, c_uv_sol, c_sol, *numeric_certs, c_line,
                   expr=sp.Tuple(*[sp.Eq(of_t(w), of_tanh_sech(solution[w]), evaluate=False) for w in (w1, w2)]),
                   hypotheses=[FRAME, POSITIVE, NONZERO_D, BRANCH_R, "rate $A=1$, $t_0=0$"])

    # 5. the printed general solution
    printed = paper.printed_o12(1, 1)
    c_pr_pr = certify_zero(log, "printed eq:o12/c's (signs coupled) solve the printed gen12", "c's",
                           ode_residuals(RING, printed, paper.GEN12_FIELD), RING.domain)
    c_pr_mixed = certify_zero(log, "printed eq:o12/c's with opposite signs in $c1$ and $c2$ solve the printed gen12",
                              "c's", ode_residuals(RING, paper.printed_o12(1, -1), paper.GEN12_FIELD),
                              RING.domain, expect=Outcome.FAIL)
    c_pr_true = certify_zero(log, "printed eq:o12/c's solve the derived Euler equations", "c's",
                             ode_residuals(RING, printed, field), RING.domain, expect=Outcome.FAIL)
    printed_other = paper.printed_o12(-1, -1)
    c_scale = certify_zero(log, "derived $omega(t)$ with $r = -(I11 I22)$ times the printed $omega(t)$ with $-r$", "c's",
                           [solution[x] + I11 * I22 * printed_other[x] for x in (w1, w2)], RING.domain)
    result.errata.append(erratum(
        paper.C_S, "corrected",
        r"a=-\frac{I_{11}I_{22}I_{23}}{D},\ b=\frac{I_{11}I_{22}I_{13}}{D},\ "
        r"\tfrac{c_1}{2}=\frac{I_{22}I_{13}r}{D},\ \tfrac{c_2}{2}=\frac{I_{11}I_{23}r}{D},\ r=\pm\sqrt{I_{11}I_{22}}",
        "the printed coefficients solve the printed gen12 (the signs of $c1$ and $c2$ are coupled: opposite signs fail) "
        "but not the derived equations; derived equals $-I11 I22$ times printed (with the opposite branch of the sign)",
        c_pr_pr, c_pr_mixed, c_pr_true, c_scale))

    # 6. first integrals and the energy level
    F1 = (inertia * omega).dot(omega)
    F2 = gamma.dot(gamma)
    c_f1 = certify_zero(log, "$F1 = I11 w1^2 + I22 w2^2$ is conserved by the derived Euler equations", "derived",
                        lie_derivative(F1, field), RATIONAL)
    c_f1p = certify_zero(log, "$F1$ is conserved by the printed gen12", paper.GEN12.label,
                         lie_derivative(F1, paper.GEN12_FIELD), RATIONAL)
    c_f2 = certify_zero(log, "$F2 = inner(gamma, gamma)$ is conserved by the Poisson equations", "eq:whole",
                        lie_derivative(F2, poisson), RATIONAL)
    energy = (I11 * I22) ** 2 / D
    c_en = certify_zero(log, "$F1$ on the derived normalised solution equals $(I11 I22)^2/D$", "eq:enlev",
                        F1.subs(solution, simultaneous=True) - energy, RING.domain)
    c_en_pr = certify_zero(log, "printed eq:enlev: $F1 = 1/D$ on the printed solution", paper.ENLEV.label,
                           F1.subs(printed, simultaneous=True) - paper.ENLEV_VALUE, RING.domain)
    c_en_true = certify_zero(log, "printed eq:enlev: $F1 = 1/D$ on the derived solution", paper.ENLEV.label,
                             F1.subs(solution, simultaneous=True) - paper.ENLEV_VALUE, RING.domain,
                             expect=Outcome.FAIL)
    result.formula("integrals", "section 2", "First integrals",
                   r"F_1=" + latex(sp.expand(F1)) + r",\quad F_2=" + latex(F2), c_f1, c_f1p, c_f2,
                   expr=sp.Tuple(sp.Eq(sp.Symbol("F1"), sp.expand(F1), evaluate=False),
                                 sp.Eq(sp.Symbol("F2"), F2, evaluate=False)),
                   hypotheses=[FRAME, CONSTRAINT])
    # D is named in the title: the printer would spell it out (kept as TeX; expr has it written out)
    result.formula("enlev", "eq:enlev", "Energy on the normalised solution ($D=I_{13}^2I_{22}+I_{23}^2I_{11}$)",
                   r"F_1=\frac{(I_{11}I_{22})^2}{D}", c_en, expr=sp.Eq(sp.Symbol("F1"), energy, evaluate=False),
                   hypotheses=[FRAME, POSITIVE, NONZERO_D, r"$\omega(t)$ the general solution above, either branch of $r$"])
    result.errata.append(erratum(
        paper.ENLEV, "corrected", r"F_1=\frac{(I_{11}I_{22})^2}{I_{13}^2I_{22}+I_{23}^2I_{11}}",
        "$1/D$ is the energy of the printed solution of the printed gen12; on the solution of the derived "
        "equations the factor $(I11 I22)^2$ comes from the time scale of gen12", c_en_pr, c_en_true, c_en))

    emit = [Emitted("omega_general", (t, I11, I22, I13, I23, r), ((T, sp.tanh(t)), (S, sp.sech(t))),
                    (solution[w1], solution[w2]), (c_sol.key,),
                    "General solution of the reduced Euler equations (eq:o12 corrected), r = +-sqrt(I11 I22).", (T, S))]
    result.exports.update(field=field, poisson=poisson, solution=solution, coefficients=coeff, emit=emit,
                          energy=energy)
    return result
