"""Jinja2 rendering of the derived results into LaTeX and Python.

Two environments share one loader on ``templates/``:

* ``*.tex.j2``: delimiters that do not clash with TeX braces
  (``\\VAR{...}``, ``\\BLOCK{...}``, ``\\#{...}``);
* ``*.py.j2``: Jinja's usual ``{{ }}``/``{% %}`` (Python rarely doubles braces).

Both use ``autoescape=False``, ``trim_blocks=True`` and ``StrictUndefined``
(a missing value is an error, never an empty string).  Filters turn SymPy
expressions into Python source (``py``), escape plain text for TeX (``tex``) and typeset a
statement of words and formulas (``claim``: :mod:`derivations.core.statement`).  For the documents'
apparatus: ``paper_label`` prints a label field by the paper's printed numbers
(:mod:`derivations.core.paper_numbers`: ``eq:o12, c's`` -> ``(2.7), (2.8)``), ``numbered_rows`` gives one
equation number to a multi-row ``gather`` (``\\notag`` on every row but the last), ``literature`` names
the bibliography entries a text draws on (Kimura, DLMF, Levelt), ``cite`` adds the ``\\cite`` after
each mention in prose and ``paper_refs`` (``paper_refs_display`` in mathematics: its ``\\text{...}``) replaces
the paper's labels in prose by its printed numbers.
"""
from __future__ import annotations

import functools
import re
from pathlib import Path

import jinja2
import sympy as sp
from sympy.printing.pycode import PythonCodePrinter

from derivations.core.paper_numbers import PRINTED, label_statement, printed_parts
from derivations.core.statement import tex as statement_tex
from derivations.core.statement import tex_escape   # the templates' tex filter (prose parts escape alike)
from derivations.core.typeset import latex

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


def paper_label(label_field: str, prefix: bool = False) -> str:
    """A label field in the paper's printed numbers, as TeX: ``(2.7), (2.8)``, ``Theorem 5.4 (p)``.

    A part the paper prints no number for stays as words (``derived`` reads ``derived here``); with
    ``prefix`` the printed numbers are introduced by ``paper``.
    """
    numbered = [printed for _, printed in printed_parts(label_field) if printed is not None]
    words = ["derived here" if part == "derived" else part
             for part, printed in printed_parts(label_field) if printed is None]
    shown = ", ".join(numbered)
    if prefix and shown:
        shown = "paper " + shown
    return "; ".join(statement_tex(label_statement(item)) for item in [shown, *words] if item)


def numbered_rows(display: str) -> str:
    """A ``gather`` body with ``\\notag`` before every row break at the top level: one number, on the last row
    (row breaks inside braces or an inner environment, ``pmatrix``, ``cases``, are not rows)."""
    out, depth, env, i = [], 0, 0, 0
    while i < len(display):
        if display.startswith("\\\\", i):
            if depth == 0 and env == 0:
                out.append("\\notag")
            out.append("\\\\")
            i += 2
            continue
        if display.startswith("\\begin{", i):
            env += 1
        elif display.startswith("\\end{", i):
            env -= 1
        if display[i] == "\\":      # a control symbol such as \{ or \} is not a brace
            out.append(display[i:i + 2])
            i += 2
            continue
        depth += (display[i] == "{") - (display[i] == "}")
        out.append(display[i])
        i += 1
    return "".join(out)


# paper labels recognised in prose: every eq:... label and the others that are no English word
_PROSE_LABELS = sorted((k for k in PRINTED if k.startswith("eq:") or k in (
    "omegas", "gen12", "gam1", "gam2", "gam3", "gam_0", "pol_sol", "poly_F", "poly_F2", "F_23_pol", "F_23_splitted",
    "a'ss", "t->z", "c's", "ep3.26", "gen_sol_u")), key=len, reverse=True)
_LABEL_IN_PROSE = re.compile(r"(?<![\\\w:])(\()?(" + "|".join(re.escape(k).replace("_", r"\\?_") for k in _PROSE_LABELS)
                             + r")(?!\w)((?(1)\)|))")
_MATH = re.compile(r"(?<!\\)\$[^$]*(?<!\\)\$")


def _relabel(text: str) -> str:
    def number(m):
        printed = PRINTED[m.group(2).replace("\\_", "_")]
        # "(eq:lina)" reads "(3.3)", not "((3.3))"; "(Theorem 3.2)" keeps its parentheses
        if m.group(1) and m.group(3):
            return printed if printed.startswith("(") else "(" + printed + ")"
        return (m.group(1) or "") + printed
    return _LABEL_IN_PROSE.sub(number, text)


def paper_refs_display(math: str) -> str:
    """Mathematics with the paper's labels inside its ``\\text{...}`` replaced by the printed numbers."""
    out, i = [], 0
    while (j := math.find("\\text{", i)) >= 0:
        depth, k = 0, j + len("\\text")
        while k < len(math):      # k: the brace closing the one at j + 5
            depth += (math[k] == "{") - (math[k] == "}")
            if depth == 0:
                break
            k += 1
        out += [math[i:j], "\\text{" + _relabel(math[j + 6:k]) + "}"]
        i = k + 1
    return "".join(out + [math[i:]])


def paper_refs(tex: str) -> str:
    """TeX prose with the paper's labels (``eq:sysfin``, ``omegas``, ``eq:gamma\\_1``) replaced by the numbers
    the paper prints (``(4.2)``, ``(4.1)``, ``(5.5)``), in the prose and in the ``\\text{...}`` of its ``$...$``;
    an underscore left bare in the prose is escaped (an unknown label stays readable instead of breaking the
    document)."""
    out, last = [], 0
    for m in _MATH.finditer(tex):
        out += [re.sub(r"(?<!\\)_", r"\\_", _relabel(tex[last:m.start()])), paper_refs_display(m.group(0))]
        last = m.end()
    return "".join(out + [re.sub(r"(?<!\\)_", r"\\_", _relabel(tex[last:]))])


# the bibliography entries (keys of \suslovbibliography, in its order) and the words that draw on them
LITERATURE = (("Kimura69", re.compile(r"\bKimura(?:'s theorem)?")), ("DLMF", re.compile(
    r"\bDLMF(?: \d+(?:\.\d+)*(?:\([ivx]+\))?(?:-\d+)?)?")), ("Levelt61", re.compile(r"\bLevelt(?:'s theorem)?")))


def literature(text: str) -> list[str]:
    """The bibliography keys whose names ``text`` mentions (Kimura, DLMF, Levelt), in the bibliography's order."""
    return [key for key, pattern in LITERATURE if pattern.search(text)]


def cite(tex: str) -> str:
    """``tex`` with ``~\\cite{KEY}`` after each mention of Kimura, DLMF (with its section) or Levelt."""
    for key, pattern in LITERATURE:
        tex = pattern.sub(lambda m, key=key: m.group(0) + "~\\cite{" + key + "}", tex)
    return tex


@functools.lru_cache(maxsize=2)
def _environment(tex: bool) -> jinja2.Environment:
    # one per kind, kept: Jinja compiles a template once per environment (a build renders twice; it reloads a
    # template whose file changed, so an edit between two renders in one process is still seen)
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
    env.filters["paper_label"] = paper_label
    env.filters["numbered_rows"] = numbered_rows
    env.filters["literature"] = literature
    env.filters["cite"] = cite
    env.filters["paper_refs"] = paper_refs
    env.filters["paper_refs_display"] = paper_refs_display
    return env


def render(template: str, context: dict) -> str:
    """Render ``templates/<template>`` with ``context``."""
    env = _environment(tex=template.endswith(".tex.j2"))
    return env.get_template(template).render(**context)
