"""What a derivation hands to the renderer: formulas, errata, exports, notes.

A formula has two faces from one record: ``latex`` (the display the documents print) and ``expr``
(the same formula as a standard SymPy object: an equation, a tuple of equations, a matrix), which
the formula catalog (``generated/catalog.json``, ``suslov.catalog``) serialises and exports to
Mathematica, Maple and JSON.  ``hypotheses`` are the conditions under which the formula holds
(TeX, e.g. ``$d>0$``), printed with it in the documents and attached to its catalog entry.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field

import sympy as sp

from derivations.core.certificates import Certificate
from derivations.core.errata import Erratum
from derivations.core.typeset import clauses, display


@dataclass
class DerivedFormula:
    """A derived, certified formula as it appears in the LaTeX document and in the catalog.

    ``expr`` is None only for prose (a proof in words); every other formula carries it.
    """

    key: str
    label: str
    title: str
    latex: str
    certificates: list[str] = field(default_factory=list)
    expr: sp.Basic | None = None
    hypotheses: list[str] = field(default_factory=list)


_TEX_NAME = re.compile(r"\\(?:mathcal|mathrm|operatorname|bar|hat|tilde)\b|[\\{}_^\s']")


def plain_name(tex: str) -> str:
    """A symbol name for the left-hand side ``tex`` of a display row: ``\\omega_1`` -> ``omega1``.

    >>> plain_name(r"\\omega_{2}"), plain_name("F_1")
    ('omega2', 'F1')
    """
    return _TEX_NAME.sub("", tex)


def rows_expr(rows) -> sp.Tuple | None:
    """The SymPy form of display rows given as ``(lhs TeX, expr)`` pairs (None if any row is plain TeX)."""
    if not rows or not all(isinstance(row, tuple) for row in rows):
        return None
    return sp.Tuple(*[sp.Eq(sp.Symbol(plain_name(lhs)), value, evaluate=False) for lhs, value in rows])


@dataclass
class DerivationResult:
    name: str
    formulas: list[DerivedFormula] = field(default_factory=list)
    errata: list[Erratum] = field(default_factory=list)
    exports: dict = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    def formula(self, key: str, label: str, title: str, latex: str | sp.Basic | list,
                *certificates: Certificate, expr: sp.Basic | None = None,
                hypotheses: tuple[str, ...] | list[str] = ()) -> DerivedFormula:
        """Record a formula; ``latex`` is LaTeX text, an expression, or display rows (:func:`typeset.display`).

        Text wider than the page is set one clause per line (split after the ``,\\quad`` that
        separate clauses at brace depth 0).  ``expr`` defaults to the expression or the rows'
        equations when ``latex`` is given as SymPy; TeX text needs it given.
        """
        if isinstance(latex, list):
            text = display(*latex)
            expr = rows_expr(latex) if expr is None else expr
        elif isinstance(latex, str):
            text = display(*clauses(latex))
        else:
            text = display(("", latex))
            expr = latex if expr is None else expr
        item = DerivedFormula(key, label, title, text, [c.key for c in certificates], expr, list(hypotheses))
        self.formulas.append(item)
        return item
