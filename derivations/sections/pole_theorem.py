"""Meromorphy and logarithms at the poles of omega, for every p and every body (Theorem 3.2, Conjecture 1).

Paper: Theorem 3.2 (``eq:necc1``: all solutions meromorphic needs I13 = 0 and p^2 = I22 (I11 - I22)/I23^2
with p an odd integer), section 3.2 (logarithms at t0 = i pi/2), Conjecture 1 (the points s1, s2 of
the section-5.2 equation logarithmic for even p, s3, s4 never), checked there for p <= 10.  The build's
per-p routes decide these one p at a time (``residue``: Frobenius recursion of the Poisson system at t0;
``galois``: obstructions at s1..s4).  From Gauss's form (:mod:`derivations.sections.gauss`) they follow for
every p and every body.  Notation: ``w_-^2 = (u - i v).(u - i v) = -conj(Lambda^2)`` (Lambda: the
Kovalevskaya exponent of eq:kowal; for I13 = 0, Lambda = p).

**Theorem.**  Let I11, I22 > 0, I12 = 0 and (I13, I23) != 0.  At every pole t0 = +-i pi/2 + i pi k of omega:

* if Lambda is an **odd** integer, every solution of the Poisson equations is meromorphic at t0;
* if Lambda is an **even** integer (Lambda = 0 included), some solution has a logarithm at t0;
* otherwise (Lambda not an integer) some solution branches at t0 (multiplied by e^(2 pi i Lambda) != 1 on a
  loop about it).

Lambda is an integer only if u.v = 0, i.e. I13 I23 (I11 - I22) = 0.  For I13 = 0: odd p is Theorem 3.2 with its
converse, for every odd p; even p refutes its meromorphy claim at every pole for every d > 0, and proves
Conjecture 1 at s1, s2 for every even p (the per-p obstruction says "all but finitely many d").

**Proof** (each step an exact certificate below, or a classical theorem named in its method):

1. *Poles.*  ``sinh(+-i pi/2 + e) -+ i = +-i (e^e - 1)^2/(2 e^e)``: near t0 the variable s = sinh t of the
   Gauss form has ``s -+ i ~ (t - t0)^2``, so one loop about t0 is two loops about s = +-i; and
   ``sinh(t + i pi) = -sinh t``: the poles alternate between s = i and s = -i.
2. *Exponents in t.*  ``sinh(e) omega(t0 + e) = u cosh e - i v``: omega has a simple pole with residue
   ``u - i v``, whose cross-product matrix has characteristic polynomial ``l (l^2 + w.w)``: the Poisson
   exponents at t0 are 0, +-sqrt(-w_-^2) = 0, +-conj(Lambda).
3. *Monodromy.*  The spinor lift's residue at s = i has eigenvalues +-kappa/2, ``kappa^2 = -w_-^2/4``
   (``gauss``), so its local monodromy M has eigenvalues ``e^(+-i pi kappa)`` (the eigenvalues of the local
   monodromy at a regular singular point are ``e^(2 pi i rho)`` for the residue's eigenvalues rho: Levelt's
   normal form; Ilyashenko-Yakovenko, *Lectures on Analytic Differential Equations*, Thm 16.16); about t0
   the Poisson solutions turn by ``Ad(M^2)``, ``2 kappa = +-Lambda``.
4. *Odd Lambda.*  kappa is half-odd, tr M = 2 cos(pi kappa) = 0 and det M = 1, so ``M^2 = -I``
   (Cayley-Hamilton, certified) and Ad(M^2) = 1: the solutions are single-valued near t0, a regular singular
   point, hence meromorphic (a single-valued solution of moderate growth has at most a pole).
5. *Non-integer Lambda.*  Ad(M^2) has the eigenvalue ``e^(2 pi i Lambda) != 1``.
6. *Even Lambda.*  u.v = 0, so w_-^2 = -Lambda^2 is real: w_- = i Lambda (X = 0), kappa = -+Lambda/2 an
   integer, mu = -conj(kappa).  Gauss's parameters are then ``A = 1 + iU/2``, ``B = -iU/2``,
   ``C = 1 + kappa`` and ``C - A``, ``C - B`` have imaginary parts ``+-U/2`` (certified), non-zero since
   U > 0 for every body.  With C an integer, Gauss's equation is free of logarithms at z = 0 only if one of
   A, B is an integer (DLMF 15.10(ii); Abramowitz-Stegun 15.5.16-15.5.21: the degenerate cases are A or B in
   a finite set of integers): so psi1 = z^(kappa/2)(1 - z)^(mu/2) F, and with it the lift, has a logarithm,
   M = +-(I + N) with N != 0 nilpotent, and ``Ad(M^2) = Ad(I + 2N)`` is unipotent and not the identity
   (certified): a logarithm in the Poisson solutions at t0.
7. *The paper's s3, s4* (``x = e^t = -i(c +- d)``, c = sqrt(d^2 + 1)) are ``s = -i c``, where ``1 + s^2 = -d^2
   != 0``: ordinary points of the Poisson system.  The section-5.2 equation's projective monodromy there is
   the system's, trivial, so its local monodromy is a scalar: no logarithm, for every p and d.  Its s1, s2
   (``x = +-i``) are the poles: logarithmic exactly for even p.

Cross-checks (comparisons, not part of the proof): the per-p Frobenius verdicts of ``residue`` (p <= pmax) and
of ``galois`` (s1..s4, p <= galois_pmax), and the ball monodromy of the representative bodies of ``fuchsian``
(the loop about x = i excludes the identity exactly where the theorem predicts a logarithm or a branch).
Since the theorem covers every p, the per-p recursions (cost ~p^3 per p) run for every p <= ``cross_check_pmax``
(101 by default, ``--cross-check-pmax``) and above it for a sample only
(:func:`derivations.core.options.cross_check_p_values`: p = 150, 151, 200, 201, ... and the largest even and
odd p of the stage's range); the comparisons below take exactly the rows that ran and name them
(:func:`derivations.core.options.checked_words`: "every p <= 101 and the sample p = 150, 151, 200, 201").
The run-time decision for any body: :func:`suslov.validated.local_behaviour`.
"""
from __future__ import annotations

import sympy as sp

from derivations.core.certificates import Certificate, CertificateLog, Outcome
from derivations.core.exact import Domain, Extension, certify_zero
from derivations.core.options import checked_words, dense_prefix
from derivations.core.result import DerivationResult
from derivations.sections.fuchsian import cross
from derivations.core.differential import t
from derivations.core.symbols import p
from derivations.sections.gauss import (
    A_NAME,
    B_NAME,
    BODY_HYPOTHESES,
    BRANCH_HYPOTHESIS,
    C_NAME,
    FRAME_HYPOTHESIS,
    I_EXT,
    LAMBDA,
    WMINUS,
    U,
    gauss_equation_expr,
    j,
    kappa,
    s,
    spinor,
    v1,
    v2,
)
from suslov.kernel.local_behaviour import local_behaviour

NAME = "pole_theorem"
TITLE = "Meromorphy and logarithms at the poles for every $p$ and every body"
REQUIRES = ("gauss", "residue", "galois", "fuchsian")

E, lam = sp.symbols("q l")                       # q = e^eps (eps: the offset from the pole), l: an eigenvalue
Lam = sp.Symbol("Lambda", real=True)
u_, v_, w_, g_ = (sp.symbols(f"{n}1:4") for n in ("u", "v", "w", "g"))
a_, b_, n_ = sp.symbols("a b n")
c_, d_ = sp.symbols("c d", positive=True)
EXP = Domain("Q(u, v, q)[i]/(i^2+1)", (I_EXT,))
PLAIN = Domain("Q(a, b, n, l, w, g)")
GAUSS_REAL = Domain("Q(U, Lambda)[i]/(i^2+1)", (I_EXT,))
S34 = Domain("Q(d)[c, i]/(c^2 - d^2 - 1, i^2 + 1)", (Extension(c_, d_**2 + 1, "c = sqrt(d^2+1)"), I_EXT))

THEOREM = ("meromorphic at every pole iff Lambda is odd; a logarithm at every pole iff Lambda is even; "
           "branching otherwise")


def _conj(expr):
    return expr.subs(j, -j)


def _im(expr):
    return sp.expand((expr - _conj(expr)) / (2 * j))


def theorem_expr() -> sp.Tuple:
    """The theorem's relations: the poles t0 of omega, the exponents 0, +-conj(Lambda) there (c_char with
    w_-^2 = -conj(Lambda)^2), and Lambda = p for I13 = 0."""
    t0, k = sp.Symbol("t0"), sp.Symbol("k", integer=True)
    return sp.Tuple(sp.Eq(t0, sp.I * sp.pi / 2 + sp.I * sp.pi * k, evaluate=False),
                    *[sp.Eq(sp.Symbol(f"rho{n}"), value, evaluate=False)
                      for n, value in enumerate((0, sp.conjugate(LAMBDA), -sp.conjugate(LAMBDA)), 1)],
                    sp.Eq(WMINUS**2, -sp.conjugate(LAMBDA) ** 2, evaluate=False), sp.Eq(LAMBDA, p, evaluate=False))


def proof_expr() -> sp.Tuple:
    """The formulas of the proof: kappa^2 = -w_-^2/4, and for even Lambda w_- = i Lambda and Gauss's A, B, C
    (c_params); the paper's s3, s4 at s = -i c (c_s34)."""
    return sp.Tuple(sp.Eq(kappa**2, -WMINUS**2 / 4, evaluate=False), sp.Eq(WMINUS, sp.I * LAMBDA, evaluate=False),
                    sp.Eq(A_NAME, 1 + sp.I * U / 2, evaluate=False), sp.Eq(B_NAME, -sp.I * U / 2, evaluate=False),
                    sp.Eq(C_NAME, 1 + kappa, evaluate=False), sp.Eq(s, -sp.I * c_, evaluate=False),
                    sp.Eq(1 + s**2, -d_**2, evaluate=False))


def no_painleve_expr() -> sp.Tuple:
    """psi1 = z^(kappa/2) (1-z)^(mu/2) F(z), psi2 = (psi1' - a psi1)/b (a, b: the lift's entries in the frame
    u = (U, 0, 0), v = (v1, v2, 0), as in gauss), z = (1 + i s)/2, s = sinh t, and Gauss's equation for F."""
    A = -spinor([U * s + v1, v2, 0]).subs(j, sp.I) / (1 + s**2)
    a, b = A[0, 0], A[0, 1]
    f1, f2 = sp.Function("psi1")(s), sp.Function("psi2")(s)
    gauss = gauss_equation_expr()
    return sp.Tuple(sp.Eq(f1, gauss[0].rhs, evaluate=False), sp.Eq(f2, (f1.diff(s) - a * f1) / b, evaluate=False),
                    gauss[1], sp.Eq(s, sp.sinh(t), evaluate=False), *gauss[2:])


def run(log: CertificateLog, options, gauss_result, residue_result, galois_result, fuchsian_result) -> DerivationResult:
    result = DerivationResult(NAME)
    cosh_e, sinh_e = (E + 1 / E) / 2, (E - 1 / E) / 2
    sinh_at = {+1: (j * E + j / E) / 2, -1: (-j * E - j / E) / 2}        # sinh(+-i pi/2 + e): e^(+-i pi/2) = +-i
    cosh_at = {+1: (j * E - j / E) / 2, -1: (-j * E + j / E) / 2}

    # 1. the poles: s -+ i has a double zero in e; consecutive poles alternate between s = i and s = -i
    c_pole = certify_zero(log, "$sinh(i pi/2 + eps) - i = i (q - 1)^2/(2 q)$ and $sinh(-i pi/2 + eps) + i = -i (q - 1)^2/(2 q)$ "
                          "($q = e^(eps)$): one loop about a pole $t0$ of $omega$ is two loops about $s = i$ or $s = -i$; "
                          "$sinh(t + i pi) = -sinh(t)$", "eq:whole",
                          [sinh_at[1] - j - j * (E - 1) ** 2 / (2 * E), sinh_at[-1] + j + j * (E - 1) ** 2 / (2 * E),
                           (-E + 1 / E) / 2 + sinh_e], EXP)

    # 2. exponents of the Poisson equations at t0 = i pi/2: residue u - i v
    omega = [uk * sinh_at[1] / cosh_at[1] + vk / cosh_at[1] for uk, vk in zip(u_, v_)]
    c_residue = certify_zero(log, "$sinh(eps) omega(i pi/2 + eps) = u cosh(eps) - i v$: a simple pole with residue $u - i v$",
                             "eq:o12", [sinh_e * w - (uk * cosh_e - j * vk) for w, uk, vk in zip(omega, u_, v_)], EXP)
    c_char = certify_zero(log, "$det(l I - C(w)) = l (l^2 + inner(w, w))$: the exponents at $t0$ are $0$ and "
                          "$pm sqrt(-w_m^2) = pm conjugate(Lambda)$", "eq:necc1",
                          (lam * sp.eye(3) - cross(w_)).det() - lam * (lam**2 + sum(x * x for x in w_)), PLAIN)

    # 4. odd Lambda: a traceless M with det 1 squares to -I (Cayley-Hamilton)
    M = sp.Matrix([[a_, b_], [(-a_**2 - 1) / b_, -a_]])
    c_square = certify_zero(log, "$M$ with $tr(M) = 0$ and $det(M) = 1$ has $M^2 = -I$: for odd $Lambda$ ($kappa$ half-odd, "
                            "$tr(M) = 2 cos(pi kappa) = 0$) the loop about $t0$ acts by $Ad(M^2) = 1$", "Theorem 3.2",
                            list(M * M + sp.eye(2)) + [M.det() - 1], PLAIN)

    # 6. even Lambda: Gauss's parameters are not real; a non-trivial unipotent M^2 acts non-trivially
    certs_gauss = []
    for sign in (1, -1):
        kappa = -sign * Lam / 2                      # w_- = i Lambda (X = 0): kappa = (i/2) w_- or its negative
        mu = -_conj(kappa)
        A, B, C = (2 + kappa + mu + j * U) / 2, (kappa + mu - j * U) / 2, 1 + kappa
        certs_gauss.append([_im(A) - U / 2, _im(B) + U / 2, _im(C - A) + U / 2, _im(C - B) - U / 2,
                            sp.expand(A - 1 - j * U / 2), sp.expand(B + j * U / 2)])
    c_params = certify_zero(log, "$inner(u, v) = 0$, $w_m = i Lambda$: $A = 1 + i U/2$, $B = -i U/2$, and $A$, $B$, $C - A$, $C - B$ "
                            "have imaginary parts $U/2$ or $-U/2$ for either branch $2 kappa = pm Lambda$: none is an integer "
                            "($U > 0$), so Gauss's equation has a logarithm at $z = 0$ when $C = 1 + kappa$ is an integer",
                            "Conjecture 1", certs_gauss[0] + certs_gauss[1], GAUSS_REAL)
    unipotent = sp.Matrix([[1, 2 * n_], [0, 1]])       # M^2 = (+-(I + N))^2 = I + 2N, N = [[0, n], [0, 0]]
    gamma_s = spinor(g_)
    moved = unipotent * gamma_s * unipotent.inv() - gamma_s
    h_ = g_[0] + n_ * (g_[1] + j * g_[2])
    expected = n_ * spinor((2 * (g_[1] + j * g_[2]), -2 * h_, -2 * j * h_))
    c_unipotent = certify_zero(log, "$M^2 = I + 2 N$, $N^2 = 0$, $N_12 = n$: $Ad(M^2) S(g) - S(g) = n S(2 (g2 + i g3), -2 h, -2 i h)$, "
                               "$h = g1 + n (g2 + i g3)$: non-zero for $n != 0$ and every real $g != 0$, a logarithm in the "
                               "Poisson solutions",
                               "Conjecture 1", list(moved - expected), Domain("Q(n, g)[i]/(i^2+1)", (I_EXT,)))

    # 7. the paper's s3, s4 are ordinary points of the system
    x34 = -j * (c_ - d_)
    s34 = (x34 - 1 / x34) / 2
    c_s34 = certify_zero(log, "at $x = -i (c - d)$ (and $x = -i (c + d)$): $s = sinh(t) = -i c$ and $1 + s^2 = -d^2 != 0$: the "
                         "paper's $s3$, $s4$ are ordinary points of the Poisson system", "Conjecture 1",
                         [s34 + j * c_, 1 + s34**2 + d_**2, (-j * (c_ + d_) - 1 / (-j * (c_ + d_))) / 2 + j * c_], S34)

    # cross-checks: the per-p routes and the balls against the theorem (comparisons, not part of the proof)
    mismatches = []
    for row in residue_result.exports["log_rows"]:
        predicted = "no logarithms" if row["p"] % 2 else "logarithms"
        if (row["verdict"] == "no logarithms") != (predicted == "no logarithms"):
            mismatches.append(f"$p = {row['p']}$: {row['verdict']}")
    # the p that ran (every p <= cross_check_pmax and a sample above it: derivations.core.options.cross_check_p_values)
    residue_ps = [row["p"] for row in residue_result.exports["log_rows"]]
    c_residue_agree = log.record(Certificate(
        f"the theorem agrees with the exact Frobenius recursion at $t0 = i pi/2$ for {checked_words(residue_ps)} "
        "($I13 = 0$, $Lambda = p$: no logarithms exactly for odd $p$)", "Theorem 3.2",
        "comparison of the per-$p$ verdicts (`residue`) with the theorem's", Outcome.FAIL if mismatches else Outcome.PASS,
        0.0, len(residue_ps), "; ".join(mismatches) or _agree_words(residue_ps)))
    galois_rows = galois_result.exports["log_rows"]
    galois_ps = [row["p"] for row in galois_rows]
    wrong = [row["p"] for row in galois_rows
             if [_logarithmic(row[k]) for k in ("s1", "s2", "s3", "s4")] != [row["p"] % 2 == 0] * 2 + [False] * 2]
    c_galois_agree = log.record(Certificate(
        f"the theorem agrees with the exact obstructions at $s1$, $s2$, $s3$, $s4$ for {checked_words(galois_ps)} "
        "($s1$, $s2$ logarithmic exactly for even $p$, $s3$, $s4$ never)", "Conjecture 1",
        "comparison of the per-$p$ verdicts (`galois`) with the theorem's", Outcome.FAIL if wrong else Outcome.PASS,
        0.0, len(galois_rows), ("differ at " + ", ".join(f"$p = {q}$" for q in wrong)) if wrong
        else _agree_words(galois_ps)))
    ball_rows = fuchsian_result.exports["rows"]
    disagree = []
    for row in ball_rows:
        exact = local_behaviour(*row["body"])
        # a ball can prove M(x = i) != I; it cannot prove equality: consistent means "excluded" iff not meromorphic
        if row["not_identity_at_i"] == exact.meromorphic:
            disagree.append(f"({', '.join(row['body'])}): balls {'exclude' if row['not_identity_at_i'] else 'contain'} $I$, "
                            f"theorem {exact.kind}")
    c_ball_agree = log.record(Certificate(
        f"the theorem agrees with the ball monodromy about $x = i$ on {fuchsian_result.exports['bodies_words']}: "
        "the ball of $M(x = i) - I$ excludes 0 exactly where a logarithm or a branch is predicted",
        "Theorem 3.2", "comparison with the certified ball enclosures (`fuchsian`)",
        Outcome.FAIL if disagree else Outcome.PASS, 0.0, len(ball_rows),
        "; ".join(disagree) or ", ".join(f"({', '.join(r['body'])}): {local_behaviour(*r['body']).kind}" for r in ball_rows)))

    proof = (c_pole, c_residue, c_char, c_square, c_params, c_unipotent)
    result.formula("pole_theorem", "Theorem 3.2", "Meromorphy and logarithms at the poles, every $p$, every body (theorem)",
                   [r"\text{at every pole }t_0\text{ of }\omega:\ \text{exponents }0,\ \pm\bar\Lambda,\quad "
                    r"w_-^2=-\bar\Lambda^2",
                    r"\Lambda\ \text{odd}\ \Rightarrow\ \text{every solution meromorphic};\quad \Lambda\ \text{even}\ "
                    r"\Rightarrow\ \text{logarithms};\quad \Lambda\notin\mathbb Z\ \Rightarrow\ \text{branching}",
                    r"I_{13}=0:\ \Lambda=p\quad(\text{Theorem 3.2 and its converse; Conjecture 1 at }s_1,s_2\text{, for every }p)"],
                   *proof, c_residue_agree, c_ball_agree, expr=theorem_expr(),
                   hypotheses=[*BODY_HYPOTHESES, r"$t_0=i\pi/2+i\pi k$, $k\in\mathbb Z$: the poles of $\omega$",
                               r"$\rho_{1,2,3}$: the exponents of the Poisson equations at $t_0$",
                               r"$\Lambda$: the Kovalevskaya exponent of the body",
                               r"$\Lambda=p$: for $I_{13}=0$ ($p$ of section 4)"])
    result.formula("pole_theorem_proof", "Theorem 3.2", "Proof (local monodromy of Gauss's equation)",
                   r"\parbox{0.94\linewidth}{\small Near a pole, $s=\sinh t$ has $s\mp i\sim(t-t_0)^2$, so a loop about "
                   r"$t_0$ is two loops about $s=\pm i$, where the spinor lift has exponents $\pm\kappa/2$, "
                   r"$\kappa^2=-w_-^2/4$, and local monodromy $M$ with eigenvalues $e^{\pm i\pi\kappa}$ (Levelt); the "
                   r"Poisson solutions turn by $\mathrm{Ad}(M^2)$, $2\kappa=\pm\Lambda$. $\Lambda$ odd: $\operatorname{tr}M=0$, "
                   r"$\det M=1$, so $M^2=-I$ and $\mathrm{Ad}(M^2)=1$: single-valued at a regular singular point, hence "
                   r"meromorphic. $\Lambda\notin\mathbb Z$: $\mathrm{Ad}(M^2)$ has the eigenvalue $e^{2\pi i\Lambda}\ne1$. "
                   r"$\Lambda$ even: $u\cdot v=0$, $w_-=i\Lambda$, and Gauss's $A=1+iU/2$, $B=-iU/2$ are not real; with "
                   r"$C=1+\kappa$ an integer the equation has a logarithm at $z=0$ unless $A$ or $B$ is an integer (DLMF "
                   r"15.10(ii)), so $M=\pm(I+N)$, $N\ne0$, and $\mathrm{Ad}(M^2)$ is unipotent, not $1$. The paper's "
                   r"$s_3,s_4$ are $s=-ic$ with $1+s^2=-d^2\ne0$: ordinary points, never logarithmic.}",
                   *proof, c_s34, c_galois_agree, expr=proof_expr(),
                   hypotheses=[*BODY_HYPOTHESES, r"$\Lambda$ even for $w_-=i\Lambda$ and $A$, $B$, $C$ (then $u\cdot v=0$)",
                               r"$s=-ic$: for $I_{13}=0$, $c=\sqrt{d^2+1}$, $d>0$"])
    keys = gauss_result.exports["certificates"]
    result.formula("no_painleve", "Conclusion", "Every solution through Gauss's ${}_2F_1$, for every $p$ (no Painlev\\'e reduction needed)",
                   r"\parbox{0.94\linewidth}{\small The Conclusion expects a Painlev\'e reduction for even $p$. Instead, "
                   r"for every $p$ and every body, $S(\gamma)=\Psi S(\gamma_0)\Psi^{-1}$ with the spinor lift $\Psi$, "
                   r"whose first row is $z^{\kappa/2}(1-z)^{\mu/2}F$ with $F$ solving Gauss's equation "
                   r"($z=(1+i\sinh t)/2$) and the second $(\psi_1'-a\psi_1)/b$: every solution of the Poisson equations "
                   r"is quadratic in ${}_2F_1$ functions and their derivatives.}",
                   *(c for c in log.certificates if c.key in (keys["lift"], keys["gauss"])), expr=no_painleve_expr(),
                   hypotheses=[*BODY_HYPOTHESES, FRAME_HYPOTHESIS, BRANCH_HYPOTHESIS])
    result.exports.update(certificates={"pole": c_pole.key, "residue": c_residue.key, "square": c_square.key,
                                        "params": c_params.key, "unipotent": c_unipotent.key, "s34": c_s34.key,
                                        "residue_agree": c_residue_agree.key, "galois_agree": c_galois_agree.key,
                                        "ball_agree": c_ball_agree.key})
    return result


def _agree_words(values) -> str:
    """The detail of an agreeing comparison: how many p, and which when the recursion was sampled."""
    if dense_prefix(values) == max(values):
        return f"{len(values)} values of $p$ agree"
    return f"{len(values)} values of $p$ agree: {checked_words(values)}"


def _logarithmic(verdict: str) -> bool:
    """A galois row's verdict at one point (``decide_logarithms``: "log" or "no log")."""
    return verdict == "log"
