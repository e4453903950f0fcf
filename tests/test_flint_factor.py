"""derivations.core.flint_factor against SymPy's own factor (the expression the printer used to get).

The build's LaTeX must stay byte-identical, so the FLINT route has to give the *same SymPy object*,
not merely an equal rational function: compared by ``srepr`` on random rational functions of one
variable (products of random factors, repeated factors, rational coefficients, factors shared by
numerator and denominator) and on the written-out first integrals of the build.
"""
from __future__ import annotations

import doctest

import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from derivations.core import flint_factor
from derivations.core.flint_factor import factor_univariate
from derivations.core.symbols import d, w1, w2

small = st.fractions(min_value=-6, max_value=6, max_denominator=4)
polynomial = st.lists(small, min_size=1, max_size=4)


def _expr(factors: list) -> sp.Expr:
    product = sp.Integer(1)
    for coefficients in factors:
        product *= sum(sp.Rational(c.numerator, c.denominator) * d**k for k, c in enumerate(coefficients))
    return sp.expand(product)


@settings(max_examples=150, deadline=None)
@given(st.lists(polynomial, min_size=1, max_size=3), st.lists(polynomial, min_size=1, max_size=3),
       st.booleans())
def test_same_object_as_sympy_factor(num_factors, den_factors, shared):
    if shared:  # a factor common to numerator and denominator: SymPy cancels it through Mul
        den_factors = den_factors + num_factors[:1]
    N, D = _expr(num_factors), _expr(den_factors)
    if D == 0:
        return
    expected = sp.factor(N / D)
    got = factor_univariate(sp.Poly(N, d).all_coeffs()[::-1], sp.Poly(D, d).all_coeffs()[::-1], d)
    assert sp.srepr(got) == sp.srepr(expected)


def test_zero_numerator():
    assert factor_univariate([0], [1, 1], d) == 0


def test_zero_denominator_refused():
    try:
        factor_univariate([1], [0], d)
    except ZeroDivisionError:
        return
    raise AssertionError("a zero denominator must raise")


def test_written_out_first_integrals_as_collect_gives_them():
    """rational_forms (FLINT) against SymPy's collect(expand(P), [w1, w2], factor) of the same P."""
    from derivations.sections.first_integrals import construct, rational_forms, to_sympy

    for p in (1, 3, 5):
        ff, _ = construct(p)
        den, K = to_sympy(ff.Den), to_sympy(ff.K)
        plain = [to_sympy(ff.P1t) / den, to_sympy(ff.M2) / (K**2 * den), to_sympy(ff.M3) / (K * den)]
        expected = [sp.collect(sp.expand(x.subs(sp.Symbol("d"), d)), [w1, w2], sp.factor) for x in plain]
        assert [sp.srepr(x) for x in rational_forms(ff)] == [sp.srepr(x) for x in expected]


def test_doctests():
    assert doctest.testmod(flint_factor).failed == 0


gaussian = st.tuples(st.fractions(min_value=-4, max_value=4, max_denominator=3),
                     st.fractions(min_value=-4, max_value=4, max_denominator=3))


def _gaussian_product(roots, lead) -> list:
    """Coefficients (constant first, (re, im) pairs) of lead * prod (x - r)."""
    x = sp.Symbol("x")
    expr = sp.expand((lead[0] + sp.I * lead[1]) * sp.Mul(*[x - (r[0] + sp.I * r[1]) for r in roots]))
    return [(sp.Rational(sp.re(c)), sp.Rational(sp.im(c))) for c in sp.Poly(expr, x).all_coeffs()[::-1]], expr


@settings(max_examples=80, deadline=None)
@given(st.lists(gaussian, min_size=0, max_size=3), st.lists(gaussian, min_size=0, max_size=3),
       gaussian, gaussian)
def test_gaussian_linear_products_as_sympy(num_roots, den_roots, num_lead, den_lead):
    from fractions import Fraction

    from derivations.core.flint_factor import factor_gaussian

    if num_lead == (0, 0) or den_lead == (0, 0):
        return
    x = sp.Symbol("x")
    num, num_expr = _gaussian_product(num_roots, num_lead)
    den, den_expr = _gaussian_product(den_roots, den_lead)
    as_fractions = [[(Fraction(int(a.p), int(a.q)), Fraction(int(b.p), int(b.q))) for a, b in c] for c in (num, den)]
    got = factor_gaussian(*as_fractions, x)
    if den_lead[1] != 0:
        assert got is None           # left to SymPy (its form of 1/(a + b i) is not canonical)
        return
    assert sp.srepr(got) == sp.srepr(sp.factor(num_expr / den_expr, gaussian=True))


def test_gaussian_refuses_what_does_not_split():
    from fractions import Fraction as Q

    from derivations.core.flint_factor import factor_gaussian

    x = sp.Symbol("x")
    one, zero = (Q(1), Q(0)), (Q(0), Q(0))
    assert factor_gaussian([(Q(-2), Q(0)), zero, one], [one], x) is None           # x^2 - 2: real irrational roots
    assert factor_gaussian([one, zero, zero, one], [one], x) is None               # x^3 + 1: (x+1)(x^2-x+1)
    assert factor_gaussian([zero], [one], x) == 0


def test_f_fhat_tables_as_sympy_factors_them():
    """Every entry of the F / F-hat coefficient tables (odd p <= 7) against SymPy's own factorisation over Q(i)."""
    from derivations.core.options import BuildOptions
    from derivations.core.typeset import latex
    from derivations.sections.meromorphic_printed import (
        coefficient_tables,
        hypergeometric_polynomials,
        to_sympy,
    )

    xs, ds = sp.symbols("x d")
    rows = {(r["p"], r["k"]): r for r in coefficient_tables(BuildOptions(pmax=7))["f"]}
    for p in (1, 3, 5, 7):
        F, Fhat = hypergeometric_polynomials(p)
        den2 = sp.Mul(*[(3 + 2 * j) ** 2 * ds**2 + p * p for j in range((p - 1) // 2)])
        for name, poly in (("F", F), ("Fhat", Fhat)):
            expanded = sp.Poly(to_sympy(poly), xs)
            for k in range(expanded.degree() + 1):
                expected = latex(sp.factor(expanded.coeff_monomial(xs**k) / den2, gaussian=True))
                assert rows[p, k][name] == expected, (p, k, name)


def test_rational_polys_are_the_parsed_forms():
    """rational_polys (built from coefficients) equals Poly(rational_forms(...)) over QQ(d), p = 1, 3, 5."""
    from derivations.sections.first_integrals import (
        _poly,
        construct,
        rational_forms,
        rational_polys,
    )

    for p in (1, 3, 5):
        ff, _ = construct(p)
        parsed, built = [_poly(a) for a in rational_forms(ff)], rational_polys(ff)
        assert [(x.rep, x.gens, x.domain) for x in parsed] == [(x.rep, x.gens, x.domain) for x in built]


# ---- several variables: the written-out basis rows (numerator_to_tanh_sech), generators T, c, d

T_, c_, d_ = sp.symbols("T c d")
monomial = st.tuples(st.integers(0, 2), st.integers(0, 1), st.integers(0, 2))
trivariate = st.dictionaries(monomial, st.integers(-4, 4).filter(bool), min_size=1, max_size=4)


def _mpoly_of(terms_list: list, ctx, order: tuple):
    """The product of the given polynomials ({(T, c, d) exponents: coefficient}) in ``ctx`` (generators ``order``)."""
    where = {"T": 0, "c": 1, "d": 2}
    product = ctx.constant(1)
    for terms in terms_list:
        product *= ctx.from_dict({tuple(e[where[str(x)]] for x in order): v for e, v in terms.items()})
    return product


@settings(max_examples=150, deadline=None)
@given(st.lists(trivariate, min_size=1, max_size=3), st.lists(trivariate, min_size=1, max_size=2),
       st.booleans(), st.fractions(min_value=-5, max_value=5, max_denominator=6).filter(bool))
def test_several_variables_same_object_as_sympy_factor(num_factors, den_factors, shared, scale):
    """Random products (negative leading coefficients in either order of the generators, repeated and shared
    factors, a rational scale): the same SymPy object as ``sympy.factor``, by srepr."""
    import flint

    from derivations.core.flint_factor import factor_multivariate, generator_order

    if shared:
        den_factors = den_factors + num_factors[:1]
    order = generator_order({T_, c_, d_})
    assert [str(x) for x in order] == ["c", "d", "T"]       # SymPy's order: lower-case letters before 'T'
    ctx = flint.fmpq_mpoly_ctx.get(tuple(str(x) for x in order), "lex")
    N = _mpoly_of(num_factors, ctx, order) * flint.fmpq(scale.numerator, scale.denominator)
    D = _mpoly_of(den_factors, ctx, order)
    if D.is_zero():
        return
    as_expr = lambda P: sp.Add(*(sp.Rational(int(v.p), int(v.q)) * sp.Mul(*(x ** int(e) for x, e in zip(order, m)))  # noqa: E731
                                 for m, v in zip(P.monoms(), P.coeffs())))
    expected = sp.factor(as_expr(N) / as_expr(D))
    assert sp.srepr(factor_multivariate(N, D, order)) == sp.srepr(expected)


def test_several_variables_refuses_another_order():
    import flint

    from derivations.core.flint_factor import factor_multivariate

    ctx = flint.fmpq_mpoly_ctx.get(("T", "c", "d"), "lex")
    T, c, d = ctx.gens()
    try:
        factor_multivariate(T - d, c + 1, (T_, c_, d_))
    except ValueError:
        return
    raise AssertionError("symbols not in SymPy's generator order must be refused")


def test_written_out_basis_rows_as_sympy_factor_gives_them(monkeypatch):
    """numerator_to_tanh_sech with FLINT's factors against the same function with sympy.factor, p = 1, 3, 5."""
    from derivations.sections import meromorphic, meromorphic_printed

    def rows():
        return [meromorphic_printed.written_out(meromorphic.certify_p(_Log(), p)) for p in (1, 3, 5)]

    fast = rows()

    def through_sympy(numerator, denominator, symbols):
        as_expr = lambda P: sp.Add(*(sp.Rational(int(v.p), int(v.q)) * sp.Mul(*(x ** int(e) for x, e in zip(symbols, m)))  # noqa: E731
                                     for m, v in zip(P.monoms(), P.coeffs())))
        return sp.factor(as_expr(numerator) / as_expr(denominator))

    monkeypatch.setattr(meromorphic_printed, "factor_multivariate", through_sympy)
    assert [[sp.srepr(x) for x in r] for r in fast] == [[sp.srepr(x) for x in r] for r in rows()]


class _Log:
    """A certificate log that keeps nothing (certify_p records into it)."""

    def record(self, certificate):
        return certificate


# ---- the drop-in: flint_factor.factor(expr) on rational expressions as the derivations write them

_SYMBOLS = sp.symbols("I11 I13 d T")
_atom = st.sampled_from(_SYMBOLS) | st.integers(-3, 3).map(sp.Integer) | st.fractions(
    min_value=-2, max_value=2, max_denominator=3).map(lambda q: sp.Rational(q.numerator, q.denominator))


def _combine(children):
    pair = st.tuples(children, children)
    return (pair.map(lambda ab: ab[0] + ab[1]) | pair.map(lambda ab: ab[0] * ab[1])
            | pair.filter(lambda ab: ab[1] != 0).map(lambda ab: ab[0] / ab[1])
            | st.tuples(children, st.integers(2, 3)).map(lambda ab: ab[0] ** ab[1]))


@settings(max_examples=200, deadline=None)
@given(st.recursive(_atom, _combine, max_leaves=7))
def test_factor_is_sympys_on_nested_rational_expressions(expr):
    from derivations.core.flint_factor import factor

    assert sp.srepr(factor(expr)) == sp.srepr(sp.factor(expr))


def test_factor_leaves_what_flint_cannot_read_to_sympy():
    from derivations.core.flint_factor import factor

    x = sp.Symbol("x")
    x_positive = sp.Symbol("x", positive=True)
    for expr in (x**2 + sp.I, sp.sqrt(2) * x + 2, sp.sin(x) ** 2 - 1, x + x_positive, sp.Integer(6), x**sp.Rational(1, 2) - 1):
        assert sp.srepr(factor(expr)) == sp.srepr(sp.factor(expr)), expr
