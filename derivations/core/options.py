"""Build options shared by the pipeline and the derivations."""
from __future__ import annotations

from dataclasses import dataclass, field

PMAX_LIMIT = 401
BALL_CHECKS = ("default", "full")


@dataclass(frozen=True)
class BuildOptions:
    """``pmax``: largest p for the per-p tables (both parities up to it); ``ball_checks``: how many
    bodies and points the ball checks that corroborate exact results run on (part of what the build yields).

    ``jobs`` (local worker processes for the per-p certificates; None: all cores, 1: none) and
    ``scheduler`` (a dask.distributed address) choose how the work runs, and ``cache`` whether
    per-p results may come from the content-keyed cache (:mod:`derivations.core.cache`), never what
    it yields: the outputs are identical whatever they are.
    """

    pmax: int = 15
    # the ball checks that corroborate exact results, "default" on a few bodies or points, "full" on all: the general
    # angle's connection on seeded bodies (derivations.sections.general_angle.BALL_TIERS), the monodromy of the
    # representative bodies (fuchsian.BODY_TIERS), the scattering angle's enclosed grid and fast-rotation column
    # (scattering_balls.GRIDS, scattering_evidence.COLUMNS); the certificates say which ran
    ball_checks: str = "default"
    jobs: int | None = field(default=None, compare=False)
    scheduler: str | None = field(default=None, compare=False)
    cache: bool = field(default=False, compare=False)   # per-p results from/to derivations.core.cache

    def __post_init__(self):
        if isinstance(self.pmax, bool) or not isinstance(self.pmax, int):
            raise ValueError(f"pmax={self.pmax!r}: must be an integer")
        if not 1 <= self.pmax <= PMAX_LIMIT:
            raise ValueError(f"pmax={self.pmax}: must be between 1 and {PMAX_LIMIT}")
        if self.ball_checks not in BALL_CHECKS:
            raise ValueError(f"ball_checks={self.ball_checks!r}: must be one of {', '.join(BALL_CHECKS)}")
        if self.jobs is not None and (isinstance(self.jobs, bool) or not isinstance(self.jobs, int) or self.jobs < 1):
            raise ValueError(f"jobs={self.jobs!r}: must be a positive integer")

    def p_values(self) -> list[int]:
        return list(range(1, self.pmax + 1))

    def odd_p_values(self) -> list[int]:
        """Odd p <= pmax; an even pmax stops at pmax - 1."""
        return list(range(1, self.pmax + 1, 2))

    def even_p_values(self) -> list[int]:
        return list(range(2, self.pmax + 1, 2))
