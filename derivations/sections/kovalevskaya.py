"""Necessary conditions of Theorem 3.2: the Kovalevskaya-Lyapunov analysis (paper section 3.1).

Labels: ``eq:d``, the characteristic polynomial of K, ``eq:neccg1``,
``eq:neccg12``, ``eq:necc1``, ``eq:necc11``, ``eq:neccg2``, ``eq:necc2``,
``eq:lina``, ``eq:ro`` (the link with the residue matrix).

Method
------
The system is the derived one (``derivations.sections.model``: Euler equations solved
from ``d/dt(I w) = I w x w + lambda a``, not the printed ``ep3.26``) plus the
Poisson equations; x = (w1, w2, g1, g2, g3), v(x) homogeneous quadratic.

* Darboux points ``v(d) = -d`` with ``g = 0``: the Euler part forces
  ``m3^2 = -I11 I22`` for ``m3 = I13 w1 + I23 w2``, so ``m3 = i r`` with
  ``r^2 = I11 I22``, and then ``w`` is the solution of a linear system.  Exact
  in ``Q(I)[r, i]/(r^2 - I11 I22, i^2 + 1)``; ``r -> -r`` is the complex
  conjugate point.
* ``K = dv/dx(d) + Id`` is block triangular (the Poisson rows vanish at
  g = 0 in their w-derivatives), so ``det(K - lambda) = (lambda+1)(lambda-2)
  (lambda-1)((lambda-1)^2 - Lambda^2)`` with ``Lambda^2 = -(w1^2 + w2^2)(d)``;
  certified as a polynomial identity in lambda.
* ``Lambda^2 = I11 I22 (I11-I22)(I11 I23^2 - I22 I13^2)/D^2
  - 2 i r I11 I22 I13 I23 (I11 - I22)/D^2`` with ``D = I11 I23^2 + I22 I13^2``
  (``= I11 I22 I33 - 1`` when det I = 1): real iff ``I13 I23 (I11-I22) = 0``
  (``eq:neccg1``, confirmed); the real part is ``(I11 I22)^2`` times the
  printed ``eq:neccg12`` (the printed time scale of ``gen12`` again), and for
  ``I13 = 0`` it is ``I22 (I11 - I22)/I23^2``, the parameter found independently
  from the general solution in ``derivations.sections.special_case``.
* ``I11 = I22``: the eigenvalue 1 has algebraic multiplicity 3 and
  ``rank(K - Id) = 3``, so K is not semi-simple (a non-zero 3x3 minor).
* The symmetry ``eq:lina`` maps the derived vector field with (I11, I22, I13,
  I23) to the one with the roles exchanged (exact identity of vector fields).
"""
from __future__ import annotations

import sympy as sp

from derivations.core import flint_factor, paper
from derivations.core.certificates import (
    Certificate,
    CertificateLog,
    Outcome,
    stopwatch,
)
from derivations.core.emit import Emitted
from derivations.core.errata import erratum
from derivations.core.exact import Domain, Extension, certify_zero, normal_form
from derivations.core.result import DerivationResult
from derivations.core.symbols import I11, I13, I22, I23, g1, g2, g3, p, r, w1, w2
from derivations.core.typeset import latex
from derivations.sections.model import FRAME, NONZERO_D, POSITIVE

NAME = "kovalevskaya"
TITLE = "Kovalevskaya exponents and the necessary conditions (section 3.1)"
REQUIRES = ("model",)

R_EXT = Extension(r, I11 * I22, "r = +-sqrt(I11 I22)")
DOMAIN = Domain("Q(I11,I22,I13,I23)[r,i]/(r^2-I11 I22, i^2+1)", (R_EXT,))
PLAIN = Domain("Q(I11,I22,I13,I23)")
lam = sp.Symbol("lambda")
STATE = (w1, w2, g1, g2, g3)
# Lambda of the paper; not named "Lambda", which sympify and the export readers take for sympy.Lambda
Lambda = sp.Symbol("Lam")
BRANCH = "$m_3=ir$ with $r=\\pm\\sqrt{I_{11}I_{22}}$ (either branch; $-r$ gives the conjugate point)"


def full_field(euler: dict, poisson: dict) -> dict:
    field = dict(euler)
    field.update(poisson)
    return field


def darboux_point(euler: dict) -> dict:
    """The Darboux point with m3 = i r (g = 0), derived from the Euler part."""
    m3 = sp.I * r
    (sol,) = sp.linsolve([w1 - m3 * w2 / I11, I13 * w1 + I23 * w2 - m3], [w1, w2])
    point = {w1: sol[0], w2: sol[1], g1: 0, g2: 0, g3: 0}
    return point


def kovalevskaya_matrix(field: dict, point: dict) -> sp.Matrix:
    J = sp.Matrix([[sp.diff(field[x], y) for y in STATE] for x in STATE])
    return J.xreplace(point) + sp.eye(5)


def lambda_squared_closed_form():
    D = I11 * I23**2 + I22 * I13**2
    real = I11 * I22 * (I11 - I22) * (I11 * I23**2 - I22 * I13**2) / D**2
    imag = -2 * r * I11 * I22 * I13 * I23 * (I11 - I22) / D**2
    return real, imag, D


def swap(expr):
    """The parameter part of eq:lina: I11 <-> I22, I13 <-> I23."""
    return sp.sympify(expr).subs({I11: I22, I22: I11, I13: I23, I23: I13}, simultaneous=True)


def run(log: CertificateLog, options, model_result) -> DerivationResult:
    result = DerivationResult(NAME)
    euler = model_result.exports["field"]
    field = full_field(euler, model_result.exports["poisson"])

    point = darboux_point(euler)
    c_point = certify_zero(log, "Darboux point: $v(d) = -d$ with $m3 = i r$, $r^2 = I11 I22$, $gamma = 0$ ($r$ replaced by $-r$: the "
                           "conjugate point)", "eq:d", [field[x].xreplace(point) + point[x]
                                                        for x in STATE], DOMAIN)
    printed_point = {w1: 1 / (I11 * I23 + sp.I * I13 * r), w2: -1 / (I13 * I22 - sp.I * I23 * r),
                     g1: 0, g2: 0, g3: 0}
    printed_field = full_field(paper.GEN12_FIELD, model_result.exports["poisson"])
    c_point_pr = certify_zero(log, "printed eq:d is a Darboux point of the printed gen12 + Poisson", "eq:d",
                              [printed_field[x].xreplace(printed_point) + printed_point[x]
                               for x in STATE], DOMAIN)
    c_point_true = certify_zero(log, "printed eq:d is a Darboux point of the derived equations", "eq:d",
                                [field[x].xreplace(printed_point) + printed_point[x]
                                 for x in STATE], DOMAIN, expect=Outcome.FAIL)
    c_point_scale = certify_zero(log, "derived Darboux point equals $-I11 I22$ times the printed eq:d", "eq:d",
                                 [point[x] + I11 * I22 * printed_point[x] for x in (w1, w2)], DOMAIN)
    result.formula("darboux", "eq:d", "Darboux point ($m_3=I_{13}\\bar\\omega_1+I_{23}\\bar\\omega_2=ir$, "
                   "$r=\\sqrt{I_{11}I_{22}}$)",
                   r"\bar\omega_1=" + latex(flint_factor.factor(point[w1])) + r",\quad\bar\omega_2="
                   + latex(flint_factor.factor(point[w2])) + r",\quad\bar\gamma=0", c_point, c_point_scale,
                   expr=sp.Tuple(*[sp.Eq(sp.Symbol(f"omegabar{k}"), flint_factor.factor(point[x]), evaluate=False)
                                   for k, x in ((1, w1), (2, w2))],
                                 sp.Eq(sp.ImmutableMatrix([sp.Symbol(f"gammabar{k}") for k in (1, 2, 3)]),
                                       sp.ImmutableMatrix([point[x] for x in (g1, g2, g3)]), evaluate=False)),
                   hypotheses=[FRAME, POSITIVE, NONZERO_D, BRANCH])
    result.errata.append(erratum(paper.EQ_D, "corrected",
                                 r"\bar\omega=-I_{11}I_{22}\times\text{printed}",
                                 "the printed point belongs to the printed gen12 (time scale $-I11 I22$)",
                                 c_point_pr, c_point_true, c_point_scale))

    K = kovalevskaya_matrix(field, point)
    real, imag, D = lambda_squared_closed_form()
    D_name = sp.Symbol("D")
    Lam2 = real + sp.I * imag
    with stopwatch() as elapsed:
        charpoly = sp.expand((K - lam * sp.eye(5)).det(method="berkowitz"))
    target = -(lam + 1) * (lam - 2) * (lam - 1) * ((lam - 1) ** 2 - Lam2)
    c_char = certify_zero(log, "$det(K - lam) = -(lam+1)(lam-2)(lam-1)((lam-1)^2 - Lambda^2)$: exponents "
                          "$-1$, $2$, $1$, $1 + Lambda$, $1 - Lambda$", "Kovalevskaya matrix", charpoly - target, DOMAIN)
    c_char.seconds += elapsed[0]
    c_lam = certify_zero(log, "$Lambda^2 = -(w1^2 + w2^2)$ at the Darboux point (closed form)", "Kovalevskaya matrix",
                         -(point[w1] ** 2 + point[w2] ** 2) - Lam2, DOMAIN)
    result.formula("exponents", "section 3.1", "Kovalevskaya exponents",
                   r"-1,\ 1,\ 2,\ 1\pm\Lambda,\quad\Lambda^2=\frac{I_{11}I_{22}(I_{11}-I_{22})(I_{11}I_{23}^2-I_{22}I_{13}^2)}"
                   r"{D^2}-2ir\frac{I_{11}I_{22}I_{13}I_{23}(I_{11}-I_{22})}{D^2},\ D=I_{11}I_{23}^2+I_{22}I_{13}^2",
                   c_char, c_lam,
                   expr=sp.Tuple(sp.Eq(sp.Symbol("exponents"), sp.Tuple(-1, 1, 2, 1 + Lambda, 1 - Lambda), evaluate=False),
                                 sp.Eq(Lambda**2, Lam2.xreplace({D: D_name}), evaluate=False),
                                 sp.Eq(D_name, D, evaluate=False)),
                   hypotheses=[FRAME, POSITIVE, NONZERO_D,
                               (r"$K$ at the Darboux point above, $m_3=ir$, $r=\pm\sqrt{I_{11}I_{22}}$ ($\Lambda^2$ "
                                "depends on the branch)")])

    # necessary conditions
    c_g1 = certify_zero(log, "$Im(Lambda^2) = 0$ iff $I13 I23 (I11 - I22) = 0$ (imaginary part is $-2 r I11 I22 I13 I23 "
                        "(I11-I22)/D^2$)", "eq:neccg1", imag + 2 * r * I11 * I22 * I13 * I23 * (I11 - I22) / D**2, DOMAIN)
    det_one_D = I11 * I22 * paper_I33() - 1
    printed_g12 = (I11 - I22) * (I11 * I23**2 - I22 * I13**2) / (I11 * I22 * det_one_D**2)
    c_g12 = certify_zero(log, "printed eq:neccg12 ($det(I) = 1$) equals $Re(Lambda^2)$", "eq:neccg12",
                         printed_g12 - real, PLAIN, expect=Outcome.FAIL)
    c_g12_scale = certify_zero(log, "$Re(Lambda^2) = (I11 I22)^2$ times the printed eq:neccg12 left-hand side ($det(I) = 1$)",
                               "eq:neccg12", real - (I11 * I22) ** 2 * printed_g12, PLAIN)
    c_n1 = certify_zero(log, "$I13 = 0$: $Lambda^2 = I22 (I11 - I22)/I23^2$", "eq:necc1",
                        Lam2.subs(I13, 0) - I22 * (I11 - I22) / I23**2, DOMAIN)
    c_n11 = certify_zero(log, "$I23 = 0$: $Lambda^2 = -I11 (I11 - I22)/I13^2$", "eq:necc11",
                         Lam2.subs(I23, 0) + I11 * (I11 - I22) / I13**2, DOMAIN)
    printed_n11 = (I11 - I22) / (I11 * I22 * (I11 * I22 * paper_I33().subs(I23, 0) - 1))  # printed: = -p^2
    derived_n11 = -Lam2.subs(I23, 0)  # derived: = -p^2
    c_n11_pr = certify_zero(log, "printed eq:necc11 left-hand side ($det(I) = 1$) equals $-Lambda^2$ for $I23 = 0$",
                            "eq:necc11", printed_n11 - derived_n11, DOMAIN, expect=Outcome.FAIL)
    c_n11_scale = certify_zero(log, "$-Lambda^2$ ($I23 = 0$) equals $(I11 I22)^2$ times the printed eq:necc11 left-hand side",
                               "eq:necc11", derived_n11 - (I11 * I22) ** 2 * printed_n11, DOMAIN)
    result.formula("necessary", "eq:neccg1, eq:neccg12, eq:necc1, eq:necc11", "Necessary conditions",
                   r"I_{13}I_{23}(I_{11}-I_{22})=0,\quad \Lambda^2=p^2:\quad I_{13}=0:\ \frac{I_{22}(I_{11}-I_{22})}{I_{23}^2}=p^2,"
                   r"\quad I_{23}=0:\ \frac{I_{11}(I_{11}-I_{22})}{I_{13}^2}=-p^2", c_g1, c_n1, c_n11,
                   # the cases I13 = 0, I23 = 0 are substitutions (Eq(I13, 0) is False for the nonzero symbol I13)
                   expr=sp.Tuple(sp.Eq(I13 * I23 * (I11 - I22), 0, evaluate=False),
                                 sp.Eq(Lambda**2, p**2, evaluate=False),
                                 sp.Eq(flint_factor.factor(sp.cancel(Lam2.subs(I13, 0))), p**2, evaluate=False),
                                 sp.Eq(flint_factor.factor(sp.cancel(-Lam2.subs(I23, 0))), -p**2, evaluate=False)),
                   hypotheses=[FRAME, POSITIVE, NONZERO_D,
                               r"all solutions meromorphic, so $1\pm\Lambda\in\mathbb Z$",
                               "third relation if $I_{13}=0$, fourth if $I_{23}=0$"])
    result.errata.append(erratum(paper.NECCG1, "confirmed", paper.NECCG1.latex, "imaginary part of $Lambda^2$", c_g1))
    result.errata.append(erratum(
        paper.NECCG12, "corrected",
        r"\frac{I_{11}I_{22}(I_{11}-I_{22})(I_{11}I_{23}^2-I_{22}I_{13}^2)}{(I_{11}I_{22}I_{33}-1)^2}=p^2",
        "factor $(I11 I22)^2$ (the printed gen12 time scale); for $I13 = 0$ this agrees with the parameter "
        "derived from the general solution (`special_case`), so eq:necc1 is corrected the same way",
        c_g12, c_g12_scale, c_n1))
    result.errata.append(erratum(
        paper.NECC11, "corrected", r"I_{23}=0,\ \frac{I_{11}(I_{11}-I_{22})}{I_{13}^2}=-p^2"
        r"\ \Big(=-\frac{I_{11}I_{22}(I_{11}-I_{22})}{I_{11}I_{22}I_{33}-1},\ \det\mathbb I=1\Big)",
        "same factor $(I11 I22)^2$ as eq:necc1", c_n11_pr, c_n11_scale, c_n11))

    # I11 = I22: non-semisimple
    same = {I22: I11, r: I11}
    K_same = K.xreplace(same)
    N = K_same - sp.eye(5)
    with stopwatch() as elapsed:
        minors = [(rows, cols) for rows in ([0, 2, 4], [1, 2, 4], [0, 3, 4], [1, 3, 4], [2, 3, 4], [0, 1, 4])
                  for cols in ([0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3], [0, 1, 4], [2, 3, 4], [0, 3, 4], [1, 3, 4])]
        witness = None
        for rows, cols in minors:
            value = N.extract(rows, cols).det()
            if not normal_form(value, Domain("Q(I11,I13,I23)[i]")).is_zero:
                witness = (rows, cols)
                break
        lam_same = sp.expand(Lam2.xreplace(same))
    outcome = Outcome.PASS if witness is not None and lam_same == 0 else Outcome.FAIL
    c_ss = log.record(Certificate(
        "$I11 = I22$: $Lambda = 0$, eigenvalue 1 has multiplicity 3 and $rank(K - Id) >= 3$: $K$ is not semi-simple",
        "section 3.1", "a non-zero minor of order 3 in $Q(I11, I13, I23)[i]$ (exact)", outcome, elapsed[0], 1,
        ("the minor of rows " + ", ".join(str(k + 1) for k in witness[0]) + " and columns "
         + ", ".join(str(k + 1) for k in witness[1]) + " is non-zero") if witness else "no non-zero minor found"))
    # the certificate shows rank >= 3 (a non-zero 3x3 minor), which with the multiplicity 3 of the
    # eigenvalue 1 is what non-semi-simplicity needs (the rank is 4)
    result.formula("semisimple", "section 3.1", "The case $I_{11}=I_{22}$",
                   r"\Lambda=0,\ \operatorname{rank}(K-\mathrm{Id})\ge3:\ K\text{ not semi-simple}", c_ss,
                   expr=sp.Tuple(sp.Eq(Lambda, sp.sqrt(lam_same), evaluate=False),
                                 sp.Ge(sp.Symbol("rankKminusId"), 3, evaluate=False)),
                   hypotheses=["$I_{11}=I_{22}$", FRAME, POSITIVE, "$I_{13}\\ne0$",
                               "$r=I_{11}$ ($m_3=ir$ at the Darboux point)"])

    # eq:lina: (w1, w2, g1, g2, g3) -> (-w2, -w1, g2, g1, g3) with the parameter swap
    image = {w1: -w2, w2: -w1, g1: g2, g2: g1, g3: g3}
    jac = sp.Matrix([[sp.diff(image[x], y) for y in STATE] for x in STATE])
    swapped = {x: swap(field[x]) for x in STATE}
    pushed = jac * sp.Matrix([field[x] for x in STATE])
    target_field = sp.Matrix([swapped[x].xreplace(image) for x in STATE])
    c_lina = certify_zero(log, "eq:lina maps the derived system with $(I11,I22,I13,I23)$ to the one with "
                          "$(I22,I11,I23,I13)$", "eq:lina", list(pushed - target_field), PLAIN)
    c_lina_p = certify_zero(log, "eq:lina maps $Lambda^2$ of the case $I23 = 0$ to $Lambda^2$ of the case $I13 = 0$",
                            "eq:lina", swap(Lam2.subs(I23, 0)) - Lam2.subs(I13, 0), DOMAIN)
    result.errata.append(erratum(paper.LINA, "confirmed", paper.LINA.latex,
                                 "exact identity of vector fields; $p^2$ changes sign as eq:necc1 / eq:necc11 say",
                                 c_lina, c_lina_p))
    # the two cases of Theorem 3.2 as emitted by meromorphy(): Lambda^2 restricted (real there)
    restricted = {name: flint_factor.factor(sp.cancel(real.subs(zero, 0))) for name, zero in (("i13", I13), ("i23", I23))}
    c_real_cases = certify_zero(log, "$Lambda^2$ is real on $I13 = 0$ and on $I23 = 0$ (its imaginary part vanishes "
                                "identically there), so $p^2 = Re(Lambda^2)$ restricted", "eq:neccg1",
                                [imag.subs(I13, 0), imag.subs(I23, 0)], DOMAIN)
    emit = [Emitted("lambda_squared", (I11, I22, I13, I23), ((r, sp.sqrt(I11 * I22)),), (real, imag),
                    (c_char.key, c_lam.key), "(Re, Im) of Lambda^2 at the Darboux point with m3 = i sqrt(I11 I22)."),
            Emitted("p_squared_i13_zero", (I11, I22, I23), (), (restricted["i13"],), (c_lam.key, c_real_cases.key),
                    "p^2 = Lambda^2 in the case I13 = 0."),
            Emitted("p_squared_i23_zero", (I11, I22, I13), (), (restricted["i23"],), (c_lam.key, c_real_cases.key),
                    "p^2 = Lambda^2 in the case I23 = 0.")]
    result.exports.update(lambda_real=real, lambda_imag=imag, point=point, emit=emit, matrix=K)
    return result


def paper_I33():
    """I33 from det I = 1."""
    return (1 + I11 * I23**2 + I22 * I13**2) / (I11 * I22)
