"""The exact Galois decision and Gauss's form of every body (issue 37), against independent routes.

Expected verdicts come from the paper's odd-p case and the exact Frobenius analysis (I13 = 0: p odd
gives the torus, even and non-integer p SO(3, C)) and from the complex-path monodromy balls; the
exponents of ``hypergeometric_form`` are checked against the traces of the validated monodromy.
"""
from fractions import Fraction

import pytest
from flint import acb, ctx

from suslov.validated import galois_group, hypergeometric_form, monodromy


@pytest.mark.parametrize("body, group", [
    (("2", "1", "0", "-1"), "reducible"),           # p = 1
    (("2", "1", "0", "-1/3"), "reducible"),         # p = 3
    (("10", "1", "0", "-3/5"), "reducible"),        # p^2 = 9 * 1/(9/25) = 25: p = 5
    (("1", "2", "-1", "0"), "reducible"),           # I23 = 0, p = 1 by eq:lina
    (("2", "1", "0", "-1/2"), "SO(3,C)"),           # p = 2 (even)
    (("2", "1", "0", "-2/5"), "SO(3,C)"),           # p = 5/2
    (("2", "1", "0", "-0.3333333333333333"), "SO(3,C)"),   # a decimal next to p = 3, read exactly
    (("2", "1", "1/10**12", "-1/3"), "SO(3,C)"),    # I13 != 0 next to the odd case
    (("5/4", "1", "3/10", "-1/2"), "SO(3,C)"),
    (("1", "1", "0", "1"), "SO(3,C)"),              # I11 = I22: w_-^2 = 0
    (("1", "2", "0", "1"), "SO(3,C)"),              # I11 < I22, I13 = 0: p^2 < 0
])
def test_exact_verdicts(body, group):
    body = tuple(str(Fraction(1, 10**12)) if x == "1/10**12" else x for x in body)
    g = galois_group(*body)
    assert g.group == group
    assert g.liouvillian == (group == "reducible")
    assert "exact" in g.method


def test_odd_square_detection_is_exact():
    # p^2 = I22 (I11 - I22)/I23^2 = 49 for I23 = -1/7: odd; 1 more in I11 breaks it
    assert galois_group(2, 1, 0, Fraction(-1, 7)).P == 7
    assert galois_group(Fraction(2) + Fraction(1, 10**30), 1, 0, Fraction(-1, 7)).group == "SO(3,C)"
    assert galois_group(2.0, 1.0, 0.0, -1.0).group == "reducible"     # floats: their binary value, exact here


@pytest.mark.parametrize("field, body", [
    ("I11", (0, 1, 0, 1)), ("I22", (1, -1, 0, 1)), ("I11", ("x", 1, 0, 1)), ("I23", (1, 1, 0, float("nan"))),
    ("I13", (1, 1, float("inf"), 1)), ("I13=0 and I23=0", (2, 1, 0, 0))])
def test_bad_input_names_the_field(field, body):
    with pytest.raises(ValueError, match=field.replace("=", ".")):
        galois_group(*body)
    with pytest.raises(ValueError, match=field.replace("=", ".")):
        hypergeometric_form(*body)


def test_gauss_parameters_and_points():
    form = hypergeometric_form(2, 1, 0, "-1/3", prec=200)    # I13 = 0, p = 3: kappa = mu = -3/2 (either root)
    assert form.points == {"s=i": 0, "s=-i": 1, "s=oo": "oo"}
    kappa, mu, nu = form.gauss_exponent_differences
    # Riemann scheme of the Gauss equation, independent of how A, B, C were formed
    assert (1 - form.C + kappa).contains(0) and (form.C - form.A - form.B + mu).contains(0)
    assert (form.A - form.B - nu).contains(0)
    assert abs(abs(kappa.real) - 1.5) < 1e-50 and abs(kappa.imag) < 1e-50
    assert form.exact["U^2"] == 9 and form.exact["Re w_-^2"] == -9


@pytest.mark.parametrize("body", [("5/4", "1", "3/10", "-1/2"), ("1", "2", "1/3", "1/5"), ("2", "1", "0", "-2/5")])
def test_exponents_against_validated_monodromy_traces(body):
    """x = e^t is a double cover of s = sinh t ramified at s = +-i: the loop about x = +-i is twice the loop
    about s = +-i, so tr M(x=+-i) = 1 + 2 cos(4 pi kappa) (resp. mu); the loop about x = 0 is one loop about
    s = oo: tr M(x=0) = 1 + 2 cosh(2 pi U).  The monodromy is the independent complex-path computation."""
    mono = monodromy(*body, dps=20)
    form = hypergeometric_form(*body, prec=120)
    kappa, mu = form.exponent_differences["s=i"], form.exponent_differences["s=-i"]
    iU = form.exponent_differences["s=oo"]
    with ctx.workprec(120):
        predicted = {"x=i": 1 + 2 * (4 * kappa).cos_pi(), "x=-i": 1 + 2 * (4 * mu).cos_pi(),
                     "x=0": 1 + 2 * (2 * iU).cos_pi()}
    for point, value in predicted.items():
        trace = mono.matrices[point].trace()
        assert (trace - value).contains(0) and abs(trace - value) < 1e-10 * max(1.0, float(abs(value).upper())), \
            (point, trace, value)


def test_monodromy_verdict_uses_the_exact_decision():
    m = monodromy("2", "1", "0", "-0.3333333333333333", dps=10, max_dps=10)
    assert m.verdict == "SO(3,C)" and m.liouvillian is False
    assert any("exactly" in claim for claim, *_ in m.certificates)


def test_no_acb_needed_for_exact_squares():
    form = hypergeometric_form("5/4", 1, "3/10", "-1/2")
    q, radicand = form.exact["Im w_-^2"]
    assert radicand == Fraction(5, 4) and q != 0       # u.v != 0: w_-^2 not real
    assert isinstance(form.A, acb)
