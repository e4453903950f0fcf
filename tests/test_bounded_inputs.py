"""Bounded before any work, and the right exception types (issue 44).

``Fraction("1e10000000")`` was built before any time limit started: ``galois_group('5/4', 1, '1e10000000',
'-1/2')`` took 100 s, and the ball, enclosure and ``monodromy(max_seconds=10)`` routes alike.  Exact input
is now measured before it is converted and refused beyond ``MAX_ENTRY_BITS`` (one limit for every route) with
a ValueError naming the field.  Bad numbers raised ZeroDivisionError ('1/0'), OverflowError (10**1000 in a
float64 route), a python-flint TypeError (np.int64) or were accepted (arb('inf') gave [+/- 6.29]).  Scenes
the schema accepts failed with wrong reasons: p = 1e300 or d = 1e-300 "equilibrium", p = 1e-300 or
d = 1e300 "NaN or inf", the window [-1e308, 1e308] "t[0]=nan".

No test times the machine: "before conversion" is shown by a ``Fraction`` that refuses to be built from an
oversized number (the old code built it), and a subprocess with a generous timeout is a hang guard only.
Expected values come from mpmath and exact Fractions computed here, not from the code under test.
"""
import re
import subprocess
import sys
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from flint import arb

import suslov
from suslov import validated
from suslov.kernel import validate
from suslov.loader import gf
from suslov.simulator.scene import SceneError, parse_scene

HUGE = ["1e10000000", "-2.5e-10000000", "1" * 7000, "1/" + "3" * 7000, "0." + "0" * 9000 + "7"]
BIG = 4 * validate.MAX_ENTRY_BITS    # bits: no Fraction this size may be built from a refused input


def _oversized(text: str) -> bool:
    """Whether a string denotes a number beyond 10^10000 or 10^-10000 (here, independently of the code)."""
    match = re.fullmatch(r"\s*[-+]?([0-9_]*)(?:\.([0-9_]*))?(?:[eE]([-+]?[0-9_]+))?\s*", text)
    if match is None:
        return max(len(part) for part in text.split("/")) > 10_000
    exponent = (match[3] or "0").replace("_", "").lstrip("+-")
    return len(exponent) > 5 or len(match[1]) + len(match[2] or "") + int(exponent or "0") > 10_000


@pytest.fixture
def guarded_fraction(monkeypatch):
    """``Fraction`` refusing oversized strings and ints: a conversion before the size check fails at once."""
    original = Fraction.__new__

    def guard(cls, numerator=0, denominator=None, **keywords):
        for x in (numerator, denominator):
            if isinstance(x, str) and _oversized(x) or isinstance(x, int) and x.bit_length() > BIG:
                shown = x[:30] if isinstance(x, str) else f"an int of {x.bit_length()} bits"
                raise AssertionError(f"Fraction built from an oversized number ({shown}): before the size check")
        return original(cls, numerator, denominator, **keywords)

    monkeypatch.setattr(Fraction, "__new__", staticmethod(guard))


BODY = ("5/4", 1, "3/10", "-1/2")
BODY_CALLS = {   # name -> call with the body (I11, I22, I13, I23)
    "galois_group": validated.galois_group,
    "hypergeometric_form": validated.hypergeometric_form,
    "omega_coefficients": validated.omega_coefficients,
    "enclosure": lambda *b: validated.scattering_angle_enclosure(*b, dps=10),
    "enclosure_integration": lambda *b: validated.scattering_angle_enclosure(*b, dps=10, method="integration"),
    "monodromy": lambda *b: validated.monodromy(*b, dps=10, max_seconds=10),
    "general_scattering_angle_ball": gf.general_scattering_angle_ball,
    "general_scattering_angle_mp": gf.general_scattering_angle_mp,
    "omega_general_mp": lambda *b: gf.omega_general_mp(0.5, *b),
}
PD_CALLS = {     # name -> call with (p, d)
    "scattering_angle_ball": gf.scattering_angle_ball,
    "scattering_angle_mp": gf.scattering_angle_mp,
    "omega_mp": lambda p, d: gf.omega_mp(0.5, p, d),
}
D_CALLS = {      # name -> call with d (p = 3, a certified odd p)
    "gamma_basis_mp": lambda d: gf.gamma_basis_mp(0.5, 3, d),
    "first_integral_coefficients": lambda d: gf.first_integral_coefficients(3, d),
    "first_integral_mp": lambda d: gf.first_integral_mp(3, d, 0.1, 0.2, 0.3, 0.4, 0.5),
}


def _each(value):
    """(label, field, call) for every exact entry point, with ``value`` in one field."""
    for name, call in BODY_CALLS.items():
        yield name, "I13", lambda c=call: c("5/4", 1, value, "-1/2")
        yield name, "I11", lambda c=call: c(value, 1, "3/10", "-1/2")
    for name, call in PD_CALLS.items():
        yield name, "p", lambda c=call: c(value, "1/2")
        yield name, "d", lambda c=call: c("5/2", value)
    for name, call in D_CALLS.items():
        yield name, "d", lambda c=call: c(value)


# ------------------------------------------------------------------ 1. the size is checked before conversion

@pytest.mark.parametrize("text", HUGE, ids=range(len(HUGE)))
def test_oversized_strings_are_refused_by_name_before_any_conversion(text, guarded_fraction):
    for label, field, call in _each(text):
        with pytest.raises(ValueError, match=rf"^{field}=.*bits.*beyond the {validate.MAX_ENTRY_BITS} bits") as caught:
            call()
        assert len(str(caught.value)) < 600, (label, "the value is abbreviated in the message")


def test_oversized_strings_in_scenes_and_sweeps_are_refused_by_name(guarded_fraction):
    effects = {"compute": ["galois_group"]}
    with pytest.raises(SceneError, match=r"body\.d.*bits"):
        parse_scene({"body": {"p": 3, "d": "1e-10000000"}, "effects": effects})
    with pytest.raises(SceneError, match=r"body\.inertia\[1\]\[2\].*bits"):
        parse_scene({"body": {"inertia": [[2, 0, 0], [0, 1, "1e10000000"], [0, "1e10000000", 3]]}, "effects": effects})
    with pytest.raises(SceneError, match=r"sweep\.p\[1\].*bits"):
        parse_scene({"sweep": {"p": ["3", "1e10000000"], "d": 0.5}, "effects": effects})


def test_bodies_csv_cells_are_refused_by_name(tmp_path, guarded_fraction):
    bodies = tmp_path / "bodies.csv"
    bodies.write_text("I11,I22,I33,I12,I13,I23\n2,1,3,0,0.3,-0.5\n2,1,3,0,1e-10000000,-0.5\n")
    with pytest.raises(SceneError, match=r"row 2, column I13.*bits"):
        parse_scene({"sweep": {"bodies": str(bodies)}, "effects": {"compute": ["galois_group"]}})


def test_the_issue_calls_return_at_once():
    """End to end, in a child process: the hang guard is a generous timeout, not a measurement."""
    script = (
        "from suslov import validated as v\n"
        "from suslov.loader import gf\n"
        "calls = [lambda x: v.galois_group('5/4', 1, x, '-1/2'), lambda x: v.hypergeometric_form('5/4', 1, x, '-1/2'),\n"
        "         lambda x: gf.general_scattering_angle_ball('5/4', 1, x, '-1/2'),\n"
        "         lambda x: v.scattering_angle_enclosure('5/4', 1, x, '-1/2'),\n"
        "         lambda x: v.monodromy('5/4', 1, x, '-1/2', max_seconds=10)]\n"
        "for call in calls:\n"
        "    for x in ('1e10000000', '1e100000000', '1e-1000000000000'):\n"
        "        try:\n"
        "            call(x)\n"
        "        except ValueError as error:\n"
        "            print(str(error)[:4])\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["I13="] * 15


# ------------------------------------------------------------------ 2. the limit, exactly, in lowest terms

def test_the_limit_is_one_documented_constant():
    assert validated.MAX_ENTRY_BITS is validate.MAX_ENTRY_BITS == 20_000
    assert "MAX_ENTRY_BITS" in validate.__doc__ and "MAX_ENTRY_BITS" in validated.hypergeometric_form.__doc__


@pytest.mark.parametrize("value, expected", [
    ("1" + "0" * 5999 + "7", Fraction(10**6000 + 7)),          # 6001 digits: more than int()'s 4300, within the limit
    ("-1e6020", Fraction(-(10**6020))),
    ("5e-6021", Fraction(5, 10**6021)),                         # 10^6021 is beyond, 2^6021 5^6020 is not
    ("0.000_5", Fraction(1, 2000)),
    (" 12/" + "0" * 4000 + "8 ", Fraction(12, 8)),             # a/b: its integers as written
    (2**validate.MAX_ENTRY_BITS - 1, Fraction(2**validate.MAX_ENTRY_BITS - 1)),
    (Fraction(3, 2**validate.MAX_ENTRY_BITS - 1), Fraction(3, 2**validate.MAX_ENTRY_BITS - 1)),
], ids=["6001 digits", "-1e6020", "5e-6021", "0.000_5", "a/b", "2^20000 - 1", "3/(2^20000 - 1)"])
def test_numbers_within_the_limit_are_read_exactly(value, expected):
    bits = max(expected.numerator.bit_length(), expected.denominator.bit_length())
    assert bits <= validate.MAX_ENTRY_BITS
    assert validate.rational("x", value) == expected
    assert validated.hypergeometric_form(2, 1, value, "-1/3").exact == validated.hypergeometric_form(2, 1, expected,
                                                                                                     "-1/3").exact


@pytest.mark.parametrize("value, largest", [   # largest: the integer held to the limit
    ("1e6021", 10**6021),
    ("1e-6021", 10**6021),                                       # 1/10^6021 in lowest terms
    ("1" * 6100 + "/" + "1" * 6100, (10**6100 - 1) // 9),       # a/b (= 1): its integers as written
    (2**validate.MAX_ENTRY_BITS, 2**validate.MAX_ENTRY_BITS),
    (10**7000, 10**7000),
    (Fraction(1, 2**validate.MAX_ENTRY_BITS), 2**validate.MAX_ENTRY_BITS),
], ids=["1e6021", "1e-6021", "a/b", "2^20000", "10^7000", "1/2^20000"])
def test_numbers_beyond_the_limit_are_refused_by_name(value, largest):
    assert largest.bit_length() > validate.MAX_ENTRY_BITS
    for call in (validated.galois_group, gf.general_scattering_angle_ball, gf.general_scattering_angle_mp):
        with pytest.raises(ValueError, match=r"^I23=.*bits.*beyond the 20000 bits"):
            call(2, 1, "3/10", value)


def test_an_mpf_is_exact_where_the_route_is_exact():
    """An mpf is its binary value: within the limit on the exact routes; the mp route takes it as it is."""
    tiny = mpmath.ldexp(3, -validate.MAX_ENTRY_BITS)      # 3/2^20000: the denominator has 20001 bits
    with pytest.raises(ValueError, match=r"^I23=.*20001 bits"):
        validated.galois_group(2, 1, "3/10", tiny)
    assert validated.galois_group(2, 1, "3/10", mpmath.ldexp(3, -100)).group == "SO(3,C)"
    assert validate.rational("x", mpmath.ldexp(3, -100)) == Fraction(3, 2**100)


# ------------------------------------------------------------------ 3. one exception type for bad numbers

@pytest.mark.parametrize("bad, why", [("1/0", "zero denominator"), ("inf", "finite"), ("0.7x", "not a decimal"),
                                      (arb("inf"), "finite"), (arb("nan"), "finite"), (float("nan"), "finite"),
                                      (float("-inf"), "finite"), (mpmath.inf, "finite")],
                         ids=["1/0", "'inf'", "0.7x", "arb inf", "arb nan", "nan", "-inf", "mpf inf"])
def test_bad_numbers_are_value_errors_naming_the_field(bad, why):
    for label, field, call in _each(bad):
        with pytest.raises(ValueError, match=rf"^{field}=.*{why}"):
            call()


@pytest.mark.parametrize("call", [
    lambda x: gf.scattering_angle(x, 0.5),
    lambda x: gf.scattering_angle(2.5, x),
    lambda x: gf.omega(0.5, x, 0.5),
    lambda x: gf.gamma_basis(0.5, 3, x),
    lambda x: gf.first_integral(3, x, 0.1, 0.2, 0.3, 0.4, 0.5),
    lambda x: gf.general_scattering_angle(2.0, 1.0, x, -0.5),
], ids=["angle p", "angle d", "omega p", "gamma_basis d", "first_integral d", "general angle I13"])
@pytest.mark.parametrize("value, why", [(10**1000, "beyond float64"), (Fraction(10**1000, 3), "beyond float64"),
                                        ([0.5, -(10**400)], "beyond float64"), (Fraction(1, 10**400), "0 in float64")],
                         ids=["10**1000", "Fraction", "list", "tiny Fraction"])
def test_float64_routes_refuse_numbers_beyond_float64_by_name(call, value, why):
    with pytest.raises(ValueError, match=why) as caught:
        call(value)
    assert re.match(r"^(p|d|I13)(\[1\])?=", str(caught.value)), str(caught.value)


def test_numpy_scalars_are_the_numbers_they_are():
    # np.int64(3) is 3, np.float32(0.3) its binary value: the same answers as the Python numbers
    f32 = Fraction(*np.float32(0.3).as_integer_ratio())
    assert f32 != Fraction(3, 10)
    assert gf.first_integral_coefficients(3, np.int64(2)) == gf.first_integral_coefficients(3, 2)
    assert validated.hypergeometric_form(np.int64(5), np.int32(4), np.float32(0.3), "-1/2").exact == \
        validated.hypergeometric_form(5, 4, f32, "-1/2").exact
    assert validated.galois_group(np.int64(2), 1, 0, Fraction(-1, 3)).group == "reducible"   # odd p = 3
    ball = gf.general_scattering_angle_ball(np.int64(5), np.int64(4), np.float32(0.3), np.float64(-0.5), prec=100)
    same = gf.general_scattering_angle_ball(5, 4, f32, -0.5, prec=100)
    assert ball.mid() == same.mid() and ball.rad() == same.rad()
    assert gf.scattering_angle_mp(np.float32(2.5), np.int64(1), dps=30) == gf.scattering_angle_mp(2.5, 1, dps=30)
    # I11 = 2, I22 = 1, I13 = 0, I23 = -1/2: d^2 = (I11 - I22)/I22 = 1, p^2 = I22 (I11 - I22)/I23^2 = 4
    enclosure = validated.scattering_angle_enclosure(np.int64(2), 1, 0, np.float16(-0.5), dps=20).angle
    assert contains(enclosure, angle_reference(2, 1))


def contains(ball, reference) -> bool:
    """Whether a python-flint ball contains an mpmath number (midpoint and radius read exactly)."""
    mid, rad = (mpmath.ldexp(int(m), int(e)) for m, e in (ball.mid().man_exp(), ball.rad().man_exp()))
    with mpmath.workdps(60):
        return abs(mid - reference) <= rad + mpmath.mpf(10) ** -55 * abs(reference)


def test_messages_never_print_huge_numbers():
    with pytest.raises(ValueError) as caught:
        validated.galois_group(2, 1, 10**7000, -1)
    assert "about 10^7000" in str(caught.value) and len(str(caught.value)) < 400
    with pytest.raises(ValueError, match=r"^p=<an int of \d+ bits.*odd positive integer"):
        gf.gamma_basis(0.5, 2 * 10**5000, 0.5)


def test_monodromy_near_the_equilibrium_says_unknown_never_overflows():
    """|omega| ~ 1e150: the guard digits were an int too large for a C long (OverflowError)."""
    body = ("5/4", 1, "1e-150", "-1e-150")
    exact = [Fraction(x) for x in body]
    assert exact[2] * exact[3] * (exact[0] - exact[1]) != 0       # u.v != 0: SO(3,C) by Kimura's theorem
    result = validated.monodromy(*body, dps=10, max_seconds=10)
    assert result.verdict == "SO(3,C)" and not result.matrices
    assert any("not integrated" in claim for claim, _, _ in result.certificates)


# ------------------------------------------------------------------ 4. scenes at the ends of float64

def angle_reference(p, d):
    """Theorem 5.4 (corrected), evaluation form, in mpmath at 60 digits for the binary values of p and d."""
    with mpmath.workdps(60):
        p, d = mpmath.mpf(p), mpmath.mpf(d)
        x = mpmath.pi * p / (2 * d)
        s, c = abs(mpmath.sinpi(p / 2)), abs(mpmath.cospi(p / 2))
        return 2 * mpmath.atan2(mpmath.sqrt(s * s * mpmath.sech(x) ** 2 + mpmath.tanh(x) ** 2), c * mpmath.sech(x))


def omega_reference(t, p, d):
    """omega = (p/d) (tanh t, -sqrt(1 + d^2) sech t) at rate 1 (eq:o12, I13 = 0), in mpmath."""
    with mpmath.workdps(60):
        p, d, t = mpmath.mpf(p), mpmath.mpf(d), mpmath.mpf(t)
        return [p / d * mpmath.tanh(t), -p / d * mpmath.sqrt(1 + d * d) * mpmath.sech(t)]


def close(value, reference, relative=1e-14, absolute=0.0) -> bool:
    return abs(mpmath.mpf(value) - reference) <= relative * abs(reference) + absolute


@pytest.mark.parametrize("p, d", [(1e300, 0.5), (2.0, 1e-300), (1e-300, 0.5), (2.0, 1e300), (1e12, 1.0)],
                         ids=["p=1e300", "d=1e-300", "p=1e-300", "d=1e300", "p=1e12"])
def test_extreme_p_and_d_run_where_the_closed_form_answers(p, d):
    result = suslov.simulate({"body": {"p": p, "d": d}, "motion": {"time": [-4.0, 4.0], "samples": 5},
                              "effects": {"compute": ["omega", "scattering_angle", "scattering_angle_enclosure",
                                                      "galois_group"]}})
    reference = angle_reference(p, d)
    assert close(result["scattering_angle"]["radians"], reference, 1e-14, 1e-15)
    ball = result["scattering_angle_enclosure"]
    assert abs(mpmath.mpf(ball["midpoint"]) - reference) <= ball["radius"] + 1e-15 * abs(reference) + 1e-320
    assert result["galois_group"]["verdict"] == "SO(3,C)"     # p is not an odd integer (1e300 is even)
    omega = result["omega"]
    assert np.all(np.isfinite(omega)) and np.all(omega[:, 2] == 0)
    for t, row in zip(np.linspace(-4.0, 4.0, 5), omega):
        w1, w2 = omega_reference(t, p, d)
        assert close(row[0], w1, 1e-13) and close(row[1], w2, 1e-13), (t, row, w1, w2)


def test_odd_p_with_tiny_d_keeps_its_closed_form_basis():
    result = suslov.simulate({"body": {"p": 3, "d": 1e-300}, "motion": {"time": [-2.0, 2.0], "samples": 5},
                              "effects": {"compute": ["gamma", "galois_group", "scattering_angle"]}})
    assert result["galois_group"]["verdict"] == "reducible"           # odd p (Kimura: w_-^2 = -p^2)
    assert result.results["gamma"]["method"] == "closed form gamma_basis"
    gamma = result["gamma"]
    assert np.all(np.isfinite(gamma)) and np.allclose(np.linalg.norm(gamma, axis=-1), 1.0, atol=1e-12)
    assert close(result["scattering_angle"]["radians"], angle_reference(3, 1e-300))


@pytest.mark.parametrize("p, d", [(1e-300, 0.5), (2.0, 1e300)], ids=["p=1e-300", "d=1e300"])
def test_integral_drift_beyond_float64_is_refused_by_name(p, d):
    with pytest.raises(SceneError, match=r"effects\.compute: integral_drift.*beyond float64"):
        parse_scene({"body": {"p": p, "d": d}, "motion": {"time": [-1.0, 1.0]}, "effects": {"compute": ["integral_drift"]}})


def test_a_body_beyond_float64_numerics_is_refused_with_the_reason():
    with pytest.raises(SceneError, match=r"body: p=1e\+300, d=1e-300: p/d .*beyond float64"):
        suslov.simulate({"body": {"p": 1e300, "d": 1e-300}, "motion": {"time": [-1.0, 1.0]},
                         "effects": {"compute": ["scattering_angle"]}})


def test_an_integration_that_cannot_finish_is_refused_before_it_starts():
    with pytest.raises(RuntimeError, match=r"Taylor steps .*not integrated"):
        suslov.simulate({"body": {"p": 1e300, "d": 0.5}, "motion": {"time": [-1.0, 1.0]},
                         "effects": {"compute": ["scattering_angle_integrated"]}})


def test_the_widest_time_window_has_finite_times():
    result = suslov.simulate({"body": {"p": 2.5, "d": 0.5}, "motion": {"time": [-1e308, 1e308], "samples": 5},
                              "effects": {"compute": ["omega"]}})
    t = result["t"]
    assert t[0] == -1e308 and t[-1] == 1e308 and np.all(np.diff(t) > 0)
    for time, row in zip(t, result["omega"]):
        w1, w2 = omega_reference(time, 2.5, 0.5)
        assert close(row[0], w1) and close(row[1], w2, 1e-14, 1e-300)
