"""Work-precision study, the methods timed: SciPy, heyoka, a 4th-order Magnus integrator, mpmath odefun,
and how a run is measured and judged (see ``bench/bench_work_precision.py``).
"""
from __future__ import annotations

import math
import sys
import time
import warnings
from pathlib import Path

import matplotlib
import mpmath
import numpy as np
from scipy.integrate import solve_ivp

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from work_precision_reference import dpsi_from_gamma  # noqa: E402
from work_precision_setup import ABS_FAIL, CLOSED_REF_DPS, REL_FAIL, T0, T1, hy, omega  # noqa: E402

# --------------------------------------------------------------------------------------------
# methods

def rhs_and_jac(p, d):
    a = p / d
    b = a * math.sqrt(d * d + 1)

    def w(t):
        e = math.exp(-abs(t))
        return a * math.tanh(t), -b * 2.0 * e / (1.0 + e * e)

    def f(t, g):
        w1, w2 = w(t)
        g1, g2, g3 = g
        return np.array([-w2 * g3, w1 * g3, w2 * g1 - w1 * g2])

    def jac(t, g):
        w1, w2 = w(t)
        return np.array([[0.0, 0.0, -w2], [0.0, 0.0, w1], [w2, -w1, 0.0]])

    return f, jac


def scipy_run(method, p, d, y0, rtol, max_step=np.inf):
    f, jac = rhs_and_jac(p, d)
    kw = {"jac": jac} if method in ("Radau", "LSODA") else {}

    def run():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sol = solve_ivp(f, (T0, T1), y0, method=method, rtol=rtol, atol=rtol * 1e-3, max_step=max_step, **kw)
        work = {"nfev": int(sol.nfev), "steps": int(len(sol.t) - 1)}
        if method in ("Radau", "LSODA"):
            work.update(njev=int(sol.njev), nlu=int(sol.nlu))
        return {"y": sol.y[:, -1].copy(), "success": bool(sol.success) and sol.t[-1] == T1,
                "message": str(sol.message), "work": work}
    return run


def heyoka_integrator(p, d, y0, tol, max_delta_t=np.inf):
    """Build (JIT-compile) a taylor_adaptive once; the returned run() resets and propagates."""
    g1, g2, g3 = hy.make_vars("g1", "g2", "g3")
    a = p / d
    b = a * math.sqrt(d * d + 1)
    w1 = a * hy.tanh(hy.time)
    w2 = -b / hy.cosh(hy.time)  # cosh(40) = 1.2e17: no overflow on [-40, 40]
    sys_ = [(g1, -w2 * g3), (g2, w1 * g3), (g3, w2 * g1 - w1 * g2)]
    kw = {} if tol is None else {"tol": tol}
    hy.llvm_state.clear_memcache()  # a cold JIT compile (the disk cache is off for this process: main())
    start = time.perf_counter()
    ta = hy.taylor_adaptive(sys_, list(y0), time=T0, **kw)
    compile_s = time.perf_counter() - start

    def run():
        ta.time = T0
        ta.state[:] = y0
        res = ta.propagate_until(T1, max_delta_t=max_delta_t)
        outcome, nsteps = res[0], int(res[3])
        return {"y": ta.state.copy(), "success": outcome == hy.taylor_outcome.time_limit,
                "message": str(outcome), "work": {"steps": nsteps, "order": int(ta.order)}}
    return run, compile_s, float(ta.tol), int(ta.order)


def magnus4(p, d, y0, h, t0=T0, t1=T1):
    """4th-order Magnus: Omega = h/2 (A1 + A2) + sqrt(3)/12 h^2 [A2, A1] at the Gauss points.

    gamma' = gamma x omega = A gamma with A = hat(-omega) (hat(u) v = u x v); for hat matrices
    [hat(u), hat(v)] = hat(u x v), so Omega = hat(v), v = h/2 (u1 + u2) + sqrt(3)/12 h^2 u2 x u1,
    u = -omega.  exp(hat(v)) by Rodrigues' formula, so every step is an exact rotation and |gamma|
    is kept to roundoff.  The step products are formed by pairwise (tree) reduction in NumPy.
    """
    n = round((t1 - t0) / h)
    h = (t1 - t0) / n
    tk = t0 + h * np.arange(n)
    r = math.sqrt(3) / 6
    wa1, wa2 = omega(tk + (0.5 - r) * h, p, d)
    wb1, wb2 = omega(tk + (0.5 + r) * h, p, d)
    zero = np.zeros(n)
    u1 = -np.stack([wa1, wa2, zero], axis=1)
    u2 = -np.stack([wb1, wb2, zero], axis=1)
    v = 0.5 * h * (u1 + u2) + (math.sqrt(3) / 12) * h * h * np.cross(u2, u1)
    th = np.sqrt(np.einsum("ij,ij->i", v, v))
    A = np.sinc(th / np.pi)                       # sin th / th
    B = 0.5 * np.sinc(th / (2 * np.pi)) ** 2      # (1 - cos th) / th^2
    K = np.zeros((n, 3, 3))
    K[:, 0, 1], K[:, 0, 2], K[:, 1, 2] = -v[:, 2], v[:, 1], -v[:, 0]
    K[:, 1, 0], K[:, 2, 0], K[:, 2, 1] = v[:, 2], -v[:, 1], v[:, 0]
    R = np.eye(3) + A[:, None, None] * K + B[:, None, None] * (K @ K)
    while len(R) > 1:  # product R_{n-1} ... R_1 R_0 by pairwise reduction
        if len(R) % 2:
            R = np.concatenate([R, np.eye(3)[None]], axis=0)
        R = R[1::2] @ R[0::2]
    return R[0] @ np.asarray(y0, dtype=float), n


def magnus_run(p, d, y0, h):
    def run():
        y, n = magnus4(p, d, y0, h)
        return {"y": y, "success": True, "message": "", "work": {"steps": n, "omega_evals": 2 * n}}
    return run


def odefun_run(p, d, g_start, t_start, t_end, dps):
    def run():
        count = [0]
        with mpmath.workdps(dps):
            a = mpmath.mpf(p) / mpmath.mpf(d)
            b = a * mpmath.sqrt(mpmath.mpf(d) ** 2 + 1)

            def F(t, g):
                count[0] += 1
                w1, w2 = a * mpmath.tanh(t), -b * mpmath.sech(t)
                return [-w2 * g[2], w1 * g[2], w2 * g[0] - w1 * g[1]]

            sol = mpmath.odefun(F, mpmath.mpf(t_start), [mpmath.mpf(v) for v in g_start])
            y = [+v for v in sol(mpmath.mpf(t_end))]   # kept at dps digits (no rounding to 15)
            degree = 3 + int(3 * mpmath.mp.dps / 2.0)
        return {"y": y, "success": True, "message": "",
                "work": {"F_evals": count[0], "degree": degree, "steps": count[0] // degree}}
    return run


# --------------------------------------------------------------------------------------------
# timing and bookkeeping

def measure(fn, repeat, budget):
    """One warm-up run, then up to ``repeat`` timed runs (stopping once they used ``budget`` s)."""
    start = time.perf_counter()
    out = fn()
    warm = time.perf_counter() - start
    samples = []
    for _ in range(max(repeat, 1)):
        start = time.perf_counter()
        out = fn()
        samples.append(time.perf_counter() - start)
        if sum(samples) > budget:
            break
    return out, warm, samples


def error_of(y, quantity, ref, dps):
    """Max-norm error of gamma(40), or |Dpsi - Dpsi_ref|, computed in mpmath from exact inputs."""
    with mpmath.workdps(max(dps + 10, CLOSED_REF_DPS)):
        y = [mpmath.mpf(v) if not isinstance(v, mpmath.mpf) else v for v in y]
        if quantity == "gamma":
            return float(max(abs(y[i] - ref["at"][40.0][i]) for i in range(3)))
        return float(abs(dpsi_from_gamma(*y, ctx=mpmath) - ref["dpsi_closed"]))


def judge(error, tol, success, message):
    if not success:
        return True, f"solver reported failure: {message}"
    if not math.isfinite(error):
        return True, "non-finite result"
    if error > ABS_FAIL:
        return True, f"success reported but error {error:.1e} > {ABS_FAIL:g}"
    if tol is not None and error > REL_FAIL * tol:
        return True, f"success reported but error {error:.1e} > {REL_FAIL:g} x tolerance {tol:g}"
    return False, ""


