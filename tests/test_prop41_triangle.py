"""Proposition 4.1's last step (I11^2 - (J2 - J3)^2 > 0): the exact condition against mpmath eigenvalues."""
import random
from fractions import Fraction

import mpmath
import pytest

from derivations.sections.prop41_triangle import COUNTEREXAMPLE, condition_value, sign_of_surd, triangle_gap_parts


def gap_by_eigenvalues(values, dps=50):
    """I11^2 - (J2 - J3)^2 from the eigenvalues of the lower block, the proof's root with sign -, in mpmath."""
    with mpmath.workdps(dps):
        i11, i22, i33, p = (mpmath.mpf(Fraction(values[k]).numerator) / Fraction(values[k]).denominator
                            for k in ("I11", "I22", "I33", "p"))
        delta = i11 - i22
        i23sq = i22 / (2 * delta) * (p**2 + 2 * i33 * delta - p * mpmath.sqrt(p**2 + 4 * i33 * delta))
        i23 = mpmath.sqrt(i23sq)
        j = mpmath.eig(mpmath.matrix([[i22, i23], [i23, i33]]))[0]
        return i11**2 - (j[0] - j[1]) ** 2, i23sq


def test_counterexample_of_the_issue():
    gap, i23sq = gap_by_eigenvalues(COUNTEREXAMPLE)
    assert abs(i23sq - mpmath.mpf("0.2917960675006309")) < 1e-15
    assert abs(mpmath.mpf("1.21") - gap - mpmath.mpf("2.1671842700025237")) < 1e-15
    a, b, r = triangle_gap_parts(COUNTEREXAMPLE)
    assert sign_of_surd(a, b, r) == -1 and condition_value(COUNTEREXAMPLE) < 0


def test_condition_decides_the_sign_on_random_bodies():
    rng = random.Random(41)
    seen = set()
    for _ in range(300):
        i22 = Fraction(rng.randint(1, 40), rng.randint(1, 20))
        i11 = i22 + Fraction(rng.randint(1, 40), rng.randint(1, 20))
        i33 = i11 - i22 + Fraction(rng.randint(1, 40), rng.randint(1, 20))   # I33 + I22 > I11
        body = {"I11": i11, "I22": i22, "I33": i33, "p": Fraction(rng.randint(1, 9), rng.randint(1, 3))}
        gap, _ = gap_by_eigenvalues(body)
        bracket = condition_value(body)
        if abs(gap) < mpmath.mpf(10) ** -30 or bracket == 0:
            continue
        assert (gap > 0) == (bracket > 0), body
        assert sign_of_surd(*triangle_gap_parts(body)) == (1 if gap > 0 else -1), body
        seen.add(gap > 0)
    assert seen == {True, False}     # both sides of the condition were exercised


@pytest.mark.parametrize("a,b,r", [(3, -1, 9), (-3, 1, 9), (3, -1, 8), (-3, 1, 10), (0, -2, 5), (2, 0, 7),
                                   (Fraction(-2779, 100), 20, Fraction(9, 5))])
def test_sign_of_surd_against_mpmath(a, b, r):
    a, b, r = Fraction(a), Fraction(b), Fraction(r)
    with mpmath.workdps(60):
        value = mpmath.mpf(a.numerator) / a.denominator + mpmath.mpf(b.numerator) / b.denominator * mpmath.sqrt(
            mpmath.mpf(r.numerator) / r.denominator)
    expected = 0 if abs(value) < 1e-50 else (1 if value > 0 else -1)
    assert sign_of_surd(a, b, r) == expected


def test_sign_of_surd_refuses_a_negative_radicand():
    with pytest.raises(ValueError, match="r = -1"):
        sign_of_surd(Fraction(1), Fraction(1), Fraction(-1))
