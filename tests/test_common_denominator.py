"""derivations.core.common_denominator against SymPy's ``together`` (the count every exact certificate prints).

Independent route: ``sympy.together`` itself, expanded as ``exact.normal_form`` always expanded it.
Whenever the flint route answers, its numerator must have exactly together's number of terms and
``numerator/denominator`` must be the expression; it must answer on the shapes the certificates use
(expanded denominators, nested fractions, shared and content-scaled bases) and decline where SymPy's
structure cancels.  Every input of the build's certificates is compared too: the cold build against
the committed ``generated/`` (tests/test_build.py, byte-identical, the counts included), and here
the two largest derivations with the flint route on and off.
"""
from __future__ import annotations

import doctest
from fractions import Fraction

import pytest
import sympy as sp
from flint import fmpq_mpoly_ctx
from hypothesis import given, settings
from hypothesis import strategies as st

from derivations.core import common_denominator as module
from derivations.core import exact
from derivations.core.common_denominator import common_denominator
from derivations.core.options import BuildOptions
from derivations.output.pipeline import derive

x, y, z = sp.symbols("x y z")
NAMES = ("x", "y", "z")
RING = fmpq_mpoly_ctx.get(NAMES, "lex")
POINT = {x: sp.Rational(3, 7), y: sp.Rational(-5, 11), z: sp.Rational(13, 17)}


def together_count(expr) -> int:
    numerator = sp.fraction(sp.together(expr))[0]
    return len(sp.Add.make_args(sp.expand(numerator)))


def value(poly) -> Fraction:
    """``poly`` of RING at POINT, exactly."""
    total = Fraction(0)
    for monomial, coefficient in zip(poly.monoms(), poly.coeffs()):
        term = Fraction(int(coefficient.p), int(coefficient.q))
        for symbol, power in zip((x, y, z), monomial):
            term *= Fraction(int(POINT[symbol].p), int(POINT[symbol].q)) ** int(power)
        total += term
    return total


def check(expr) -> bool:
    """Assert the flint route agrees with together where it answers; True when it answered."""
    pair = common_denominator(expr, NAMES, RING)
    if pair is None:
        return False
    numerator, denominator = pair
    assert max(1, len(numerator.coeffs())) == together_count(expr), expr
    at_point = expr.subs(POINT)
    if at_point.is_finite and value(denominator) != 0:
        assert value(numerator) / value(denominator) == Fraction(int(sp.fraction(at_point)[0]),
                                                                 int(sp.fraction(at_point)[1])), expr
    return True


small = st.integers(-3, 3)
monomial = st.builds(lambda c, a, b, e: c * x**a * y**b * z**e, st.integers(-4, 4).filter(bool),
                     st.integers(0, 2), st.integers(0, 2), st.integers(0, 1))
polynomial = st.lists(monomial, min_size=1, max_size=4).map(lambda ms: sp.Add(*ms)).filter(lambda p: p != 0)


def _compound(children):
    return st.one_of(
        st.builds(sp.Add, children, children),
        st.builds(sp.Mul, children, children),
        st.builds(lambda a, b: a / b, children, children.filter(lambda b: b != 0)),
        st.builds(lambda a, k: a**k, children.filter(lambda a: a != 0), st.integers(-2, 3)),
    )


leaves = st.one_of(st.sampled_from([x, y, z]), small.map(sp.Integer), polynomial)
expressions = st.recursive(leaves, _compound, max_leaves=8)


@settings(max_examples=300, deadline=None)
@given(expressions)
def test_count_is_together_s_wherever_an_answer_is_given(expr):
    if expr.has(sp.zoo, sp.nan, sp.oo):
        return
    check(expr)


@settings(max_examples=200, deadline=None)
@given(polynomial, st.lists(st.tuples(st.integers(-2, 2).filter(bool), st.integers(-2, 2), st.integers(1, 2)),
                            min_size=1, max_size=4), monomial)
def test_shared_and_scaled_bases(base, uses, numerator):
    """Terms over c*B, -B, B*x, B^k of one base B: together identifies some and keeps others apart."""
    expr = sp.Add(*(numerator / (scale * base * x**shift) ** power for scale, shift, power in uses))
    if expr.has(sp.zoo, sp.nan):
        return
    check(expr)


@pytest.mark.parametrize("expr", [
    x / (x + y) + y / (x - y),
    1 / (2 * x + 2) - 1 / (x + 1) + y / (x**2 + x),
    x * (1 / y + 1 / z) - (x + 1) / (y * z),
    1 / (x + 1 / y) + 1 / (x - 1 / y),
    (x / (1 - x) + x / (x - 1)) * y,
    (x**2 + y) ** 2 / (3 * x * y + 3 * y) - z / (x + 1) ** 2,
])
def test_answers_on_the_certificates_shapes(expr):
    assert check(expr)


@pytest.mark.parametrize("expr", [
    x / (x + 1) + 1 / (x + 1),                   # together: 1 (the numerator is the base)
    (x**2 - 1) / (x - 1),                        # not reduced: together keeps it, counts 2
    (x * y + x) / (y + 1) + z,                   # together cancels y + 1 through gcd_terms
    # one polynomial, two structures: together keeps both bases (its numerator has 9 terms, the flint one 2), so no answer here
    1 / ((x + 1) * (y + 1) + 1 / z) + 1 / (x * y * z + x * z + y * z + z + 1),
    x + sp.sin(y),
    x ** sp.Rational(1, 2) + y,
    sp.Float(0.5) * x + y,
])
def test_declines_where_structure_decides(expr):
    assert common_denominator(expr, NAMES, RING) is None


@pytest.mark.parametrize("section", ["kovalevskaya", "galois"])
def test_build_certificates_identical_without_the_flint_route(monkeypatch, section):
    """The two derivations with the largest together inputs (a 1203-term numerator; rational functions
    of z, m, p with nested fractions): the same certificates with and without the flint route."""
    def details(build):
        return [(c.label, c.outcome, c.work, c.detail) for c in build.log.certificates]

    names = {"kovalevskaya": ["model", "kovalevskaya"], "galois": ["model", "special_case", "galois"]}[section]
    options = BuildOptions(jobs=1)
    with_flint = details(derive(options, names))
    monkeypatch.setattr(exact, "common_denominator", lambda *args: None)
    assert details(derive(options, names)) == with_flint


def test_doctests():
    assert doctest.testmod(module).failed == 0
