"""Numeric corroboration with mpmath at 30+ digits at seeded random points.

A numeric check is *evidence*, not a proof (docs/design.md, "Certification"): the
certificate's method says so, with the precision, the number of points, the
seed and the largest relative residual seen.  It is meant as an independent
route beside the exact zero tests: ODE residuals are evaluated with
``mpmath.diff`` (numerical differentiation at raised precision) applied to the
closed forms written with ``tanh``/``sech``/``exp``, so the check does not reuse
the symbolic derivation rules of ``derivations.core.differential``.
"""
from __future__ import annotations

import random
from typing import Callable

import mpmath
import sympy as sp

from derivations.core.certificates import (
    Certificate,
    CertificateLog,
    Outcome,
    stopwatch,
)

DEFAULT_DPS = 40
DEFAULT_POINTS = 6


def mp_function(expr: sp.Expr, symbols: list[sp.Symbol]) -> Callable:
    """Compile a SymPy expression into a function of mpmath numbers."""
    return sp.lambdify(symbols, expr, modules="mpmath")


def sample_points(seed: int, count: int, ranges: dict) -> list[dict]:
    """Seeded random points, one ``{name: mpf}`` dict each.

    ``ranges`` maps a name to ``(low, high)``; values are drawn as decimal
    strings so that they are exact in any precision.
    """
    rng = random.Random(seed)
    points = []
    for _ in range(count):
        points.append(
            {name: mpmath.mpf(f"{rng.uniform(lo, hi):.12f}") for name, (lo, hi) in sorted(ranges.items())}
        )
    return points


def corroborate(
    log: CertificateLog,
    claim: str,
    label: str,
    residual: Callable[[dict], tuple],
    ranges: dict,
    *,
    seed: int,
    points: int = DEFAULT_POINTS,
    dps: int = DEFAULT_DPS,
    digits_required: int = 30,
    expect: Outcome = Outcome.PASS,
) -> Certificate:
    """Check ``|residual| <= 10**-digits_required * scale`` at random points.

    ``residual(point)`` returns ``(value, scale)`` computed at the current
    mpmath precision; ``value`` may be a number or a sequence of numbers.
    """
    if digits_required < 30:
        raise ValueError(f"digits_required={digits_required}: numeric certificates need 30+ digits")
    worst = mpmath.mpf(0)
    outcome, detail = Outcome.PASS, ""
    with stopwatch() as elapsed:
        with mpmath.workdps(dps):
            for point in sample_points(seed, points, ranges):
                try:
                    value, scale = residual(point)
                except (ZeroDivisionError, ValueError) as exc:
                    outcome, detail = Outcome.UNKNOWN, f"evaluation failed at {point}: {exc}"
                    break
                values = value if isinstance(value, (list, tuple)) else [value]
                size = max(abs(v) for v in values) / max(abs(scale), mpmath.mpf(1))
                worst = max(worst, size)
            if outcome is Outcome.PASS and worst > mpmath.mpf(10) ** (-digits_required):
                outcome = Outcome.FAIL
    if not detail:
        detail = f"{points} points, seed ${seed}$, max relative residual ${mpmath.nstr(worst, 3)}$"
    method = f"mpmath corroboration at {dps} digits (evidence, not proof)"
    return log.record(
        Certificate(claim, label, method, outcome, elapsed[0], points, detail, expected=expect)
    )


def ode_residual(solution: list[sp.Expr], field: list[sp.Expr], state: list[sp.Symbol],
                 t: sp.Symbol, params: list[sp.Symbol]) -> Callable[[dict], tuple]:
    """Residual ``x'(t) - f(x(t))`` with ``x'`` from ``mpmath.diff``.

    ``solution`` are closed forms in ``t`` and ``params``; ``field`` the
    right-hand sides in ``state`` and ``params``.
    """
    x_of_t = [mp_function(s, [t] + params) for s in solution]
    f_of_x = [mp_function(f, state + params) for f in field]
    names = [str(s) for s in [t] + params]

    def residual(point: dict) -> tuple:
        args = [point[n] for n in names]
        values = [x(*args) for x in x_of_t]
        derivs = [mpmath.diff(lambda tt, x=x: x(tt, *args[1:]), args[0]) for x in x_of_t]
        rhs = [f(*values, *args[1:]) for f in f_of_x]
        scale = max(abs(v) for v in derivs + values)
        return [dv - r for dv, r in zip(derivs, rhs)], scale

    return residual
