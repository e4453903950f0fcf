"""The differential Galois group of the Poisson equations of every body, exactly (the Conclusion's open problem).

Paper: the Conclusion (the monodromy group "in the general case" is left open), Theorem 3.2 and the
odd-p case.  From :mod:`derivations.sections.gauss`: the spinor lift is gauge-equivalent over C(s),
s = sinh t, to Gauss's equation with exponent differences ``kappa``, ``mu``, ``1 + iU``.  The theorem
(proof in :mod:`suslov.kernel.kimura`, the run-time decision):

    **Theorem.**  For a body with I11, I22 > 0, (I13, I23) != 0, the Poisson equations have Liouvillian
    solutions iff I13 I23 (I11 - I22) = 0 and ``w_-^2 = |u|^2 - |v|^2 = -P^2`` with P an odd integer
    (equivalently the Kovalevskaya exponent Lambda is an odd integer; for I13 = 0 this is the paper's
    odd p).  Then the Galois group over C(e^t) is the torus SO(2, C) (reducible); otherwise SO(3, C).

The algebraic steps are exact certificates here: ``w_+^2 = conj(w_-^2)`` for real u, v; ``kappa + mu =
iX`` and ``kappa - mu = -Y``; half-odd ``kappa`` means ``w_-^2 = -(2 kappa)^2``; the imaginary part of
``iX +- (1 + iU)`` is ``X +- U``, zero only when the gap ``U - X`` vanishes, which needs ``(u x v)_3 = 0``
(certified non-zero for every body in ``gauss``); the exact decision agrees with every ball verdict of
the complex-path monodromy (``fuchsian``).  Kimura's theorem itself (T. Kimura, Funkcialaj Ekvacioj
12 (1969) 269-281; see also Morales-Ruiz, *Differential Galois Theory and Non-Integrability of
Hamiltonian Systems*, Thm 2.21) and the classification of algebraic subgroups of SL(2, C) are cited,
not re-proved.
"""
from __future__ import annotations

import sympy as sp

from derivations.core.certificates import Certificate, CertificateLog, Outcome
from derivations.core.exact import Domain, certify_zero
from derivations.core.result import DerivationResult
from derivations.core.symbols import I11, I22
from derivations.sections.gauss import (
    BODY_HYPOTHESES,
    I_EXT,
    LAMBDA,
    W_MINUS2,
    W_PLUS2,
    WMINUS,
    WPLUS,
    U,
    gauss_equation_expr,
    j,
    mu,
)
from derivations.sections.gauss import kappa as gauss_kappa
from suslov.kernel.kimura import galois_group

NAME = "general_galois"
TITLE = "The differential Galois group of every body, exactly (Kimura's theorem)"
REQUIRES = ("gauss", "fuchsian")

X, Y, kappa = sp.symbols("X Y kappa")
REAL = Domain("Q(U, v1, v2, X, Y)[i]/(i^2+1)", (I_EXT,))


def _group(verdict: str) -> str:
    """A group verdict (``"SO(3,C)"``, ``"reducible"``, ``"unknown"``) as a statement's words and mathematics."""
    return "$SO(3, C)$" if verdict == "SO(3,C)" else verdict


def theorem_expr() -> sp.Tuple:
    """The theorem's relations: the condition I13 I23 (I11 - I22) = 0 (I13, I23 real, zero allowed: the project's
    symbols are non-zero), w_-^2 = -P^2 and Lambda = P with P odd, and the Gauss equation it applies Kimura's
    theorem to (A, B, C, kappa, mu as in :mod:`derivations.sections.gauss`)."""
    i13, i23 = sp.symbols("I13 I23", real=True)
    P = sp.Symbol("P", odd=True)
    return sp.Tuple(sp.Eq(i13 * i23 * (I11 - I22), 0, evaluate=False),
                    sp.Eq(WMINUS**2, -P**2, evaluate=False), sp.Eq(LAMBDA, P, evaluate=False),
                    *gauss_equation_expr()[3:],
                    sp.Eq(gauss_kappa, sp.I / 2 * WMINUS, evaluate=False), sp.Eq(mu, sp.I / 2 * WPLUS, evaluate=False))


def proof_expr() -> sp.Tuple:
    """The relations the proof states (c_sum, c_half): w_- = X + i Y, kappa + mu = i X, kappa - mu = -Y, and kappa
    half-odd iff w_-^2 = -(2l + 1)^2."""
    x_, y_ = sp.symbols("X Y", real=True)
    ell = sp.Symbol("l", integer=True)
    return sp.Tuple(sp.Eq(WMINUS, x_ + sp.I * y_, evaluate=False),
                    sp.Eq(gauss_kappa + mu, sp.I * x_, evaluate=False), sp.Eq(gauss_kappa - mu, -y_, evaluate=False),
                    sp.Eq(gauss_kappa, ell + sp.Rational(1, 2), evaluate=False),
                    sp.Eq(WMINUS**2, -(2 * ell + 1) ** 2, evaluate=False))


def run(log: CertificateLog, options, gauss_result, fuchsian_result) -> DerivationResult:
    result = DerivationResult(NAME)
    c_conj = certify_zero(log, "for real $u$, $v$: $w_p^2 = conjugate(w_m^2)$, so $w_p = conjugate(w_m)$ and $mu = -conjugate(kappa)$", "derived",
                          W_PLUS2 - W_MINUS2.subs(j, -j), REAL)
    k_, m_ = j / 2 * (X + j * Y), j / 2 * (X - j * Y)
    c_sum = certify_zero(log, "$w_m = X + i Y$: $kappa + mu = i X$ (imaginary), $kappa - mu = -Y$ (real), "
                         "the imaginary parts of $i X + 1 + i U$, $i X - 1 - i U$ and $-Y + 1 + i U$ are $X + U$, $X - U$ and $U$, non-zero", "derived",
                         [k_ + m_ - j * X, k_ - m_ + Y,
                          ((j * X + (1 + j * U)) - (j * X + (1 + j * U)).subs(j, -j)) / (2 * j) - (X + U)], REAL)
    c_half = certify_zero(log, "$kappa^2 = -w_m^2/4$: $kappa = 1/2 + l$ (half-odd) iff $w_m^2 = -(2 l + 1)^2$", "derived",
                          (kappa**2 + W_MINUS2 / 4).subs(kappa, (2 * sp.Symbol("l") + 1) / 2)
                          - (W_MINUS2 + (2 * sp.Symbol("l") + 1) ** 2) / 4, REAL)
    rows = fuchsian_result.exports["rows"]
    disagreements = []
    for row in rows:
        exact = galois_group(*row["body"])
        if row["verdict"] in ("SO(3,C)", "reducible") and row["verdict"] != exact.group:
            disagreements.append(f"({', '.join(row['body'])}): balls {_group(row['verdict'])}, exact {_group(exact.group)}")
    c_agree = log.record(Certificate(
        "the exact decision (Kimura) agrees with the ball verdicts of the complex-path monodromy on "
        + fuchsian_result.exports["bodies_words"], "Conclusion",
        "comparison of the exact verdicts with the certified ball verdicts", Outcome.FAIL if disagreements else Outcome.PASS,
        0.0, len(rows), "; ".join(disagreements) or ", ".join(f"({', '.join(r['body'])}): {_group(r['verdict'])}" for r in rows)))
    keys = gauss_result.exports["certificates"]
    result.formula("general_galois", "Conclusion", "Galois group of every body (theorem)",
                   [r"\text{Liouvillian}\iff I_{13}I_{23}(I_{11}-I_{22})=0\ \text{and}\ w_-^2=-P^2,\ P\ \text{odd}"
                    r"\quad(\Lambda=P\ \text{odd})",
                    r"\mathrm{Gal}=SO(2,\mathbb C)\ \text{(reducible) then, else}\ SO(3,\mathbb C)\quad"
                    r"(\text{over }\mathbb C(e^t))",
                    r"\text{spinor lift over }\mathbb C(\sinh t)\text{: imprimitive, resp. }SL(2,\mathbb C)"], c_conj, c_sum, c_half, c_agree,
                   expr=theorem_expr(),
                   hypotheses=[*BODY_HYPOTHESES, r"$\Lambda$: the Kovalevskaya exponent, $w_-^2=-\overline{\Lambda^2}$",
                               r"$\mathrm{Gal}$: the differential Galois group of the Poisson equations",
                               r"$A$, $B$, $C$: Gauss's equation of the spinor lift (exponent differences $\kappa$, $\mu$, $1+iU$)"])
    result.formula("general_galois_proof", "Conclusion", "Proof (Kimura's theorem on Gauss's equation)",
                   r"\parbox{0.94\linewidth}{\small The spinor lift is gauge-equivalent over $\mathbb C(\sinh t)$ to "
                   r"Gauss's equation with exponent differences $\kappa$, $\mu$, $1+iU$; the Poisson equations are its "
                   r"adjoint, so both have Liouvillian solutions or neither. By Kimura's theorem they exist iff (i) some "
                   r"$\pm\kappa\pm\mu\pm(1+iU)$ is an odd integer or (ii) the exponent differences are on Schwarz's "
                   r"list. (i): $\kappa+\mu=iX$ is imaginary and $\kappa-\mu=-Y$ real ($w_-=X+iY$), so the candidates "
                   r"have imaginary parts $X\pm U$ or $\pm U$; $U>0$, and $X=U$ needs $(u\times v)_3=0$, which no body "
                   r"has. (ii): every family but the first needs three real rationals, and $1+iU$ is not real; the first "
                   r"needs $\kappa,\mu$ half-odd, that is $w_-^2=-(2l+1)^2$, which forces $u\cdot v=0$. Then the local "
                   r"monodromies of the lift at $s=\pm i$ have trace $0$ and the one at $s=\infty$ infinite order: over "
                   r"$\mathbb C(\sinh t)$ the lift's group is the normaliser of a torus (imprimitive). In $x=e^t$ the "
                   r"points $s=\pm i$ are ramified ($s-i\sim(x-i)^2$), the loops about $x=\pm i$ give $M^2=-I$, and the "
                   r"Poisson group is the closure of the cyclic group of the loop about $x=0$: the torus of rotations "
                   r"about $u/|u|$. Otherwise the identity component is not solvable: $SL(2,\mathbb C)$ for the lift, "
                   r"$SO(3,\mathbb C)$ for the Poisson equations.}", c_conj, c_sum, c_half,
                   *(c for c in (log.certificates) if c.key in (keys["lift"], keys["gauss"])),
                   expr=proof_expr(),
                   hypotheses=[*BODY_HYPOTHESES, r"$w_+=\overline{w_-}$, so $\mu=-\bar\kappa$",
                               r"$X$, $Y$ real, $l$ an integer"])
    result.exports.update(certificates={"agree": c_agree.key, "conj": c_conj.key})
    return result
