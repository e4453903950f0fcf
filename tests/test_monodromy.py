"""Logarithms at t0 = i pi/2: the exact verdicts against a numerical monodromy.

Independent route: integrate eq:ps with omega of `omegas` around the circle
|t - i pi/2| = 0.6 (SciPy DOP853 on the angle, complex state) and compare the
monodromy matrix with the identity: identity <=> no logarithms (the exponents
0, +-p are integers).
"""
import numpy as np
import pytest
from conftest import circle_monodromy

from derivations.core.options import BuildOptions
from derivations.output.pipeline import derive


def monodromy(p, d, radius=0.6):
    a, c = p / d, np.sqrt(d * d + 1)

    def matrix(t):
        w1, w2 = a * np.tanh(t), -a * c / np.cosh(t)
        return np.array([[0, 0, -w2], [0, 0, w1], [w2, -w1, 0]])

    return circle_monodromy(matrix, 1j * np.pi / 2, radius, 3)


@pytest.fixture(scope="module")
def verdicts():
    rows = derive(BuildOptions(pmax=6), ["residue"]).results["residue"].exports["log_rows"]
    return {row["p"]: row["verdict"] for row in rows}


@pytest.mark.parametrize("p", range(1, 7))
@pytest.mark.parametrize("d", [0.5, 2.0])
def test_exact_verdict_matches_numeric_monodromy(verdicts, p, d):
    deviation = np.max(np.abs(monodromy(p, d) - np.eye(3)))
    if verdicts[p] == "no logarithms":
        assert p % 2 == 1 and deviation < 1e-9
    else:
        assert p % 2 == 0 and deviation > 1e-3
