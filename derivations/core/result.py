"""What a derivation hands to the renderer: formulas, errata, exports, notes."""
from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from derivations.core.certificates import Certificate
from derivations.core.errata import Erratum
from derivations.core.typeset import clauses, display


@dataclass
class DerivedFormula:
    """A derived, certified formula as it appears in the LaTeX document."""

    key: str
    label: str
    title: str
    latex: str
    certificates: list[str] = field(default_factory=list)


@dataclass
class DerivationResult:
    name: str
    formulas: list[DerivedFormula] = field(default_factory=list)
    errata: list[Erratum] = field(default_factory=list)
    exports: dict = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    def formula(self, key: str, label: str, title: str, latex: str | sp.Basic | list,
                *certificates: Certificate) -> DerivedFormula:
        """Record a formula; ``latex`` is LaTeX text, an expression, or display rows (:func:`typeset.display`).

        Text wider than the page is set one clause per line (split after the ``,\\quad`` that
        separate clauses at brace depth 0).
        """
        if isinstance(latex, list):
            text = display(*latex)
        elif isinstance(latex, str):
            text = display(*clauses(latex))
        else:
            text = display(("", latex))
        item = DerivedFormula(key, label, title, text, [c.key for c in certificates])
        self.formulas.append(item)
        return item
