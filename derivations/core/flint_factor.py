"""``sympy.factor`` of a rational function over Q (one variable or several) or Q(i) (one), computed by python-flint.

Used where the build prints a coefficient in factored form (paper section 6.2, ``eq:p1``,
``eq:p23``: the written-out P1, P2, P3; section 5.1, ``eq:ghyp`` and ``poly_F2``: the F and F-hat
coefficient tables, factored over the Gaussian rationals).  The factorisation itself is FLINT's
(``fmpz_poly.factor``: Zassenhaus / van Hoeij over Z; over Q(i) through the norm, for products of
linear factors, see below); only the result is turned into a SymPy expression, for the printer.

**Same expression as SymPy.**  ``sympy.factor(N/D)`` factors numerator and denominator over Z
separately (content with its sign, primitive irreducible factors with positive leading
coefficient), and multiplies them into one ``Mul`` in which equal factors of N and D combine their
exponents.  That normal form is unique, so building it from FLINT's factors gives the identical
SymPy object (``tests/test_flint_factor.py`` compares the two on random and on the build's rational
functions); the build's outputs are byte-identical (``bench/bench_build_profile.py`` compares trees).

Several variables (:func:`factor_multivariate`, ``fmpz_mpoly.factor``): the same normal form, provided the
generators are in the order SymPy gives them (x, y, z, then p..w, a..o, then other names) and the
context is lexicographic in it, so that "positive leading coefficient" means the same for both.
:func:`factor` is the drop-in for ``sympy.factor`` the derivations call: FLINT where the expression is a
rational function over Q (``common_denominator.rational_function`` reads it), SymPy otherwise.

Measured (one cold build, one process): the factorisations of the written-out P1, P2, P3 cost SymPy
about 0.7 s (``factor`` inside ``collect``), the F / F-hat tables 0.6 s (over ``QQ_I``); here 0.1 s
for both, conversions included.  With the written-out bases' rows and the other printed
factorisations (model, special case, Kovalevskaya, hypergeometric, the emitted coefficients) on this
route too, SymPy's self time under all of the build's factorisations went from 0.87 s to 0.41 s
under cProfile (one process, f602048 against the revision after it); what is left is mostly the
expressions with i, which stay SymPy's.
"""
from __future__ import annotations

import math
from fractions import Fraction

import flint
import sympy as sp
from sympy.core.exprtools import _keep_coeff
from sympy.polys.polyutils import _sort_gens

from derivations.core.common_denominator import rational_function


def integer_poly(coefficients: list) -> tuple[flint.fmpz_poly, Fraction]:
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
    return _sympy_normal_form(integer_poly(numerator), integer_poly(denominator), lambda f: _as_expr(f, x))


def _sympy_normal_form(numerator: tuple, denominator: tuple, as_expr) -> sp.Expr:
    """The module docstring's normal form of N/D from (integer polynomial, rational scale) pairs (FLINT
    ``fmpz_poly`` or ``fmpz_mpoly``), their factors turned into SymPy by ``as_expr``."""
    (num, num_scale), (den, den_scale) = numerator, denominator
    if den.is_zero():
        raise ZeroDivisionError("denominator is the zero polynomial")
    if num.is_zero():
        return sp.Integer(0)
    num_content, num_factors = num.factor()
    den_content, den_factors = den.factor()
    coefficient = Fraction(int(num_content)) * num_scale / (Fraction(int(den_content)) * den_scale)
    product = sp.Mul(*([as_expr(f) ** e for f, e in num_factors] + [as_expr(f) ** -e for f, e in den_factors]))
    return _keep_coeff(sp.Rational(coefficient.numerator, coefficient.denominator), product)


def factor_list_univariate(coefficients: list, x: sp.Symbol) -> tuple[sp.Rational, list]:
    """``sympy.factor_list`` of the polynomial with these rational coefficients (constant first), not zero.

    SymPy's result: the content with the sign, and the primitive irreducible factors (positive leading
    coefficient) with their multiplicities, as expressions, in the order of SymPy's ``_sorted_factors``
    (length of the dense coefficient list, number of generators, multiplicity, domain, the coefficients
    from the leading one down).  The multiplicities are ints (SymPy writes that of ``x`` as an
    ``Integer``: equal, and the same power ``x**k``).

    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> factor_list_univariate([0, 0, -8, 0, -2], x)
    (-2, [(x, 2), (x**2 + 4, 1)])
    >>> factor_list_univariate([0, 0, -8, 0, -2], x) == sp.factor_list(-8*x**2 - 2*x**4)
    True
    """
    poly, scale = integer_poly(coefficients)
    if poly.is_zero():
        raise ValueError("the zero polynomial has no factor list")
    content, factors = poly.factor()
    ordered = sorted(((f, e) for f, e in factors),
                     key=lambda fe: (fe[0].degree() + 1, 1, fe[1], "ZZ", [int(c) for c in reversed(fe[0].coeffs())]))
    lead = Fraction(int(content)) * scale
    return sp.Rational(lead.numerator, lead.denominator), [(_as_expr(f, x), int(e)) for f, e in ordered]


def _integer_mpoly(poly, ctx) -> tuple:
    """(``fmpz_mpoly`` in ``ctx``, rational scale) with the ``fmpq_mpoly`` ``poly`` = scale * that polynomial."""
    coefficients = poly.coeffs()
    lcm = math.lcm(*(int(c.q) for c in coefficients)) if coefficients else 1
    terms = {tuple(int(e) for e in m): int(c.p) * (lcm // int(c.q)) for m, c in zip(poly.monoms(), coefficients)}
    return ctx.from_dict(terms), Fraction(1, lcm)


def _mpoly_expr(poly, symbols: tuple) -> sp.Expr:
    return sp.Add(*(sp.Integer(int(c)) * sp.Mul(*(x ** int(e) for x, e in zip(symbols, m)))
                    for m, c in zip(poly.monoms(), poly.coeffs())))


def generator_order(symbols) -> tuple:
    """The order in which SymPy makes ``symbols`` a polynomial's generators (``Poly(expr).gens``)."""
    return tuple(_sort_gens(list(symbols)))


def factor_multivariate(numerator, denominator, symbols: tuple) -> sp.Expr:
    """``sympy.factor(N/D)`` for N, D ``fmpq_mpoly`` in generators named as ``symbols``, in SymPy's order.

    ``symbols`` must be in the order SymPy gives a polynomial's generators (:func:`generator_order`: x, y,
    z, then p..w, then a..o, then other names; not alphabetical) and the polynomials' context
    lexicographic in that order: then FLINT's irreducible factors over Z (primitive, leading coefficient
    positive in that order) are SymPy's, and the normal form of the module docstring is the same object.

    >>> import flint, sympy as sp
    >>> T, d = sp.symbols("T d")
    >>> generator_order({T, d})
    (d, T)
    >>> ctx = flint.fmpq_mpoly_ctx.get(("d", "T"), "lex")
    >>> dd, t = ctx.gens()
    >>> factor_multivariate((dd**2 - t) * (1 - t * dd), 3 * dd**2 + 3, (d, T))
    -(-T + d**2)*(T*d - 1)/(3*(d**2 + 1))
    >>> _ == sp.factor((d**2 - T) * (1 - T * d) / (3*d**2 + 3))
    True
    """
    if tuple(symbols) != generator_order(symbols):
        raise ValueError(f"symbols {symbols} are not in SymPy's generator order {generator_order(symbols)}")
    ctx = flint.fmpz_mpoly_ctx.get(tuple(str(x) for x in symbols), "lex")
    return _sympy_normal_form(_integer_mpoly(numerator, ctx), _integer_mpoly(denominator, ctx),
                              lambda f: _mpoly_expr(f, symbols))


def factor(expr) -> sp.Expr:
    """``sympy.factor(expr)``: by FLINT (:func:`factor_multivariate`) when ``expr`` is a rational function over
    Q of its symbols, else by SymPy itself (complex or irrational numbers, functions, two symbols of one
    name with different assumptions, which SymPy keeps apart and FLINT's named generators would not).

    >>> import sympy as sp
    >>> a, b = sp.symbols("a b", positive=True)
    >>> factor(a / (a + b) - b / (a + b) + 1 / (2 * a))
    (2*a**2 - 2*a*b + a + b)/(2*a*(a + b))
    >>> _ == sp.factor(a / (a + b) - b / (a + b) + 1 / (2 * a))
    True
    """
    expr = sp.sympify(expr)
    gens = generator_order(expr.free_symbols)
    names = tuple(str(x) for x in gens)
    if not gens or len(set(names)) != len(names) or expr.has(sp.I):
        return sp.factor(expr)
    pair = rational_function(expr, names, flint.fmpq_mpoly_ctx.get(names, "lex"))
    return sp.factor(expr) if pair is None else factor_multivariate(*pair, gens)

# --- over the Gaussian rationals Q(i): products of linear factors --------------------------------------
# python-flint 0.9 factors over Z only.  A polynomial f in Q(i)[x] whose roots all lie in Q(i) (the F and
# F-hat coefficient tables, section 5.1, eq:ghyp and poly_F2: Pochhammer products) is split through its
# norm f * conj(f), a polynomial over Z: each root r of f is a root of a factor of the norm of degree 1
# (r rational) or 2 (r = (-b +- i k)/(2a) with b^2 - 4ac = -k^2), so FLINT's factorisation of the norm
# lists every candidate and exact division by (x - r) in Q(i) keeps those of f with their multiplicity.

def _g_mul(a: tuple, b: tuple) -> tuple:
    return (a[0] * b[0] - a[1] * b[1], a[0] * b[1] + a[1] * b[0])


def _g_div(a: tuple, b: tuple) -> tuple:
    norm = b[0] * b[0] + b[1] * b[1]
    return ((a[0] * b[0] + a[1] * b[1]) / norm, (a[1] * b[0] - a[0] * b[1]) / norm)


def _divide_linear(coefficients: list, root: tuple) -> tuple[list, tuple]:
    """(quotient, remainder) of f / (x - root) by synthetic division (coefficients constant first)."""
    acc, quotient = (Fraction(0), Fraction(0)), []
    for c in reversed(coefficients):
        acc = _g_mul(acc, root)
        acc = (acc[0] + c[0], acc[1] + c[1])
        quotient.append(acc)
    remainder = quotient.pop()
    return quotient[::-1], remainder


def _candidate_roots(coefficients: list) -> list | None:
    """The roots in Q(i) of the norm of f, or None if the norm has an irreducible factor without them."""
    lcm = math.lcm(*(c.denominator for pair in coefficients for c in pair))
    real = flint.fmpz_poly([int(c[0] * lcm) for c in coefficients])
    imaginary = flint.fmpz_poly([int(c[1] * lcm) for c in coefficients])
    norm = real * real + imaginary * imaginary          # f conj(f) for f = real + i imaginary
    roots = []
    for factor, _ in norm.factor()[1]:
        c = [int(v) for v in factor.coeffs()]
        if len(c) == 2:
            roots.append((Fraction(-c[0], c[1]), Fraction(0)))
        elif len(c) == 3:
            k = math.isqrt(4 * c[2] * c[0] - c[1] * c[1]) if 4 * c[2] * c[0] > c[1] * c[1] else -1
            if k < 0 or k * k != 4 * c[2] * c[0] - c[1] * c[1]:
                return None
            roots += [(Fraction(-c[1], 2 * c[2]), Fraction(s * k, 2 * c[2])) for s in (1, -1)]
        else:
            return None
    return roots


def _linear_factors(coefficients: list) -> tuple[tuple, dict] | None:
    """(leading coefficient, {root: multiplicity}) of f in Q(i)[x], or None unless f splits over Q(i)."""
    coefficients = list(coefficients)
    while coefficients and coefficients[-1] == (0, 0):
        coefficients.pop()
    if not coefficients:
        raise ZeroDivisionError("the zero polynomial has no factorisation")
    roots = {}
    candidates = _candidate_roots(coefficients) if len(coefficients) > 1 else []
    if candidates is None:
        return None
    for root in dict.fromkeys(candidates):
        while len(coefficients) > 1:
            quotient, remainder = _divide_linear(coefficients, root)
            if remainder != (0, 0):
                break
            coefficients, roots[root] = quotient, roots.get(root, 0) + 1
    return (coefficients[0], roots) if len(coefficients) == 1 else None


def _gaussian(value: tuple) -> sp.Expr:
    return sp.Rational(value[0].numerator, value[0].denominator) + sp.I * sp.Rational(value[1].numerator,
                                                                                      value[1].denominator)


def factor_gaussian(numerator: list, denominator: list, x: sp.Symbol) -> sp.Expr | None:
    """``sympy.factor(N(x)/D(x), gaussian=True)`` when N and D split into linear factors over Q(i) and D's
    leading coefficient is real, else None.

    N, D: coefficients (constant first) as pairs ``(real, imaginary)`` of Fractions.  The result is
    SymPy's object: the quotient of the leading coefficients times monic factors ``x - r``.

    >>> import sympy as sp
    >>> from fractions import Fraction as Q
    >>> x = sp.Symbol("x")
    >>> factor_gaussian([(Q(1), Q(0)), (Q(0), Q(0)), (Q(1), Q(0))], [(Q(0), Q(0)), (Q(3), Q(0))], x)
    (x - I)*(x + I)/(3*x)
    >>> factor_gaussian([(Q(2), Q(0)), (Q(0), Q(0)), (Q(1), Q(0))], [(Q(1), Q(0))], x) is None   # x^2 + 2
    True
    """
    if all(c == (0, 0) for c in numerator):
        return sp.Integer(0)
    num, den = _linear_factors(numerator), _linear_factors(denominator)
    if num is None or den is None or den[0][1] != 0:
        # (a non-real leading coefficient of D: SymPy keeps 1/(a + b i) as an unevaluated product, a form
        # not worth imitating; the tables' denominators are real)
        return None
    exponents = dict(num[1])
    for root, k in den[1].items():
        exponents[root] = exponents.get(root, 0) - k
    product = sp.Mul(*[(x - _gaussian(root)) ** k for root, k in exponents.items()])
    return _keep_coeff(_gaussian(_g_div(num[0], den[0])), product)
