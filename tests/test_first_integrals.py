"""First integrals P1, P2, P3 (Theorem 6.2): invariance, exactness, errors.

References: SciPy's DOP853 integrating eq:sysfin + Poisson (typed here from the
paper, with the + sign), exact Fraction evaluation through the derivation's
fraction-free polynomials (python-flint, a different code path from the
generated module's recipe), the paper's printed p = 1 integral, and mpmath.
"""
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from derivations.sections import first_integrals as fi
from generated import suslov_formulas as sf


def system(p, d):
    def rhs(_, y):
        w1, w2, g1, g2, g3 = y
        return [d / (p * (d * d + 1)) * w2**2, -d / p * w1 * w2, -w2 * g3, w1 * g3, w2 * g1 - w1 * g2]
    return rhs


def flint_value(ff, d, point):
    """K^2 Den F3 / (K^2 Den) evaluated exactly from the fraction-free polynomials."""
    def ev(poly):
        total = Fraction(0)
        for monomial, coefficient in poly.to_dict().items():
            term = Fraction(int(coefficient)) * d ** int(monomial[0])
            for value, exponent in zip(point, monomial[1:]):
                term *= value ** int(exponent)
            total += term
        return total
    G, K, Den = ev(ff.scaled_integral()), ev(ff.K), ev(ff.Den)
    return G / (K * K * Den)


@pytest.mark.parametrize("p", [1, 3, 5, 9, 15])
@pytest.mark.parametrize("d", [Fraction(1, 2), Fraction(7, 3)])
def test_generated_coefficients_equal_certified_polynomials(p, d):
    ff, divisible = fi.construct(p)
    assert divisible
    point = [Fraction(3, 5), Fraction(-2, 7), Fraction(1, 3), Fraction(5, 11), Fraction(-4, 9)]
    exact = flint_value(ff, d, point)
    coefficients = sf.first_integral_coefficients(p, d)
    w1, w2, *g = point
    value = sum(gi * sum(a * w1 ** (p - k) * w2**k for k, a in enumerate(coefficients[name]))
                for name, gi in zip(("P1", "P2", "P3"), g))
    assert value == exact
    # float64 evaluation: relative accuracy 1e-12 at this rational point
    approx = sf.first_integral(p, float(d), *map(float, point))
    assert abs(float(approx) - float(exact)) <= 1e-12 * abs(float(exact))


@pytest.mark.parametrize("p, d", [(1, 0.5), (3, 0.5), (7, 1.3), (15, 2.0), (15, 0.2)])
def test_F3_is_conserved_along_integrated_trajectories(p, d):
    y0 = [0.3, -1.1, 0.6, 0.0, 0.8]
    sol = solve_ivp(system(p, d), (0, 6), y0, method="DOP853", rtol=1e-12, atol=1e-12, dense_output=True)
    ts = np.linspace(0, 6, 25)
    w1, w2, g1, g2, g3 = sol.sol(ts)
    F3 = sf.first_integral(p, d, w1, w2, g1, g2, g3)
    scale = np.max(np.abs(F3))
    assert scale > 0
    # relative drift stated: 1e-8 of the integral's magnitude (integrator tolerance 1e-12)
    assert np.ptp(F3) <= 1e-8 * scale, (np.ptp(F3), scale)


def test_printed_p1_integral_is_conserved_and_proportional():
    """The paper's p = 1 integral, typed here, is d times ours along a trajectory."""
    d = 0.7
    sol = solve_ivp(system(1, d), (0, 5), [0.5, 0.9, 0.0, 1.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-12,
                    dense_output=True)
    w1, w2, g1, g2, g3 = sol.sol(np.linspace(0, 5, 11))
    printed = d * w1 * g1 + d / (d * d + 1) * w2 * g2 - d * d / (d * d + 1) * w2 * g3
    ours = sf.first_integral(1, d, w1, w2, g1, g2, g3)
    assert np.ptp(printed) < 1e-9
    assert np.allclose(printed, d * ours, rtol=1e-12, atol=1e-14)


def test_mp_twin_agrees():
    args = (11, 0.8, 0.9, -0.4, 0.2, 0.7, -0.1)
    assert abs(float(sf.first_integral(*args)) - float(sf.first_integral_mp(*args))) < 1e-12 * abs(
        float(sf.first_integral_mp(*args)))


def test_large_omega_scales_homogeneously():
    base = sf.first_integral(15, 1.5, 0.3, 0.4, 0.1, 0.2, 0.3)
    big = sf.first_integral(15, 1.5, 300.0, 400.0, 0.1, 0.2, 0.3)
    assert abs(big / base / 1000.0**15 - 1) < 1e-13
    with pytest.raises(ValueError, match="overflows"):
        sf.first_integral(15, 1.5, 1e30, 1.0, 0.1, 0.2, 0.3)


def test_coefficients_beyond_float64_are_scaled_not_overflowed():
    """At d = 1e23 the coefficients of P1 reach (d^2+1)^7 ~ 1e322 (beyond float64; they reach 1e340 at
    p = 201, d = 50): the float path scales them by a power of two, and agrees with the exact-coefficient
    mpmath twin; where the value itself exceeds float64 it raises and says so."""
    args = (15, 1e23, 2e-3, -1e-3, 0.6, 0.0, 0.8)
    exact = sf.first_integral_mp(*args, dps=40)
    assert 1e250 < abs(exact) < 1e300
    assert abs(float(sf.first_integral(*args)) - exact) < 1e-13 * abs(exact)
    with pytest.raises(ValueError, match=r"overflows float64 at p=15, d=1e\+23"):
        sf.first_integral(15, 1e23, 2.0, -1.0, 0.6, 0.0, 0.8)


def test_subnormal_scale_is_applied_once():
    """s^p below float64's normal range (s = 5e-21, p = 15: 3e-311): s^p is never formed; the result
    is one rounding of the value, so its error is within the docstring bound with the 5e-324 floor."""
    args = (15, 1.5, 3e-21, -5e-21, 0.36, 0.48, 0.8)
    exact = sf.first_integral_mp(*args, dps=40)
    coefficients = sf.first_integral_coefficients(15, 1.5)
    sizes = [sum(abs(a) for a in coefficients[name]) for name in ("P1", "P2", "P3")]
    bound = 2e-15 * 16 * float(mpmath.mpf(5e-21) ** 15 * sum(g * s for g, s in zip((0.36, 0.48, 0.8), sizes))) + 5e-324
    assert 0 < abs(exact) < 1e-300
    assert abs(float(sf.first_integral(*args)) - exact) <= bound


@pytest.mark.parametrize("p, needle", [(2, "p=2"), (4, "p=4"), (3.5, "p=3.5"), ("3", "p='3'"), (-1, "p=-1"),
                                       (10**6 + 1, "outside the certified range"), (True, "p=True")])
def test_bad_p(p, needle):
    with pytest.raises(ValueError) as info:
        sf.first_integral(p, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0)
    assert needle in str(info.value)
    with pytest.raises(ValueError):
        sf.first_integral_coefficients(p, 1)


def test_bad_d_and_input():
    with pytest.raises(ValueError, match="d=0"):
        sf.first_integral(3, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="rational"):
        sf.first_integral_coefficients(3, "one half")
    with pytest.raises(ValueError, match="finite"):
        sf.first_integral(3, 1.0, np.nan, 1.0, 1.0, 0.0, 0.0)


def test_construct_rejects_even_p():
    with pytest.raises(ValueError, match="odd"):
        fi.construct(4)


def test_pmax_101_certifies_every_odd_p():
    from derivations.core.options import BuildOptions
    from derivations.output.pipeline import derive

    build = derive(BuildOptions(pmax=101), ["first_integrals"])
    rows = build.results["first_integrals"].exports["rows"]
    assert [r["p"] for r in rows] == list(range(1, 102, 2))
    integral_certs = [c for c in build.log.certificates if c.label == "eq:liniowiec"]
    assert len(integral_certs) == 51 and all(c.outcome.value == "pass" for c in integral_certs)


def test_scaled_field_is_sympys_cancelled_field():
    """scaled_field (symengine products, read into flint) against SymPy's cancel and Poly of the same
    K times right-hand side, for the derived field and the Poisson field, odd p <= 21."""
    import sympy as sp

    from derivations.core.options import BuildOptions
    from derivations.core.recipe_rings import INTEGRAL_CTX
    from derivations.core.symbols import d, g1, g2, g3, p, w1, w2
    from derivations.output.pipeline import derive
    from derivations.sections import first_integrals

    field = derive(BuildOptions(), ["special_case"]).results["special_case"].exports["field"]
    poisson = {g1: -w2 * g3, g2: w1 * g3, g3: w2 * g1 - w1 * g2}
    for p_value in range(1, 22, 2):
        scaled = first_integrals.scaled_field(field, p_value)
        for var, rhs in list(field.items()) + list(poisson.items()):
            cancelled = sp.Poly(sp.cancel(p_value * (d**2 + 1) * rhs.subs(p, p_value)), d, w1, w2, g1, g2, g3)
            assert all(c.is_Integer for c in cancelled.coeffs())
            expected = INTEGRAL_CTX.from_dict({m: int(c) for m, c in cancelled.terms()})
            assert scaled[str(var)] == expected, (p_value, var)


def test_integer_polynomial_refuses_a_fraction():
    import pytest
    import sympy as sp

    from derivations.core.symbols import d, w1
    from derivations.sections.first_integrals import _integer_polynomial

    assert str(_integer_polynomial((d**2 + 1) * w1 / (d**2 + 1))) == "w1"
    with pytest.raises(ArithmeticError):
        _integer_polynomial(w1 / 2)
    with pytest.raises(ArithmeticError):
        _integer_polynomial(sp.Integer(1) / (d + 1))
