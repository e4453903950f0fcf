"""sigma = -1 for every odd p: the sign that makes the real basis of Theorem 6.1 positively oriented.

Labels: ``asymp`` (the limits of the basis as t -> -oo), ``eq:gam3`` (the components of the complex solution
from its first one).  The real basis is ``gamma^(2) + i sigma gamma^(3) = Gamma`` with ``V/k -> (0, 1, i sigma)``
as t -> -oo, ``k = V2(0)``.  The emitted module needs sigma for every p before the round trip certifies the
bases beyond the kept ones on the numerators the module computes (:mod:`derivations.sections.meromorphic`), so
it is proven here once for every odd p: the recipe's own ``complete`` (:mod:`suslov.recipes.basis`, the code
that builds every basis) is run on SymPy expressions with p and d symbolic and ``g1 = x (P0 + x^2 S(x))``, S an
undefined function (any polynomial P), and its values at x = 0 satisfy ``V3(0) = -i V2(0)`` and
``V2(0) = i p (d + i p) P0`` by an exact zero test.  Each p's asymp certificate then requires the numerators'
own sigma to be this one, and ``k`` not zero.
"""
from __future__ import annotations

import sympy as sp

from derivations.core.certificates import Certificate, CertificateLog
from derivations.core.exact import Domain, Extension, certify_zero
from suslov.recipes import basis as recipe

SIGMA = -1   # V3(0) = i sigma V2(0) for every odd p: sigma_certificate


class _JetRing:
    """The recipe's ring operations (``suslov.recipes.basis``) on SymPy expressions in x, d, i and a symbolic p,
    for :func:`sigma_certificate`: ``dx`` differentiates (an undefined function of x stays one), ``red`` expands
    (i^2 + 1 is reduced by the zero test), ``divide_exact(P, Q)`` is the quotient ``P/Q`` as a rational function
    (``P/x`` expanded term by term: every term of the recipe's ``DD(N1)`` carries x), which is the polynomial
    quotient wherever the division is exact (certified per p: eq:gam3)."""

    def __init__(self, x, d, i):
        self.x, self.d, self.i = x, d, i

    def dx(self, P):
        return sp.diff(P, self.x)

    @staticmethod
    def red(P):
        return sp.expand(P)

    def divide_exact(self, P, Q):
        return (sp.expand(P / Q) if Q == self.x else P / Q), True


def sigma_values() -> tuple:
    """(V2(0), V3(0), p, d, i, P0): the complex solution's components at x = 0 (t -> -oo) from the recipe's own
    :func:`suslov.recipes.basis.complete` (the function ``construct`` calls, on ``g1 = x P(x^2)``), with p and d
    symbols and ``P(x^2) = P0 + x^2 S(x)``, S an undefined function (any polynomial P)."""
    x, p, d, P0, i = sp.symbols("x p d P0 i")
    S = sp.Function("S")
    solution = recipe.complete(x * (P0 + x**2 * S(x)), p, 1, _JetRing(x, d, i))
    V2, V3 = (sp.expand(m.subs(x, 0)) for m in solution.M[1:])
    return V2, V3, p, d, i, P0


def sigma_certificate(log: CertificateLog, values: tuple | None = None) -> Certificate:
    """sigma = -1 for every odd p, before any basis beyond KEEP_BASES is built (the module is emitted with it;
    the round trip's asymp certificate then requires the emitted core's numerators to give the same sigma).

    At x = 0 the recipe's complex solution (``complete`` on ``g1 = x P(x^2)``) has ``V3(0) = p P0 (d + i p)``
    and ``V2(0) = i p P0 (d + i p)`` (``P0 = P(0) = F(0) Fhat(0)``), so ``V3(0) = -i V2(0)``: the two
    identities below, exact zero tests in ``Q(p, d, P0)[i]/(i^2+1)`` with p symbolic (every p at once; the
    terms with the rest of P vanish at x = 0 for any S).  ``V2(0)`` is not zero (``F(0) = prod_j ((3+2j)^2 d^2
    + p^2)``, ``Fhat(0) = -(d + i p) F(0)``), which asymp checks per p (``k`` not zero).  ``values``: the
    inputs :func:`sigma_values` makes (a test passes perturbed ones)."""
    V2, V3, p, d, i, P0 = sigma_values() if values is None else values
    domain = Domain("Q(p,d,P0)[i]/(i^2+1)", (Extension(i, sp.Integer(-1), "i = sqrt(-1)"),))
    return certify_zero(log, "for every odd $p$: the complex solution of eq:gam3 from $g1 = x P(x^2)$ has "
                        "$V_3(0) = -i V_2(0)$ and $V_2(0) = i p (d + i p) P(0)$ at $x = 0$ ($t$ tends to $-oo$), so "
                        "$V/k$ tends to $(0, 1, -i)$: $sigma = -1$ (the code of the recipe run with $p$ and $d$ "
                        "symbolic; that $k = V_2(0)$ is not zero is checked for each $p$ with the limits)", "asymp",
                        [V3 + i * V2, V2 - i * p * (d + i * p) * P0], domain)
