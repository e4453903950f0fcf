"""Build options shared by the pipeline and the derivations."""
from __future__ import annotations

from dataclasses import dataclass

PMAX_LIMIT = 401


@dataclass(frozen=True)
class BuildOptions:
    """``pmax``: largest p for the per-p tables (both parities up to it)."""

    pmax: int = 15

    def __post_init__(self):
        if isinstance(self.pmax, bool) or not isinstance(self.pmax, int):
            raise ValueError(f"pmax={self.pmax!r}: must be an integer")
        if not 1 <= self.pmax <= PMAX_LIMIT:
            raise ValueError(f"pmax={self.pmax}: must be between 1 and {PMAX_LIMIT}")

    def p_values(self) -> list[int]:
        return list(range(1, self.pmax + 1))

    def odd_p_values(self) -> list[int]:
        """Odd p <= pmax; an even pmax stops at pmax - 1."""
        return list(range(1, self.pmax + 1, 2))

    def even_p_values(self) -> list[int]:
        return list(range(2, self.pmax + 1, 2))
