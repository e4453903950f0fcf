"""Jinja2 rendering of the derived results into LaTeX and Python.

Two environments share one loader on ``templates/``:

* ``*.tex.j2``: delimiters that do not clash with TeX braces
  (``\\VAR{...}``, ``\\BLOCK{...}``, ``\\#{...}``);
* ``*.py.j2``: Jinja's usual ``{{ }}``/``{% %}`` (Python rarely doubles braces).

Both use ``autoescape=False``, ``trim_blocks=True`` and ``StrictUndefined``
(a missing value is an error, never an empty string).  Filters turn SymPy
expressions into Python source (``py``), escape plain text for TeX (``tex``) and typeset a
statement of words and formulas (``claim``: :mod:`derivations.core.statement`).
"""
from __future__ import annotations

from pathlib import Path

import jinja2
import sympy as sp
from sympy.printing.pycode import PythonCodePrinter

from derivations.core.typeset import latex
from derivations.core.statement import tex as statement_tex
from derivations.core.statement import tex_escape   # the templates' tex filter (prose parts escape alike)

TEMPLATES = Path(__file__).resolve().parents[2] / "templates"


class _ArithmeticPrinter(PythonCodePrinter):
    """Plain arithmetic that works on floats, NumPy arrays and mpmath numbers."""

    def _print_Pow(self, expr, rational=False):
        base, exp = expr.as_base_exp()
        if exp.is_Integer and exp > 0:
            # parenthesised: the product may stand in a denominator (x/(y*y), not x/y*y)
            factors = [self.parenthesize(base, sp.printing.precedence.PRECEDENCE["Mul"])] * int(exp)
            return factors[0] if exp == 1 else "(" + "*".join(factors) + ")"
        return super()._print_Pow(expr, rational)


def python_source(expr) -> str:
    """Python source for a rational expression in plain symbols."""
    return _ArithmeticPrinter({"standard": "python3"}).doprint(sp.sympify(expr))


def _environment(tex: bool) -> jinja2.Environment:
    options = dict(loader=jinja2.FileSystemLoader(str(TEMPLATES)), autoescape=False, trim_blocks=True,
                   lstrip_blocks=True, keep_trailing_newline=True, undefined=jinja2.StrictUndefined)
    if tex:
        options.update(block_start_string=r"\BLOCK{", block_end_string="}", variable_start_string=r"\VAR{",
                       variable_end_string="}", comment_start_string=r"\#{", comment_end_string="}")
    env = jinja2.Environment(**options)
    env.filters["tex"] = tex_escape
    env.filters["py"] = python_source
    env.filters["latex"] = latex
    env.filters["claim"] = statement_tex
    return env


def render(template: str, context: dict) -> str:
    """Render ``templates/<template>`` with ``context``."""
    env = _environment(tex=template.endswith(".tex.j2"))
    return env.get_template(template).render(**context)
