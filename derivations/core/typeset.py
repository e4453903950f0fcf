"""Publication typesetting of the derived formulas (issue 14: a document researchers paste from).

Two concerns, both structural (no string surgery on printed LaTeX):

* **Unambiguous notation.**  :class:`FormulaPrinter` is SymPy's ``LatexPrinter`` with two rules
  for the elementary functions of one symbol (``tanh t``, ``sech t``, ``cos t``, ...): powers are
  written on the function name (``\\tanh^{2} t``, never ``\\tanh t^{2}``), and in a product the
  function factors come last (``d \\operatorname{sech} t``, never ``\\operatorname{sech} t d``, which
  reads as sech(td)), so nothing follows a bare argument.  The closed forms of eq:o12 / c's and the
  bases of Theorem 4.3 (``meromorphic``) are printed with it.

* **Line breaking.**  :func:`display` turns a formula given as rows (strings, or ``(lhs, expr)``
  pairs) into the body of a ``gather*`` environment: each row on its own line, and a row whose
  estimated width exceeds the text width is broken at the top-level terms of its sum (an
  ``aligned`` block with ``lhs ={}&`` and continuation lines ``&+ ...``), inside parentheses
  and fractions as a last resort (``\\frac{1}{D}\\Big(...\\Big)``).  The width estimate
  (:func:`visible_width`) counts what TeX sets, not the source; the compile test of the
  document (``tests/test_latex.py``: no overfull box over 1 pt) is what certifies the layout.
"""
from __future__ import annotations

import re

import sympy as sp
from sympy.printing.latex import LatexPrinter
from sympy.printing.precedence import PRECEDENCE

# Text width of the formulas document (A4, 2 cm margins, 10 pt) in the units of
# visible_width (calibrated on the compiled document: 483 pt is about 80 units).
LINE_WIDTH = 76

_NAMES = {"tanh": r"\tanh", "sech": r"\operatorname{sech}", "cosh": r"\cosh", "sinh": r"\sinh",
          "cos": r"\cos", "sin": r"\sin", "tan": r"\tan", "exp": r"\exp"}


def _function_of_symbol(expr) -> bool:
    return isinstance(expr, sp.Function) and type(expr).__name__ in _NAMES and len(expr.args) == 1 \
        and expr.args[0].is_Symbol


def _trailing(factor) -> bool:
    """A factor printed as ``\\tanh^{k} t``: it must come last in a product."""
    base = factor.base if factor.is_Pow and factor.exp.is_Integer and factor.exp > 0 else factor
    return _function_of_symbol(base)


class FormulaPrinter(LatexPrinter):
    """LaTeX with function powers on the name and function factors last in a product."""

    def _print_Function(self, expr, exp=None):
        if _function_of_symbol(expr):
            name = _NAMES[type(expr).__name__]
            power = f"^{{{exp}}}" if exp is not None else ""
            return f"{name}{power} {self._print(expr.args[0])}"
        return super()._print_Function(expr, exp)

    def _print_Mul(self, expr):
        if not any(_trailing(f) for f in expr.args):
            return super()._print_Mul(expr)
        if expr.could_extract_minus_sign():
            return "- " + self._print(-expr)
        numerator, denominator = sp.fraction(expr)
        if denominator != 1:
            return r"\frac{%s}{%s}" % (self._print(numerator), self._print(denominator))
        functions = [f for f in expr.args if _trailing(f)]
        rest = sp.Mul(*[f for f in expr.args if not _trailing(f)])
        tail = " ".join(self._print(f) for f in functions)
        if rest == 1:
            return tail
        return self.parenthesize(rest, PRECEDENCE["Mul"], strict=True) + " " + tail


def latex(expr) -> str:
    """LaTeX of a SymPy expression with the conventions above."""
    return FormulaPrinter().doprint(sp.sympify(expr))


_COMMAND = re.compile(r"\\(left|right|Big|big|Bigg|bigg|operatorname|mathcal|mathrm|displaystyle|,|;|!)(?![a-zA-Z])")
_SPACE_COMMAND = re.compile(r"\\(quad|qquad)(?![a-zA-Z])")
_NAMED_COMMAND = re.compile(r"\\[a-zA-Z]+")


def visible_width(tex: str) -> float:
    """Rough width of typeset math, in units of about 6 pt (a math-italic letter with its spacing).

    Binary operators and relations count with their spacing, scripts at 70 %, a fraction
    as its longer part; an estimate for choosing break points, checked by the compile test.
    """
    text = _SPACE_COMMAND.sub(lambda m: "  " if m.group(1) == "quad" else "    ", tex)
    text = _COMMAND.sub("", text)
    text = _NAMED_COMMAND.sub("x", text)      # \omega, \tanh, ... as about one glyph
    width, script = 0.0, False
    for ch in text:
        if ch in "{}":
            continue
        if ch in "^_":
            script = True
            continue
        unit = 2.2 if ch in "+-=<>" else 0.6 if ch in ",;. " else 1.0
        width += 0.7 * unit if script else unit
        script = script and ch not in " +-=,"
    return width * (0.72 if r"\frac" in tex else 1.0)


def _signed(printer: FormulaPrinter, term, first: bool) -> str:
    text = printer._print(term)
    if first or text.startswith("-"):
        return text
    return "+ " + text


def break_sum(lhs: str, expr, width: float = LINE_WIDTH) -> str:
    """``lhs = expr``, broken after whole terms of the top-level sum when too wide.

    A product ``c * (sum)`` or a fraction ``(sum)/D`` with a long sum is opened up as
    ``c\\Big(...\\Big)`` or ``\\frac{1}{D}\\Big(...\\Big)`` and broken inside.
    """
    printer = FormulaPrinter()
    whole = printer.doprint(expr)
    equals = "=" if lhs else ""
    if visible_width(lhs + equals + whole) <= width:
        return f"{lhs}{equals}{whole}"
    prefix, inner, suffix = "", expr, ""
    if not expr.is_Add:
        numerator, denominator = sp.fraction(expr)
        sums = [f for f in sp.Mul.make_args(numerator) if f.is_Add]
        if sums:
            inner = max(sums, key=lambda f: visible_width(printer.doprint(f)))
            lead = numerator / inner / denominator
            prefix = ("" if lead == 1 else "- " if lead == -1 else printer.doprint(lead)) + r"\Big("
            suffix = r"\Big)"
    terms = [_signed(printer, t, i == 0) for i, t in enumerate(printer._as_ordered_terms(inner))]
    # widths term by term: a fraction in the prefix must not shrink the estimate of the sum after it
    budget = width - visible_width(lhs)
    lines, current, used = [], prefix, visible_width(prefix)
    for term in terms:
        cost = visible_width(term + " ")
        if current.strip() and used + cost > budget:
            lines.append(current)
            current, used = "", 0.0
        current += term + " "
        used += cost
    lines.append(current + suffix)
    return r"\begin{aligned}" + lhs + equals + "{}&" + r"\\&".join(line.rstrip() for line in lines) + r"\end{aligned}"


def display(*rows) -> str:
    """Body of a ``gather*``: rows are LaTeX strings or ``(lhs, expr)`` pairs (broken if too wide)."""
    out = []
    for row in rows:
        out.append(break_sum(*row) if isinstance(row, tuple) else row)
    return r"\\".join(out)


_CLAUSE = re.compile(r",\\(quad|qquad)(?![a-zA-Z])|;\\quad(?![a-zA-Z])")


def clauses(tex: str, width: float = LINE_WIDTH) -> list[str]:
    """Rows of a formula written as clauses separated by ``,\\quad`` (brace depth 0), if too wide."""
    if visible_width(tex) <= width:
        return [tex]
    rows, depth, start = [], 0, 0
    for match_at in range(len(tex)):
        ch = tex[match_at]
        depth += (ch == "{") - (ch == "}")
        if depth == 0 and match_at >= start:
            match = _CLAUSE.match(tex, match_at)
            if match:
                rows.append(tex[start:match_at] + tex[match_at])
                start = match.end()
    rows.append(tex[start:])
    return [row for row in rows if row.strip()]


def breakable_product(expr) -> str:
    """Inline LaTeX of a factored rational function with a permitted line break between factors.

    ``-\\frac{49}{1061683200 d^{15}}\\,(d^{2} + 49)\\allowbreak(4 d^{2} + 49)...``: the monomial
    part as a fraction, then each polynomial factor, so a table cell can wrap it.
    """
    numerator, denominator = sp.fraction(sp.cancel(expr))
    lead, polynomial = lead_and_sums(*sp.factor_list(numerator))   # primitive factors, positive leading coefficients
    return breakable_factors(lead / denominator, polynomial, expr)


def lead_and_sums(content, factor_powers: list) -> tuple:
    """A ``sympy.factor_list`` result split into the content times the powers of its monomial factors,
    and the list of the powers of its sums (in the list's order)."""
    sums = [base**power for base, power in factor_powers if base.is_Add]
    return content * sp.Mul(*[base**power for base, power in factor_powers if not base.is_Add]), sums


def breakable_factors(lead, polynomial: list, expr) -> str:
    """:func:`breakable_product` from its parts: ``expr = lead * prod(polynomial)``, ``lead`` a rational
    times a monomial, ``polynomial`` the powers of the sums in ``sympy.factor_list``'s order (for a caller
    that factors with python-flint: :func:`derivations.core.flint_factor.factor_list_univariate`)."""
    printer = FormulaPrinter()
    if not polynomial:
        return printer.doprint(expr)
    sign = "- " if lead.could_extract_minus_sign() else ""
    lead = -lead if sign else lead
    head = "" if lead == 1 else printer.doprint(lead) + r"\,"
    return sign + head + r"\allowbreak ".join(printer.parenthesize(f, PRECEDENCE["Mul"], strict=True)
                                              if f.is_Add else printer.doprint(f) for f in polynomial)
