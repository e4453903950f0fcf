"""Publication typesetting (derivations/core/typeset.py): unambiguous notation and line breaking."""
import re

import sympy as sp

from derivations.core.typeset import (
    LINE_WIDTH,
    break_sum,
    breakable_product,
    clauses,
    latex,
    visible_width,
)

t, d, c, w1, w2 = sp.symbols("t d c omega_1 omega_2")
T, S = sp.tanh(t), sp.sech(t)


def test_function_powers_are_written_on_the_name():
    assert latex(T**2) == r"\tanh^{2} t"
    assert latex(S**3 * T) == r"\operatorname{sech}^{3} t \tanh t"
    assert r"\tanh t^{2}" not in latex(4 * d**2 * T**2 - 3)


def test_nothing_follows_a_bare_function_argument():
    assert latex(S * d) == r"d \operatorname{sech} t"                         # not "sech t d" = sech(td)
    assert latex(T * (d**2 - 1)) == r"\left(d^{2} - 1\right) \tanh t"          # not "tanh t d^2 - 1"
    assert latex(-S / c) == r"- \frac{\operatorname{sech} t}{c}"
    for expr in (S * d, T * (d**2 - 1), 3 * d * S * T**2, S * d / (c * (d**2 + 9))):
        text = latex(expr)
        # after "\tanh t" or "\operatorname{sech} t" only another function, the end, or a closing brace may follow
        for match in re.finditer(r"(\\tanh|\\operatorname\{sech\})(\^\{\d+\})? t", text):
            rest = text[match.end():].lstrip()
            assert rest == "" or rest.startswith(("}", r"\tanh", r"\operatorname{sech}")), text


def test_long_sums_are_broken_at_terms_within_the_line():
    expr = sp.expand((w1 + 2 * w2 + d + 3 * c) ** 5)
    text = break_sum("P", expr)
    assert text.startswith(r"\begin{aligned}P={}&") and text.endswith(r"\end{aligned}")
    rows = text[len(r"\begin{aligned}P={}&"):-len(r"\end{aligned}")].split(r"\\&")
    assert len(rows) > 3
    assert all(visible_width(row) <= LINE_WIDTH for row in rows)
    # the rows, joined, are exactly the printed sum: no term lost, none repeated
    assert "".join(rows).replace(" ", "") == latex(expr).replace(" ", "")


def test_short_rows_are_left_alone_and_factored_products_open_up():
    assert break_sum("a_0", w1 * (d**2 + 1)) == r"a_0=\omega_{1} \left(d^{2} + 1\right)"
    long_factor = sp.expand((w1 + w2 + d + c + 1) ** 4)
    text = break_sum("a_3", -d * w2**2 * long_factor)
    assert text.startswith(r"\begin{aligned}a_3={}&- d \omega_{2}^{2}\Big(") and r"\Big)\end{aligned}" in text


def test_clauses_split_only_when_too_wide_and_only_at_depth_zero():
    short = r"F_1=a,\quad F_2=b"
    assert clauses(short) == [short]
    wide = r"\frac{x,\quad y}{z}" + "+x" * 60 + r",\quad " + "y+" * 40 + "y"
    rows = clauses(wide)
    assert len(rows) == 2 and rows[0].endswith(",") and rows[0].startswith(r"\frac{x,\quad y}{z}")


def test_breakable_products_wrap_between_polynomial_factors():
    text = breakable_product(-49 * (d**2 + 49) * (4 * d**2 + 49) / (1061683200 * d**15))
    assert text == (r"- \frac{49}{1061683200 d^{15}}\,\left(d^{2} + 49\right)\allowbreak \left(4 d^{2} + 49\right)")
    assert breakable_product((-2 * d**2 - 8) / d**5) == r"- \frac{2}{d^{5}}\,\left(d^{2} + 4\right)"
