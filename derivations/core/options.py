"""Build options shared by the pipeline and the derivations."""
from __future__ import annotations

from dataclasses import dataclass, field

PMAX_LIMIT = 401


@dataclass(frozen=True)
class BuildOptions:
    """``pmax``: largest p for the per-p tables (both parities up to it).

    ``jobs`` (local worker processes for the per-p certificates; None: all cores, 1: none) and
    ``scheduler`` (a dask.distributed address) choose how the work runs, and ``cache`` whether
    per-p results may come from the content-keyed cache (:mod:`derivations.core.cache`), never what
    it yields: the outputs are identical whatever they are.
    """

    pmax: int = 15
    jobs: int | None = field(default=None, compare=False)
    scheduler: str | None = field(default=None, compare=False)
    cache: bool = field(default=False, compare=False)   # per-p results from/to derivations.core.cache

    def __post_init__(self):
        if isinstance(self.pmax, bool) or not isinstance(self.pmax, int):
            raise ValueError(f"pmax={self.pmax!r}: must be an integer")
        if not 1 <= self.pmax <= PMAX_LIMIT:
            raise ValueError(f"pmax={self.pmax}: must be between 1 and {PMAX_LIMIT}")
        if self.jobs is not None and (isinstance(self.jobs, bool) or not isinstance(self.jobs, int) or self.jobs < 1):
            raise ValueError(f"jobs={self.jobs!r}: must be a positive integer")

    def p_values(self) -> list[int]:
        return list(range(1, self.pmax + 1))

    def odd_p_values(self) -> list[int]:
        """Odd p <= pmax; an even pmax stops at pmax - 1."""
        return list(range(1, self.pmax + 1, 2))

    def even_p_values(self) -> list[int]:
        return list(range(2, self.pmax + 1, 2))
