"""Build options shared by the pipeline and the derivations."""
from __future__ import annotations

from dataclasses import dataclass, field

PMAX_LIMIT = 401
BALL_CHECKS = ("default", "full")
# The per-p logarithm recursions (``residue.logarithm_verdict``, ``galois.decide_logarithms``) are cross-checks of
# ``pole_theorem``, which proves the verdict for every p: every p <= CROSS_CHECK_PMAX runs, above it a sample
# (:func:`cross_check_p_values`); ``--cross-check-pmax N`` moves the threshold (N >= pmax: every p).
CROSS_CHECK_PMAX = 101
CROSS_CHECK_STEP = 50


def cross_check_p_values(top: int, dense: int = CROSS_CHECK_PMAX) -> list[int]:
    """The p a per-p cross-check runs on, for a stage whose range is 1..``top``: every p <= ``dense``; above it
    the p = 0 or 1 mod :data:`CROSS_CHECK_STEP` (150, 151, 200, 201, ...) and the largest even and the largest
    odd p <= ``top`` (both parities at the top of the range).  ``dense >= top``: every p <= top.

    Sound because the verdict the recursions compute is a theorem for every p (``pole_theorem``: odd Lambda
    meromorphic, even Lambda logarithmic); a recursion compares one p with it, and its cost grows like p^3."""
    if dense >= top:
        return list(range(1, top + 1))
    sample = {q for q in range(dense + 1, top + 1) if q % CROSS_CHECK_STEP in (0, 1)}
    sample |= {q for q in (top, top - 1) if q > dense}
    return list(range(1, dense + 1)) + sorted(sample)


def checked_words(values) -> str:
    """Which p a cross-check ran on, as a claim's words: "every $p <= N$" when ``values`` is 1..N, else
    "every $p <= N$ and the sample $p$ = 150, 151, 200, 201" (N: :func:`dense_prefix`)."""
    dense = dense_prefix(values)
    sample = sorted(q for q in set(values) if q > dense)
    return f"every $p <= {dense}$" + (" and the sample $p$ = " + ", ".join(map(str, sample)) if sample else "")


def dense_prefix(values) -> int:
    """The largest n with every p = 1..n in ``values`` (what a table of :func:`cross_check_p_values` covers
    without gaps): 0 when 1 is missing."""
    present, n = set(values), 0
    while n + 1 in present:
        n += 1
    return n


@dataclass(frozen=True)
class BuildOptions:
    """``pmax``: largest p for the per-p tables (both parities up to it); ``ball_checks``: how many
    bodies and points the ball checks that corroborate exact results run on (part of what the build yields);
    ``cross_check_pmax``: every p up to it runs the per-p logarithm recursions, above it a sample
    (:func:`cross_check_p_values`; also part of what the build yields: the tables list the p that ran).

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
    cross_check_pmax: int = CROSS_CHECK_PMAX
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
        if isinstance(self.cross_check_pmax, bool) or not isinstance(self.cross_check_pmax, int) \
                or not 1 <= self.cross_check_pmax <= PMAX_LIMIT:
            raise ValueError(f"cross_check_pmax={self.cross_check_pmax!r}: must be an integer between 1 and {PMAX_LIMIT}")
        if self.jobs is not None and (isinstance(self.jobs, bool) or not isinstance(self.jobs, int) or self.jobs < 1):
            raise ValueError(f"jobs={self.jobs!r}: must be a positive integer")

    def p_values(self) -> list[int]:
        return list(range(1, self.pmax + 1))

    def cross_check_p_values(self, top: int | None = None) -> list[int]:
        """The p the per-p logarithm cross-checks run on for a stage whose range is 1..``top`` (default pmax):
        :func:`cross_check_p_values` with this build's ``cross_check_pmax``."""
        return cross_check_p_values(self.pmax if top is None else top, self.cross_check_pmax)

    def odd_p_values(self) -> list[int]:
        """Odd p <= pmax; an even pmax stops at pmax - 1."""
        return list(range(1, self.pmax + 1, 2))

    def even_p_values(self) -> list[int]:
        return list(range(2, self.pmax + 1, 2))
