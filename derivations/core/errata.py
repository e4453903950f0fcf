"""Errata records: the paper's printed form beside the derived one.

Each derivation that compares a derived formula with a transcription from
``derivations.core.paper`` files one :class:`Erratum` with a status:

* ``confirmed``: the printed form is certified equal to the derived one;
* ``corrected``: the printed form is refuted (certificate with outcome
  ``fail``, as predicted) and the derived form is certified instead;
* ``not comparable``: the printed text cannot be compared as it stands
  (undefined symbol, sentence that breaks off, statement without formula),
  with the reason.

The build renders them into the LaTeX errata table (``templates/``); the
certificate keys let a reader find the proof behind each row.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from derivations.core.certificates import Certificate
from derivations.core.paper import Printed

STATUSES = ("confirmed", "corrected", "not comparable")


@dataclass
class Erratum:
    label: str
    status: str
    printed: str
    derived: str
    note: str
    certificates: list[str] = field(default_factory=list)

    def __post_init__(self):
        if self.status not in STATUSES:
            raise ValueError(f"erratum status {self.status!r} is not one of {STATUSES}")


def erratum(printed: Printed, status: str, derived_latex: str, note: str,
            *certificates: Certificate) -> Erratum:
    """Build an erratum row from a transcription and the certificates behind it."""
    return Erratum(printed.label, status, printed.latex, derived_latex, note,
                   [cert.key for cert in certificates])
