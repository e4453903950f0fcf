"""The per-p logarithm table's factorisations by python-flint against SymPy's (residue.logarithm_verdict).

``positive_factors``, ``printed_parts`` and ``flint_factor.factor_list_univariate`` replace
``nowhere_zero_for_positive_d`` (kept here as the reference), ``str(sympy.factor(v))``,
``typeset.breakable_product(v)`` and ``sympy.factor_list``: the independent route is SymPy itself, on every non-zero Frobenius obstruction
of p <= 30 and on random Laurent polynomials (odd powers, mixed signs, repeated factors, shifts of
either sign).  The texts must be identical: they are printed in the tables and certificates.
"""
from __future__ import annotations

from fractions import Fraction

import flint
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from derivations.core.flint_factor import factor_list_univariate
from derivations.core.rational_field import LaurentQD
from derivations.core.symbols import d
from derivations.core.typeset import breakable_product
from derivations.sections import residue


def nowhere_zero_for_positive_d(value: sp.Expr) -> bool:
    """The SymPy reference (the build's own test before python-flint): True when every irreducible
    factor of ``value`` is +-d^k or a polynomial in d^2 with coefficients of one sign."""
    num, den = sp.fraction(sp.together(value))
    for expr in (num, den):
        for factor, _ in sp.factor_list(expr)[1]:
            poly = sp.Poly(factor, d)
            if poly.is_monomial:
                continue
            coeffs = poly.all_coeffs()
            if not (all(c >= 0 for c in coeffs) or all(c <= 0 for c in coeffs)):
                return False
            if any(m[0] % 2 for m in poly.monoms()):
                return False
    return value != 0


def sympy_route(value: sp.Expr) -> tuple:
    return nowhere_zero_for_positive_d(value), str(sp.factor(value)), breakable_product(value)


def flint_route(value: LaurentQD) -> tuple:
    return (residue.positive_factors(value), *residue.printed_parts(value))


@pytest.mark.parametrize("p_value", range(1, 31))
def test_obstructions_print_as_sympy_prints_them(p_value):
    for _, _, value in residue.frobenius_obstructions_exact(p_value):
        if not value.is_zero():
            assert flint_route(value) == sympy_route(value.to_sympy(d))


def _laurent(factors, shift):
    poly = flint.fmpq_poly([1])
    for coefficients, power in factors:
        poly *= flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in coefficients]) ** power
    return LaurentQD(poly, shift)


coefficient = st.fractions(min_value=-9, max_value=9, max_denominator=5)
factor = st.tuples(st.lists(coefficient, min_size=2, max_size=4).filter(lambda c: c[-1] != 0 and c[0] != 0),
                   st.integers(1, 3))


@settings(max_examples=120, deadline=None)
@given(st.lists(factor, min_size=0, max_size=3), st.integers(-6, 6), coefficient.filter(bool))
def test_random_laurent_polynomials(factors, shift, scale):
    value = _laurent(factors, shift)
    value = LaurentQD(value.num * flint.fmpq(scale.numerator, scale.denominator), value.shift)
    assert flint_route(value) == sympy_route(value.to_sympy(d))


@settings(max_examples=150, deadline=None)
@given(st.lists(factor, min_size=1, max_size=3), st.integers(0, 3), coefficient.filter(bool))
def test_factor_list_is_sympy_s(factors, power_of_x, scale):
    x = sp.Symbol("x")
    poly = _laurent(factors, 0).num * flint.fmpq(scale.numerator, scale.denominator)
    coefficients = [Fraction(0)] * power_of_x + [Fraction(int(c.p), int(c.q)) for c in poly.coeffs()]
    expr = sp.Add(*(sp.Rational(c.numerator, c.denominator) * x**k for k, c in enumerate(coefficients)))
    ours, theirs = factor_list_univariate(coefficients, x), sp.factor_list(expr)
    # the same objects in the same order; an exponent may be int or Integer (SymPy writes x's as Integer)
    assert sp.srepr(ours[0]) == sp.srepr(theirs[0])
    assert [sp.srepr(f) for f, _ in ours[1]] == [sp.srepr(f) for f, _ in theirs[1]]
    assert [k for _, k in ours[1]] == [k for _, k in theirs[1]]
