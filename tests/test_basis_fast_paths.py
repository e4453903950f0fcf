"""The exact-ring routes of the basis recipe (``exact = True``, ``mul_i``) return the polynomials of the generic ones.

``suslov.recipes.basis`` regroups some sums and products when the ring declares exact arithmetic (the build's
``FlintBasisRing``); the ball ring of the module does not, and runs the operations as written.  Here the same
ring with the declaration switched off stands for the generic route: every numerator equal term by term (p = 3,
17, 31; the one-off comparison up to p = 61 and at p = 101, 151, 201 is in the report of this change), and the
pieces (``gamma1_numerator``, ``hypergeometric_polynomials``, ``DD``, ``mul_i``) equal on their own.
"""
import random

import flint
import pytest

from derivations.core.recipe_rings import BASIS_CTX, BASIS_RING
from derivations.sections import meromorphic
from derivations.sections.meromorphic_ring import DD_split, split_i, third_order_holds
from suslov.recipes import basis as recipe
from suslov.recipes.flint_rings import FlintBasisRing
from suslov.recipes.rings import AcbBasisRing

X, D, I = BASIS_CTX.gens()


class GenericRing(FlintBasisRing):
    """The build's exact ring without the declaration: the recipe's generic operations, as the ball ring runs them."""

    exact = False


GENERIC = GenericRing()


def identical(a, b) -> bool:
    return a == b and a.monoms() == b.monoms() and a.coeffs() == b.coeffs()


def test_only_the_exact_ring_declares_exact_arithmetic():
    assert recipe.exact(BASIS_RING) and not recipe.exact(GENERIC)
    assert not recipe.exact(AcbBasisRing(0.5))


@pytest.mark.parametrize("p", [1, 3, 17, 31])
def test_construct_gives_the_numerators_of_the_generic_route(p):
    fast, generic = recipe.construct(p, BASIS_RING), recipe.construct(p, GENERIC)
    for a, b in zip(fast, generic):
        assert a.divisions_exact and b.divisions_exact and (a.p, a.rate) == (b.p, b.rate)
        assert all(identical(m, n) for m, n in zip(a.M, b.M))
    assert meromorphic.numerators_digest(fast[0].M, fast[1].M) == meromorphic.numerators_digest(generic[0].M, generic[1].M)


@pytest.mark.parametrize("p", [1, 5, 17, 31])
def test_the_pieces_agree(p):
    assert identical(recipe.gamma1_numerator(p, BASIS_RING), recipe.gamma1_numerator(p, GENERIC))
    fast, generic = recipe.hypergeometric_polynomials(p, BASIS_RING), recipe.hypergeometric_polynomials(p, GENERIC)
    assert all(identical(a, b) for a, b in zip(fast, generic))
    F, Fhat = fast
    N = BASIS_RING.red(X * BASIS_RING.square_x(BASIS_RING.mul_red(F, Fhat)))
    for rate in (0, 1, -1):
        for q in (None, p + 1):
            assert identical(recipe.DD(N, p, rate, BASIS_RING, q), recipe.DD(N, p, rate, GENERIC, q))


@pytest.mark.parametrize("seed", range(6))
def test_mul_i_is_the_reduced_product_by_i(seed):
    rng = random.Random(seed)
    terms = {(rng.randrange(9), rng.randrange(9), rng.randrange(3 if seed == 5 else 2)):
             flint.fmpq(rng.randint(-10**30, 10**30), rng.choice([1, 7])) for _ in range(rng.choice([0, 1, 40]))}
    P = BASIS_CTX.from_dict(terms)
    assert identical(BASIS_RING.mul_i(P), BASIS_RING.red(I * P))


def test_the_split_passed_in_answers_as_the_split_made_inside():
    real, cplx = recipe.construct(13, BASIS_RING)
    N = cplx.M[0]
    for candidate in (N, N + X**3 * D):
        parts = split_i(candidate)
        first = DD_split(parts, 13, 1)
        assert third_order_holds(candidate, 13, 1, first, parts) is third_order_holds(candidate, 13, 1)
        sol = recipe.Solution(13, 1, [candidate, cplx.M[1], cplx.M[2]])
        assert meromorphic.poisson_hold(sol, first, parts) is meromorphic.poisson_hold(sol)
    assert meromorphic.poisson_hold(cplx, DD_split(split_i(N), 13, 1), split_i(N))


def test_coefficient_of_a_power_of_x_reads_the_leading_terms_only_as_far_as_needed():
    rng = random.Random(4)
    for _ in range(50):
        P = BASIS_CTX.from_dict({(rng.randrange(8), rng.randrange(5), rng.randrange(2)): flint.fmpq(rng.randint(-9, 9), 3)
                                 for _ in range(rng.randrange(30))})
        for degree in range(-1, 10):
            expected = sum((c * D**b * I**e for (a, b, e), c in zip(P.monoms(), P.coeffs()) if a == degree),
                           BASIS_CTX.constant(0))
            assert meromorphic._coefficient_x(P, degree) == expected
