"""Guarded numerical integration of the Poisson equations ``gamma' = gamma x omega(t)`` (paper ``eq:whole``).

Used where no certified closed form exists (non-odd p, general bodies).

Guards (why): near the limit axis the vector field is nearly zero, and an
adaptive solver started there can take one huge step across the whole
transition and report success with a wrong answer.  The step is therefore
bounded by a quarter of the shortest time scale of omega: ``1/lam`` (the
tanh/sech transition) and ``1/max|omega|`` (the rotation).  Every result
carries an error estimate: the same problem solved again at a tolerance 100
times tighter, the largest difference over the samples, and the drift of
``|gamma|`` (a rigid rotation preserves it).

The boundary condition ``ss`` (gamma -> the limit axis at t -> -oo) starts
from the convergent Frobenius series of the exponent-0 solution in
``x = e^(lam t)`` (radius 1): ``x dgamma/dx = gamma x omega(x)`` with
``omega(x) = (u (x^2-1) + 2 v x)/(x^2+1)``.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np

log = logging.getLogger(__name__)

SERIES_START = -1.0  # lam t at which the ss series is evaluated when the window starts later
MAX_STEPS = 5_000_000


@dataclass
class Integration:
    """Samples of one or several solutions with their error estimate."""

    t: np.ndarray
    values: np.ndarray          # shape (len(t), k, 3)
    error_estimate: float       # max |solution(rtol) - solution(rtol/100)| over the samples
    norm_drift: float           # max | |gamma| - |gamma(t0)| |
    nfev: int
    method: str
    max_step: float

    def summary(self) -> dict:
        return {"method": self.method, "error_estimate": self.error_estimate, "norm_drift": self.norm_drift,
                "function_evaluations": self.nfev, "max_step": self.max_step}


def _cross(g, w):
    """g x (w1, w2, 0) for g of shape (..., 3)."""
    return np.stack([-g[..., 2] * w[1], g[..., 2] * w[0], g[..., 0] * w[1] - g[..., 1] * w[0]], axis=-1)


def ss_series_value(u, v, s):
    """The ss solution (``gamma(-oo) = -u/|u|``) at rate-1 time s <= -0.5 from its series in x = e^s."""
    if s > -0.5:
        raise ValueError(f"series start at s = {s}: needs s <= -0.5 for fast convergence")
    x = np.exp(s)
    u, v = np.asarray(u, float), np.asarray(v, float)
    axis = np.array([*u / np.hypot(*u), 0.0])   # hypot: |u| = 2e-300 (p = 1e-300) has |u|^2 = 0 in float64
    terms = int(np.ceil(40.0 / max(-s, 1e-3))) + 10
    inv = np.array([(-1.0) ** (k // 2) if k % 2 == 0 else 0.0 for k in range(terms + 1)])
    w = np.zeros((terms + 1, 2))
    w[:, :] = -u[None, :] * inv[:, None]
    w[2:, :] += u[None, :] * inv[:-2, None]
    w[1:, :] += 2 * v[None, :] * inv[:-1, None]
    coeffs = [-axis]
    w0 = w[0]
    total, power = -axis.copy(), 1.0
    for k in range(1, terms + 1):
        rhs = sum(_cross(coeffs[k - j], w[j]) for j in range(1, k + 1))
        M = np.array([[k, 0, w0[1]], [0, k, -w0[0]], [-w0[1], w0[0], k]])
        coeffs.append(np.linalg.solve(M, rhs))
        power *= x
        total = total + coeffs[-1] * power
        if np.max(np.abs(coeffs[-1])) * power < 1e-18:
            break
    return total


def max_step_for(body) -> float:
    """A quarter of the shortest time scale of omega (see the module docstring)."""
    peak = body.rate * (np.hypot(*body.u) + np.hypot(*body.v))   # hypot: no overflow of |u|^2 at |u| = 2e300
    return 0.25 / max(body.rate, peak)


def solve_poisson(body, t_eval, initial, rtol=1e-10, atol=1e-12, method="DOP853", t_start=None) -> Integration:
    """Integrate one or several solutions (rows of ``initial``, paper frame) over ``t_eval``.

    ``t_start`` (<= t_eval[0]) is where ``initial`` holds; default t_eval[0].  Raises
    RuntimeError when the solver fails (message from SciPy) or the window needs more than
    MAX_STEPS bounded steps.
    """
    t_eval = np.asarray(t_eval, dtype=float)
    initial = np.atleast_2d(np.asarray(initial, dtype=float))
    t0 = float(t_eval[0] if t_start is None else t_start)
    h = max_step_for(body)
    if (t_eval[-1] - t0) / h > MAX_STEPS:
        raise RuntimeError(f"window [{t0}, {t_eval[-1]}] needs more than {MAX_STEPS} steps of {h:.3g}")
    k = initial.shape[0]

    def rhs(t, y):
        return _cross(y.reshape(k, 3), body.omega_at(t)).ravel()

    from scipy.integrate import (
        solve_ivp,  # SciPy only when this route runs (sweep workers start faster)
    )

    def run(tol_r, tol_a):
        sol = solve_ivp(rhs, (t0, float(t_eval[-1])), initial.ravel(), method=method, t_eval=t_eval,
                        rtol=tol_r, atol=tol_a, max_step=h)
        if not sol.success:
            raise RuntimeError(f"{method} failed: {sol.message}")
        return sol.y.T.reshape(len(t_eval), k, 3), sol.nfev

    values, nfev = run(rtol, atol)
    check, nfev2 = run(max(rtol / 100, 3e-14), atol / 100)  # SciPy's floor for rtol is 2.2e-14
    error = float(np.max(np.abs(values - check)))
    norms = np.linalg.norm(values, axis=-1)
    drift = float(np.max(np.abs(norms - np.linalg.norm(initial, axis=-1)[None, :])))
    log.info("%s: %d + %d evaluations, error estimate %.2e, |gamma| drift %.2e", method, nfev, nfev2, error, drift)
    return Integration(t_eval, values, error, drift, nfev + nfev2, f"{method} rtol={rtol:g} atol={atol:g}", h)


def ss_initial(body, t0):
    """(t_start, gamma) to start the ss solution for a window beginning at t0 (paper frame)."""
    s0 = body.rate * t0
    s_start = min(s0, SERIES_START)
    return s_start / body.rate, ss_series_value(body.u, body.v, s_start)


def numeric_angle(body, rtol=1e-12, atol=1e-14, horizon=40.0, method="DOP853"):
    """Delta psi of a general body by integrating ss to lam t = horizon; returns (angle, error estimate, Integration).

    cos(Delta psi) = -<gamma(+oo), n> with n the limit axis; the component along n converges
    like e^(-lam t) and the perpendicular part only rotates, so
    ``Delta psi = atan2(|gamma_perp|, -<gamma, n>)`` at the horizon (no arccos near 1).
    """
    t_start, g0 = ss_initial(body, SERIES_START / body.rate)
    t_eval = np.array([t_start, horizon / body.rate])
    run = solve_poisson(body, t_eval, g0, rtol=rtol, atol=atol, method=method, t_start=t_start)
    g = run.values[-1, 0]
    n = body.limit_axis()
    along = float(g @ n)
    perp = float(np.linalg.norm(g - along * n))
    angle = float(np.arctan2(perp, -along))
    truncation = float(np.exp(-horizon)) * 10.0
    return angle, run.error_estimate + truncation, run
