"""Logarithms at s1 = i of the linear equation eq:2rzedu: exact verdicts against a numerical monodromy.

Independent route: integrate w'' + p(z) w' + q(z) w = 0 (the printed p, q, typed here) around
|z - i| = 0.3 with SciPy; the exponent difference is an integer, so the monodromy is a scalar
matrix exactly when there is no logarithm (otherwise it is a non-trivial Jordan block).
"""
import numpy as np
import pytest

from derivations.options import BuildOptions
from derivations.pipeline import derive

from conftest import circle_monodromy


def monodromy(p, d, center=1j, radius=0.3):
    c = np.sqrt(d * d + 1)

    def coefficients(z):
        pz = (z**2 * (z**2 + 4j * c * z - 4) - 1) / (z * (z**2 + 1) * (z**2 + 2j * c * z - 1))
        qz = p**2 / (4 * (c * c - 1)) / z**2 + p**2 / (z**2 + 1) ** 2
        return pz, qz

    def matrix(z):
        pz, qz = coefficients(z)
        return np.array([[0, 1], [-qz, -pz]])  # (w, w')

    return circle_monodromy(matrix, center, radius, 2)


@pytest.fixture(scope="module")
def verdicts():
    rows = derive(BuildOptions(pmax=4), ["galois"]).results["galois"].exports["log_rows"]
    return {row["p"]: row["s1"] for row in rows}


@pytest.mark.parametrize("p", [1, 2, 3, 4])
def test_s1_verdict_matches_numeric_monodromy(verdicts, p):
    M = monodromy(p, 0.75)
    scalar = M[0, 0]
    deviation = np.max(np.abs(M - scalar * np.eye(2)))
    if verdicts[p] == "no log":
        assert p % 2 == 1 and deviation < 1e-8
    else:
        assert p % 2 == 0 and deviation > 1e-3


def test_value_at_m_agrees_with_the_polynomial():
    """The even-p shortcut (the obstruction's exact value at m = 3) against the full polynomial in m,
    evaluated afterwards: non-zero for even p, zero for odd p, at s1 and s2."""
    from derivations import galois

    num_mip, rests, points = galois._obstruction_data()
    three = galois.MI.constant(3)
    for p_value in (4, 6, 7, 9):
        num_p = [c.compose(galois.M_, galois.I_, galois.MI.constant(p_value), ctx=galois.MI) for c in num_mip]
        for name in ("s1", "s2"):
            _, polynomial = galois.log_obstruction_fraction_free(num_p, rests[name], points[name], p_value)
            at_three = galois._red(polynomial.compose(three, galois.I_, ctx=galois.MI))
            assert galois._nonzero_at(3, num_p, rests[name], points[name], p_value) == (not at_three.is_zero())
            assert at_three.is_zero() == (p_value % 2 == 1)
