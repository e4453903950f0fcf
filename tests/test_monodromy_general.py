"""Monodromy and Galois group of the Poisson equations for any body (issue 23; suslov.kernel.monodromy).

Expected values from independent routes:

* the local exponents: a loop about one simple pole with residue C(w) (non-resonant, or resonant
  without logarithms) has trace ``1 + 2 cosh(2 pi sqrt(w.w))`` (the eigenvalues of exp(2 pi i C(w)));
  evaluated in mpmath from u, v, no integration;
* the exact results for I13 = 0: trivial local monodromy at the poles for odd p, unipotent (trace 3,
  not the identity: logarithms) for even p, eigenvalues 1, exp(+-2 pi i p) for non-integer p;
* a SciPy DOP853 integration in the t-plane around t0 = i pi/2 (the pole x = i), compared by trace
  and, from the same base t = -ln 2 (x = 1/2) along a homotopic loop, entry by entry;
* one Taylor step against the matrix exponential (a single pole: the transfer is exp(C(w) log(x/c))),
  at 300 digits.
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
    m = monodromy(2, 1, 0, I23, dps=25)
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
    m = monodromy(*body, dps=25)
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
    m = monodromy(*body, dps=20)
    assert contains(m.matrices["x=i"].trace(), np.trace(numeric), 1e-8)


def test_relation_group_membership_and_verdict_for_a_general_body():
    m = monodromy("5/4", 1, "3/10", "-1/2", dps=30)
    assert m.radius < 1e-25
    outcomes = {text.split(":")[0]: outcome for text, outcome, _ in m.certificates}
    assert all(outcome == "pass" for outcome in outcomes.values()), outcomes
    assert m.verdict == "SO(3,C)" and m.liouvillian is False


def test_verdict_is_the_same_at_two_precisions():
    for body in (("5/4", 1, "3/10", "-1/2"), (2, 1, 0, "-1/3"), (2, 1, 0, "-2/5")):
        assert monodromy(*body, dps=15).verdict == monodromy(*body, dps=45).verdict


def test_a_wrong_claim_about_the_group_is_refuted_not_unknown():
    m = monodromy(2, 1, 0, "-1/2", dps=20)              # p = 2
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


def test_the_whole_loop_matrix_agrees_with_scipy_from_the_same_base():
    """M(x=i) entry by entry: the lasso's t-image (x = e^t stays in the first quadrant) is homotopic to a
    segment from t = -ln 2 to i pi/2 + 0.6, the circle |t - i pi/2| = 0.6, and back."""
    from scipy.integrate import solve_ivp

    body = ("5/4", "1", "3/10", "-1/2")
    u, v = (np.array([float(a) for a in vec]) for vec in uv(body))

    def matrix(t):   # column form of gamma' = gamma C(omega): (gamma^T)' = C(omega)^T gamma^T
        w = u * np.tanh(t) + v / np.cosh(t)
        return np.array([[0, 0, w[1]], [0, 0, -w[0]], [-w[1], w[0], 0]], dtype=complex).T

    def segment(a, b):
        def rhs(s, y):
            return (matrix(a + s * (b - a)) @ y.reshape(3, 3) * (b - a)).ravel()
        sol = solve_ivp(rhs, (0, 1), np.eye(3, dtype=complex).ravel(), method="DOP853", rtol=1e-12, atol=1e-12)
        return sol.y[:, -1].reshape(3, 3)

    base, start = -math.log(2), 1j * math.pi / 2 + 0.6
    column = segment(start, base) @ circle_monodromy(matrix, 1j * math.pi / 2, 0.6, 3) @ segment(base, start)
    M = monodromy(*body, dps=20).matrices["x=i"]
    for r in range(3):
        for c in range(3):
            assert contains(M[r, c], column.T[r, c], 1e-8)


def test_one_taylor_step_against_the_matrix_exponential_at_300_digits():
    """With one simple pole (residue C(w) at 0) the transfer from c to c + h is exp(log(1 + h/c) C(w)):
    the step's ball, truncation bound included, contains it (log10 eps = -300: no float underflow)."""
    from flint import acb, ctx

    from suslov.kernel.fuchsian_flow import cross_matrix, transfer

    with ctx.workprec(1100):
        R = [cross_matrix([acb("0.3"), acb("-1.7"), acb("0.4", "0.2")]), acb_mat(3, 3), acb_mat(3, 3)]
        c, h = acb("0.5"), acb("0.1", "0.2")     # rho(c) = 1/2 (x = 0), |h| < rho/2
        step = transfer(R, c, h, -300)
        exact = (R[0] * (1 + h / c).log()).exp()
        radius = max(float(step[r, k].rad()) for r in range(3) for k in range(3))
        assert radius < 1e-295
        assert all((step[r, k] - exact[r, k]).contains(0) for r in range(3) for k in range(3))
        assert not all((transfer(R, c, h * acb("1.001"), -300)[r, k] - exact[r, k]).contains(0)
                       for r in range(3) for k in range(3))


def test_the_relation_holds_in_its_one_order_and_the_others_are_excluded():
    from suslov.kernel.monodromy import RELATION

    m = monodromy("2", "1", "3/10", "-1/5", dps=30)
    A, B, C = (m.matrices[name] for name in RELATION)
    assert _contains(A * B * C, m.matrices["x=oo"]) and _excludes(B * A * C, m.matrices["x=oo"])
    relation = next(c for c in m.certificates if c[0].startswith("the ordered product"))
    assert relation[1] == "pass" and relation[2].startswith("5 of the 5")


def test_near_the_equilibrium_the_radius_is_still_as_asked_and_the_verdict_decided():
    """|u| = 19: entries about 1e51, and each Taylor sum cancels about 40 digits; the guard digits
    keep the radius at 10^-digits (before them: relative precision 1e-17 at 40 digits, 'unknown')."""
    m = monodromy("2", "1", "1/20", "-1/20", dps=20, max_dps=20)
    assert m.guard > 60 and m.radius < 1e-20
    assert m.verdict == "SO(3,C)"


def test_too_close_to_the_equilibrium_the_balls_say_unknown_and_the_exact_decision_decides():
    """The balls are not integrated (the digits it would need are said); the verdict is Kimura's, exactly."""
    m = monodromy("2", "1", "1/1000", "1/1000", dps=20)
    assert m.matrices == {} and m.radius == math.inf
    assert "working digits" in m.certificates[0][0] and m.certificates[0][1] == "unknown"
    assert m.verdict == "SO(3,C)" and m.liouvillian is False
    assert m.certificates[-1][1] == "pass" and "exactly" in m.certificates[-1][0]


def test_the_mirror_axis_i23_zero_through_eq_lina():
    """eq:lina (I11 <-> I22, I13 <-> I23): p^2 = I11 (I22 - I11)/I13^2 on I23 = 0."""
    odd = monodromy(1, 2, -1, 0, dps=20)                 # p = 1
    assert odd.verdict == "reducible" and odd.liouvillian is True
    assert _contains(odd.matrices["x=i"], I3) and _contains(odd.matrices["x=-i"], I3)
    even = monodromy(1, 2, "-1/2", 0, dps=20)            # p = 2
    assert even.verdict == "SO(3,C)" and (even.matrices["x=i"].trace() - 3).contains(0)


def test_odd_p_beyond_the_loaded_pmax_is_decided_by_the_theorem(monkeypatch):
    """The balls cannot prove M(+-i) = I.  That identity used to rest on the per-p Frobenius certificate, up to the
    loaded formulas' PMAX (p = 3 undecided with a module certified to p = 1).  The meromorphy theorem
    (derivations/sections/pole_theorem.py: Lambda odd gives M^2 = -I for the lift) covers every odd p, so PMAX no
    longer matters; Kimura's theorem decides the group (reducible) as before."""
    import suslov.validated as validated

    real = validated.gf

    class Formulas:
        PMAX = 1

        def __getattr__(self, name):
            return getattr(real, name)

    monkeypatch.setattr(validated, "gf", Formulas())
    m = monodromy(2, 1, 0, "-1/3", dps=20)
    assert m.verdict == "reducible" and m.liouvillian is True
    assert any(outcome == "pass" and "exactly" in claim for claim, outcome, _ in m.certificates)
    assert _contains(m.matrices["x=i"], I3)                # consistent with p = 3, and certified by the theorem
    assert any("theorem for every p" in str(detail) for _, _, detail in m.certificates)
    assert not any("beyond the certified range" in str(detail) for _, _, detail in m.certificates)
    monkeypatch.undo()
    assert monodromy(2, 1, 0, "-1/3", dps=20).verdict == "reducible"
