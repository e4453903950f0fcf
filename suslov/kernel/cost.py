"""Cost estimates and time limits of the validated routines, said before they start (issue 38).

``suslov.validated.monodromy`` and ``scattering_angle_enclosure(method="integration")`` grow without
bound near the equilibrium I13 = I23 = 0 (``|omega|`` like ``1/|(I13, I23)|``): the monodromy loses
``guard`` digits to the size of its matrices (:func:`suslov.kernel.fuchsian_flow.guard_digits`), the
integration's steps shrink like ``1/|omega|``.  The estimates below are power laws fitted on the project's
benchmark machine (AMD EPYC, 2 cores shared, one core used; ``bench/bench_monodromy.py`` style runs):

* monodromy, one pass of four loops at W = digits + guard working digits: ``0.045 W^1.25`` s
  (measured 3.0 s at W = 29, 5.1 s at 43, 8.1 s at 66, 13.5 s at 97);
* integration enclosure at ``digits`` with ``N = max |u_i|, |v_i|``: ``0.1 N (digits/10)^1.66`` s
  (measured 0.18 s at N = 1.7, digits 10; 1.1 s at digits 30; 1.8 s at N = 17; 3.3 s at N = 47).

They are estimates (another machine scales them by a constant factor); the routines also stop
at ``max_seconds`` while running.  No SymPy.
"""
from __future__ import annotations

import math

__all__ = ["monodromy_seconds", "enclosure_seconds", "seconds_limit"]


def monodromy_seconds(working_digits: int) -> float:
    """Estimated seconds of one pass (four loops) of the monodromy at ``working_digits``."""
    return 0.045 * max(working_digits, 1) ** 1.25


def enclosure_seconds(size: float, digits: float) -> float:
    """Estimated seconds of the validated integration for ``|omega|`` coefficients up to ``size``."""
    return 0.1 * max(size, 1.0) * (max(digits, 1) / 10) ** 1.66


def seconds_limit(value) -> float | None:
    """``max_seconds`` validated: a positive finite number of seconds, or None (no limit)."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (0 < value < math.inf):
        raise ValueError(f"max_seconds={value!r}: must be a positive number of seconds (or None for no limit)")
    return float(value)
