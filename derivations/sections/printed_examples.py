"""The printed p = 1 and p = 3 bases of section 6.2 (``example p = 1``, ``example p = 3``), decided exactly.

The printed rows are rational in x = e^t, cos(p t/d), sin(p t/d) and c = sqrt(d^2 + 1)
(``paper.printed_example``, one transcription used by mpmath and here), and so is our basis
(``Basis`` numerators over (1 + x^2)^p times the phase e^{i p t/d} = C + i Sn).  With
``d/dt = x d/dx + (p/d)(C d/dSn - Sn d/dC)`` (``derivations.core.exp_substitution``) the claims are
exact zero tests in Q(d)(x)[c, C]/(c^2 - d^2 - 1, C^2 + Sn^2 - 1):

* the three printed rows solve the Poisson equations eq:ps with omega = ((p/d) tanh t, -(p/d) c sech t);
* the printed rows are orthonormal and their gamma^(1) is ours; then ours(t) printed(t)^T is constant
  (both bases' rows solve row' = row B with the same skew B, so (ours P^T)' = ours (B + B^T) P^T = 0):
  a constant orthogonal matrix relates the two bases.

(Were the mpmath.diff spot checks at 40 digits of ``meromorphic_printed``.)  The handedness of the printed
basis (det of that constant matrix) is read at one point with mpmath: it is the note of the errata row,
not a claim.
"""
from __future__ import annotations

import mpmath
import sympy as sp

from derivations.core import paper
from derivations.core.certificates import CertificateLog
from derivations.core.errata import erratum
from derivations.core.exact import Domain, Extension, certify_zero
from derivations.core.exp_substitution import COS, PHASE, SIN, X, d_dt
from derivations.core.result import DerivationResult
from derivations.sections.meromorphic_ring import Basis

t_, d_, c_ = sp.symbols("t d c")
C_EXT = Extension(c_, d_**2 + 1, "c = +-sqrt(d^2+1)")
DOMAIN = Domain("Q(d)(x)[c, C]/(c^2-d^2-1, C^2+Sn^2-1) with $x = exp(t)$, $C + i Sn = exp(i p t/d)$", (C_EXT, PHASE))


class ExactOps:
    """The functions ``paper.printed_example`` calls, as rational expressions in x = e^t, C, Sn, c."""

    def __init__(self, rate: sp.Expr):
        self.rate = rate

    @staticmethod
    def _multiple(arg) -> int:
        k = sp.simplify(arg / t_)
        if not k.is_integer:
            raise ValueError(f"{arg}: expected an integer multiple of t")
        return int(k)

    def sqrt(self, arg):
        if sp.expand(arg - (d_**2 + 1)) != 0:
            raise ValueError(f"sqrt({arg}): only c = sqrt(d^2 + 1) is expected")
        return c_

    def exp(self, arg):
        return X ** self._multiple(arg)

    def cosh(self, arg):
        k = self._multiple(arg)
        return (X**k + X**-k) / 2

    def sinh(self, arg):
        k = self._multiple(arg)
        return (X**k - X**-k) / 2

    def tanh(self, arg):
        return self.sinh(arg) / self.cosh(arg)

    def sech(self, arg):
        return 1 / self.cosh(arg)

    def _phase(self, arg):
        if sp.simplify(arg - self.rate * t_) != 0:
            raise ValueError(f"{arg}: the printed phase should be (p/d) t")

    def cos(self, arg):
        self._phase(arg)
        return COS

    def sin(self, arg):
        self._phase(arg)
        return SIN


def printed_rows(p: int) -> sp.Matrix:
    rate = sp.Integer(p) / d_
    return sp.Matrix(paper.printed_example(p, t_, d_, ExactOps(rate)))


def our_rows(basis: Basis) -> sp.Matrix:
    """Our basis as in ``meromorphic_printed.basis_mp``, exactly: gamma^(1), Re and Im of e^{ipt/d} G."""
    from derivations.sections.meromorphic_printed import to_sympy

    xs, ds = sp.symbols("x d")
    swap = {xs: X, ds: d_}
    conj = lambda e: e.xreplace({sp.I: -sp.I})  # noqa: E731  (x, d, C, Sn are real)
    M = [to_sympy(m).xreplace(swap) for m in basis.real.M + basis.complex_.M]
    s_real = (lambda e: (e + conj(e)) / 2)(to_sympy(basis.scale_real).xreplace(swap))
    k = to_sympy(basis.k).xreplace(swap)
    den = (1 + X**2) ** basis.p
    first = [(m + conj(m)) / 2 / (f * s_real * den) for m, f in zip(M[:3], (1, c_, c_))]
    G = [(COS + sp.I * SIN) * v / (k * den) for v in (c_ * M[3], M[4], M[5])]
    return sp.Matrix([first, [(g + conj(g)) / 2 for g in G], [(g - conj(g)) / (2 * sp.I) for g in G]])


def poisson_residuals(P: sp.Matrix, p: int) -> list:
    """gamma' - gamma x omega for each printed row (omega3 = 0; eq:ps in the form of basis_mp's check)."""
    rate = sp.Integer(p) / d_
    w1 = rate * (X**2 - 1) / (X**2 + 1)
    w2 = -rate * c_ * 2 * X / (X**2 + 1)
    out = []
    for r in range(3):
        v = list(P.row(r))
        dv = [d_dt(e, rate) for e in v]
        out += [dv[0] + w2 * v[2], dv[1] - w1 * v[2], dv[2] - (w2 * v[0] - w1 * v[1])]
    return out


def compare_printed_examples(log: CertificateLog, result: DerivationResult, bases: dict) -> None:
    """The printed p = 1 and p = 3 bases: solutions, orthonormal, and how they relate to ours (exact)."""
    from derivations.sections.meromorphic_printed import basis_mp

    for p, printed in ((1, paper.EXAMPLE_P1), (3, paper.EXAMPLE_P3)):
        if p not in bases:
            continue
        P, ours = printed_rows(p), our_rows(bases[p])
        c_sol = certify_zero(
            log, f"printed $p = {p}$ example: the three rows solve the Poisson equations ($x = exp(t)$, "
                 "$C + i Sn = exp(i p t/d)$)",
            printed.label, poisson_residuals(P, p), DOMAIN)
        # ours(t) printed(t)^T is constant without a further test: both bases' rows solve row' = row B with
        # the same skew B (the printed ones by c_sol, ours by the basis certificates), and
        # (ours P^T)' = ours (B + B^T) P^T = 0
        c_rel = certify_zero(
            log, f"printed $p = {p}$ example: orthonormal and $gammaI$ equal to ours; with the solution certificate "
            "and our basis's, our basis times the transposed printed one is a constant orthogonal matrix",
            printed.label,
            list(P * P.T - sp.eye(3)) + list(P.row(0) - ours.row(0)), DOMAIN)
        d0 = mpmath.mpf("0.7")
        R = mpmath.matrix(basis_mp(bases[p], mpmath.mpf("0.31"), d0)) * mpmath.matrix(
            paper.printed_example(p, mpmath.mpf("0.31"), d0)).T
        handed = "right-handed (det +1), like ours" if mpmath.det(R) > 0 else "left-handed (det -1); ours is right-handed"
        result.errata.append(erratum(
            printed, "confirmed", r"\text{our basis }=R\cdot\text{printed},\ R\text{ constant orthogonal}",
            f"the printed rows solve eq:ps and are orthonormal; $gammaI$ coincides with ours, $gammaII$ and $gammaIII$ "
            f"differ by a constant rotation in their plane; the printed basis is {handed}", c_sol, c_rel))
