"""The figures of the formulas document (issue 46): right data, the same bytes at every build, drawn with
``texlive-latex-base`` alone, in the PDF.

The data (:mod:`derivations.output.figures`) come from the build's emitted functions; here they are checked
against independent routes evaluated at 50 digits in mpmath at every plotted point: Theorem 5.4's closed form
``cos(Delta psi/2) = |cos(pi p/2)|/cosh(pi p/(2d))`` for the first figure, the general closed form from the
inertia entries (``u``, ``v`` of the general solution, ``w_-``, ``tau``) for the second, the rule "odd ``p``:
Liouvillian and meromorphic, even: logarithms, else branching" for the map.  The figure file renders to the
same bytes twice (caches cleared between), uses only ``picture`` rules, boxes and dots (no font-drawn circles,
vectors or slopes that need pict2e), and the compiled document shows the three captions, with no layout problem
and no prose-lint finding in a document of the figures and the notation alone.
"""
import itertools
import re
from fractions import Fraction

import mpmath
import pytest
from conftest import require_tools

from derivations.output import figures, pdf
from derivations.output.pipeline import context, render_into
from derivations.output.render import render

WRAPPER = ("\\documentclass[10pt,a4paper]{article}\n\\usepackage[a4paper,margin=2cm]{geometry}\n"
           "\\input{suslov-preamble}\n\\begin{document}\n\\input{notation}\n\\input{figures}\n\\end{document}\n")


@pytest.fixture(scope="module")
def ctx(default_build):
    return context(default_build)


@pytest.fixture(scope="module")
def by_key(ctx):
    found = {fig.key: fig for fig in ctx["figures"]}
    assert list(found) == ["angle", "general_angle", "decisions"]
    return found


def _theorem_54(p, d):
    with mpmath.workdps(50):
        p, d = mpmath.mpf(p), mpmath.mpf(Fraction(d).numerator) / Fraction(d).denominator
        return 2 * mpmath.acos(abs(mpmath.cospi(p / 2)) / mpmath.cosh(mpmath.pi * p / (2 * d)))


def _general(I11, I22, I13, I23):
    """The angle of every body from its definition's closed form (formula general_angle), at 50 digits."""
    with mpmath.workdps(50):
        I11, I22, I13, I23 = (mpmath.mpf(Fraction(x).numerator) / Fraction(x).denominator for x in (I11, I22, I13, I23))
        r, D = mpmath.sqrt(I11 * I22), I11 * I23**2 + I13**2 * I22
        u = (-I11 * I22 * I23 / D, I11 * I13 * I22 / D)           # omega = u tanh t + v sech t (eq:o12)
        v = (I13 * I22 * r / D, I11 * I23 * r / D)
        w = mpmath.sqrt(sum((a - 1j * b) ** 2 for a, b in zip(u, v)))
        U = mpmath.sqrt(u[0] ** 2 + u[1] ** 2)
        tau = 2 * mpmath.cos(mpmath.pi * 0.5j * w)
        c2 = (mpmath.cosh(mpmath.pi * U) * abs(tau) ** 2 - mpmath.re(tau**2)) / (2 * mpmath.sinh(mpmath.pi * U) ** 2)
        return 2 * mpmath.acos(mpmath.sqrt(c2))


def _dots(curve):
    return [tuple(map(float, m)) for line in curve.lines for m in re.findall(r"\\figdot\(([-\d.]+),([-\d.]+)\)", line)]


def test_scattering_angle_figure_agrees_with_theorem_54(by_key):
    fig = by_key["angle"]
    assert [c.label for c in fig.curves] == ["d=1/2", "d=1", "d=2", "d=4"]
    for curve, d in zip(fig.curves, figures.ANGLE_D):
        assert 150 <= len(curve.x) <= 600, len(curve.x)
        assert curve.x[0] == 0.0 and curve.x[-1] == 6.0
        for p, value in zip(curve.x, curve.y):
            assert abs(value - _theorem_54(p, d)) < 1e-12, (d, p)
        dots = _dots(curve)
        assert len(dots) == len(curve.x)
        for (X, Y), p, value in zip(dots, curve.x, curve.y):
            assert abs(X - p / 6 * figures.WIDTH) <= 0.051 and abs(Y - value / mpmath.pi * figures.HEIGHT) <= 0.051
        gaps = [((a - c) ** 2 + (b - e) ** 2) ** 0.5 for (a, b), (c, e) in itertools.pairwise(dots)]
        assert max(gaps) <= figures.GAP + 0.15                       # a curve of dots, no holes
    # odd p marked, at Delta psi = pi (the squares' lower-left corners are 2 pt off the point)
    assert [tuple(map(float, m.split(","))) for m in fig.markers] == \
        [(round(p / 6 * figures.WIDTH - 2, 1), round(figures.HEIGHT - 2, 1)) for p in (1, 3, 5)]


def test_general_angle_figure_agrees_with_the_closed_form(by_key):
    fig = by_key["general_angle"]
    assert [c.label for c in fig.curves] == ["I_{13}=0", "I_{13}=1/10", "I_{13}=1/2"]
    for curve, I13 in zip(fig.curves, figures.GENERAL_I13):
        assert 100 <= len(curve.x) <= 600
        step = max(1, len(curve.x) // 60)          # 60 points a curve at 50 digits (the route is the same at each)
        for I23, value in list(zip(curve.x, curve.y))[::step]:
            assert abs(value - _general(5, 1, I13, I23)) < 1e-12, (I13, I23)
            if I13 == 0:                             # Theorem 5.4 with d = 2, p = -2/I23
                assert abs(value - _theorem_54(-2 / I23, 2)) < 1e-12
    assert len(fig.markers) == 4                   # p = 1, 3, 5, 7 on I13 = 0


def test_decision_map_agrees_with_the_rule(by_key):
    fig = by_key["decisions"]
    assert len(fig.cells) == 3 * 64
    expected = []
    for I13 in figures.GENERAL_I13:
        for xi in figures.MAP_XI:
            if I13 == 0 and xi.denominator == 1:
                expected.append("figgreen" if xi.numerator % 2 else "figorange")
            else:
                expected.append("figgrey")
    assert [cell[3] for cell in fig.cells] == expected
    assert expected.count("figgreen") == 4 and expected.count("figorange") == 4
    assert [colour for colour, _ in fig.legend] == ["figgreen", "figorange", "figgrey"]
    with pytest.raises(ValueError):                                   # the equilibrium I13 = I23 = 0
        figures.decision(5, 1, 0, 0)


def test_figure_file_is_deterministic_and_small(ctx, default_build):
    first = render("figures.tex.j2", ctx)
    for cached in (figures.angle_figure, figures.general_angle_figure, figures.decisions):
        cached.cache_clear()
    again = context(default_build)                                    # the whole context, figures computed anew
    assert render("figures.tex.j2", again) == first
    assert len(first.encode()) < 80_000, len(first.encode())


def test_figure_file_needs_latex_base_only(ctx):
    source = render("figures.tex.j2", ctx)
    assert "\\usepackage" not in source and "tikz" not in source.lower() and "pgf" not in source.lower()
    for command in ("\\circle", "\\vector", "\\oval", "\\qbezier", "\\includegraphics"):
        assert command not in source, command
    slopes = set(re.findall(r"\\line\((-?\d+),(-?\d+)\)", source))
    assert slopes <= {("1", "0"), ("0", "1"), ("0", "-1"), ("-1", "0")}, slopes    # lines TeX sets as rules
    keys = re.findall(r"\\certkey\{([^}]*)\}", source)
    certified = {c["key"] for c in ctx["certificates"]}
    assert keys and {k.replace("\\_", "_") for k in keys} <= certified


def test_pdf_shows_the_figures(default_build, tmp_path):
    require_tools(*("pdflatex", "pdftotext", "pdftohtml"))
    from derivations.output.prose_lint import findings

    tree = tmp_path / "tree"
    tree.mkdir()
    render_into(default_build, tree)
    assert r"\input{figures}" in (tree / "suslov_formulas.tex").read_text(encoding="utf-8")
    compiled = pdf.compile_pdfs(tree, tmp_path / "pdf")
    text = pdf.pdf_text(compiled[0])
    for caption in ("Figure 1: The scattering angle", "Figure 2: The scattering angle of every body",
                    "Figure 3: The differential Galois"):
        assert caption in text, caption
    contents = text.split("Contents")[1].split("References")[0]
    assert "Figures: the scattering angle and the exact decisions" in contents and "Notation" in contents
    log = compiled[0].with_suffix(".log").read_text(encoding="latin-1")
    assert pdf.layout_problems(log) == [] and "Underfull" not in log
    alone = tree / "standalone-figures.tex"
    alone.write_text(WRAPPER, encoding="utf-8")
    parts = pdf.compile_document(tree, alone, tmp_path / "pdf")
    assert findings(parts) == []                                    # the prose of the index and the captions
    assert pdf.layout_problems(parts.with_suffix(".log").read_text(encoding="latin-1")) == []
