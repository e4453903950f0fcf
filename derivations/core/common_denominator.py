"""The common denominator of a rational expression, and the term count of SymPy's ``together``, in python-flint.

Every exact certificate (``derivations/core/exact.py``, docs/design.md "Certification") writes ``expr`` over a
common denominator, reduces the numerator modulo the extension relations and prints how many terms
the expanded numerator had ("N terms reduced to 0").  That count has always been the one of
``sympy.together``'s numerator, and ``together`` was the largest SymPy cost left on the certificates'
path (issue 24: 0.65 s of the cold build in 284 calls, 1.8 s under cProfile).  This module computes a
numerator and a denominator with python-flint polynomials and proves, case by case, that the
numerator has as many monomials as ``together``'s; where it cannot, it says ``None`` and
``exact.normal_form`` asks ``together``.

**What together does.**  Recursively, ``together`` writes every sum over the lcm of its terms'
denominators, taken *base by base*: a term is a rational times powers of bases, a base that is a sum
is made primitive (rational content and common monomial taken out) and bases are identified by
structure, never factored; a sum inside a power is combined first and its numerator becomes a base.
Here the same recursion runs on polynomials (``_Recursion.parts``), with bases identified as follows:

* a denominator that is an *expanded* polynomial (a sum of monomials) is identified by its primitive
  part, the canonical polynomial SymPy's primitive sum of monomials is (:func:`_primitive`), so these
  bases are exactly SymPy's;
* a denominator that is a combined sum gets a key of its own: SymPy's base for it is the same
  polynomial or a product of finer bases (a sum whose terms collapse into a product), and SymPy may
  identify it with another occurrence; a key of its own never merges what SymPy keeps apart.

**Why the count is the same.**  With bases either SymPy's or products of SymPy's, every SymPy base
has at least SymPy's exponent in the denominator D computed here, so ``D = D_sympy Q`` (up to a
monomial and a constant; SymPy's cancellations only shrink D_sympy), and the numerators are
``N = N_sympy Q``.  If Q is not a monomial, it divides both N and D, and one of D's bases shares a
factor with N: :func:`common_denominator` checks ``gcd(N, base)`` for every base and says ``None`` when
one is not constant.  Otherwise N is SymPy's numerator times a monomial and a constant, which changes
no monomial count (a zero polynomial counts as one term, ``0``, as ``sympy.expand`` writes it).
Anything outside the recursion (functions, non-integer exponents, floats, complex numbers) is
``None`` too.  ``tests/test_common_denominator.py`` compares the count with ``together``'s on
Hypothesis-generated expressions (nested fractions, shared and opposite bases, cancellations) and
runs the Kovalevskaya and Galois derivations with and without this module; tests/test_build.py
compares every certificate of the build with the committed ``generated/``.
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import symengine as se
from flint import fmpq

__all__ = ["NotAPolynomial", "common_denominator", "polynomial", "rational_function"]


class _NotCovered(Exception):
    """The expression's structure is outside what the module can vouch for."""


class NotAPolynomial(_NotCovered, ValueError):
    """Not an expanded polynomial over Q in the ring's generators."""


@dataclass
class _Fraction:
    """``coefficient * x^exponents * numerator / prod(part^power for part, power in bases.values())``."""

    coefficient: fmpq
    exponents: list
    numerator: object            # fmpq_mpoly
    bases: dict                  # key -> (primitive polynomial, power >= 1)


def polynomial(expanded, ring, index: dict):
    """An expanded symengine polynomial with rational coefficients as an element of ``ring`` (an
    ``fmpq_mpoly_ctx``; ``index``: generator name -> position).  Raises :class:`NotAPolynomial` on
    anything else, a non-integer or negative exponent included."""
    terms = {}
    for term in (expanded.args if isinstance(expanded, se.Add) else (expanded,)):
        coefficient, exponents = fmpq(1), [0] * len(index)
        for factor in (term.args if isinstance(term, se.Mul) else (term,)):
            if isinstance(factor, se.Symbol):
                exponents[index[factor.name]] += 1
            elif isinstance(factor, se.Pow) and isinstance(factor.args[0], se.Symbol) and isinstance(
                    factor.args[1], se.Integer):
                if int(factor.args[1]) < 0:
                    raise NotAPolynomial(f"not a polynomial: {factor}")
                exponents[index[factor.args[0].name]] += int(factor.args[1])
            elif isinstance(factor, (se.Integer, se.Rational)):
                coefficient *= _rational(factor)
            else:
                raise NotAPolynomial(f"not a polynomial over Q: {factor}")
        key = tuple(exponents)
        terms[key] = terms.get(key, fmpq(0)) + coefficient
    return ring.from_dict(terms)


def _rational(number) -> fmpq:
    numerator, denominator = number.get_num_den()
    return fmpq(int(numerator), int(denominator))


def _primitive(poly, ring) -> tuple:
    """(positive rational content, monomial content as exponents, primitive part, its canonical key)."""
    if poly.is_zero():
        raise _NotCovered("a sum that is the zero polynomial")
    coefficients, monomials = poly.coeffs(), poly.monoms()
    content = fmpq(math.gcd(*(int(c.p) for c in coefficients)), math.lcm(*(int(c.q) for c in coefficients)))
    common = [min(m[k] for m in monomials) for k in range(len(monomials[0]))]
    part = ring.from_dict({tuple(a - b for a, b in zip(m, common)): c / content for m, c in zip(monomials, coefficients)})
    key = tuple((m, (int(c.p), int(c.q))) for m, c in zip(part.monoms(), part.coeffs()))
    return content, common, part, key


class _Recursion:
    """:func:`_parts` with the ring, the generators' indices and the keys of combined bases."""

    def __init__(self, ring, index: dict):
        self.ring, self.index, self.fresh = ring, index, itertools.count()
        self.one = ring.from_dict({(0,) * len(index): 1})

    def atom(self, coefficient=None, exponents=None) -> _Fraction:
        return _Fraction(fmpq(1) if coefficient is None else coefficient, exponents or [0] * len(self.index),
                         self.one, {})

    def parts(self, expr) -> _Fraction:
        """``expr`` as a :class:`_Fraction`, bases identified as ``together`` would or more finely."""
        if isinstance(expr, (se.Integer, se.Rational)):
            return self.atom(_rational(expr))
        if isinstance(expr, se.Symbol):
            exponents = [0] * len(self.index)
            exponents[self.index[expr.name]] = 1
            return self.atom(exponents=exponents)
        if isinstance(expr, se.Mul):
            return self.product([self.parts(factor) for factor in expr.args])
        if isinstance(expr, se.Add):
            return self.combined([self.parts(term) for term in expr.args])
        if isinstance(expr, se.Pow) and isinstance(expr.args[1], se.Integer):
            base, power = expr.args[0], int(expr.args[1])
            if power > 0:
                return self.product([self.parts(base)] * power)
            return self.inverse(base, -power)
        raise _NotCovered(f"{type(expr).__name__}: {expr}")

    def product(self, factors: list) -> _Fraction:
        out = self.atom()
        for f in factors:
            out.coefficient *= f.coefficient
            out.exponents = [a + b for a, b in zip(out.exponents, f.exponents)]
            out.numerator = out.numerator * f.numerator
            for key, (part, power) in f.bases.items():
                out.bases[key] = (part, out.bases.get(key, (part, 0))[1] + power)
        return out

    def combined(self, terms: list) -> _Fraction:
        """A sum over the base-wise lcm of its terms' denominators (the numerator as one polynomial)."""
        lowest = [min(0, *(t.exponents[k] for t in terms)) for k in range(len(self.index))]
        bases = {}
        for t in terms:
            for key, (part, power) in t.bases.items():
                bases[key] = (part, max(power, bases.get(key, (part, 0))[1]))
        monomials, numerator = {}, self.ring.from_dict({})
        for t in terms:
            shifted = tuple(e - low for e, low in zip(t.exponents, lowest))
            if not t.bases and not bases and t.numerator.is_one():     # a monomial: no products needed
                monomials[shifted] = monomials.get(shifted, fmpq(0)) + t.coefficient
                continue
            term = self.ring.from_dict({shifted: t.coefficient}) * t.numerator
            for key, (part, power) in bases.items():
                missing = power - t.bases.get(key, (part, 0))[1]
                if missing:
                    term *= part**missing
            numerator += term
        numerator += self.ring.from_dict(monomials)
        return _Fraction(fmpq(1), lowest, numerator, bases)

    def inverse(self, base, power: int) -> _Fraction:
        """``base^-power``: an expanded polynomial is SymPy's base itself; a combined sum's numerator
        becomes a base with a key of its own (module docstring)."""
        if isinstance(base, se.Symbol):
            inverse = self.parts(base)
            inverse.exponents = [-power * e for e in inverse.exponents]
            return inverse
        if not isinstance(base, se.Add):
            raise _NotCovered(f"the power of a {type(base).__name__}: {base}")
        try:
            inner, key = self.atom(), None
            content, common, part, key = _primitive(polynomial(base, self.ring, self.index), self.ring)
        except _NotCovered:
            inner = self.parts(base)
            content, common, part, _ = _primitive(inner.numerator, self.ring)
            key = ("combined", next(self.fresh))
        out = self.atom(inner.coefficient**-power * content**-power,
                        [-power * (e + c) for e, c in zip(inner.exponents, common)])
        for held, held_power in inner.bases.values():   # the inner denominator moves up
            out.numerator = out.numerator * held ** (held_power * power)
        if not part.is_constant():
            out.bases[key] = (part, power)
        return out


def common_denominator(expr, names: tuple, ring):
    """(numerator, denominator) of ``expr`` (a SymPy expression) in ``ring``, an ``fmpq_mpoly_ctx`` over
    ``names``, with as many numerator monomials as ``sympy.together``'s; ``None`` where the module does
    not vouch for the count (module docstring).

    >>> import sympy as sp
    >>> from flint import fmpq_mpoly_ctx
    >>> x, y = sp.symbols("x y")
    >>> ring = fmpq_mpoly_ctx.get(("x", "y"), "lex")
    >>> common_denominator(x / (x + y) + y / (x - y), ("x", "y"), ring)
    (x^2 + y^2, x^2 - y^2)
    >>> common_denominator(x / (x + 1) + 1 / (x + 1), ("x", "y"), ring) is None   # together gives 1
    True
    """
    pair = _fraction(expr, names, ring)
    if pair is None:
        return None
    (numerator, denominator), bases = pair
    if not numerator.is_zero() and any(not numerator.gcd(part).is_constant() for part in bases):
        return None
    return numerator, denominator


def rational_function(expr, names: tuple, ring):
    """``(N, D)`` in ``ring`` with ``expr = N / D``, not reduced (any common factor left in), or ``None``
    when ``expr`` is not a rational function over Q of the generators ``names`` (functions, non-integer
    exponents, floats, complex numbers, other symbols).

    >>> import sympy as sp
    >>> from flint import fmpq_mpoly_ctx
    >>> x = sp.Symbol("x")
    >>> rational_function(x / (x + 1) + 1 / (x + 1), ("x",), fmpq_mpoly_ctx.get(("x",), "lex"))
    (x + 1, x + 1)
    """
    pair = _fraction(expr, names, ring)
    return None if pair is None else pair[0]


def _fraction(expr, names: tuple, ring):
    """(``(N, D)``, the bases of D) from :class:`_Recursion`, or ``None`` outside it."""
    try:
        recursion = _Recursion(ring, {name: k for k, name in enumerate(names)})
        whole = recursion.parts(se.sympify(expr))
    except (_NotCovered, KeyError, TypeError, ValueError, RuntimeError, ZeroDivisionError):
        return None
    numerator = ring.from_dict({tuple(max(e, 0) for e in whole.exponents): whole.coefficient}) * whole.numerator
    denominator = ring.from_dict({tuple(max(-e, 0) for e in whole.exponents): 1})
    for part, power in whole.bases.values():
        denominator *= part**power
    return (numerator, denominator), [part for part, _ in whole.bases.values()]
