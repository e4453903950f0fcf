"""Q[d, 1/d] with python-flint (derivations.core.rational_field.LaurentQD) against SymPy.

The ring operations are compared with SymPy's rational functions on random elements, and the
whole Frobenius recursion of ``derivations.sections.residue`` is rerun in SymPy's field ``QQ.frac_field(d)``
(an independent arithmetic) and compared obstruction by obstruction.
"""
import flint
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from derivations.core.rational_field import LaurentQD
from derivations.core.symbols import (
    d,  # the symbol the recursion returns its obstructions in
)
from derivations.sections import residue

coefficients = st.lists(st.fractions(min_value=-5, max_value=5, max_denominator=7), min_size=1, max_size=4)
shifts = st.integers(min_value=-3, max_value=3)


def element(coeffs, shift):
    """(LaurentQD, SymPy) of sum c_i d^(i + shift)."""
    value = LaurentQD.constant(0)
    x, inverse = LaurentQD.variable(), LaurentQD.constant(1) / LaurentQD.variable()
    for i, c in enumerate(coeffs):
        term = LaurentQD.constant(c)
        for _ in range(abs(i + shift)):
            term = term * (x if i + shift > 0 else inverse)
        value = value + term
    expr = sum(sp.Rational(c.numerator, c.denominator) * d ** (i + shift) for i, c in enumerate(coeffs))
    return value, expr


@settings(max_examples=60, deadline=None)
@given(coefficients, shifts, coefficients, shifts)
def test_ring_operations_match_sympy(c1, s1, c2, s2):
    (a, ea), (b, eb) = element(c1, s1), element(c2, s2)
    for value, expr in ((a + b, ea + eb), (a - b, ea - eb), (a * b, ea * eb)):
        assert sp.cancel(value.to_sympy(d) - expr) == 0
        assert value.is_zero() == (sp.cancel(expr) == 0)
        assert value == LaurentQD.constant(0) + value   # canonical after adding zero


def test_division_by_units_only():
    x, one = LaurentQD.variable(), LaurentQD.constant(1)
    assert sp.simplify((one / (LaurentQD.constant(-2) * x * x)).to_sympy(d) + 1 / (2 * d**2)) == 0
    with pytest.raises(ArithmeticError, match="not a unit"):
        one / (x + one)
    with pytest.raises(ZeroDivisionError):
        one / LaurentQD.constant(0)


def test_canonical_form():
    x, one = LaurentQD.variable(), LaurentQD.constant(1)
    a = (x * x + x) / x                  # = x + 1: the shift absorbs the factor d
    assert a == x + one and a.shift == 0
    assert (a - a).is_zero() and (a - a).shift == 0
    assert (x * x * x - x * x * x + x).shift == 1


class SympyField:
    """SymPy's QQ(d) with the interface of LaurentQD: the reference arithmetic."""

    K = sp.QQ.frac_field(d)

    def __init__(self, value):
        self.value = value

    @classmethod
    def constant(cls, value):
        return cls(cls.K.convert(sp.Rational(value)))

    @classmethod
    def variable(cls):
        return cls(cls.K.convert(d))

    def __add__(self, other):
        return SympyField(self.value + other.value)

    def __sub__(self, other):
        return SympyField(self.value - other.value)

    def __neg__(self):
        return SympyField(-self.value)

    def __mul__(self, other):
        return SympyField(self.value * other.value)

    def __truediv__(self, other):
        return SympyField(self.value / other.value)

    def is_zero(self):
        return not self.value

    @classmethod
    def combination(cls, pairs):
        total = cls.K.zero
        for c, x in pairs:   # c: python-flint fmpq
            total += cls.K.convert(sp.Rational(int(c.p), int(c.q))) * x.value
        return cls(total)

    def to_sympy(self, symbol):
        return self.K.to_sympy(self.value)


@pytest.mark.parametrize("p_value", [3, 4, 7, 10])
def test_recursion_matches_sympy_field(monkeypatch, p_value):
    fast = residue.frobenius_obstructions(p_value)
    monkeypatch.setattr(residue, "LaurentQD", SympyField)
    reference = residue.frobenius_obstructions(p_value)
    assert [(k, name) for k, name, _ in fast] == [(k, name) for k, name, _ in reference]
    assert all(sp.cancel(a - b) == 0 for (_, _, a), (_, _, b) in zip(fast, reference))
    assert any(value != 0 for _, _, value in reference) == (p_value % 2 == 0)


@settings(max_examples=100, deadline=None)
@given(st.lists(st.tuples(st.fractions(min_value=-5, max_value=5, max_denominator=7),
                          st.lists(st.fractions(min_value=-9, max_value=9, max_denominator=11), min_size=1, max_size=4),
                          st.integers(-4, 4)), max_size=6))
def test_combination_is_the_sum_of_products(terms):
    """LaurentQD.combination (one integer sum over a common denominator) against the ring's own + and *."""
    def element(coefficients, shift):
        poly = flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in coefficients])
        return LaurentQD(poly, shift)

    pairs = [(flint.fmpq(c.numerator, c.denominator), element(coefficients, shift)) for c, coefficients, shift in terms]
    expected = LaurentQD.constant(0)
    for c, x in pairs:
        expected = expected + LaurentQD(flint.fmpq_poly([c])) * x
    assert LaurentQD.combination(pairs) == expected
