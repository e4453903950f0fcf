"""Monodromy and Galois group of the Poisson equations for any body (issue 23; suslov.kernel.monodromy).

Expected values from independent routes:

* the local exponents: a loop about one simple pole with residue C(w) (non-resonant, or resonant
  without logarithms) has trace ``1 + 2 cosh(2 pi sqrt(w.w))`` (the eigenvalues of exp(2 pi i C(w)));
  evaluated in mpmath from u, v, no integration;
* the exact results for I13 = 0: trivial local monodromy at the poles for odd p, unipotent (trace 3,
  not the identity: logarithms) for even p, eigenvalues 1, exp(+-2 pi i p) for non-integer p;
* a SciPy DOP853 integration in the t-plane around t0 = i pi/2 (the pole x = i), compared by trace.
"""
import math

import mpmath
import numpy as np
import pytest
from flint import acb_mat

from conftest import circle_monodromy
from suslov.kernel.monodromy import _contains, _excludes, infinite_order
from suslov.validated import monodromy, omega_coefficients

I3 = acb_mat([[1, 0, 0], [0, 1, 0], [0, 0, 1]])


def uv(body):
    u, v = omega_coefficients(*body)
    return [mpmath.mpf(float(x.mid())) for x in u], [mpmath.mpf(float(x.mid())) for x in v]


def contains(ball, value, slack=1e-9):
    return abs(complex(ball.real.mid(), ball.imag.mid()) - complex(value)) <= slack * max(1.0, abs(complex(value)))


@pytest.mark.parametrize("p, I23, kind", [(1, "-1", "odd"), (3, "-1/3", "odd"), (2, "-1/2", "even"), (4, "-1/4", "even"),
                                          (2.5, "-2/5", "non-integer"), (1.3, "-10/13", "non-integer")])
def test_special_case_reproduces_the_exact_local_monodromy(p, I23, kind):
    m = monodromy(2, 1, 0, I23, digits=25)
    for name in ("x=i", "x=-i"):
        M = m.matrices[name]
        if kind == "odd":
            assert _contains(M, I3)
        elif kind == "even":
            assert (M.trace() - 3).contains(0) and _excludes(M, I3)
        else:
            assert contains(M.trace(), 1 + 2 * math.cos(2 * math.pi * p))
    assert m.verdict == ("reducible" if kind == "odd" else "SO(3,C)")
    assert m.liouvillian is (kind == "odd")


@pytest.mark.parametrize("body", [("5/4", "1", "3/10", "-1/2"), ("2", "1", "3/10", "-1/5"), ("3", "1", "-7/10", "1/5")])
def test_traces_are_those_of_the_local_exponents(body):
    u, v = uv(body)
    m = monodromy(*body, digits=25)
    with mpmath.workdps(30):
        uu = u[0] ** 2 + u[1] ** 2
        assert contains(m.matrices["x=0"].trace(), 1 + 2 * mpmath.cosh(2 * mpmath.pi * mpmath.sqrt(uu)), 1e-12)
        assert contains(m.matrices["x=oo"].trace(), 1 + 2 * mpmath.cosh(2 * mpmath.pi * mpmath.sqrt(uu)), 1e-12)
        for name, sign in (("x=i", -1), ("x=-i", 1)):
            ww = sum((a + sign * 1j * b) ** 2 for a, b in zip(u, v))
            assert contains(m.matrices[name].trace(), 1 + 2 * mpmath.cosh(2 * mpmath.pi * mpmath.sqrt(ww)), 1e-12)


def test_pole_loop_agrees_with_an_independent_integration_in_t():
    body = ("5/4", "1", "3/10", "-1/2")
    u, v = (np.array([float(a) for a in vec]) for vec in uv(body))

    def matrix(t):   # gamma' = gamma x omega as a column system: (d/dt) g^T = -C(omega) g^T ... via the transpose
        w = u * np.tanh(t) + v / np.cosh(t)
        C = np.array([[0, 0, w[1]], [0, 0, -w[0]], [-w[1], w[0], 0]], dtype=complex)
        return C.T
    numeric = circle_monodromy(matrix, 1j * np.pi / 2, 0.6, 3)
    m = monodromy(*body, digits=20)
    assert contains(m.matrices["x=i"].trace(), np.trace(numeric), 1e-8)


def test_relation_group_membership_and_verdict_for_a_general_body():
    m = monodromy("5/4", 1, "3/10", "-1/2", digits=30)
    assert m.radius < 1e-25
    outcomes = {text.split(":")[0]: outcome for text, outcome, _ in m.certificates}
    assert all(outcome == "pass" for outcome in outcomes.values()), outcomes
    assert m.verdict == "SO(3,C)" and m.liouvillian is False


def test_verdict_is_the_same_at_two_precisions():
    for body in (("5/4", 1, "3/10", "-1/2"), (2, 1, 0, "-1/3"), (2, 1, 0, "-2/5")):
        assert monodromy(*body, digits=15).verdict == monodromy(*body, digits=45).verdict


def test_a_wrong_claim_about_the_group_is_refuted_not_unknown():
    m = monodromy(2, 1, 0, "-1/2", digits=20)              # p = 2
    assert infinite_order(m.matrices["x=0"]) == "pass"        # "the group is finite": refuted
    assert _excludes(m.matrices["x=i"], I3)                   # "M(x=i) = I" (no logarithms): refuted


def test_too_low_precision_is_unknown_never_a_wrong_verdict():
    from suslov.kernel.monodromy import compute_monodromy, decide_group

    u, v = omega_coefficients(2, 1, 0, "-1/3")
    m = decide_group(compute_monodromy(u, v, 3), exact_trivial_at_poles=False)   # odd p, no exact knowledge
    assert m.verdict in ("unknown",)


@pytest.mark.parametrize("args, match", [((0, 1, "0.3", "0.5"), "I11"), ((2, 1, 0, 0), "equilibrium"),
                                         ((2, 1, float("nan"), "0.5"), "finite"), ((2, 1, "0.3", "0.5", 5), "digits"),
                                         ((2, 1, "0.3", "0.5", 500), "digits")])
def test_bad_input_is_named(args, match):
    with pytest.raises(ValueError, match=match):
        monodromy(*args)
