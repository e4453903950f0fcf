"""Taylor integration of the Poisson equations with heyoka (paper section 5.1, ``eq:whole``, ``eq:o12``).

The simulator's default integrator where no closed form exists; API as :mod:`suslov.simulator.integrate`.
Method: heyoka's ``taylor_adaptive`` (float64) integrates k solutions (3k states) of ``gamma' =
gamma x omega(t)`` (``eq:whole``) in physical time (``hy.time``), ``omega = lam (u tanh(lam t) +
v / cosh(lam t))``, ``omega3 = 0`` (``eq:o12``, paper frame).  The body enters only as runtime
parameters ``par[0..4] = (lam, u1, u2, v1, v2)``: :func:`integrator` compiles once per process
and ``(k, tol)``; a call sets ``pars``, ``state``, ``time`` (shared objects: not thread-safe; the
executor uses processes).  ``|lam t| <= 700``: ``cosh`` overflows at 710 (ValueError beyond).

Step cap (why): heyoka's step-size rule looks only at the state's Taylor coefficients.  Near
the limit axis ``gamma x omega`` and with it all of them vanish, and heyoka takes one step across
the whole tanh/sech transition, reporting success with a wrong answer
(``bench/results/work_precision.md``: uncapped heyoka fails from t = -40 at tol >= 1e-7).  Two
things are invisible to the rule there: the growth of the deviation from the axis, on the time
scale ``1/lam`` of the transition, and its rotation about the axis, on the time scale
``1/max|omega|``, both hidden while the deviation is below the tolerance.  So
:func:`solve_poisson_taylor`, which may start anywhere (``gamma0`` next to the axis at t = -30,
say), caps every step (``max_delta_t``) by :func:`suslov.simulator.integrate.max_step_for`, as the SciPy
route does: a quarter of the shorter of the two.  :func:`taylor_angle` starts from the series
at ``lam t = -1``, where the deviation from the axis is of order ``e^-1``, far above the
tolerance: heyoka's rule sees the rotation in the state's coefficients, and only the transition
needs the cap, ``TRANSITION_CAP / lam`` (general body of the tests: 166 steps instead of 1167
under the full cap, the same angle to 1e-15; 0.2 ms per angle instead of 1.3 ms).

Error estimate (how): the same problem run again by a second cached integrator at tolerance
``max(tol * 1e-3, 2.2e-16)`` with steps <= ``CHECK_CAP * h = 0.9 h``; the largest difference over
the samples (as :mod:`suslov.simulator.integrate` does with a 100x tighter run), plus the ``|gamma|`` drift.
Why 0.9 h: under the cap, truncation at order >= 15 is usually below rounding and runs on the same
step points agree bit for bit (estimate 0, measured); shifted points make the difference see the
rounding (~2e-15; true errors <= 1e-15).  Any ``propagate_*`` outcome but ``time_limit`` raises.

The ``ss`` start: the series of :func:`suslov.simulator.integrate.ss_series_value` at ``lam t = SERIES_START``
by its three-term recurrence in plain floats: 40-70 us instead of ``ss_initial``'s 11 ms (tested equal).

Compilation, cold (caches off, 2-CPU Xeon, fresh processes): k = 1: 0.10-0.19 s at tol 1e-12
(order 15), 0.15-0.25 s at 1e-15 (order 19); k = 3: 0.17-0.31 s, 0.29-0.33 s.  ``compact_mode``
compiles in 0.12-0.19 s (k = 1), 0.16-0.17 s (k = 3) but steps 1.6-2.5x slower (1169 vs 495 ns,
k = 1, order 15): not used, a process compiles once (the disk cache, on by default, reloads in ~20 ms).
Then :func:`taylor_angle` costs ~1.3 ms per general body (0.45 ms main run, 0.7 ms check run).
"""
from __future__ import annotations

import functools
import logging
import math
import time

import numpy as np

from suslov.simulator import integrate

log = logging.getLogger(__name__)
COMPILE_SECONDS: dict = {}   # (k, tol) -> seconds taken by the JIT compilation in this process
LAM_T_MAX = 700.0            # cosh(lam t) overflows at |lam t| = 710
CHECK_CAP = 0.9              # the check run's step cap, in units of the main run's cap
TRANSITION_CAP = 0.25        # taylor_angle's step cap, in units of 1/lam (see the module docstring)
ANGLE_STEP_UNITS = 100 * integrate.MAX_STEPS   # taylor_angle's bound, in steps of integrate.max_step_for


@functools.lru_cache(maxsize=16)
def integrator(k, tol):
    """The compiled Taylor integrator of k Poisson solutions at tolerance tol, cached per process.

    Parameters
    ----------
    k : int
        Number of solutions, 3k states (solution i in ``state[3i:3i+3]``); 1 and 3 are used.
    tol : float
        heyoka's tolerance (it fixes the order).  Pass both positionally: the cache keys differ.

    Returns
    -------
    heyoka.taylor_adaptive
        Runtime parameters ``pars = (lam, u1, u2, v1, v2)``; time is physical time.

    Examples
    --------
    >>> ta = integrator(1, 1e-12)
    >>> ta.dim, ta.order, len(ta.pars)
    (3, 15, 5)
    """
    try:
        import heyoka as hy
    except ImportError as exc:
        raise ImportError(f"heyoka is not importable ({exc}): install heyoka or use method = 'scipy:DOP853'") from exc
    lam, (u1, u2, v1, v2) = hy.par[0], (hy.par[i] for i in range(1, 5))
    th, sh = hy.tanh(lam * hy.time), 1.0 / hy.cosh(lam * hy.time)
    w1, w2 = lam * (u1 * th + v1 * sh), lam * (u2 * th + v2 * sh)
    g = hy.make_vars(*(f"g{i}" for i in range(3 * k)))
    system = []
    for g1, g2, g3 in zip(g[0::3], g[1::3], g[2::3]):   # gamma x (w1, w2, 0), as integrate._cross
        system += [(g1, -w2 * g3), (g2, w1 * g3), (g3, w2 * g1 - w1 * g2)]
    start = time.perf_counter()
    ta = hy.taylor_adaptive(system, [0.0] * (3 * k), tol=tol, pars=[1.0, 0.0, 0.0, 0.0, 0.0])
    COMPILE_SECONDS[(k, tol)] = time.perf_counter() - start
    log.info("heyoka: compiled k = %d, tol = %g (order %d) in %.3f s", k, tol, ta.order, COMPILE_SECONDS[(k, tol)])
    return ta


def _tolerances(tol):
    if not (isinstance(tol, (int, float)) and 2.2e-16 <= tol < 1):
        raise ValueError(f"tol={tol!r}: must be a number in [2.2e-16, 1)")
    return float(tol), max(float(tol) * 1e-3, 2.2e-16)


def _reset(ta, body, t0, g0):
    ta.pars[:], ta.time, ta.state[:] = (body.rate, body.u[0], body.u[1], body.v[0], body.v[1]), t0, g0


def _checked(result, ta, what):
    if result[0] != type(result[0]).time_limit:   # hy.taylor_outcome; success values of propagate_*
        raise RuntimeError(f"heyoka {what} stopped with {result[0]} at t = {ta.time} (tol {ta.tol:g})")
    return result


def _ss_start(body):
    """(t_start, gamma) of the ss solution at lam t = SERIES_START: integrate.ss_initial's series, fast."""
    s = integrate.SERIES_START
    (u1, u2), (v1, v2), x = map(float, body.u), map(float, body.v), math.exp(s)
    uu, nu = u1 * u1 + u2 * u2, math.hypot(u1, u2)
    b1 = b2 = b3 = 0.0                                               # c_(k-2); c_(k-1), c_0 = -u/|u|; the sum
    (a1, a2, a3), (s1, s2, s3), power, small = (-u1 / nu, -u2 / nu, 0.0), (-u1 / nu, -u2 / nu, 0.0), 1.0, 0
    for k in range(1, 2000):
        # k c_k + c_k x u = 2 c_(k-1) x v + c_(k-2) x u - (k-2) c_(k-2);  x = (w1, w2, 0) as in integrate._cross
        r1 = -2 * a3 * v2 - b3 * u2 - (k - 2) * b1
        r2 = 2 * a3 * v1 + b3 * u1 - (k - 2) * b2
        r3 = 2 * (a1 * v2 - a2 * v1) + b1 * u2 - b2 * u1 - (k - 2) * b3
        ur, den = u1 * r1 + u2 * r2, k * (k * k + uu)  # (kI + [. x u])^-1 = (k^2 I - k [. x u] + u u^T) / den
        c1 = (k * k * r1 + k * r3 * u2 + u1 * ur) / den
        c2 = (k * k * r2 - k * r3 * u1 + u2 * ur) / den
        c3 = (k * k * r3 - k * (r1 * u2 - r2 * u1)) / den
        power *= x
        s1, s2, s3 = s1 + c1 * power, s2 + c2 * power, s3 + c3 * power
        b1, b2, b3, a1, a2, a3 = a1, a2, a3, c1, c2, c3
        small = small + 1 if max(abs(c1), abs(c2), abs(c3)) * power < 1e-18 else 0
        if small == 2:   # two negligible terms in a row: the recurrence only gets smaller
            break
    return s / body.rate, (s1, s2, s3)


def solve_poisson_taylor(body, t_eval, initial, tol=1e-12, t_start=None) -> integrate.Integration:
    """Integrate one or several solutions (rows of ``initial``, paper frame) over ``t_eval`` with heyoka.

    Parameters
    ----------
    body : suslov.simulator.body.Body
        Supplies ``rate``, ``u``, ``v`` (``eq:o12``).
    t_eval : array_like
        Strictly increasing sample times (physical time).
    initial : array_like, shape (3,) or (k, 3)
        The solutions at ``t_start``.
    tol : float
        heyoka's tolerance; the check run uses ``max(tol * 1e-3, 2.2e-16)``.
    t_start : float, optional
        Where ``initial`` holds, ``<= t_eval[0]`` (default ``t_eval[0]``).

    Returns
    -------
    suslov.simulator.integrate.Integration
        ``values`` of shape ``(len(t_eval), k, 3)``; ``nfev`` counts the Taylor steps of both runs.

    Raises
    ------
    ValueError
        Bad tolerance, grid or start, or a window beyond ``|lam t| = 700``.
    RuntimeError
        heyoka stopped early (e.g. ``err_nf_state``), or more than ``integrate.MAX_STEPS`` steps.

    Examples
    --------
    >>> from suslov.simulator.body import make_body
    >>> run = solve_poisson_taylor(make_body(p=2.5, d=0.7), np.linspace(-2.0, 2.0, 5), np.eye(3))
    >>> run.values.shape, run.error_estimate < 1e-11, run.norm_drift < 1e-12
    ((5, 3, 3), True, True)
    """
    tol, tight = _tolerances(tol)
    t_eval = np.asarray(t_eval, dtype=float)
    initial = np.atleast_2d(np.asarray(initial, dtype=float))
    if t_eval.ndim != 1 or t_eval.size == 0 or np.any(np.diff(t_eval) <= 0) or initial.shape[1:] != (3,):
        raise ValueError(f"need t_eval strictly increasing, initial (k, 3); got {t_eval.shape}, {initial.shape}")
    t0 = float(t_eval[0] if t_start is None else t_start)
    if t0 > t_eval[0]:
        raise ValueError(f"t_start={t0!r} is after t_eval[0]={t_eval[0]!r}")
    if not body.rate * max(abs(t0), abs(t_eval[-1])) <= LAM_T_MAX:
        raise ValueError(f"window [{t0:g}, {t_eval[-1]:g}] reaches |lam t| > {LAM_T_MAX:g}: cosh overflows; "
                         "use method = 'scipy:DOP853'")
    h = integrate.max_step_for(body)
    if (t_eval[-1] - t0) / h > integrate.MAX_STEPS:
        raise RuntimeError(f"window [{t0}, {t_eval[-1]}] needs more than {integrate.MAX_STEPS} steps of {h:.3g}")
    k = initial.shape[0]

    def run(ta, cap):
        _reset(ta, body, t0, initial.ravel())
        steps = (_checked(ta.propagate_until(float(t_eval[0]), max_delta_t=cap), ta, "propagate_until")[3]
                 if t0 < t_eval[0] else 0)
        res = _checked(ta.propagate_grid(t_eval, max_delta_t=cap), ta, "propagate_grid")
        return res[5].reshape(len(t_eval), k, 3), steps + res[3]

    values, steps = run(main := integrator(k, tol), h)
    check, steps2 = run(integrator(k, tight), CHECK_CAP * h)
    error = float(np.max(np.abs(values - check)))
    drift = float(np.max(np.abs(np.linalg.norm(values, axis=-1) - np.linalg.norm(initial, axis=-1)[None, :])))
    log.info("heyoka: %d + %d steps, error estimate %.2e, |gamma| drift %.2e", steps, steps2, error, drift)
    method = f"heyoka taylor_adaptive tol={tol:g} (order {main.order}), step cap {h:.3g}"
    return integrate.Integration(t_eval, values, error, drift, int(steps + steps2), method, h)


def taylor_angle(body, tol=1e-12, horizon=40.0):
    """Delta psi of any body from the ss solution integrated to ``lam t = horizon`` (as ``numeric_angle``).

    ``Delta psi = atan2(|g_perp|, -<g, n>)`` at the horizon, with ``n`` the limit axis
    (:func:`suslov.simulator.integrate.numeric_angle` explains why).  Uses ``propagate_until`` only, with
    the step cap ``TRANSITION_CAP / lam`` (the start is off the axis; module docstring).

    Parameters
    ----------
    body : suslov.simulator.body.Body
        Any body (``I13 = 0`` or not).
    tol : float
        heyoka's tolerance (the check run: ``max(tol * 1e-3, 2.2e-16)``).
    horizon : float
        End of the integration in rate-1 time ``lam t``, in (0, 700].

    Returns
    -------
    angle : float
        Delta psi in [0, pi].
    error_estimate : float
        Difference of the two runs plus ``10 exp(-horizon)`` (the truncation at the horizon).
    run : suslov.simulator.integrate.Integration
        The ss solution at the start and at the horizon (``values`` of shape (2, 1, 3)).

    Examples
    --------
    >>> from suslov.simulator.body import make_body
    >>> angle, error, run = taylor_angle(make_body(p=3, d=0.5))   # odd p: Delta psi = pi
    >>> round(angle, 6), error < 1e-9
    (3.141593, True)
    """
    tol, tight = _tolerances(tol)
    if not (0 < horizon <= LAM_T_MAX):
        raise ValueError(f"horizon={horizon!r}: must be in (0, {LAM_T_MAX:g}]")
    t_end, h = horizon / body.rate, TRANSITION_CAP / body.rate
    # bounded before any work (issue 44): |omega| ~ 1e300 (p = 1e300) ended in "err_nf_state at t = nan"; heyoka
    # takes about 0.03 steps per max_step_for step (measured, p = 10 to 1e4): the bound is some 1.5e7 steps,
    # reached at |omega| ~ 3e6 (p ~ 1e6 at d = 0.5), about 10 s
    scale = (t_end - integrate.SERIES_START / body.rate) / integrate.max_step_for(body)
    if not scale <= ANGLE_STEP_UNITS:
        raise RuntimeError(f"the ss solution integrated to lam t = {horizon:g} needs some {0.03 * scale:.3g} Taylor "
                           f"steps (|omega| up to {body.rate * (math.hypot(*body.u) + math.hypot(*body.v)):.3g}; "
                           f"the limit is {0.03 * ANGLE_STEP_UNITS:.3g}): not integrated; the closed form "
                           "(scattering_angle) gives the angle of every body")
    t_start, g0 = _ss_start(body)
    ends, steps = [], 0
    for ta, cap in ((integrator(1, tol), h), (integrator(1, tight), CHECK_CAP * h)):
        _reset(ta, body, t_start, g0)
        steps += _checked(ta.propagate_until(t_end, max_delta_t=cap), ta, "propagate_until")[3]
        ends.append(tuple(map(float, ta.state)))
    (g1, g2, g3), check = ends
    n1, n2 = (float(c) / math.hypot(*body.u) for c in body.u)   # the limit axis (body.limit_axis())
    along = g1 * n1 + g2 * n2
    angle = math.atan2(math.hypot(g1 - along * n1, g2 - along * n2, g3), -along)
    error = max(abs(a - b) for a, b in zip(ends[0], check))
    drift = abs(math.hypot(g1, g2, g3) - math.hypot(*g0))
    method = f"heyoka taylor_adaptive tol={tol:g} (order {integrator(1, tol).order}), step cap {h:.3g}"
    values = np.array([[g0], [ends[0]]])
    run = integrate.Integration(np.array([t_start, t_end]), values, error, drift, steps, method, h)
    return angle, error + math.exp(-horizon) * 10.0, run
