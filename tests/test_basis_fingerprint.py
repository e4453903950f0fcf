"""The round trip's two exact tools for bases certified in workers (issue 24, ``--pmax 201``).

* ``meromorphic.numerators_digest``: the fingerprint by which the emitted core's numerators are compared
  with the certified ones.  It must change with any single term: one coefficient off by one, one
  exponent moved, a numerator and a denominator traded, two numerators' terms redistributed.
* ``float_paths._at``: a numerator at rational (x, d), exactly, as A + iB.  Checked against a second
  route: the terms summed as Python Fractions.
"""
from fractions import Fraction

import flint
import pytest

from derivations.core.recipe_rings import BASIS_CTX
from derivations.output.float_paths import _at
from derivations.sections import meromorphic

X, D, I = BASIS_CTX.gens()


def poly(terms: dict):
    return BASIS_CTX.from_dict({k: flint.fmpq(*v) if isinstance(v, tuple) else v for k, v in terms.items()})


def digest(*polys):
    return meromorphic.numerators_digest(list(polys[:3]), list(polys[3:]))


BASE = {(2, 1, 0): 3, (1, 0, 1): (-5, 7), (0, 0, 0): 12345678901234567890123}


@pytest.mark.parametrize("changed", [
    {**BASE, (2, 1, 0): 4},                                   # a coefficient off by one
    {**BASE, (0, 0, 0): 12345678901234567890122},               # a big one off by one
    {**BASE, (1, 0, 1): (-7, 5)},                              # numerator and denominator traded
    {(2, 1, 0): 3, (1, 1, 1): (-5, 7), (0, 0, 0): 12345678901234567890123},   # an exponent moved
    {**BASE, (3, 0, 0): 1},                                    # one more term
])
def test_digest_changes_with_any_single_term(changed):
    rest = [poly({(1, 0, 0): 1}), X * D, D + I, X, X + 1]
    assert digest(poly(BASE), *rest) == digest(poly(BASE), *rest)
    assert digest(poly(BASE), *rest) != digest(poly(changed), *rest)


def test_digest_tells_where_the_terms_are():
    """The same twelve terms, split differently between two numerators, or the numerators in another order."""
    a, b = X**2 + 2 * X, 3 * D + I
    c, e = X**2, 2 * X + 3 * D + I
    zero = BASIS_CTX.constant(0)
    assert digest(a, b, zero, zero, zero, zero) != digest(c, e, zero, zero, zero, zero)
    assert digest(a, b, zero, zero, zero, zero) != digest(b, a, zero, zero, zero, zero)


def test_digest_of_a_constructed_basis_is_reproducible_and_order_sensitive():
    real, cplx = meromorphic.construct(7)
    again_real, again_cplx = meromorphic.construct(7)
    assert meromorphic.numerators_digest(real.M, cplx.M) == meromorphic.numerators_digest(again_real.M, again_cplx.M)
    assert meromorphic.numerators_digest(real.M, cplx.M) != meromorphic.numerators_digest(cplx.M, real.M)


def by_fractions(P, x: Fraction, d: Fraction) -> tuple:
    """The second route: every term of P as a Fraction, summed by its power of i."""
    parts = [Fraction(0), Fraction(0)]
    for (a, b, k), c in zip(P.monoms(), P.coeffs()):
        parts[int(k)] += Fraction(int(c.p), int(c.q)) * x ** int(a) * d ** int(b)
    return tuple(parts)


@pytest.mark.parametrize("p", [1, 5, 13])
@pytest.mark.parametrize("x, d", [(Fraction(0), Fraction(3, 4)), (Fraction(2, 3), Fraction(3, 4)),
                                  (Fraction(5, 4), Fraction(15, 8)), (Fraction(-7, 3), Fraction(1, 9))])
def test_at_is_the_exact_value(p, x, d):
    real, cplx = meromorphic.construct(p)
    for P in real.M + cplx.M:
        assert _at(P, x, d) == by_fractions(P, x, d)


def test_at_refuses_a_numerator_not_reduced_modulo_i_squared_plus_one():
    with pytest.raises(ArithmeticError, match="degree > 1 in i"):
        _at(X + I**2, Fraction(1, 2), Fraction(1, 3))
