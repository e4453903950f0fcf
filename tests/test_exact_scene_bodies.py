"""The scene's body, exactly (issue 44): the simulator's exact effects are for the numbers the user wrote.

``galois_group`` and ``scattering_angle_enclosure`` used to read the float, det-normalised paper-frame entries
of the simulator's body as exact numbers: p = 3 came out SO(3,C) and the "rigorous" ball of its angle excluded
pi.  Expected values here come from the paper's theorem, not from the code under test: for I13 = 0 and odd
integer p (p^2 = I22 (I11 - I22)/I23^2) the scattering angle is exactly pi (Theorem 5.4) and the Galois group is
reducible; for u.v != 0 (I13 I23 (I11 - I22) != 0 in the paper's frame) it is SO(3,C); and p^2 not the square of
an odd integer is SO(3,C) (Kimura's criterion, suslov.kernel.kimura).  A float is the binary number it holds.
"""
from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest
from flint import arb, ctx

import suslov
from suslov import validated
from suslov.simulator import exact, sweep
from suslov.simulator.scene import SceneError, load_scene

with mpmath.workdps(60):
    PI50 = mpmath.nstr(+mpmath.pi, 50)   # 50 significant digits of pi, an independent reference


def ball(text: str) -> arb:
    """A printed ball (``arb.str``: an outward-rounded enclosure) read back at 200 bits (the default 53 would widen
    it to 1e-16 and hide what the test is about)."""
    with ctx.workprec(200):
        return arb(text)


def pi_ball() -> arb:
    """A ball around 50 digits of pi (mpmath) of radius 1e-49: it contains pi, and sits inside any ball of the
    simulator's (radius ~1e-25) that contains pi."""
    return ball(f"[{PI50} +/- 1e-49]")


def contains_pi(ball_text: str) -> bool:
    return ball(ball_text).contains(pi_ball())


def one_body(body: dict, effects=("galois_group", "scattering_angle_enclosure")):
    return suslov.simulate({"body": body, "motion": {"time": [-1, 1], "samples": 3},
                            "effects": {"compute": list(effects)}})


def paper_body(p, d) -> tuple:
    """The tensor of the case I13 = 0 with these p, d, from the paper's definitions: I22 = 1,
    d^2 = (I11 - I22)/I22, p^2 = I22 (I11 - I22)/I23^2 (I23 < 0)."""
    p, d = Fraction(p), Fraction(d)
    return 1 + d * d, Fraction(1), Fraction(0), -d / p


def test_pi_reference_is_pi():
    with ctx.workprec(200):
        assert pi_ball().contains(arb.pi())
    assert not contains_pi("[3.141592653589793226620642 +/- 1.35e-25]")     # the old p = 3 ball


@pytest.mark.parametrize("p", [1, 3, 5])
@pytest.mark.parametrize("d", [1, 0.5])
def test_odd_p_is_reducible_and_scatters_by_exactly_pi(p, d):
    """TOML-like numbers (an integer p; d = 1 or the float 0.5, which is exactly 1/2): the simulator says
    reducible, as suslov.validated does on the exact body, and its ball contains pi."""
    result = one_body({"p": p, "d": d})
    group = result["galois_group"]
    assert group["verdict"] == "reducible" and group["liouvillian"] is True
    assert validated.galois_group(*paper_body(p, d)).group == "reducible"
    assert not any(c["outcome"] == "fail" for c in group["certificates"])
    ball = result["scattering_angle_enclosure"]
    assert contains_pi(ball["ball"]), ball
    assert ball["radius"] < 1e-20
    # the result names its body: the exact paper-frame entries, and that they are the numbers as written
    assert ball["entries_paper_frame"] == [str(x) for x in paper_body(p, d)]
    assert "as written" in group["body"]["for"] and "float64 entries" not in group["body"]["for"]


def test_sweep_decides_odd_p_exactly():
    """The same six bodies as a sweep: reducible (0) everywhere, for the point's numbers, and the enclosure's
    body is the exact one."""
    result = suslov.simulate({"sweep": {"p": [1, 3, 5], "d": [1, 0.5]},
                              "effects": {"compute": ["galois_group", "scattering_angle_enclosure"]}}, workers=1)
    assert list(result["galois_group"]) == [0.0] * 6
    assert all("as written" in m for m in result["galois_group_method"])
    assert all(m.endswith("(rigorous)") for m in result["scattering_angle_enclosure_method"])
    body = sweep.point_body({"p": 3.0, "d": 1.0}, "pd", with_exact=True).exact
    assert body.entries == paper_body(3, 1)
    assert exact.enclosure(body, 20).angle.contains(pi_ball())


def test_decimal_strings_are_read_exactly_and_floats_are_their_binary_values(tmp_path):
    """I11 = 2, I22 = 1, I13 = 0, I23 = -1/5 is p = 5: reducible, angle pi.  Written as the decimal string "-0.2"
    that is the body; written as the float -0.2 it is the binary number, p^2 = 1/Fraction(-0.2)^2 is not an
    integer: SO(3,C), and the result says it answers for the float."""
    p2_of_float = 1 / Fraction(-0.2) ** 2
    assert p2_of_float.denominator != 1                 # the theorem's verdict for the float body: not odd p
    scene = tmp_path / "decimal.toml"
    text = ('[body]\ninertia = [[2, 0, 0], [0, 1, {i23}], [0, {i23}, 3]]\n[motion]\ntime = [-1.0, 1.0]\n'
            'samples = 3\n[effects]\ncompute = ["galois_group", "scattering_angle_enclosure"]\n')
    scene.write_text(text.format(i23='"-0.2"'))
    written = suslov.simulate(scene)
    assert written["galois_group"]["verdict"] == "reducible"
    assert contains_pi(written["scattering_angle_enclosure"]["ball"])
    assert written["scattering_angle_enclosure"]["entries_paper_frame"] == ["2", "1", "0", "-1/5"]
    scene.write_text(text.format(i23="-0.2"))
    floats = suslov.simulate(scene)
    assert floats["galois_group"]["verdict"] == "SO(3,C)"
    assert "float64 entries" in floats["galois_group"]["body"]["for"]
    assert "float64" in floats["scattering_angle_enclosure"]["method"]
    enclosure = ball(floats["scattering_angle_enclosure"]["ball"])
    assert enclosure.overlaps(validated.scattering_angle_enclosure(2, 1, 0, -0.2, dps=20).angle)
    assert not enclosure.contains(pi_ball())


def test_general_body_with_decimal_strings_agrees_with_validated():
    """I13 I23 (I11 - I22) != 0: SO(3,C) by Kimura's criterion; the ball agrees with suslov.validated on the
    decimals (closed form and the independent validated integration) and is not the float body's."""
    body = {"inertia": [["1.25", 0, "0.3"], [0, 1, "-0.5"], ["0.3", "-0.5", "1.5"]]}
    result = one_body(body)
    assert result["galois_group"]["verdict"] == "SO(3,C)"
    assert validated.galois_group("1.25", 1, "0.3", "-0.5").group == "SO(3,C)"
    enclosure = ball(result["scattering_angle_enclosure"]["ball"])
    assert enclosure.overlaps(validated.scattering_angle_enclosure("1.25", 1, "0.3", "-0.5", dps=20).angle)
    integrated = validated.scattering_angle_enclosure("5/4", 1, "3/10", "-1/2", dps=10, method="integration").angle
    assert enclosure.overlaps(integrated)
    float_body = validated.scattering_angle_enclosure(1.25, 1.0, 0.3, -0.5, dps=20).angle
    assert not enclosure.overlaps(float_body)       # 0.3 is not 3/10: the old route answered for this body


def test_rotated_odd_p_body_with_irrational_paper_frame():
    """I12 != 0 and the paper's frame irrational: the 2x2 block [[10, 9], [9, 10]] has eigenvalues 19 and 1,
    b = (I13, I23) = (1, -1) is the eigenvector of 1, so in the paper's frame I13 = 0, I23 = -sqrt(2), and
    p^2 = 1 (19 - 1)/2 = 9: odd p = 3, reducible, angle pi."""
    result = one_body({"inertia": [[10, 9, 1], [9, 10, -1], [1, -1, 3]]})
    assert result["galois_group"]["verdict"] == "reducible"
    assert result["galois_group"]["body"]["rational"] is False
    assert contains_pi(result["scattering_angle_enclosure"]["ball"])


def test_rotated_general_body_agrees_with_validated_on_the_rotated_entries():
    """I12 = "0.1" (decimal strings): the simulator encloses the rotation to the paper's frame in balls; the
    reference rotates with mpmath at 60 digits (eigenvectors of the 2x2 block) and asks suslov.validated."""
    rows = [["2", "0.1", "0.2"], ["0.1", "1", "-0.3"], ["0.2", "-0.3", "1.5"]]
    result = one_body({"inertia": rows})
    assert result["galois_group"]["verdict"] == "SO(3,C)"
    with mpmath.workdps(60):
        A = mpmath.matrix([[mpmath.mpf(Fraction(rows[i][j]).numerator) / Fraction(rows[i][j]).denominator
                            for j in range(2)] for i in range(2)])
        b = mpmath.matrix([mpmath.mpf(2) / 10, mpmath.mpf(-3) / 10])
        values, vectors = mpmath.eigsy(A)
        order = [1, 0] if values[1] > values[0] else [0, 1]
        entries = [values[order[0]], values[order[1]], (vectors[:, order[0]].T * b)[0], (vectors[:, order[1]].T * b)[0]]
        entries = [mpmath.nstr(x, 55) for x in entries]
    reference = validated.scattering_angle_enclosure(*entries, dps=20).angle
    assert ball(result["scattering_angle_enclosure"]["ball"]).overlaps(reference)


def test_rational_rotation_gives_exact_entries_and_the_invariant_route_agrees():
    """A block rotated by the rational rotation (cos, sin) = (4/5, 3/5) has rational paper-frame entries: the
    exact body finds them; and the rotation-invariant decision (used when the frame is irrational) agrees with
    suslov.validated on bodies of each kind."""
    c, s = Fraction(4, 5), Fraction(3, 5)

    def rotated(I11, I22, I13, I23):
        a = [[c * c * I11 + s * s * I22, c * s * (I11 - I22)], [c * s * (I11 - I22), s * s * I11 + c * c * I22]]
        b = [c * I13 - s * I23, s * I13 + c * I23]
        return [[a[0][0], a[0][1], b[0]], [a[1][0], a[1][1], b[1]], [b[0], b[1], Fraction(10)]]

    for paper in [(Fraction(2), Fraction(1), Fraction(3, 10), Fraction(-1, 2)),   # general: SO(3,C)
                  paper_body(3, 1), paper_body(4, 1), paper_body(7, Fraction(1, 3)),  # I13 = 0: odd, even, odd p
                  (Fraction(2), Fraction(1), Fraction(-1, 3), Fraction(0))]:        # I23 = 0 (eq:lina)
        body = exact.from_tensor(rotated(*paper))
        assert body.rational
        assert tuple(abs(x) for x in body.entries) == tuple(abs(x) for x in paper)
        expected = validated.galois_group(*paper).group
        assert exact.galois_group(body).group == expected
        invariant = exact.ExactBody(None, body.tensor, "inertia", "test", False)
        assert exact.galois_group(invariant).group == expected
    assert validated.galois_group(*paper_body(7, Fraction(1, 3))).group == "reducible"


@pytest.mark.parametrize("value, message", [('"0.7x"', "not a decimal"), ('"-1/2"', "must be > 0"),
                                            ('"1/0"', "not a decimal")])
def test_bad_decimal_strings_name_the_field(tmp_path, value, message):
    scene = tmp_path / "bad.toml"
    scene.write_text(f'[body]\np = 3\nd = {value}\n[motion]\ntime = [-1.0, 1.0]\n'
                     '[effects]\ncompute = ["galois_group"]\n')
    with pytest.raises(SceneError, match=f"body.d.*{message}"):
        load_scene(scene)


def test_negligible_i13_with_i23_zero_is_the_mirror_case_not_a_division_by_zero():
    """I13 = 1e-9, I23 = 0 (the mirror case I23 = 0 of eq:lina, near but not at the equilibrium) was read as the
    case I13 = 0 and divided by I23 = 0 (ZeroDivisionError, which ended a whole sweep)."""
    import math

    import suslov

    result = suslov.simulate({"body": {"inertia": [[2, 0, 1e-9], [0, 1, 0], [1e-9, 0, 3]]},
                              "motion": {"time": [-1, 1], "samples": 3},
                              "effects": {"compute": ["scattering_angle", "local_behaviour"]}})
    assert math.isfinite(result.results["scattering_angle"]["radians"])
    # exactly: p^2 = I11 (I22 - I11)/I13^2 < 0 in the mirror case: Lambda is not real, the poles branch
    assert result.results["local_behaviour"]["kind"] == "branching"
