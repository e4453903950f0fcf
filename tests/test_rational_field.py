"""Q(d) with python-flint (derivations.rational_field.QD) against SymPy's rational functions."""
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from derivations.rational_field import QD

d = sp.Symbol("d")
coefficients = st.lists(st.fractions(min_value=-5, max_value=5, max_denominator=7), min_size=1, max_size=4)


def element(num, den):
    """(QD, SymPy) of num/den with the given coefficient lists (den made non-zero)."""
    den = den if any(den) else [1]
    q = QD.constant(0)
    for coeffs, target in ((num, "num"), (den, "den")):
        poly = QD.constant(0)
        for i, c in enumerate(coeffs):
            term = QD.constant(c)
            for _ in range(i):
                term = term * QD.variable()
            poly = poly + term
        q = poly if target == "num" else q / poly
    expr = sum(sp.Rational(c.numerator, c.denominator) * d**i for i, c in enumerate(num)) / \
        sum(sp.Rational(c.numerator, c.denominator) * d**i for i, c in enumerate(den))
    return q, expr


@settings(max_examples=60, deadline=None)
@given(coefficients, coefficients, coefficients, coefficients)
def test_field_operations_match_sympy(n1, d1, n2, d2):
    (a, ea), (b, eb) = element(n1, d1), element(n2, d2)
    for value, expr in ((a + b, ea + eb), (a - b, ea - eb), (a * b, ea * eb)):
        assert sp.cancel(value.to_sympy(d) - expr) == 0
        assert value.is_zero() == (sp.cancel(expr) == 0)
    if not b.is_zero():
        assert sp.cancel((a / b).to_sympy(d) - ea / eb) == 0


def test_canonical_form():
    x = QD.variable()
    one = QD.constant(1)
    a = (x * x - one) / (x - one)          # = x + 1 after the gcd
    assert a == x + one and a.den.degree() == 0
    assert (a - a).is_zero() and ((one / (QD.constant(2) * x)).den.coeffs()[-1] == 1)
