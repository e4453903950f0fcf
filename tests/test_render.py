"""Code generation: the emitted Python source evaluates to the expression's value."""
from fractions import Fraction

import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from derivations.output.render import python_source, tex_escape

x, y, z = sp.symbols("x y z")
EXPRESSIONS = [x / y**2, x / (y**2 * z**3), (x + y) ** 3 / (x - y) ** 2, -x**2 * y / (1 + z**2) ** 2, x**-2,
               sp.Rational(3, 7) * x**5 - y / z]


@settings(max_examples=30, deadline=None)
@given(st.fractions(min_value=-5, max_value=5), st.fractions(min_value=1, max_value=5),
       st.fractions(min_value=1, max_value=5))
def test_python_source_matches_sympy(a, b, c):
    point = {x: sp.Rational(a.numerator, a.denominator), y: sp.Rational(b.numerator, b.denominator),
             z: sp.Rational(c.numerator, c.denominator)}
    for expr in EXPRESSIONS:
        exact = expr.subs(point)
        if not exact.is_finite:
            continue  # a pole of the expression
        value = eval(python_source(expr), {str(k): Fraction(int(v.p), int(v.q)) for k, v in point.items()})
        # rational constants print as Python divisions (floats): compare to 1e-12 relative
        assert abs(float(value) - float(exact)) <= 1e-12 * max(1.0, abs(float(exact)))


def test_tex_escape():
    assert tex_escape("a_b^2 < 3 & 50%") == r"a\_b\textasciicircum{}2 \textless{} 3 \& 50\%"
