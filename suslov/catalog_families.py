"""A family's formula for one value of its parameter, written at run time from the tree's certified recipe.

``catalog["first_integrals"](p=...)`` (Theorem 6.2, corrected; ``eq:p1``, ``eq:p23``): the first integral
F3 = P1 g1 + P2 g2 + P3 g3 for odd p.  The tree's build certified the shared recipe
``suslov.recipes.integrals`` for every odd p of its range (the same function, run by the build in
``Z[d, w1, w2]`` and by the generated module on numbers: ``_integral_core``); here the tree's own
``_integral_core`` is run in that exact ring (:mod:`suslov.recipes.flint_rings`), so the catalog needs no
stored copy of each P (at pmax 201 the stored forms would be tens of megabytes and minutes of SymPy).
Each P is written as the build's documents write it: one term per monomial in (omega1, omega2), its
coefficient a reduced fraction of polynomials in d, numerator and denominator factored over Z by FLINT.
The catalog's tests compare these with the document's own P forms (p <= 7) and check that F3 is
conserved along the equations of motion.
"""
from __future__ import annotations

from collections import defaultdict
from types import ModuleType

import flint

from suslov.catalog_export import sympy_module
from suslov.recipes.flint_rings import INTEGRAL_RING

__all__ = ["CONSTRUCTIONS", "first_integrals"]


def _factored(poly: flint.fmpz_poly, d):
    sp = sympy_module()
    content, factors = poly.factor()
    out = sp.Integer(int(content))
    for factor, exponent in factors:
        out *= sp.Add(*[int(c) * d**j for j, c in enumerate(factor.coeffs()) if c]) ** exponent
    return out


def _univariate(P) -> flint.fmpz_poly:
    """An element of Z[d, ...] free of the other variables, as a polynomial in d."""
    coefficients = defaultdict(int)
    for exponents, c in P.to_dict().items():
        if any(exponents[1:]):
            raise ArithmeticError("a denominator of the recipe depends on omega or gamma")
        coefficients[exponents[0]] += int(c)
    return flint.fmpz_poly([coefficients.get(j, 0) for j in range(max(coefficients) + 1)])


def _rational_form(numerator, denominator: flint.fmpz_poly, d, w1, w2):
    """``sum_(a,b) (n_ab(d)/den(d)) w1^a w2^b``, each fraction reduced and factored."""
    sp = sympy_module()
    groups: dict = defaultdict(lambda: defaultdict(int))
    for (ed, e1, e2, *rest), c in numerator.to_dict().items():
        groups[(e1, e2)][ed] += int(c)
    terms = []
    for (a, b), by_degree in sorted(groups.items(), reverse=True):
        top = flint.fmpz_poly([by_degree.get(j, 0) for j in range(max(by_degree) + 1)])
        common = top.gcd(denominator)
        if int(denominator(0)) and common.degree() == 0 and int(common(0)) < 0:
            common = -common
        num, den = top // common, denominator // common
        if den.degree() == 0 and int(den(0)) < 0:
            num, den = -num, -den
        terms.append(_factored(num, d) / _factored(den, d) * w1**a * w2**b)
    return sp.Add(*terms)


def first_integrals(module: ModuleType, p: int):
    """``(Eq(P1, ...), Eq(P2, ...), Eq(P3, ...))`` for odd ``p`` from ``module``'s certified recipe."""
    sp = sympy_module()
    d = sp.Symbol("d", positive=True)
    w1, w2 = sp.symbols("omega1 omega2", real=True)
    numerators = module._integral_core(p, INTEGRAL_RING)
    if not numerators.exact:
        raise ArithmeticError(f"p={p}: omega1 does not divide the numerator of P2 (the certified recipe says it does)")
    K, Den = _univariate(numerators.K), _univariate(numerators.Den)
    parts = ((numerators.P1t, Den), (numerators.M2, K**2 * Den), (numerators.M3, K * Den))
    names = sp.symbols("P1:4")
    return sp.Tuple(*[sp.Eq(name, _rational_form(num, den, d, w1, w2), evaluate=False)
                      for name, (num, den) in zip(names, parts)])


CONSTRUCTIONS = {"first_integrals": first_integrals}
