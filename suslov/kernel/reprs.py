"""Notebook displays of the result objects (issue 47): LaTeX and HTML pieces shared by their ``_repr_*_`` methods.

Jupyter shows an object by its richest display method, as it shows SymPy expressions, mpmath numbers and
pandas tables: ``_repr_latex_`` (one ``$...$`` of valid LaTeX math: ``\\mathrm{SO}(3,\\mathbb{C})``, subscripts
in braces, words in ``\\text{}``; it compiles with amsmath and amssymb) and ``_repr_html_`` (escaped text,
tables).  A ball is shown with the digits its radius supports (:func:`suslov.kernel.display.ball_text`), an
exact ball (radius 0) as the exact decimal it is when that is short, a Fraction as a fraction.  Standard
library and python-flint only, like the rest of the kernel.

>>> ball_latex(arb(1) / 4), ball_html(arb(1) / 3)
('0.25', '[0.33333333333333331 ± 6.04e-17]')
>>> group_latex("SO(3,C)")
'\\\\mathrm{SO}(3,\\\\mathbb{C})'
"""
from __future__ import annotations

import html
import math
import re
from fractions import Fraction

from flint import acb, arb

from suslov.kernel.display import ball_text

__all__ = ["ball_html", "ball_latex", "complex_html", "complex_latex", "enclosure_html", "enclosure_latex", "escape",
           "float_latex", "fraction_latex", "galois_html", "galois_latex", "group_latex", "hypergeometric_html",
           "hypergeometric_latex", "local_latex", "monodromy_html", "monodromy_latex", "sqrt_term_latex", "table_html",
           "text_latex"]

escape = html.escape
_EXACT_PLACES = 30        # an exact dyadic ball with at most this many decimal places is printed exactly
_SCIENTIFIC = re.compile(r"(\d+(?:\.\d*)?)e([+-]?)(\d+)")
_GROUP = re.compile(r"\b(SO|SL|GL|PSL|O)\((\d),\s*C\)")
_LATEX_SPECIAL = {"\\": r"\textbackslash{}", "{": r"\{", "}": r"\}", "$": r"\$", "&": r"\&", "#": r"\#",
                  "%": r"\%", "_": r"\_", "^": r"\^{}", "~": r"\~{}"}


def float_latex(value: float, digits: int = 3) -> str:
    """A float in LaTeX math at ``digits`` significant digits (``2.2\\cdot 10^{-40}``, ``\\infty``)."""
    if math.isinf(value):
        return r"\infty" if value > 0 else r"-\infty"
    if math.isnan(value):
        return r"\mathrm{NaN}"
    return _scientific_latex(f"{value:.{digits}g}")


def _scientific_latex(text: str) -> str:
    """``2.20e-40`` -> ``2.20\\cdot 10^{-40}`` everywhere in ``text``."""
    return _SCIENTIFIC.sub(lambda m: f"{m.group(1)}\\cdot 10^{{{'-' if m.group(2) == '-' else ''}{int(m.group(3))}}}",
                           text)


def _signed(term: str) -> str:
    """`` + term`` or `` - |term|`` (a term that may start with a minus sign)."""
    return f" - {term[1:]}" if term.startswith("-") else f" + {term}"


def _exact_decimal(x: arb) -> str | None:
    """The exact decimal of an exact ball (radius 0) when it has at most ``_EXACT_PLACES`` places, else None."""
    if not x.is_exact() or not x.is_finite():
        return None
    mantissa, exponent = (int(v) for v in x.man_exp())
    if exponent >= 0:
        value = mantissa << exponent
        return str(value) if value.bit_length() <= 200 else None
    places = -exponent
    if places > _EXACT_PLACES:
        return None
    digits = str(abs(mantissa) * 5**places).rjust(places + 1, "0")   # m / 2^k = m 5^k / 10^k
    text = (digits[:-places] + "." + digits[-places:]).rstrip("0").rstrip(".")
    return ("-" if mantissa < 0 else "") + text


def _text(x: arb) -> str:
    if x.is_zero():
        return "0"
    exact = _exact_decimal(x)
    if exact is not None:
        return exact
    try:
        return ball_text(x)
    except ValueError:   # ball_digits of an exact ball whose midpoint has more bits than the context's precision
        return x.str(radius=True)


def ball_latex(x: arb) -> str:
    """A real ball in LaTeX math: ``[2.959144176500328520 \\pm 2.20\\cdot 10^{-40}]``, or the exact number."""
    return _scientific_latex(_text(arb(x)).replace("+/-", r"\pm"))


def ball_html(x: arb) -> str:
    """A real ball as escaped text: ``[2.959144176500328520 ± 2.20e-40]``, or the exact number."""
    return escape(_text(arb(x)).replace("+/-", "±"))


def _parts(z):
    z = acb(z)
    return z.real, z.imag


def complex_latex(z) -> str:
    """A complex ball ``a + b i`` in LaTeX math (an exactly zero part left out)."""
    re_part, im_part = _parts(z)
    if im_part.is_zero():
        return ball_latex(re_part)
    imaginary = {"1": "i", "-1": "-i"}.get(ball_latex(im_part), ball_latex(im_part) + r"\,i")
    return imaginary if re_part.is_zero() else ball_latex(re_part) + _signed(imaginary)


def complex_html(z) -> str:
    """A complex ball ``a + b i`` as escaped text (an exactly zero part left out)."""
    re_part, im_part = _parts(z)
    if im_part.is_zero():
        return ball_html(re_part)
    imaginary = {"1": "i", "-1": "-i"}.get(ball_html(im_part), ball_html(im_part) + " i")
    return imaginary if re_part.is_zero() else ball_html(re_part) + _signed(imaginary)


def fraction_latex(q) -> str:
    """An exact rational in LaTeX math: ``-\\frac{9}{4}``, ``3``."""
    q = Fraction(q)
    if q.denominator == 1:
        return str(q.numerator)
    sign = "-" if q < 0 else ""
    return f"{sign}\\frac{{{abs(q.numerator)}}}{{{q.denominator}}}"


def sqrt_term_latex(q, radicand) -> str:
    """``q sqrt(R)`` (q, R rationals) in LaTeX math, as the kernel keeps the imaginary part of ``w_-^2``."""
    q, radicand = Fraction(q), Fraction(radicand)
    if q == 0:
        return "0"
    if radicand == 1:
        return fraction_latex(q)
    return f"{fraction_latex(q)}\\sqrt{{{fraction_latex(radicand)}}}"


def text_latex(words: str) -> str:
    """Prose inside LaTeX math: ``\\text{...}`` with TeX's special characters escaped."""
    return r"\text{" + "".join(_LATEX_SPECIAL.get(c, c) for c in words) + "}"


def group_latex(words: str) -> str:
    """A group verdict in LaTeX math: ``SO(3,C)`` as ``\\mathrm{SO}(3,\\mathbb{C})``, the words around it in
    ``\\text{}`` (``imprimitive (normaliser of a torus)``)."""
    pieces, last = [], 0
    for match in _GROUP.finditer(words):
        if match.start() > last:
            pieces.append(text_latex(words[last:match.start()]))
        pieces.append(f"\\mathrm{{{match.group(1)}}}({match.group(2)},\\mathbb{{C}})")
        last = match.end()
    if last < len(words):
        pieces.append(text_latex(words[last:]))
    return "".join(pieces)


def table_html(rows, header=None) -> str:
    """An HTML table of already escaped cells (``rows``: sequences of strings)."""
    head = "<tr>" + "".join(f"<th style='text-align:left'>{h}</th>" for h in header) + "</tr>" if header else ""
    body = "".join("<tr>" + "".join(f"<td style='text-align:left'>{c}</td>" for c in row) + "</tr>" for row in rows)
    return f"<table>{head}{body}</table>"


# --- the differential Galois group (suslov.kernel.kimura.GaloisGroup) -------------------------------------------

def _group_verdict_latex(group: str) -> str:
    if group == "reducible":
        return (r"\mathrm{SO}(2,\mathbb{C})\ " + text_latex("(reducible: the torus of rotations about ")
                + r"n = u/|u|" + text_latex(")"))
    if group in ("unknown", "imprimitive", "finite"):
        return text_latex(group if group != "unknown" else "undecided")
    return group_latex(group)


def _liouvillian_words(liouvillian) -> str:
    return {True: "Liouvillian", False: "not Liouvillian"}.get(liouvillian, "Liouvillian: undecided")


def galois_latex(g) -> str:
    """``$\\mathrm{Gal}_{\\mathbb{C}(e^t)} = \\mathrm{SO}(3,\\mathbb{C});\\ \\text{not Liouvillian}; ...$``"""
    parts = [r"\mathrm{Gal}_{\mathbb{C}(e^t)} = " + _group_verdict_latex(g.group), text_latex(_liouvillian_words(g.liouvillian))]
    if g.P is not None:
        parts.append(f"w_-^2 = -{g.P}^2")
    parts.append(text_latex("spinor lift over ") + r"\mathbb{C}(\sinh t)\text{: }" + group_latex(g.spinor_group))
    return "$" + r";\ ".join(parts) + "$"


def galois_html(g) -> str:
    """The verdict first (the group, Liouvillian or not), then why and how (as LocalBehaviour's display)."""
    torus = " (the torus SO(2,C))" if g.group == "reducible" else ""
    return (f"<b>{escape(g.group)}</b>{escape(torus)}, {escape(_liouvillian_words(g.liouvillian))}: "
            f"{escape(g.reason)}<br><small>the differential Galois group of the Poisson equations over C(e^t); spinor "
            f"lift over C(sinh t): {escape(g.spinor_group)}; method: {escape(g.method)}</small>")


# --- meromorphic, logarithmic or branching at the poles (suslov.kernel.local_behaviour.LocalBehaviour) -------------

def local_latex(b) -> str:
    """``$\\text{meromorphic at every pole of } \\omega;\\ \\Lambda = 3\\ \\text{(odd)};\\ \\text{exponents } 0, \\pm 3$``"""
    real, (q, radicand) = b.lambda_squared
    if b.Lambda is not None:
        value = f"\\Lambda = {b.Lambda}\\ " + text_latex("(odd)" if b.Lambda % 2 else "(even)")
        exponents = f"0, \\pm {b.Lambda}" if b.Lambda else "0, 0, 0"
    else:
        imaginary = sqrt_term_latex(q, radicand)
        square = fraction_latex(real) + ("" if imaginary == "0" else _signed(imaginary) + r"\,i")
        value = f"\\Lambda^2 = {square},\\ \\Lambda \\notin \\mathbb{{Z}}"
        exponents = r"0, \pm\Lambda" if imaginary == "0" else r"0, \pm\overline{\Lambda}"
    return ("$" + text_latex(f"{b.kind} at every pole of ") + r"\omega;\ " + value + r";\ "
            + text_latex("exponents at a pole ") + exponents + "$")


# --- Gauss's equation of a body (suslov.validated.HypergeometricForm) ----------------------------------------------

_POINT_LATEX = {"s=i": r"s = i", "s=-i": r"s = -i", "s=oo": r"s = \infty"}
_DIFFERENCE_LATEX = {"s=i": r"\kappa", "s=-i": r"\mu", "s=oo": r"iU"}


def hypergeometric_latex(f) -> str:
    """Gauss's equation, A, B, C, the exponent differences and (exact input) the invariants, as aligned math."""
    rows = [r"& z(1-z)F'' + \bigl(C - (A+B+1)z\bigr)F' - AB\,F = 0,\quad z = \tfrac{1 + i s}{2},\ s = \sinh t",
            rf"& A = {complex_latex(f.A)},\quad B = {complex_latex(f.B)},\quad C = {complex_latex(f.C)}",
            r"& " + r",\quad ".join(f"{_DIFFERENCE_LATEX[k]} = {complex_latex(v)}\\ ({_POINT_LATEX[k]}, z = {f.points[k]})"
                                     .replace("z = oo", r"z = \infty") for k, v in f.exponent_differences.items())]
    if f.exact:
        q, radicand = f.exact["Im w_-^2"]
        rows.append(rf"& U^2 = {fraction_latex(f.exact['U^2'])},\quad "
                    rf"\operatorname{{Re}} w_-^2 = {fraction_latex(f.exact['Re w_-^2'])},\quad "
                    rf"\operatorname{{Im}} w_-^2 = {sqrt_term_latex(q, radicand)}\quad " + text_latex("(exact)"))
    return r"$\begin{aligned}" + r"\\ ".join(rows) + r"\end{aligned}$"


def hypergeometric_html(f) -> str:
    rows = [[f"<b>{name}</b>", complex_html(value)] for name, value in (("A", f.A), ("B", f.B), ("C", f.C))]
    names = {"s=i": "κ", "s=-i": "μ", "s=oo": "iU"}
    rows += [[f"{names[k]} (exponent difference at {escape(k)}, z = {escape(str(f.points[k]))})", complex_html(v)]
             for k, v in f.exponent_differences.items()]
    if f.exact:
        q, radicand = f.exact["Im w_-^2"]
        rows += [["U<sup>2</sup> (exact)", escape(str(f.exact["U^2"]))],
                 ["Re w<sub>-</sub><sup>2</sup> (exact)", escape(str(f.exact["Re w_-^2"]))],
                 ["Im w<sub>-</sub><sup>2</sup> (exact)", escape(f"{q} sqrt({radicand})" if q else "0")]]
    return ("<b>Gauss's equation</b> z(1-z)F'' + (C - (A+B+1)z)F' - AB F = 0, z = (1 + i s)/2, s = sinh t"
            + table_html(rows, ["", "value (ball)"]))


# --- the scattering angle as a ball (suslov.kernel.enclosure.AngleEnclosure) ----------------------------------------

def _enclosure_method(e) -> str:
    if "closed_form" in e.error_budget:
        return f"the certified closed form of every body in ball arithmetic, {e.prec} bits"
    s0, s1 = e.window
    return (f"validated integration: {e.steps} Taylor steps of order {e.order} on s in [{float(s0):.3g}, "
            f"{float(s1):.3g}], limit series beyond, {e.prec} bits")


def enclosure_latex(e) -> str:
    """``$\\Delta\\psi \\in [\\dots \\pm \\dots]\\ \\text{rad}; \\cos\\Delta\\psi \\in \\dots; \\text{width } \\dots$``"""
    return (rf"$\Delta\psi \in {ball_latex(e.angle)}\ \text{{rad}};\ \cos\Delta\psi \in {ball_latex(e.cos_angle)};\ "
            + text_latex("width ") + float_latex(e.width) + r";\ " + text_latex(_enclosure_method(e)) + "$")


def enclosure_html(e) -> str:
    return (f"<b>Δψ ∈ {ball_html(e.angle)}</b> rad (width {e.width:.3g}); cos Δψ ∈ {ball_html(e.cos_angle)}"
            f"<br><small>rigorous: {escape(_enclosure_method(e))}</small>")


# --- monodromy and the group it certifies (suslov.kernel.monodromy.Monodromy) ---------------------------------------

_LOOP_LATEX = {"x=0": "0", "x=i": "i", "x=-i": "-i", "x=oo": r"\infty"}


def _outcomes(certificates) -> str:
    counts = {}
    for _, outcome, _ in certificates:
        counts[outcome] = counts.get(outcome, 0) + 1
    return ", ".join(f"{n} {o}" for o, n in counts.items()) or "none"


def monodromy_latex(m) -> str:
    rows = [r"& \mathrm{Gal} = " + _group_verdict_latex(m.verdict) + r";\ " + text_latex(_liouvillian_words(m.liouvillian)),
            r"& " + text_latex("monodromy of the Poisson equations in ") + r"x = e^t"
            + text_latex(" about ") + ", ".join(f"x = {_LOOP_LATEX.get(k, text_latex(k))}" for k in m.matrices)
            + text_latex(" (base ") + "x = 1/2" + text_latex(")")]
    if m.exponents:
        rows.append(r"& " + r",\quad ".join(f"\\rho_{{{_LOOP_LATEX.get(k, text_latex(k))}}} = {complex_latex(e[1])}"
                                            for k, e in m.exponents.items())
                    + r"\quad" + text_latex(" (exponents ") + r"0, \pm\rho" + text_latex(")"))
    radius = (text_latex("largest radius ") + float_latex(m.radius)) if m.matrices else text_latex("no matrices")
    rows.append(r"& " + radius + r",\ " + text_latex(f"{m.digits} digits asked, guard {m.guard};  certificates: "
                                                       f"{_outcomes(m.certificates)}"))
    return r"$\begin{aligned}" + r"\\ ".join(rows) + r"\end{aligned}$"


def _midpoint(z) -> str:
    """A complex ball's midpoint at 12 significant digits (the radius is shown once per matrix)."""
    re_part, im_part = (x.mid() for x in _parts(z))
    real = "0" if re_part.is_zero() else re_part.str(12, radius=False)
    if im_part.is_zero():
        return real
    imaginary = im_part.str(12, radius=False)
    return f"{real} {'-' if imaginary.startswith('-') else '+'} {imaginary.lstrip('-')} i"


def _matrix_html(matrix) -> str:
    return table_html([[escape(_midpoint(matrix[r, c])) for c in range(matrix.ncols())] for r in range(matrix.nrows())])


def monodromy_html(m) -> str:
    certificates = table_html([[escape(claim), f"<b>{escape(outcome)}</b>", escape(detail)]
                               for claim, outcome, detail in m.certificates], ["claim", "outcome", "detail"])
    exponents = "; ".join(f"{escape(k)}: ±{complex_html(e[1])}" for k, e in m.exponents.items())
    matrices = "".join(f"<p>M({escape(k)}), midpoints:</p>{_matrix_html(v)}" for k, v in m.matrices.items())
    radius = f"largest radius {m.radius:.3g}" if m.matrices else "no matrices"
    return (f"<b>{escape(m.verdict)}</b>, {escape(_liouvillian_words(m.liouvillian))} (monodromy about x = 0, ±i, ∞ of "
            f"the Poisson equations in x = e^t, base x = 1/2; {radius}, {m.digits} digits asked, guard {m.guard})"
            f"<br>exponents 0, ±ρ: {exponents}{certificates}"
            f"<details><summary>matrices (12 digits of each ball's midpoint; radii at most the largest radius)</summary>"
            f"{matrices}</details>")
