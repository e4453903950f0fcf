"""The Poisson equations as a Fuchsian system, and their monodromy and Galois group for any body.

Paper: eq:whole, eq:o12 (the general omega of a body with I12 = 0, a = e3), eq:genhipprep and the
Conclusion, which leaves open "the solutions of eq:genhipprep in the general case, especially its
monodromy group".  Method:

1. *Fuchsian form (exact).*  With ``omega = u T + v S`` (T = tanh t, S = sech t; u, v read off the
   certified solution of ``derivations.sections.model``) and x = e^t, ``omega(x)/x`` equals
   ``-u/x + (u - i v)/(x - i) + (u + i v)/(x + i)``: certified by an exact zero test in
   Q(I11, I22, I13, I23, x)[r, i] (r^2 = I11 I22, i^2 = -1).  So ``dgamma/dx = gamma A(x)`` has simple
   poles only, at 0, +i, -i and (A = O(1/x)) at infinity: every singular point is regular.
2. *Local exponents (exact).*  ``det(lambda - C(w)) = lambda^3 + (w.w) lambda`` for the cross-product
   matrix C(w): the exponents at a point with residue C(w) are 0 and +-i sqrt(w.w); at +-i,
   ``w.w = u.u - v.v -+ 2 i u.v``, and for I13 = 0 it equals -p^2 with p^2 = I22 (I11 - I22)/I23^2
   (the corrected eq:necc1): exponents 0, +-p, integers for integer p (certified).
3. *Monodromy and Galois group (balls).*  ``suslov.kernel.monodromy`` (its docstring names the
   theorem behind each step: Schlesinger, the classification of algebraic subgroups of SL(2, C),
   Kolchin) computes the monodromy matrices of representative bodies as python-flint balls and
   certifies the verdict; pass / fail / unknown as every ball certificate, never a wrong pass.  Which bodies:
   the build option ``ball_checks`` (``BODY_TIERS``): one of each kind at 20 digits by default, all seven at
   30 with ``--ball-checks full``; the Galois group and the local behaviour of every body are decided
   exactly (``general_galois``, ``pole_theorem``), the balls corroborate them.
   The verdicts are checked against the exact local analysis (``derivations.sections.residue``):
   trivial local monodromy exactly for odd p (also on the mirror axis I23 = 0, through the certified
   symmetry eq:lina).
4. *The Conclusion's even-p sentence.*  "Not Liouvillian" is confirmed (Galois group SO(3, C));
   "all solutions meromorphic" is refuted twice over: by the exact Frobenius recursion (logarithms,
   ``residue``) and, independently, by the balls: for p = 2 the monodromy about x = i (a loop about
   t0 = i pi/2, where x = e^t is biholomorphic) excludes the identity, so some solution is not
   single-valued near t0.  Both go to the errata row.
"""
from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from derivations.core import paper
from derivations.core.certificates import Certificate, CertificateLog, Outcome
from derivations.core.differential import S, T, t
from derivations.core.errata import erratum
from derivations.core.exact import Domain, Extension, certify_zero
from derivations.core.result import DerivationResult
from derivations.core.statement import tex
from derivations.core.symbols import I11, I13, I22, I23, p, w1, w2
from derivations.sections.fuchsian_balls import monodromy_summary
from derivations.sections.model import R_EXT

NAME = "fuchsian"
TITLE = "Monodromy and differential Galois group of the Poisson equations for every body (open problem)"
REQUIRES = ("model", "residue")

x, j, lam = sp.symbols("x j lambda")
I_EXT = Extension(j, sp.Integer(-1), "j = i = sqrt(-1)")
FUCHS = Domain("Q(I11,I22,I13,I23,x)[r,i]/(r^2-I11 I22, i^2+1)", (R_EXT, I_EXT))
PLAIN = Domain("Q(w1,w2,w3,lam)")
# (label, I11, I22, I13, I23, what the case is): I13 = 0 with odd, even and non-integer p, and two general bodies
BODIES = (("odd $p = 1$", "2", "1", "0", "-1"), ("odd $p = 3$", "2", "1", "0", "-1/3"), ("even $p = 2$", "2", "1", "0", "-1/2"),
          ("non-integer $p = 5/2$", "2", "1", "0", "-2/5"), ("general", "5/4", "1", "3/10", "-1/2"),
          ("general", "2", "1", "3/10", "-1/5"), ("odd $p = 1$, $I23 = 0$ (eq:lina)", "1", "2", "-1", "0"))


@dataclass(frozen=True)
class BodyTier:
    """Which of :data:`BODIES` the ball monodromy runs on (their indices), and at how many digits."""

    bodies: tuple
    digits: int


# The Galois group and the local behaviour at the poles of every body are decided exactly (general_galois: Kimura;
# pole_theorem); the ball monodromy corroborates them.  "default" (issue 43) runs one body of each kind the agreement
# certificates compare -- odd, even and non-integer p with I13 = 0, a general body -- at 20 digits (about 1.2 s of
# ball work instead of 2.9 s); "full" all seven at 30 (build_formulas.py --ball-checks full;
# tests/test_fuchsian_tiers.py runs them without a build in every CI run).
BODY_TIERS = {"default": BodyTier((0, 2, 3, 4), 20), "full": BodyTier(tuple(range(len(BODIES))), 30)}
LABEL = "monodromy of representative bodies"


def tier_bodies(tier: str) -> list:
    """The (case, I11, I22, I13, I23) of :data:`BODIES` that the ball checks ``tier`` run, in their order."""
    return [BODIES[i] for i in BODY_TIERS[tier].bodies]


def ball_jobs(tier: str) -> list:
    """The worker items ``((I11, I22, I13, I23), digits)`` of the ball checks ``tier``."""
    return [(tuple(body), BODY_TIERS[tier].digits) for _, *body in tier_bodies(tier)]


def PREFETCH(options) -> tuple:
    """The monodromy of the options' representative bodies needs no other result: started with the build
    (CertificateLog.prefetch)."""
    return ((LABEL, ball_jobs(options.ball_checks), monodromy_summary),)


def bodies_words(tier: str) -> str:
    """Which bodies the ball checks ``tier`` run, for the claims: their number, their kinds and the set."""
    cases = [case for case, *_ in tier_bodies(tier)]
    kinds = [words for start, words in (("odd", "odd"), ("even", "even"), ("non-integer", "non-integer"))
             if any(c.startswith(start) for c in cases)]
    text = f"{', '.join(kinds[:-1])} and {kinds[-1]} $p$" if len(kinds) > 1 else f"{kinds[0]} $p$"
    if any("I23 = 0" in c for c in cases):
        text += ", $I23 = 0$"
    general = sum(c == "general" for c in cases)
    text += ", " + ("a general body" if general == 1 else f"{general} general bodies")
    if tier == "full":
        return f"the {len(cases)} representative bodies of the full ball checks ({text})"
    return (f"the {len(cases)} representative bodies of the default ball checks ({text}, {BODY_TIERS[tier].digits} digits; "
            f"the full ones run all {len(BODIES)} at {BODY_TIERS['full'].digits} digits)")


# the tests of suslov.kernel.monodromy and suslov.validated, named for the certificates' details (their own
# statements are sentences; the details list them all, one short name each)
_TEST_NAMES = (("every monodromy matrix lies in", "matrices in $SO(3, C)$"),
               ("the ordered product", "relation of the loops"),
               ("a generator has an eigenvalue", "infinite order"),
               ("a commutator has a trace", "irreducible"),
               ("the squares of two elements", "primitive"),
               ("the local monodromy at", "trivial local monodromy at $x = pm(i)$"),
               ("the ball verdict agrees", "agreement with the exact decision"),
               ("the differential Galois group, decided exactly", "exact decision (Kimura)"))
_VERDICT_WORDS = {"SO(3,C)": "$SO(3, C)$"}


def _test_name(text: str) -> str:
    """The short name of one monodromy test (its statement's first words identify it)."""
    return next((name for start, name in _TEST_NAMES if text.startswith(start)), "another test")


def cross(w) -> sp.Matrix:
    """C(w) with y C(w) = y x w (row vectors)."""
    return sp.Matrix([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


# the conditions on the body (printed with the formulas, and in the formula catalog)
BODY_HYPOTHESES = (r"$I_{11},I_{22}>0$", r"$I_{12}=0$", r"$(I_{13},I_{23})\ne0$")
U_PLANE = sp.symbols("u1 u2", real=True) + (sp.Integer(0),)
V_PLANE = sp.symbols("v1 v2", real=True) + (sp.Integer(0),)


def fuchs_expr() -> sp.Tuple:
    """The fuchs display as SymPy: dgamma/dx = gamma A(x) componentwise (gamma_k(x) a row), A(x) from :func:`cross`,
    omega = u tanh t + v sech t, x = e^t."""
    u, v = sp.Matrix(U_PLANE), sp.Matrix(V_PLANE)
    A = cross(-u) / x + cross(u - sp.I * v) / (x - sp.I) + cross(u + sp.I * v) / (x + sp.I)
    gamma_x = sp.ImmutableMatrix([[sp.Function(f"gamma{k}")(x) for k in (1, 2, 3)]])
    return sp.Tuple(sp.Eq(gamma_x.diff(x), gamma_x * sp.ImmutableMatrix(A), evaluate=False),
                    *[sp.Eq(w, uk * sp.tanh(t) + vk * sp.sech(t), evaluate=False)
                      for w, uk, vk in zip((w1, w2), U_PLANE, V_PLANE)],
                    sp.Eq(x, sp.exp(t), evaluate=False))


def exponents_expr(p_squared) -> sp.Tuple:
    """The exponents 0, +-i sqrt(w.w) at a simple pole with residue C(w); w.w at x = +-i (residues u -+ i v) named
    w_-+^2 as in :mod:`derivations.sections.gauss`; for I13 = 0 both are -p^2 with the certified p^2."""
    W = sp.symbols("W1:4")
    root = sp.sqrt(sum(w * w for w in W))
    uu = sum(a * a for a in U_PLANE)
    vv = sum(a * a for a in V_PLANE)
    uv = sum(a * b for a, b in zip(U_PLANE, V_PLANE))
    wminus, wplus = sp.symbols("wminus wplus")
    return sp.Tuple(*[sp.Eq(sp.Symbol(f"rho{k}"), value, evaluate=False)
                      for k, value in enumerate((0, sp.I * root, -sp.I * root), 1)],
                    sp.Eq(wminus**2, uu - vv - 2 * sp.I * uv, evaluate=False),
                    sp.Eq(wplus**2, uu - vv + 2 * sp.I * uv, evaluate=False),
                    sp.Eq(wminus**2, -p**2, evaluate=False), sp.Eq(wplus**2, -p**2, evaluate=False),
                    sp.Eq(p**2, p_squared, evaluate=False))


def verdicts_expr(rows: list) -> sp.Tuple:
    """One ``((I11, I22, I13, I23), Eq(Liouvillian, True | False))`` per certified verdict (the body alone if the
    verdict is unknown)."""
    liouvillian = sp.Symbol("Liouvillian")
    out = []
    for row in rows:
        body = sp.Tuple(*[sp.Rational(value) for value in row["body"]])
        verdict = {"SO(3,C)": sp.false, "reducible": sp.true}.get(row["verdict"])
        out.append(sp.Tuple(body) if verdict is None else sp.Tuple(body, sp.Eq(liouvillian, verdict, evaluate=False)))
    return sp.Tuple(*out)


def run(log: CertificateLog, options, model_result, residue_result) -> DerivationResult:
    result = DerivationResult(NAME)
    solution = model_result.exports["solution"]
    u = [sp.diff(solution[w], T) for w in (w1, w2)]
    v = [sp.diff(solution[w], S) for w in (w1, w2)]
    tanh_x, sech_x = (x**2 - 1) / (x**2 + 1), 2 * x / (x**2 + 1)
    c_linear = certify_zero(log, "$omega$ of eq:o12 is linear in $(tanh t, sech t)$: $omega = u tanh t + v sech t$",
                            "eq:o12", [solution[w] - (uk * T + vk * S) for w, uk, vk in zip((w1, w2), u, v)], FUCHS)
    partial = [(uk * tanh_x + vk * sech_x) / x - (-uk / x + (uk - j * vk) / (x - j) + (uk + j * vk) / (x + j))
               for uk, vk in zip(u, v)]
    c_fuchs = certify_zero(log, "in $x = e^t$, $omega/x = -u/x + (u - i v)/(x - i) + (u + i v)/(x + i)$: the Poisson "
                           "equations are Fuchsian (simple poles at $0$, $i$, $-i$ and infinity)", "eq:whole", partial, FUCHS)
    W = sp.symbols("W1:4")
    c_char = certify_zero(log, "$det(lam - C(w)) = lam^3 + wdotw lam$: exponents $0$, $pm(i sqrt(wdotw))$ at a simple "
                          "pole with residue $C(w)$", "eq:whole",
                          sp.expand((lam * sp.eye(3) - cross(W)).det() - (lam**3 + (W[0]**2 + W[1]**2 + W[2]**2) * lam)),
                          PLAIN)
    p_squared = I22 * (I11 - I22) / I23**2
    at_i = [(uk - j * vk).subs(I13, 0) for uk, vk in zip(u, v)]
    c_exp = certify_zero(log, "for $I13 = 0$ the residue at $x = pm(i)$ has $wdotw = -p^2$, $p^2 = I22 (I11 - I22)/I23^2$: "
                         "exponents $0$, $pm(p)$ (integers for integer $p$)", "eq:necc1",
                         sp.together(at_i[0] ** 2 + at_i[1] ** 2 + p_squared), FUCHS)
    result.formula("fuchs", "eq:whole", "The Poisson equations in $x=e^t$: a Fuchsian system",
                   r"\frac{d\gamma}{dx}=\gamma\,A(x),\quad A(x)=\frac{C(-u)}{x}+\frac{C(u-iv)}{x-i}+\frac{C(u+iv)}{x+i},"
                   r"\quad \omega=u\tanh t+v\operatorname{sech}t,\ \ \gamma C(w)=\gamma\times w", c_linear, c_fuchs,
                   expr=fuchs_expr(), hypotheses=[*BODY_HYPOTHESES, r"$\omega=u\tanh t+v\operatorname{sech}t$: the body's solution, $u=(u_1,u_2,0)$, $v=(v_1,v_2,0)$ real",
                                                  r"$x=e^t$"])
    result.formula("exponents_fuchs", "eq:whole", "Local exponents (residue $C(w)$)",
                   r"0,\ \pm i\sqrt{w\cdot w};\quad w\cdot w\big|_{x=\pm i}=u\cdot u-v\cdot v\mp 2i\,u\cdot v"
                   r"\overset{I_{13}=0}{=}-p^2", c_char, c_exp,
                   expr=exponents_expr(p_squared),
                   hypotheses=[*BODY_HYPOTHESES, r"$\rho_{1,2,3}$: the exponents at a simple pole with residue $C(w)$",
                               r"$w_\mp^2$: $w\cdot w$ at $x=\pm i$ (residue $u\mp iv$)",
                               r"$=-p^2$: for $I_{13}=0$, $p^2=I_{22}(I_{11}-I_{22})/I_{23}^2$"])

    logarithms = {row["p"]: row["verdict"] for row in residue_result.exports["log_rows"]}
    tier = BODY_TIERS[options.ball_checks]
    bodies = tier_bodies(options.ball_checks)
    rows, verdict_certs, summaries = [], [], {}
    for (case, *body), summary in zip(bodies, log.map_per_p(*PREFETCH(options)[0])):
        summaries[case] = summary
        claim = (f"body $(I11, I22, I13, I23) = ({', '.join(body)})$, {case}: the differential Galois group of eq:whole is "
                 + ("$SO(3, C)$ (isomorphic to $PSL(2, C)$): no Liouvillian solutions" if summary["verdict"] == "SO(3,C)" else
                    "reducible (a torus): Liouvillian" if summary["verdict"] == "reducible" else "decided"))
        outcome = {"SO(3,C)": Outcome.PASS, "reducible": Outcome.PASS}.get(summary["verdict"], Outcome.UNKNOWN)
        detail = "; ".join(f"{_test_name(text)}: {outcome_}" for text, outcome_, _ in summary["certificates"])
        cert = log.record(Certificate(claim, "Conclusion", "ball enclosure (`python-flint` `acb`): validated Taylor steps "
                                      f"with majorant bounds along loops in $x = e^t$, ${tier.digits}$ digits",
                                      outcome, summary["seconds"], len(summary["certificates"]), detail[:400]))
        verdict_certs.append(cert)
        rows.append({"case": case, "body": body, "verdict": summary["verdict"], "liouvillian": summary["liouvillian"],
                     "radius": summary["radius"], "certificate": cert.key, "digits": summary["digits"],
                     "tests": "".join({"pass": "+", "fail": "-", "unknown": "?"}[outcome_]
                                      for _, outcome_, _ in summary["certificates"][:5]),
                     "exponents": summary["exponents"], "not_identity_at_i": summary["not_identity_at_i"],
                     "ball_checks": options.ball_checks})
    # agreement with the exact local analysis: trivial local monodromy at the poles exactly for odd p
    agree = all((row["verdict"] == "reducible") == (row["case"].startswith("odd")) for row in rows)
    # (the p of the exact analysis this build ran: --pmax 1 or 2 has no row for p = 2 or 3)
    agree &= all((logarithms[p_] == "no logarithms") == (p_ % 2 == 1) for p_ in (1, 2, 3) if p_ in logarithms)
    mirror = any("I23 = 0" in row["case"] for row in rows)
    c_agree = log.record(Certificate(
        f"on {bodies_words(options.ball_checks)}, the verdicts agree with the exact Frobenius analysis at $t0 = i pi/2$: "
        "reducible (Liouvillian) exactly for odd $p$ " + ("($I13 = 0$, or $I23 = 0$ by eq:lina)" if mirror else "($I13 = 0$)")
        + "; even and non-integer $p$ and $I13 != 0$ give $SO(3, C)$", "Theorem 3.5",
        "comparison of the ball verdicts with the exact logarithm verdicts", Outcome.PASS if agree else Outcome.FAIL,
        0.0, len(rows), ", ".join(f"{row['case']}: {_VERDICT_WORDS.get(row['verdict'], row['verdict'])}" for row in rows)))
    even = summaries[next(row for row in rows if row["case"].startswith("even"))["case"]]
    finite = next(c for c in even["certificates"] if "infinite order" in c[0])[1]
    c_wrong = log.record(Certificate(
        "the monodromy group of the body with $p = 2$ ($I13 = 0$) is finite", "Conclusion",
        "ball enclosure: an eigenvalue of modulus other than 1 refutes it", Outcome.FAIL if finite == "pass" else Outcome.UNKNOWN,
        0.0, 1, "$tr(M(x=0)) - 1$ lies outside $Interval(-2, 2)$: an element of infinite order", expected=Outcome.FAIL))
    # the Conclusion's meromorphy, tested on the group itself: a solution meromorphic at t0 = i pi/2 for every
    # initial value means a trivial local monodromy there (x = e^t is biholomorphic near t0, x = i)
    c_meromorphic = log.record(Certificate(
        "for $I13 = 0$ and $p = 2$ every solution of eq:whole is meromorphic at $t0 = i pi/2$ (the local monodromy, the "
        "loop about $x = i$, is the identity)", "Conclusion",
        f"ball enclosure (`python-flint` `acb`, {tier.digits} digits): an entry of $M(x=i) - I$ whose ball excludes 0 refutes it",
        Outcome.FAIL if even["not_identity_at_i"] else Outcome.UNKNOWN, 0.0, 9,
        f"the real part of $tr(M(x=i))$ is {even['re_trace_at_i']} (unipotent), $M(x=i) != I$: a logarithm "
        "at $t0$, independently of the exact Frobenius recursion (residue)", expected=Outcome.FAIL))
    result.formula("galois_group", "Conclusion", "Differential Galois group of the Poisson equations (certified verdicts)",
                   [r"\text{" + tex(row["case"]) + r"}:\ (" + ",".join(row["body"]) + r")\ \to\ "
                    + (r"SO(3,\mathbb C)\ (\text{not Liouvillian})" if row["verdict"] == "SO(3,C)" else
                       r"\text{reducible (Liouvillian)}" if row["verdict"] == "reducible" else r"\text{unknown}")
                    for row in rows], *verdict_certs, c_agree,
                   expr=verdicts_expr(rows),
                   hypotheses=[r"$(I_{11},I_{22},I_{13},I_{23})$: the listed bodies", r"$I_{12}=0$",
                               r"$\det I=1$ (fixes $I_{33}$)", r"the group over $\mathbb C(x)$, $x=e^t$"])
    result.errata.append(erratum(
        paper.CONCLUSION_EVEN, "corrected",
        r"\text{even }p:\ \text{logarithms at }t_0=i\pi/2;\ \mathrm{Gal}=SO(3,\mathbb C)",
        "the Liouvillian part holds (the Galois group is $SO(3, C)$, certified from the monodromy); the meromorphy "
        "part does not: the exact Frobenius recursion finds logarithms for every even $p$, and for $p = 2$ the ball of "
        "the monodromy about $x = i$ excludes the identity", c_agree, c_wrong, c_meromorphic, *verdict_certs))
    # which bodies ran, for the claims of the other cross-checks of these rows (pole_theorem, general_galois)
    result.exports.update(rows=rows, bodies_words=bodies_words(options.ball_checks), ball_checks=options.ball_checks)
    return result
