"""A ball's display never raises, and shows the number it holds (issue 44: "ball display never raises").

An exact ball of an integer wider than float64's 53 bits raised ``ValueError: man_exp requires an exact,
finite value`` (its midpoint was rounded by ``abs`` before its mantissa was read).  Expected values are the
integers themselves (Python's own decimal printing), not the code under test.
"""
from decimal import Decimal

import pytest
from flint import arb, ctx

from suslov.kernel.display import Ball, ball_digits, ball_fields, ball_text


@pytest.mark.parametrize("n", [12345678901234567890, -98765432109876543210987654321, 2**200 + 1, 10**60])
def test_exact_integer_balls_print_every_digit(n):
    with ctx.workprec(max(64, n.bit_length() + 8)):
        x = arb(n)
    assert x.rad() == 0 and x.mid() == n
    text = ball_text(x)
    assert Decimal(text) == n          # every digit of n, no rounding (read back by Python's decimal module)
    assert repr(Ball(x)) == text and ball_digits(x) >= 17
    assert ball_fields(x)["radius"] == 0.0


@pytest.mark.parametrize("x", [arb(0), arb(2) / 3, arb("1e-400") + arb("+/- 1e-420"), arb("inf"), arb("nan")])
def test_other_balls_print(x):
    assert isinstance(ball_text(x), str) and ball_text(x)
