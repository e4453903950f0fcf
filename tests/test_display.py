"""Printed precision shows computed precision (issue 26, item 5).

A 30-digit enclosure printed 15 digits; an mp twin at dps = 50 printed 16.  The repr of balls and mp
twins must now show the digits their radius (or working precision) supports: checked by counting
the printed digits against the radius and against an mpmath value at twice the precision.
"""
import re

import mpmath

import suslov as sf
from suslov.validated import scattering_angle_enclosure


def printed_digits(text: str) -> int:
    mantissa = re.search(r"[-+]?\d+\.\d+", text).group(0)
    return len(mantissa.replace("-", "").replace("+", "").replace(".", "").lstrip("0"))


def test_enclosure_prints_the_digits_its_width_supports():
    e = scattering_angle_enclosure("5/4", 1, "3/10", "-1/2", dps=30, method="integration")
    assert e.width < 1e-28
    assert printed_digits(repr(e.angle)) >= 28 and "+/-" in repr(e.angle)
    assert printed_digits(str(e)) >= 28     # the dataclass repr shows the ball too


def test_ball_prints_its_digits():
    ball = sf.scattering_angle_ball(2.5, "0.7", prec=200)
    assert printed_digits(repr(ball)) >= 55


def test_mp_twin_prints_its_dps_and_they_are_right():
    value = sf.scattering_angle_mp(2.5, "0.7", dps=50)
    text = repr(value)
    assert printed_digits(text) == 50
    with mpmath.workdps(100):
        reference = sf.scattering_angle_mp(2.5, "0.7", dps=90)
        assert abs(mpmath.mpf(text) - reference) < mpmath.mpf(10) ** -48
