"""``sympy.factor`` of a rational function of one variable over Q, computed by python-flint.

Used where the build prints a coefficient in factored form (paper section 6.2, ``eq:p1``,
``eq:p23``: the written-out P1, P2, P3; section 5.1, ``pol_sol``: the c_j table).  The
factorisation itself is FLINT's (``fmpz_poly.factor``: Zassenhaus / van Hoeij over Z); only the
result is turned into a SymPy expression, for the printer.

**Same expression as SymPy.**  ``sympy.factor(N/D)`` factors numerator and denominator over Z
separately (content with its sign, primitive irreducible factors with positive leading
coefficient), and multiplies them into one ``Mul`` in which equal factors of N and D combine their
exponents.  That normal form is unique, so building it from FLINT's factors gives the identical
SymPy object (``tests/test_flint_factor.py`` compares the two on random and on the build's rational
functions); the build's outputs are byte-identical (``bench/bench_build_profile.py`` compares trees).

Measured (``tests`` aside, one build): the factorisations of the written-out P1, P2, P3 cost SymPy
about 1.5 s (``factor`` inside ``collect``); here a few milliseconds plus the conversions.
"""
from __future__ import annotations

import math
from fractions import Fraction

import flint
import sympy as sp
from sympy.core.exprtools import _keep_coeff


def _integer_poly(coefficients: list) -> tuple[flint.fmpz_poly, Fraction]:
    """(integer polynomial, rational scale) with the given polynomial = scale * integer polynomial."""
    fractions = [Fraction(c) for c in coefficients]
    lcm = math.lcm(*(c.denominator for c in fractions))
    return flint.fmpz_poly([int(c * lcm) for c in fractions]), Fraction(1, lcm)


def _as_expr(poly: flint.fmpz_poly, x: sp.Symbol) -> sp.Expr:
    return sp.Add(*(sp.Integer(int(c)) * x**k for k, c in enumerate(poly.coeffs()) if c != 0))


def factor_univariate(numerator: list, denominator: list, x: sp.Symbol) -> sp.Expr:
    """``sympy.factor(N(x)/D(x))`` for N, D given by their rational coefficients (constant first).

    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> factor_univariate([-2, 0, -2], [6, 3], x)
    -2*(x**2 + 1)/(3*(x + 2))
    >>> factor_univariate([-2, 0, -2], [6, 3], x) == sp.factor((-2 - 2*x**2)/(6 + 3*x))
    True
    """
    num, num_scale = _integer_poly(numerator)
    den, den_scale = _integer_poly(denominator)
    if den.is_zero():
        raise ZeroDivisionError("denominator is the zero polynomial")
    if num.is_zero():
        return sp.Integer(0)
    num_content, num_factors = num.factor()
    den_content, den_factors = den.factor()
    coefficient = Fraction(int(num_content)) * num_scale / (Fraction(int(den_content)) * den_scale)
    product = sp.Mul(*([_as_expr(f, x) ** e for f, e in num_factors]
                       + [_as_expr(f, x) ** -e for f, e in den_factors]))
    return _keep_coeff(sp.Rational(coefficient.numerator, coefficient.denominator), product)


def factor_rational(expr: sp.Expr, x: sp.Symbol) -> sp.Expr:
    """``sympy.factor(expr)`` for a rational function ``expr`` of the single symbol ``x`` over Q.

    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> factor_rational(x/2 + x**2/2, x)
    x*(x + 1)/2
    """
    num, den = sp.fraction(sp.together(expr))
    return factor_univariate(sp.Poly(num, x).all_coeffs()[::-1], sp.Poly(den, x).all_coeffs()[::-1], x)
