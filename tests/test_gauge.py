"""The printed gauge of Theorem 3.5's proof (section 3.2): residue.gauge_transformed_pole against a second route.

The build expands B = U^-1 S^-1 A S U in tau with the Bernoulli-number Laurent coefficients of coth and
csch, in symengine, and zero-tests each coefficient in Q(d)[c, i].  Here: SymPy's ``series`` of the
functions coth(tau), csch(tau) themselves, at the rational point d = 3/4 (c = sqrt(d^2 + 1) = 5/4), each
entry's Laurent expansion read off directly.  The highest pole order and whether the residue of the
conjugated matrix is diag(p, 0, -p) (so that B has residue -p Id) must agree.
"""
import pytest
import sympy as sp

from derivations.core.symbols import c, d
from derivations.sections.residue import gauge_transformed_pole

S_PRINTED = sp.Matrix([[-sp.I * c / d, -sp.I / c, sp.I * c / d], [1 / d, 1, -1 / d], [1, 0, 1]])


def by_series(p: int):
    d_value, c_value = sp.Rational(3, 4), sp.Rational(5, 4)     # c = sqrt(d^2 + 1), rational here
    tau = sp.Symbol("tau")
    w1 = sp.Integer(p) / d_value * sp.coth(tau)                   # tanh(i pi/2 + tau) = coth(tau)
    w2 = -sp.Integer(p) / d_value * c_value * (-sp.I) * sp.csch(tau)   # sech(i pi/2 + tau) = -i csch(tau)
    A = sp.Matrix([[0, 0, -w2], [0, 0, w1], [w2, -w1, 0]])
    S = S_PRINTED.subs({c: c_value, d: d_value})
    U = sp.diag(tau ** (2 * p), tau**p, 1)
    M = U.inv() * S.inv() * A * S * U
    worst, residue = 1, sp.zeros(3, 3)
    for i in range(3):
        for j in range(3):
            series = sp.series(M[i, j], tau, 0, 1).removeO()
            laurent = sp.Poly(sp.expand(series * tau ** (3 * p)), tau)
            for (degree,), coefficient in laurent.terms():
                if coefficient != 0:
                    worst = max(worst, 3 * p - degree)
            residue[i, j] = laurent.coeff_monomial(tau ** (3 * p - 1))
    return worst, residue == sp.diag(p, 0, -p)


@pytest.mark.parametrize("p", [2, 3, 4])
def test_gauge_pole_against_series(p):
    assert gauge_transformed_pole(S_PRINTED, p) == by_series(p)
