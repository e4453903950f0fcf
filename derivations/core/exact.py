"""Exact zero tests in canonical polynomial / rational-function domains.

An identity ``expr == 0`` is certified by bringing ``expr`` to a canonical form
in a ring where "zero" is decidable (docs/design.md, "Certification"):

1. ``expr`` is written over a common denominator, ``num/den``, with ``num`` and
   ``den`` polynomials over Q in the generators of the domain;
2. algebraic quantities are explicit extension symbols with a monic quadratic
   relation ``s**2 = D`` (for example ``c**2 = d**2 + 1`` for
   ``c = sqrt(d^2+1)``, ``r**2 = I11*I22`` for ``sqrt(I11*I22)``, and
   ``S**2 = 1 - T**2`` tying ``S = sech t`` to ``T = tanh t``);
3. ``num`` is reduced modulo the relations.  The leading monomials ``s_i**2``
   are pairwise coprime, so the relations form a Groebner basis (Buchberger's
   first criterion) and the remainder is a unique normal form: the identity
   holds iff the remainder is the zero polynomial.  The denominator is reduced
   too, and must not vanish.

An identity in ``Q(x)[s]/(s**2 - D)`` holds for *both* roots ``s = +-sqrt(D)``,
which is how "both sign choices" are certified at once.  A non-zero remainder
is a refutation when the quotient ring is a domain (``D`` not a square), which
holds for every extension used here.  ``simplify`` is never called.

Tools (issue 24: a profile of the cold build put SymPy's expansion and polynomial construction on
every certificate's path): SymPy's ``together`` writes the common denominator; symengine expands
numerator and denominator (about 40x faster than ``sympy.expand`` on the Kovalevskaya
characteristic polynomial, 1203 terms); the remainder modulo the relations is python-flint's
multivariate division in ``fmpq_mpoly`` (lexicographic order, extension symbols first: the
remainder has no monomial divisible by any ``s_i**2``).  The certificate's "ring that decided" is
the domain; the term count is that of the expanded numerator of ``together``, as before.  For an
expression that is zero, :mod:`derivations.core.common_denominator` finds a numerator with that
same count in python-flint without ``together`` (235 of the default build's 284 zero tests; it
proves the count or declines, and a declined or non-zero case takes the route above).
"""
from __future__ import annotations

from dataclasses import dataclass

import symengine as se
import sympy as sp
from flint import fmpq_mpoly_ctx

from derivations.core.certificates import (
    Certificate,
    CertificateLog,
    Outcome,
    stopwatch,
)
from derivations.core.common_denominator import common_denominator, polynomial
from derivations.core.statement import Statement, ring


@dataclass(frozen=True)
class Extension:
    """An algebraic generator ``symbol`` with ``symbol**2 == square``."""

    symbol: sp.Symbol
    square: sp.Expr
    meaning: str

    def relation(self) -> sp.Expr:
        return self.symbol**2 - self.square


@dataclass(frozen=True)
class Domain:
    """Q(variables)[extensions] with the extensions' quadratic relations.

    ``name`` is what certificates print as the method's domain: the ring in the notation of
    :func:`derivations.core.statement.ring` (``Q(p,d)[c]/(c^2-d^2-1)``), typeset as mathematics.
    """

    name: str
    extensions: tuple[Extension, ...] = ()

    def extension_symbols(self) -> tuple[sp.Symbol, ...]:
        return tuple(e.symbol for e in self.extensions)

    def with_extensions(self, name: str, *more: Extension) -> "Domain":
        return Domain(name, self.extensions + tuple(more))


@dataclass(frozen=True)
class NormalForm:
    """The reduced numerator and denominator of an expression (python-flint ``fmpq_mpoly`` in ``gens``)."""

    numerator: object
    denominator: object
    terms_tested: int
    gens: tuple = ()

    @property
    def is_zero(self) -> bool:
        return self.numerator.is_zero()

    def leading_term(self) -> sp.Expr:
        """The numerator's leading term (lexicographic, ``gens`` in order) as a SymPy expression."""
        monomial, coefficient = next(iter(self.numerator.terms()))
        return sp.Rational(int(coefficient.p), int(coefficient.q)) * sp.Mul(
            *(g**e for g, e in zip(self.gens, monomial)))


def _generators(expr: sp.Expr, domain: Domain) -> list[sp.Symbol]:
    ext = list(domain.extension_symbols())
    symbols = set(expr.free_symbols)
    for e in domain.extensions:
        symbols |= sp.sympify(e.square).free_symbols  # the relations' variables are generators too
    rest = sorted((s for s in symbols if s not in ext), key=sp.default_sort_key)
    # a constant still needs one generator to be a polynomial
    return ext + rest or [sp.Symbol("_constant")]


def _ring(gens: list[sp.Symbol]):
    """The ``fmpq_mpoly`` ring (lexicographic, ``gens`` in order) and the index of each generator's name."""
    names = tuple(str(g) for g in gens)
    if len(set(names)) != len(names):
        raise ValueError(f"two generators share a name: {names}")
    return fmpq_mpoly_ctx.get(names, "lex"), {name: k for k, name in enumerate(names)}


def _reduce(expanded, gens: list[sp.Symbol], domain: Domain):
    ring, index = _ring(gens)
    return _reduce_poly(polynomial(expanded, ring, index), ring, index, domain)


def _reduce_poly(poly, ring, index: dict, domain: Domain):
    relations = [polynomial(se.expand(se.sympify(e.relation())), ring, index) for e in domain.extensions]
    while True:   # the leading monomials s_i**2 are coprime: division by each until none divides a term
        reduced = poly
        for relation in relations:
            reduced = divmod(reduced, relation)[1]
        if reduced == poly:
            return reduced
        poly = reduced


def _expand(expr: sp.Expr):
    """symengine's expansion of a SymPy polynomial, and its number of terms as ``sympy.expand`` counts
    them (a zero polynomial is one term, ``0``)."""
    expanded = se.expand(se.sympify(expr))
    return expanded, len(expanded.args) if isinstance(expanded, se.Add) else 1


IMAGINARY = Extension(sp.Symbol("i_"), sp.Integer(-1), "i_ = sqrt(-1)")


def normal_form(expr: sp.Expr, domain: Domain) -> NormalForm:
    """Canonical (numerator, denominator) of ``expr`` in ``domain``.

    ``expr`` must be a rational expression in its symbols (no functions):
    callers replace ``tanh t`` etc. by ring generators first.  The imaginary
    unit, where it occurs, becomes the generator ``i_`` with ``i_**2 = -1``.
    """
    expr = sp.sympify(expr)
    if expr.has(sp.I):
        expr = expr.xreplace({sp.I: IMAGINARY.symbol})   # an atom: subs would ask every node to rewrite itself
        domain = domain.with_extensions(domain.name, IMAGINARY)
    if expr.atoms(sp.Function):
        names = sorted({type(f).__name__ for f in expr.atoms(sp.Function)})
        raise ValueError(
            f"normal_form needs a rational expression; found functions {names}: "
            "substitute them by ring generators first"
        )
    fast = _zero_without_together(expr, domain)
    if fast is not None:
        return fast
    num, den = sp.fraction(sp.together(expr))
    gens = _generators(num * den, domain)
    expanded, terms = _expand(num)
    return NormalForm(_reduce(expanded, gens, domain), _reduce(_expand(den)[0], gens, domain), terms, tuple(gens))


def _zero_without_together(expr: sp.Expr, domain: Domain) -> NormalForm | None:
    """The normal form of an ``expr`` that is zero in ``domain``, its term count that of ``together``'s
    numerator, from :func:`derivations.core.common_denominator.common_denominator`; ``None`` when that
    module does not vouch for the count, or the expression is not zero (a refutation prints its normal
    form's leading term, which stays ``together``'s), or its denominator vanishes."""
    gens = _generators(expr, domain)
    try:
        ring, index = _ring(gens)
    except ValueError:
        return None
    pair = common_denominator(expr, tuple(ring.names()), ring)
    if pair is None:
        return None
    numerator = _reduce_poly(pair[0], ring, index, domain)
    if not numerator.is_zero():
        return None
    denominator = _reduce_poly(pair[1], ring, index, domain)
    if denominator.is_zero():
        return None
    return NormalForm(numerator, denominator, max(1, len(pair[0].coeffs())), tuple(gens))


def is_identically_zero(expr: sp.Expr, domain: Domain) -> bool:
    """Decide ``expr == 0`` in ``domain`` (raises if the denominator vanishes)."""
    form = normal_form(expr, domain)
    if form.denominator.is_zero():
        raise ZeroDivisionError("denominator vanishes identically in the domain")
    return form.is_zero


def cancelled(expr: sp.Expr, domain: Domain) -> sp.Expr:
    """``sympy.cancel(expr)``, without SymPy's gcds when ``expr`` is zero in ``domain``.

    The canonical-domain test (:func:`normal_form`, python-flint) decides zero first; SymPy's ``cancel``
    (a canonical form too: ``0`` exactly when the expression is zero) runs only on a non-zero expression,
    so the result is the object ``cancel`` gives in every case.  For identities whose cancelled
    difference is then certified: r(z; 1/m) = r(z; m) costs 0.36 s in ``cancel``, 0.09 s here.
    """
    form = normal_form(expr, domain)
    if not form.denominator.is_zero() and form.is_zero:
        return sp.Integer(0)
    return sp.cancel(expr)


def certify_zero(
    log: CertificateLog,
    claim: str,
    label: str,
    expr,
    domain: Domain,
    *,
    expect: Outcome = Outcome.PASS,
) -> Certificate:
    """Certify ``expr == 0`` (or each entry of a list/Matrix) in ``domain``.

    ``expect=Outcome.FAIL`` records a claim that the derivation predicts to be
    false (a printed form refuted); the build fails only on a surprise.
    """
    exprs = list(expr) if isinstance(expr, (list, tuple, sp.MatrixBase)) else [expr]
    outcome, work, detail = Outcome.PASS, 0, ""
    with stopwatch() as elapsed:
        for index, item in enumerate(exprs):
            try:
                form = normal_form(item, domain)
            except Exception as exc:  # unsupported input is "unknown", not a pass
                outcome, detail = Outcome.UNKNOWN, f"entry {index}: `{type(exc).__name__}`: {exc}"
                break
            work += form.terms_tested
            if form.denominator.is_zero():
                outcome, detail = Outcome.UNKNOWN, f"entry {index}: denominator vanishes"
                break
            if not form.is_zero:
                outcome = Outcome.FAIL
                lead = form.leading_term()    # the generator i (i^2 + 1 = 0) is the imaginary unit
                lead = lead.xreplace({g: sp.I for g in lead.free_symbols if g.name in ("i", "i_")})
                detail = Statement(f"entry {index}: normal form has {len(form.numerator.coeffs())} "
                                   "non-zero terms, leading ", lead)
                break
    if outcome is Outcome.PASS:
        detail = f"{len(exprs)} identit{'y' if len(exprs) == 1 else 'ies'}, {work} terms reduced to 0"
    method = Statement("exact zero test in ", ring(domain.name))
    return log.record(
        Certificate(claim, label, method, outcome, elapsed[0], work, detail, expected=expect)
    )


def certify_polys_zero(log: CertificateLog, claim: str, label: str, polys, domain_name: str, *,
                       expect: Outcome = Outcome.PASS, seconds: float = 0.0) -> Certificate:
    """Record the zero test of polynomials already held in a canonical domain.

    For ``sympy.Poly`` objects over a field such as ``QQ(d)``: their dense
    representation is canonical, so ``is_zero`` decides the identity.
    ``seconds`` adds the cost of building the polynomials.
    """
    polys = list(polys)
    with stopwatch() as elapsed:
        nonzero = [i for i, poly in enumerate(polys) if not poly.is_zero]
    work = sum(len(poly.terms()) for poly in polys)
    outcome = Outcome.FAIL if nonzero else Outcome.PASS
    detail = (f"entry {nonzero[0]} has {len(polys[nonzero[0]].terms())} non-zero terms" if nonzero
              else f"{len(polys)} polynomial{'' if len(polys) == 1 else 's'} identically 0")
    return log.record(Certificate(claim, label, Statement("exact zero test in ", ring(domain_name)), outcome,
                                  elapsed[0] + seconds, work, detail, expected=expect))
