"""Work-precision study: what a digit of accuracy costs in time for the Poisson equations.

The Poisson equations of the Suslov problem (conventions of ``generated/suslov_formulas.py``)::

    gamma' = gamma x omega(t),   omega(t) = ((p/d) tanh t, -(p/d) sqrt(d^2+1) sech t, 0)

    g1' = -w2 g3,   g2' = w1 g3,   g3' = w2 g1 - w1 g2,

solved for the ``ss`` solution (gamma -> (-1, 0, 0) as t -> -oo) by several methods side by side:

* the generated closed form ``gamma_basis`` (float64) and its mpmath twin ``gamma_basis_mp``
  (odd p only: problem 1);
* SciPy ``solve_ivp`` (RK45, DOP853, Radau, LSODA) over a sweep of tolerances;
* heyoka's Taylor integrator ``taylor_adaptive`` over a sweep of tolerances (skipped with a note
  if heyoka cannot be imported);
* a 4th-order Magnus integrator (two Gauss points + commutator, Rodrigues exponential) written
  here in NumPy, over fixed step sizes;
* mpmath's ``odefun`` (Taylor series, arbitrary precision);
* for the scattering angle, the closed form cos(Dpsi/2) = |cos(pi p/2)| / cosh(pi p/(2d)) in
  float64 and in mpmath.

Problems (the same for every method):

1. closed form case: gamma(40) for p = 3, d = 0.5 from t0 = -40;
2. generic case: gamma(40) for p = 2.5, d = 0.7 from t0 = -40;
3. scattering angle Delta psi (cos Dpsi = -g1(+oo)) for (p, d) = (2.5, 0.7) and (2, 2) from
   gamma(40), integrated from t0 = -40.

The reference is independent of every method timed: the ss power series in x = e^t (exact start
values, any real p) and a Taylor-series integrator written here in mpmath (the Taylor
coefficients of tanh and sech by their own recurrences T' = 1 - T^2, S' = -S T), run twice with
different start points, step sizes and precisions; the difference of the two runs is the
reference error estimate.  For p = 3 it is also compared with ``gamma_basis_mp``.

Run:  python bench/bench_work_precision.py [--quick] [--repeat N] [--budget S] [--out DIR]
writes work_precision.md, work_precision.json and work_precision.png to DIR (default bench/results).
"""
from __future__ import annotations

import argparse
import json
import math
import os
import platform
import statistics
import sys
import time
import warnings
from pathlib import Path

import matplotlib
import mpmath
import numpy as np
import scipy
from scipy.integrate import solve_ivp

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from generated.suslov_formulas import gamma_basis, gamma_basis_mp, omega  # noqa: E402
from work_precision_plot import METHOD_ORDER, METHOD_STYLE, XMIN, draw  # noqa: E402, F401
from bench.machine_info import cpu_name  # noqa: E402

try:  # optional: the Taylor integrator heyoka (pip install heyoka)
    import heyoka as hy
    HEYOKA_ERROR = None
except Exception as exc:  # noqa: BLE001 - any import failure means "skip with a note"
    hy = None
    HEYOKA_ERROR = f"{type(exc).__name__}: {exc}"

T0, T1 = -40.0, 40.0
CASES = {  # integration cases: (p, d) as float64; the problems are defined with these binary values
    "p3_d0.5": (3.0, 0.5),
    "p2.5_d0.7": (2.5, 0.7),
    "p2_d2": (2.0, 2.0),
}
PROBLEMS = {  # problem -> (title, case, quantity)
    "1_closed_form": ("1. closed form case: gamma(40), p = 3, d = 0.5", "p3_d0.5", "gamma"),
    "2_generic": ("2. generic case: gamma(40), p = 2.5, d = 0.7", "p2.5_d0.7", "gamma"),
    "3a_scattering": ("3a. scattering angle, p = 2.5, d = 0.7", "p2.5_d0.7", "dpsi"),
    "3b_scattering": ("3b. scattering angle, p = 2, d = 2", "p2_d2", "dpsi"),
}

HEYOKA_MAX_DT = 0.5   # the step cap of the second heyoka curve (propagate_until's max_delta_t)
CLOSED_REF_DPS = 100  # precision of the closed-form Delta psi reference and of the error arithmetic
ABS_FAIL = 1e-2       # an error above this is a failure whatever the tolerance
REL_FAIL = 100.0      # an error above REL_FAIL * requested tolerance is a failure


# --------------------------------------------------------------------------------------------
# machine

def machine() -> dict:
    cpu = cpu_name()
    u = platform.uname()
    versions = {"python": platform.python_version(), "numpy": np.__version__, "scipy": scipy.__version__,
                "mpmath": mpmath.__version__, "matplotlib": matplotlib.__version__,
                "heyoka": getattr(hy, "__version__", None) if hy is not None else None}
    try:
        affinity = len(os.sched_getaffinity(0))
    except AttributeError:
        affinity = None
    return {"cpu": cpu, "machine": u.machine, "system": f"{u.system} {u.release}",
            "cpu_count": os.cpu_count(), "cpus_usable": affinity, "versions": versions,
            "mpmath_backend": mpmath.libmp.BACKEND}


def machine_line(m: dict) -> str:
    v = m["versions"]
    hey = f"heyoka {v['heyoka']}" if v["heyoka"] else "heyoka not available"
    return (f"{m['cpu']}; {m['machine']}; {m['system']}; {m['cpu_count']} CPUs ({m['cpus_usable']} usable); "
            f"Python {v['python']}; NumPy {v['numpy']}; SciPy {v['scipy']}; mpmath {v['mpmath']} "
            f"(backend {m['mpmath_backend']}); matplotlib {v['matplotlib']}; {hey}")


# --------------------------------------------------------------------------------------------
# reference (mpmath): ss power series in x = e^t and a Taylor-series integrator in t

def ss_series(t, p, d, dps):
    """The ss solution at t < 0 from its power series in x = e^t (gamma_0 = (-1, 0, 0)).

    x dgamma/dx = gamma x omega(x), omega1 = (p/d)(x^2-1)/(x^2+1), omega2 = -(p/d) c 2x/(1+x^2):
    k gamma_k - gamma_k x omega_0 = sum_{j>=1} gamma_{k-j} x omega_j, a 3x3 system per k
    (omega_0 = (-p/d, 0, 0): det = k^2 + (p/d)^2, never resonant).  Returns (values, terms).
    """
    with mpmath.workdps(dps + 10):
        p, d, t = mpmath.mpf(p), mpmath.mpf(d), mpmath.mpf(t)
        a = p / d
        c = mpmath.sqrt(d * d + 1)
        x = mpmath.exp(t)
        if not x < 1:
            raise ValueError("the ss series converges for t < 0 only")
        tol = mpmath.mpf(10) ** (-(dps + 5))
        zero = mpmath.mpf(0)

        def w(j):  # Taylor coefficients of (omega1, omega2) in x
            if j == 0:
                return -a, zero
            if j % 2 == 0:
                return 2 * a * (-1) ** (j // 2 + 1), zero
            return zero, -2 * a * c * (-1) ** ((j - 1) // 2)

        gs = [(mpmath.mpf(-1), zero, zero)]
        total = list(gs[0])
        xk = mpmath.mpf(1)
        k = small = 0
        while small < 3:
            k += 1
            r1 = r2 = r3 = zero
            for j in range(1, k + 1):
                w1, w2 = w(j)
                g1, g2, g3 = gs[k - j]
                r1 += -g3 * w2
                r2 += g3 * w1
                r3 += g1 * w2 - g2 * w1
            den = k * k + a * a
            gk = (r1 / k, (k * r2 - a * r3) / den, (k * r3 + a * r2) / den)
            gs.append(gk)
            xk *= x
            for i in range(3):
                total[i] += gk[i] * xk
            small = small + 1 if max(abs(v) for v in gk) * xk < tol else 0
            if k > 20000:
                raise RuntimeError("ss series did not converge")
        return total, k


def taylor_mp(t_start, g_start, checkpoints, p, d, dps, h, grid=None):
    """Taylor-series integration in mpmath from t_start through the sorted checkpoints.

    At each step point t_n the Taylor coefficients of T = tanh, S = sech come from exact values
    at t_n and the recurrences T' = 1 - T^2, S' = -S T; those of gamma from the Poisson equations
    (Cauchy products).  Radius of convergence pi/2 (poles of tanh, sech at t_n +- i pi/2); the
    order is chosen so that (h / (pi/2))^N < 10^-(dps+10).  Returns {checkpoint: [g1, g2, g3]}, the
    number of steps and the order; the value at every step point is put into ``grid`` if given.
    """
    out = {}
    with mpmath.workdps(dps + 10):
        p, d = mpmath.mpf(p), mpmath.mpf(d)
        a = p / d
        b = a * mpmath.sqrt(d * d + 1)
        g = [mpmath.mpf(v) for v in g_start]
        order = int((dps + 10) / -mpmath.log10(mpmath.mpf(h) / (mpmath.pi / 2))) + 10
        t_a = mpmath.mpf(t_start)
        steps = 0
        for t_b in checkpoints:
            t_b = mpmath.mpf(t_b)
            n = int(mpmath.ceil((t_b - t_a) / h))
            H = (t_b - t_a) / n
            for s in range(n):
                tt = t_a + s * H
                T, S = [mpmath.tanh(tt)], [mpmath.sech(tt)]
                G1, G2, G3 = [g[0]], [g[1]], [g[2]]
                W1, W2 = [a * T[0]], [-b * S[0]]
                for k in range(order):
                    rG1, rG2, rG3 = G1[::-1], G2[::-1], G3[::-1]
                    r1 = -mpmath.fdot(W2, rG3)
                    r2 = mpmath.fdot(W1, rG3)
                    r3 = mpmath.fdot(W2, rG1) - mpmath.fdot(W1, rG2)
                    rT = T[::-1]
                    Tn = ((1 if k == 0 else 0) - mpmath.fdot(T, rT)) / (k + 1)
                    Sn = -mpmath.fdot(S, rT) / (k + 1)
                    T.append(Tn)
                    S.append(Sn)
                    W1.append(a * Tn)
                    W2.append(-b * Sn)
                    G1.append(r1 / (k + 1))
                    G2.append(r2 / (k + 1))
                    G3.append(r3 / (k + 1))
                g = [mpmath.polyval(G[::-1], H) for G in (G1, G2, G3)]
                steps += 1
                if grid is not None:
                    grid[float(t_a + (s + 1) * H)] = list(g)
            out[float(t_b)] = list(g)
            t_a = t_b
    return out, steps, order


def dpsi_from_gamma(g1, g2, g3, ctx=math):
    """Delta psi = angle between gamma(-oo) = (-1, 0, 0) and gamma(T): atan2(|a x g|, a.g).

    cos Dpsi = -g1 for |gamma| = 1.  The half-angle form 2 atan2(sqrt(1+g1), sqrt(1-g1)) is the
    same angle for |gamma| = 1 but loses digits where g1 ~ +-1; atan2(sqrt(g2^2+g3^2), -g1) keeps
    full relative accuracy everywhere and does not depend on |gamma| (a norm drift of the
    integrator does not enter).
    """
    return ctx.atan2(ctx.sqrt(g2 * g2 + g3 * g3), -g1)


def dpsi_closed_mp(p, d, dps):
    """cos(Dpsi/2) = |cos(pi p/2)| / cosh(pi p/(2d)), Dpsi = 2 atan2(sin(Dpsi/2), cos(Dpsi/2))."""
    with mpmath.workdps(dps):
        p, d = mpmath.mpf(p), mpmath.mpf(d)
        x = mpmath.pi * p / (2 * d)
        y = mpmath.pi * p / 2
        sech = mpmath.sech(x)
        return 2 * mpmath.atan2(mpmath.sqrt(mpmath.tanh(x) ** 2 + mpmath.sin(y) ** 2 * sech ** 2),
                                abs(mpmath.cos(y)) * sech)


def dpsi_closed_np(p, d):
    """The same closed form in NumPy float64 (sech x = 2 e^-|x| / (1 + e^-2|x|))."""
    x = np.float64(np.pi) * p / (2 * d)
    y = np.float64(np.pi) * p / 2
    e = np.exp(-np.abs(x))
    sech = 2 * e / (1 + e * e)
    return 2 * np.arctan2(np.sqrt(np.tanh(x) ** 2 + np.sin(y) ** 2 * sech ** 2), np.abs(np.cos(y)) * sech)


CHECKPOINTS = [5.0, 40.0, 60.0]


def reference_main(p, d, dps):
    """Series at -40, -5, -1; Taylor run from -1 (step 0.5) through the checkpoints, all step points kept."""
    start = time.perf_counter()
    g_m40, terms_m40 = ss_series(T0, p, d, dps + 20)
    g_m5, _ = ss_series(-5.0, p, d, dps + 20)
    g_m1, terms_m1 = ss_series(-1.0, p, d, dps)
    grid = {T0: g_m40, -5.0: g_m5, -1.0: g_m1}
    main, steps, order = taylor_mp(-1.0, g_m1, CHECKPOINTS, p, d, dps, 0.5, grid)
    grid = {t: v for t, v in grid.items() if t <= T1}
    return {"start": g_m40, "m5": g_m5, "grid": grid, "at": main,
            "info": {"series_terms_at_-40": terms_m40, "series_terms_at_-1": terms_m1, "taylor_steps": steps,
                     "taylor_order": order, "taylor_step": 0.5, "main_seconds": time.perf_counter() - start}}


def reference_check(p, d, dps):
    """The check run: series at -2, Taylor step 0.4, 10 more digits."""
    start = time.perf_counter()
    g_m2, _ = ss_series(-2.0, p, d, dps + 10)
    check, steps, order = taylor_mp(-2.0, g_m2, CHECKPOINTS, p, d, dps + 10, 0.4)
    return {"at": check, "info": {"check_taylor_steps": steps, "check_taylor_order": order,
                                  "check_taylor_step": 0.4, "check_dps": dps + 10,
                                  "check_seconds": time.perf_counter() - start}}


def build_references(ref_dps, jobs, log):
    """Reference ss values at -40 (start), the step points, -5, 5, 40 and 60, with an error estimate.

    The main and check runs of the three cases are independent: they run in ``jobs`` processes
    (nothing is timed meanwhile).
    """
    from concurrent.futures import ProcessPoolExecutor

    start = time.perf_counter()
    with ProcessPoolExecutor(max_workers=max(jobs, 1)) as pool:
        futures = {case: (pool.submit(reference_main, p, d, ref_dps[case]),
                          pool.submit(reference_check, p, d, ref_dps[case]))
                   for case, (p, d) in CASES.items()}
        results = {case: (fm.result(), fc.result()) for case, (fm, fc) in futures.items()}
    refs = {}
    for case, (main, check) in results.items():
        p, d = CASES[case]
        dps = ref_dps[case]
        with mpmath.workdps(dps + 10):
            diff = {tc: float(max(abs(main["at"][tc][i] - check["at"][tc][i]) for i in range(3)))
                    for tc in CHECKPOINTS}
            dpsi_T = {tc: dpsi_from_gamma(*main["at"][tc], ctx=mpmath) for tc in (40.0, 60.0)}
        ref = {"case": case, "p": p, "d": d, "dps": dps, "start": main["start"], "m5": main["m5"],
               "grid": main["grid"], "at": main["at"], "dpsi_T": dpsi_T,
               "info": dict(main["info"], **check["info"],
                            error_estimate={f"t={tc:g}": diff[tc] for tc in CHECKPOINTS})}
        if p == int(p) and int(p) % 2 == 1:
            B = gamma_basis_mp(T1, int(p), d, dps + 20)
            with mpmath.workdps(dps + 10):
                ref["info"]["vs_gamma_basis_mp_at_40"] = float(max(abs(main["at"][40.0][i] - B[0, i])
                                                                   for i in range(3)))
        ref["info"]["seconds"] = ref["info"]["main_seconds"] + ref["info"]["check_seconds"]
        log(f"reference {case}: dps {dps}, error estimate at t=40 {diff[40.0]:.1e} "
            f"(main {ref['info']['main_seconds']:.1f} s + check {ref['info']['check_seconds']:.1f} s)")
        refs[case] = ref
    log(f"references done in {time.perf_counter() - start:.1f} s wall ({jobs} processes)")
    return refs


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


# --------------------------------------------------------------------------------------------
# the study

def run_study(args, log):
    quick = args.quick
    if quick:
        rtols = [1e-3, 1e-6, 1e-9]
        hy_tols = [1e-3, 1e-9, None]
        hs = [0.2, 0.1, 0.05]
        mp_dps = [15]
        ref_dps = {"p3_d0.5": 22, "p2.5_d0.7": 22, "p2_d2": 22}
        hazard_rtols = [1e-5]
    else:
        rtols = [1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-13]
        hy_tols = [1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-13, 1e-15, None]
        hs = [0.5, 0.2, 0.1, 0.05, 0.02, 0.01, 0.005]
        mp_dps = [15, 30, 50]
        ref_dps = {"p3_d0.5": 60, "p2.5_d0.7": 40, "p2_d2": 40}
        hazard_rtols = [1e-3, 1e-5, 1e-7, 1e-9]
    # mpmath odefun on the full window [-40, 40]: 15 digits for every case (~4 s a run), 25 digits for
    # problem 2 only (~20 s a run); --quick runs 15 digits on the shorter window [-5, 5] only
    odefun_full = {case: [15] + ([25] if case == "p2.5_d0.7" else []) for case in CASES}
    odefun_window = (-5.0, 5.0)
    odefun_window_dps = [15] if quick else []

    refs = build_references(ref_dps, args.jobs, log)
    for case, (p, d) in CASES.items():
        ref = refs[case]
        with mpmath.workdps(ref["dps"] + 10):
            ref["dpsi_closed"] = dpsi_closed_mp(p, d, CLOSED_REF_DPS)
            ref["info"]["dpsi_closed"] = mpmath.nstr(ref["dpsi_closed"], 30)
            ref["info"]["dpsi_integrated_T60_minus_closed"] = float(ref["dpsi_T"][60.0] - ref["dpsi_closed"])
            ref["info"]["dpsi_integrated_T40_minus_closed"] = float(ref["dpsi_T"][40.0] - ref["dpsi_closed"])
            # the two other forms of the same angle (|gamma| = 1 to dps digits)
            g = ref["at"][60.0]
            ref["info"]["dpsi_forms_disagreement"] = float(max(
                abs(mpmath.acos(-g[0]) - ref["dpsi_T"][60.0]),
                abs(2 * mpmath.atan2(mpmath.sqrt(max(1 + g[0], 0)), mpmath.sqrt(max(1 - g[0], 0)))
                    - ref["dpsi_T"][60.0])))
            ref["info"]["norm_minus_1_at_60"] = float(mpmath.sqrt(sum(v * v for v in g)) - 1)

    runs = []   # one record per (problem, method, setting)

    def record(problem, method, setting, sort_key, out, warm, samples, tol, extra=None):
        _, case, quantity = PROBLEMS[problem]
        ref = refs[case]
        try:
            err = error_of(out["y"], quantity, ref, ref["dps"])
        except Exception as exc:  # noqa: BLE001
            err = float("nan")
            out = dict(out, success=False, message=f"{type(exc).__name__}: {exc}")
        # Delta psi from gamma(40) differs from Delta psi(oo) by the T = 40 truncation (~1e-17): a method
        # is not failed for that, so its tolerance is taken as at least the truncation
        trunc = abs(ref["info"]["dpsi_integrated_T40_minus_closed"]) if quantity == "dpsi" else 0.0
        failed, reason = judge(err, None if tol is None else max(tol, trunc), out["success"], out["message"])
        rec = {"problem": problem, "method": method, "setting": setting, "sort_key": sort_key,
               "error": err, "tolerance": tol, "failed": failed, "reason": reason,
               "work": out.get("work", {}), "time_median_s": statistics.median(samples) if samples else None,
               "time_samples_s": samples, "time_first_call_s": warm, "n_timed": len(samples)}
        if extra:
            rec.update(extra)
        runs.append(rec)
        tag = f"FAILED ({reason})" if failed else ""
        log(f"  {problem:15s} {method:22s} {setting:28s} err {err:9.2e}  t {rec['time_median_s'] or 0:9.2e} s {tag}")
        return rec

    def run_case(case, method, setting, sort_key, fn, tol, extra=None):
        """Time one integration and record it for every problem that uses this case."""
        try:
            out, warm, samples = measure(fn, args.repeat, args.budget)
        except Exception as exc:  # noqa: BLE001 - a raising solver is a failure, shown
            out, warm, samples = {"y": [float("nan")] * 3, "success": False,
                                  "message": f"raised {type(exc).__name__}: {exc}", "work": {}}, None, []
        for problem, (_, pcase, _) in PROBLEMS.items():
            if pcase == case:
                record(problem, method, setting, sort_key, out, warm, samples, tol, extra)
        return out

    y0s = {case: np.array([float(v) for v in refs[case]["start"]]) for case in CASES}

    # closed forms ----------------------------------------------------------------------------
    log("closed forms")
    p, d = CASES["p3_d0.5"]
    out, warm, samples = measure(lambda: {"y": gamma_basis(np.float64(T1), 3, d)[0], "success": True,
                                          "message": "", "work": {"calls": 1}}, args.repeat, args.budget)
    record("1_closed_form", "closed form (float64)", "gamma_basis(40)[0]", (0,), out, warm, samples, None,
           {"note": "first call computes and caches the coefficients with mpmath"})
    grid_t = np.array(sorted(refs["p3_d0.5"]["grid"]))
    out, warm, samples = measure(lambda: {"Y": gamma_basis(grid_t, 3, d)[:, 0, :], "success": True, "message": "",
                                          "work": {"calls": 1, "points": len(grid_t)}}, args.repeat, args.budget)
    with mpmath.workdps(refs["p3_d0.5"]["dps"] + 10):
        err = float(max(abs(mpmath.mpf(float(out["Y"][k, i])) - refs["p3_d0.5"]["grid"][float(t)][i])
                        for k, t in enumerate(grid_t) for i in range(3)))
        err_where = float(grid_t[int(np.argmax([max(abs(mpmath.mpf(float(out["Y"][k, i]))
                                                        - refs["p3_d0.5"]["grid"][float(t)][i]) for i in range(3))
                                                    for k, t in enumerate(grid_t)]))])
    runs.append({"problem": "1_closed_form", "method": "closed form (float64)",
                 "setting": f"gamma_basis on {len(grid_t)} points t = -40, -5, -1, -0.5, ..., 40: max error "
                            f"(at t = {err_where:g})",
                 "sort_key": (1,), "error": err, "tolerance": None, "failed": err > ABS_FAIL, "reason": "",
                 "work": out["work"], "time_median_s": statistics.median(samples), "time_samples_s": samples,
                 "time_first_call_s": warm, "n_timed": len(samples), "grid": True})
    log(f"  1_closed_form   gamma_basis on the grid: max err {err:.2e} at t = {err_where:g}")
    for dps in mp_dps:
        fn = (lambda dps=dps: {"y": [gamma_basis_mp(T1, 3, d, dps)[0, j] for j in range(3)], "success": True,
                               "message": "", "work": {"calls": 1}})
        out, warm, samples = measure(fn, args.repeat, args.budget)
        record("1_closed_form", "closed form (mpmath)", f"gamma_basis_mp dps {dps}", (dps,), out, warm, samples,
               10.0 ** -dps)
    for problem in ("3a_scattering", "3b_scattering"):
        case = PROBLEMS[problem][1]
        p, d = CASES[case]
        ref = refs[case]

        def closed_np(p=p, d=d):
            return {"dpsi": float(dpsi_closed_np(p, d)), "success": True, "message": "", "work": {"calls": 1}}
        for label, fn, tol, key in [("NumPy float64", closed_np, None, 0)] + [
                (f"mpmath dps {dps}", (lambda dps=dps, p=p, d=d: {"dpsi": dpsi_closed_mp(p, d, dps), "success": True,
                                                                  "message": "", "work": {"calls": 1}}),
                 10.0 ** -dps, dps) for dps in mp_dps]:
            out, warm, samples = measure(fn, args.repeat, args.budget)
            with mpmath.workdps(CLOSED_REF_DPS):
                err = float(abs(mpmath.mpf(out["dpsi"]) - ref["dpsi_closed"]))
            failed, reason = judge(err, tol, True, "")
            method = "closed form (float64)" if key == 0 else "closed form (mpmath)"
            runs.append({"problem": problem, "method": method, "setting": f"cos(Dpsi/2) formula, {label}",
                         "sort_key": (key,), "error": err, "tolerance": tol, "failed": failed, "reason": reason,
                         "work": out["work"], "time_median_s": statistics.median(samples),
                         "time_samples_s": samples, "time_first_call_s": warm, "n_timed": len(samples)})
            log(f"  {problem:15s} {method:22s} {label:28s} err {err:9.2e}  t {statistics.median(samples):9.2e} s")

    # SciPy --------------------------------------------------------------------------------------
    for method in ("RK45", "DOP853", "Radau", "LSODA"):
        log(f"SciPy {method}")
        for case, (p, d) in CASES.items():
            for rtol in rtols:
                run_case(case, method, f"rtol {rtol:.0e}", (-math.log10(rtol),),
                         scipy_run(method, p, d, y0s[case], rtol), rtol)

    # heyoka -------------------------------------------------------------------------------------
    if hy is not None:
        log("heyoka")
        for case, (p, d) in CASES.items():
            for tol in hy_tols:
                try:
                    fn, compile_s, tol_used, order = heyoka_integrator(p, d, y0s[case], tol)
                except Exception as exc:  # noqa: BLE001
                    fn, compile_s, tol_used, order = (lambda exc=exc: (_ for _ in ()).throw(exc)), None, tol, None
                label = f"tol {tol:.0e}" if tol is not None else f"tol default ({tol_used:.1e})"
                run_case(case, "heyoka", label, (-math.log10(tol_used),), fn, tol_used,
                         {"compile_s": compile_s, "taylor_order": order})
                fn, compile_s, tol_used, order = heyoka_integrator(p, d, y0s[case], tol, HEYOKA_MAX_DT)
                run_case(case, "heyoka + max_delta_t", label,
                         (-math.log10(tol_used),), fn, tol_used, {"compile_s": compile_s, "taylor_order": order})

    # Magnus -------------------------------------------------------------------------------------
    log("Magnus-4")
    magnus_norm = {}
    for case, (p, d) in CASES.items():
        for h in hs:
            out = run_case(case, "Magnus-4 (NumPy)", f"h {h:g}", (1 / h,), magnus_run(p, d, y0s[case], h), None)
            magnus_norm.setdefault(case, {})[f"h={h:g}"] = float(abs(np.linalg.norm(out["y"]) - 1.0))

    # mpmath odefun ------------------------------------------------------------------------------
    log("mpmath odefun")
    for case, (p, d) in CASES.items():
        if quick:
            break
        g_start = refs[case]["start"]
        for dps in odefun_full[case]:
            run_case(case, "mpmath odefun", f"dps {dps}, [-40, 40]", (dps,),
                     odefun_run(p, d, g_start, T0, T1, dps), 10.0 ** -dps)
    window_runs = []
    p, d = CASES["p2.5_d0.7"]
    ref = refs["p2.5_d0.7"]
    for dps in odefun_window_dps:
        out, warm, samples = measure(odefun_run(p, d, ref["m5"], odefun_window[0], odefun_window[1], dps),
                                     args.repeat, args.budget)
        with mpmath.workdps(ref["dps"] + 10):
            err = float(max(abs(out["y"][i] - ref["at"][5.0][i]) for i in range(3)))
        failed, reason = judge(err, 10.0 ** -dps, True, "")
        rec = {"problem": "2_generic", "method": "mpmath odefun",
               "setting": f"dps {dps}, window [-5, 5] only", "sort_key": (100 + dps,), "error": err,
               "tolerance": 10.0 ** -dps, "failed": failed, "reason": reason, "work": out["work"],
               "time_median_s": statistics.median(samples), "time_samples_s": samples,
               "time_first_call_s": warm, "n_timed": len(samples), "window": list(odefun_window)}
        runs.append(rec)
        window_runs.append(rec)
        log(f"  2_generic       mpmath odefun          dps {dps} window [-5,5]       err {err:9.2e}  "
            f"t {rec['time_median_s']:9.2e} s")

    # hazard: started on the axis -----------------------------------------------------------------
    log("hazard rows (problem 2, started on the axis)")
    hazard = []
    p, d = CASES["p2.5_d0.7"]
    ref = refs["p2.5_d0.7"]
    axis = np.array([-1.0, 0.0, 0.0])
    for method in ("RK45", "DOP853", "Radau", "LSODA") + (("heyoka",) if hy is not None else ()):
        for start_label, y0, max_step in [("reference ss value", y0s["p2.5_d0.7"], np.inf),
                                          ("on the axis (-1, 0, 0)", axis, np.inf),
                                          ("on the axis (-1, 0, 0)", axis, 0.5)]:
            for rtol in hazard_rtols:
                if method == "heyoka":
                    fn = heyoka_integrator(p, d, y0, rtol, max_step)[0]
                else:
                    fn = scipy_run(method, p, d, y0, rtol, max_step)
                start = time.perf_counter()
                try:
                    out = fn()
                except Exception as exc:  # noqa: BLE001
                    out = {"y": [float("nan")] * 3, "success": False, "message": f"raised {exc}", "work": {}}
                seconds = time.perf_counter() - start
                err = error_of(out["y"], "gamma", ref, ref["dps"])
                failed, reason = judge(err, rtol, out["success"], out["message"])
                hazard.append({"method": method, "start": start_label,
                               "max_step": None if max_step == np.inf else max_step, "rtol": rtol, "error": err,
                               "failed": failed, "reason": reason, "work": out["work"], "time_s": seconds})
                log(f"  {method:7s} {start_label:24s} max_step {max_step:<4} rtol {rtol:.0e}: err {err:9.2e} "
                    f"work {out['work'].get('nfev', out['work'].get('steps'))} {'FAILED' if failed else ''}")

    # checks ---------------------------------------------------------------------------------------
    checks = {"magnus_norm_drift": magnus_norm, "magnus_order": {}, "dop853_smallest_rtol": {}}
    for problem in PROBLEMS:
        mag = sorted([r for r in runs if r["problem"] == problem and r["method"] == "Magnus-4 (NumPy)"],
                     key=lambda r: r["sort_key"])
        hv = [(float(r["setting"].split()[1]), r["error"]) for r in mag]
        # observed order: least-squares slope over step sizes whose error is above the roundoff floor
        pts = [(h, e) for h, e in hv if e > 1e-12]
        if len(pts) >= 2:
            xs = [math.log(h) for h, _ in pts]
            ys = [math.log(e) for _, e in pts]
            mx, my = statistics.fmean(xs), statistics.fmean(ys)
            sl = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
        else:
            sl = None
        halving = [(hv[i][1] / hv[i + 1][1]) ** (math.log(2) / math.log(hv[i][0] / hv[i + 1][0]))
                   for i in range(len(hv) - 1)]  # error ratio per halving of h (16 for 4th order)
        checks["magnus_order"][problem] = {"slope": sl, "points": hv, "ratios_per_halving": halving}
        dop = [r for r in runs if r["problem"] == problem and r["method"] == "DOP853"]
        if dop:
            best = min(dop, key=lambda r: r["tolerance"])
            checks["dop853_smallest_rtol"][problem] = {"rtol": best["tolerance"], "error": best["error"]}
    return refs, runs, hazard, checks, window_runs


# --------------------------------------------------------------------------------------------
# output

def fmt_e(x):
    return "n/a" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.2e}"


def fmt_t(x):
    if x is None:
        return "n/a"
    return f"{x * 1e6:.0f} µs" if x < 1e-3 else (f"{x * 1e3:.2f} ms" if x < 1 else f"{x:.2f} s")


def fmt_work(w):
    if not w:
        return ""
    if "calls" in w:
        return f"{w['calls']} call" + (f" ({w['points']} points)" if "points" in w else "")
    if "nfev" in w:
        s = f"nfev {w['nfev']}, steps {w['steps']}"
        if "njev" in w:
            s += f", njev {w['njev']}, nlu {w['nlu']}"
        return s
    if "omega_evals" in w:
        return f"steps {w['steps']}, ω evals {w['omega_evals']}"
    if "F_evals" in w:
        return f"F evals {w['F_evals']} (≈ {w['steps']} steps × degree {w['degree']})"
    if "order" in w:
        return f"steps {w['steps']} (order {w['order']})"
    return json.dumps(w, sort_keys=True)


def sorted_runs(runs, problem):
    return sorted([r for r in runs if r["problem"] == problem],
                  key=lambda r: (METHOD_ORDER.index(r["method"]), r["sort_key"], r["setting"]))


def one_off(r):
    """Cost of a single integration: the first (cold) call plus heyoka's JIT compilation."""
    first = r["time_first_call_s"] if r.get("time_first_call_s") is not None else r["time_median_s"]
    return first + (r.get("compile_s") or 0.0)


def cheapest_table(runs, single_shot):
    """Markdown rows: per problem, the cheapest non-failed run reaching each target (median or one-off time)."""
    rows = ["| problem | " + " | ".join(f"error <= {t:.0e}" for t in TARGETS) + " |",
            "|---|" + "---|" * len(TARGETS)]
    for problem in PROBLEMS:
        cells = []
        for t in TARGETS:
            r = cheapest(runs, problem, t, single_shot=single_shot)
            cost = one_off(r) if (r and single_shot) else (r["time_median_s"] if r else None)
            cells.append(f"{r['method']}, {r['setting']}: {fmt_t(cost)}" if r else "—")
        rows.append(f"| {problem} | " + " | ".join(cells) + " |")
    return rows


def cheapest(runs, problem, target, method=None, single_shot=False, exclude=()):
    ok = [r for r in runs if r["problem"] == problem and not r["failed"] and r["error"] <= target
          and r["time_median_s"] is not None and "window" not in r and "grid" not in r
          and (method is None or r["method"] == method) and r["method"] not in exclude]
    key = one_off if single_shot else (lambda r: r["time_median_s"])
    return min(ok, key=key) if ok else None


TARGETS = [1e-3, 1e-6, 1e-9, 1e-12, 1e-14, 1e-20]
METHOD_TARGETS = [1e-3, 1e-6, 1e-9, 1e-12, 1e-14]


def ratio_range(runs, problem, slow, fast):
    """min and max of time(slow) / time(fast) over the settings both ran without failure."""
    a = {r["setting"]: r for r in runs if r["problem"] == problem and r["method"] == slow and not r["failed"]}
    b = {r["setting"]: r for r in runs if r["problem"] == problem and r["method"] == fast and not r["failed"]}
    rs = [a[k]["time_median_s"] / b[k]["time_median_s"] for k in a if k in b]
    return (min(rs), max(rs)) if rs else None


def recommendation(runs, hazard, checks, refs):
    """One paragraph, built from the measured numbers (every figure below is computed)."""
    P2 = "2_generic"

    def get(problem, method, setting_start):
        return next((r for r in runs if r["problem"] == problem and r["method"] == method
                     and r["setting"].startswith(setting_start)), None)

    def c(problem, target, method=None, **kw):
        return cheapest(runs, problem, target, method, **kw)

    parts = ["**Recommendation.**"]
    gb = get("1_closed_form", "closed form (float64)", "gamma_basis(40)")
    grid = get("1_closed_form", "closed form (float64)", "gamma_basis on")
    f64 = [get(pr, "closed form (float64)", "cos(Dpsi/2)") for pr in ("3a_scattering", "3b_scattering")]
    mp50 = [r for r in runs if r["method"] == "closed form (mpmath)" and "cos(Dpsi/2)" in r["setting"]]
    if gb and grid and all(f64):
        integ = [c(pr, 1e-12, exclude=("closed form (float64)", "closed form (mpmath)"))
                 for pr in ("3a_scattering", "3b_scattering")]
        parts.append(
            f"Where a closed form exists, use it. For odd p, `gamma_basis` costs {fmt_t(gb['time_median_s'])} per "
            f"call (the first call for a given (p, d) computes its coefficients: {fmt_t(gb['time_first_call_s'])}) "
            f"and is accurate to {fmt_e(grid['error'])} over [-40, 40]. For Delta psi the formula costs "
            f"{fmt_t(max(r['time_median_s'] for r in f64))} in float64 (error <= "
            f"{fmt_e(max(r['error'] for r in f64))}) and <= {fmt_t(max(r['time_median_s'] for r in mp50))} in "
            f"mpmath up to 50 digits, while the cheapest integration reaching 1e-12 took "
            + " / ".join(f"{fmt_t(r['time_median_s'])} ({r['method']}, {pr[:2]})"
                         for r, pr in zip(integ, ("3a", "3b")) if r)
            + " (plus its one-off costs) and cannot go below double-precision roundoff.")
    # generic p, double precision
    hmd = "heyoka + max_delta_t"
    h9, h14 = c(P2, 1e-9, hmd), c(P2, 1e-14, hmd)
    m9, d9 = c(P2, 1e-9, "Magnus-4 (NumPy)"), c(P2, 1e-9, "DOP853")
    compile_med = statistics.median([r["compile_s"] for r in runs if r.get("compile_s")] or [0.0])
    if h9 and m9 and d9:
        parts.append(
            f"For generic p in double precision the fastest integrator measured is heyoka with a step cap "
            f"(`max_delta_t = {HEYOKA_MAX_DT:g}`): {fmt_t(h9['time_median_s'])} for 1e-9 ({h9['setting']}),"
            + (f" {fmt_t(h14['time_median_s'])} for 1e-14 ({h14['setting']})," if h14 else "")
            + f" i.e. {m9['time_median_s'] / h9['time_median_s']:.0f}x faster than the Magnus-4 integrator and "
            f"{d9['time_median_s'] / h9['time_median_s']:.0f}x faster than DOP853 at 1e-9, plus a one-off JIT "
            f"compilation of about {fmt_t(compile_med)} per (system, tolerance), so it pays off from a few "
            f"integrations on.")
    hz_fail = [h for h in hazard if h["method"] == "heyoka" and h["failed"] and h["max_step"] is None]
    hey_fail = [r for r in runs if r["method"] == "heyoka" and r["failed"]]
    if hey_fail or hz_fail:
        tols = sorted({r["tolerance"] for r in hey_fail}, reverse=True)
        parts.append(
            "Without the step cap heyoka is unsafe here: started from the ss value at t0 = -40 (next to the axis, "
            "where gamma' ~ 1e-17) it "
            + (f"jumped over the whole dynamics or missed its tolerance by >100x at tol "
               f"{', '.join(f'{t:.0e}' for t in tols)}" if tols else "failed in the hazard rows")
            + " while reporting success.")
    if m9 and d9:
        mag_best = min((r for r in runs if r["problem"] == P2 and r["method"] == "Magnus-4 (NumPy)"),
                       key=lambda r: r["error"])
        slope = checks["magnus_order"][P2]["slope"]
        drift = max(v for cc in checks["magnus_norm_drift"].values() for v in cc.values())
        d12 = c(P2, 1e-12, exclude=("heyoka", hmd, "mpmath odefun"))
        d14 = c(P2, 1e-14, exclude=("heyoka", hmd, "mpmath odefun"))
        parts.append(
            f"Without heyoka (NumPy/SciPy only), the Magnus-4 integrator is the method of choice up to ~1e-11: "
            f"{fmt_t(m9['time_median_s'])} for 1e-9 ({m9['setting']}) against {fmt_t(d9['time_median_s'])} for "
            f"DOP853 ({d9['setting']}), {d9['time_median_s'] / m9['time_median_s']:.0f}x cheaper because its "
            f"omega evaluations are vectorised; it keeps |gamma| = 1 to {drift:.0e}, converges with order "
            f"{slope:.2f}, and reached {fmt_e(mag_best['error'])} at the smallest step ({mag_best['setting']})."
            + (f" For 1e-12 and below use {d12['method']} ({d12['setting']}: {fmt_e(d12['error'])} in "
               f"{fmt_t(d12['time_median_s'])})" if d12 else "")
            + (f"; of the NumPy/SciPy runs only {d14['method']} ({d14['setting']}, {fmt_t(d14['time_median_s'])}) "
               f"reached 1e-14." if d14 and d14 is not d12 else ("." if d12 else "")))
    rk = ratio_range(runs, P2, "RK45", "DOP853")
    ra = ratio_range(runs, P2, "Radau", "DOP853")
    ls_fail = [r for r in runs if r["method"] == "LSODA" and r["failed"] and r["problem"] != "3a_scattering"]
    ls_best = min((r for r in runs if r["problem"] == P2 and r["method"] == "LSODA"), key=lambda r: r["error"])
    avoid = []
    if rk:
        avoid.append(f"RK45 costs {rk[0]:.0f}-{rk[1]:.0f}x the time of DOP853 at the same rtol")
    if ra:
        avoid.append(f"Radau (implicit, analytic Jacobian) {ra[0]:.0f}-{ra[1]:.0f}x on this non-stiff problem")
    if ls_fail:
        n_ls = sum(1 for r in runs if r["method"] == "LSODA" and r["problem"] != "3a_scattering")
        avoid.append(f"LSODA failed {len(ls_fail)} of its {n_ls} "
                     f"runs (mostly by jumping over the dynamics from the start next to the axis, reporting success) "
                     f"and does not get below {fmt_e(ls_best['error'])} on problem 2")
    if avoid:
        parts.append("Among SciPy's methods DOP853 is the one to use: " + "; ".join(avoid) + ".")
    capped = [h for h in hazard if h["max_step"] is not None]
    uncapped_fail = [h for h in hazard if h["max_step"] is None and h["failed"]]
    parts.append(
        f"Any adaptive solver started on or next to the limit axis should get a step cap (`max_step` / "
        f"`max_delta_t` {HEYOKA_MAX_DT:g}): in the hazard table {len(uncapped_fail)} uncapped runs failed and "
        f"{sum(h['failed'] for h in capped)} of the {len(capped)} capped ones.")
    ode15 = get(P2, "mpmath odefun", "dps 15, [-40")
    ref_s = refs["p2.5_d0.7"]["info"]["main_seconds"]
    parts.append(
        "Beyond double precision use the mpmath closed forms (odd p, Delta psi); for generic p a Taylor method in "
        f"mpmath: the reference integrator written here took {ref_s:.0f} s for {refs['p2.5_d0.7']['dps']} digits "
        "on [-1, 60], "
        + (f"while `mpmath.odefun` already takes {fmt_t(ode15['time_median_s'])} at 15 digits on [-40, 40]." if ode15
           else "`mpmath.odefun` was not run on the full window."))
    return " ".join(parts)


def write_markdown(path, meta, refs, runs, hazard, checks, window_runs):
    m = meta["machine"]
    L = []
    L.append("# Work-precision study: the Poisson equations of the Suslov problem")
    L.append("")
    L.append(f"Machine: {machine_line(m)}.")
    L.append("")
    L.append(f"Command: `{meta['command']}` — total run time {meta['total_seconds']:.0f} s.")
    L.append("")
    L.append("![work-precision diagram](work_precision.png)")
    L.append("")
    L.append("## Set-up")
    L.append("")
    L.append("* Equations: gamma' = gamma x omega(t), omega = ((p/d) tanh t, -(p/d) sqrt(d^2+1) sech t, 0); the "
             "`ss` solution (gamma -> (-1, 0, 0) as t -> -oo), integrated from t0 = -40 to t1 = 40 starting from "
             "the reference value at -40 rounded to float64 (|g2|, |g3| ~ 1e-17 there). p and d are the float64 "
             "values (d = 0.7 means the double nearest 0.7), for every method and for the reference, so that "
             "parameter rounding is not counted as method error.")
    L.append("* Error: max-norm of gamma(40) minus the reference (problems 1, 2); |Dpsi - Dpsi_ref| with "
             "Dpsi_ref from the closed form cos(Dpsi/2) = |cos(pi p/2)| / cosh(pi p/(2d)) at high precision "
             "(problem 3). Integrators give Dpsi = atan2(sqrt(g2^2+g3^2), -g1) at T = 40 (the angle between "
             "gamma(-oo) = (-1,0,0) and gamma(T); equal to arccos(-g1) and to the half-angle form "
             "2 atan2(sqrt(1+g1), sqrt(1-g1)) for |gamma| = 1, but without their cancellation near g1 = +-1 and "
             "independent of a norm drift). Dpsi(40) differs from Dpsi(oo) by ~1e-17 (table of references), "
             "below every float64 error.")
    L.append(f"* Time: median wall time of up to {meta['repeat']} timed runs after one warm-up run; the timed "
             f"runs of a configuration stop once they have used {meta['budget']:g} s (column n = number of "
             "timed runs; only the slowest configurations have n < repeat). The first (warm-up) call's time is "
             "in the JSON (`time_first_call_s`). heyoka: the timed run is reset + `propagate_until`; the cold "
             "JIT compilation of each integrator is reported separately ('+ compile'; heyoka's in-memory cache "
             "is cleared before each build and its on-disk cache is switched off for this process, so with its "
             "default cache a rebuild of the same system costs a few ms). The scattering rows of "
             "(p, d) = (2.5, 0.7) are the same integrations as problem 2 (same runs, same times).")
    L.append("* SciPy `solve_ivp`: rtol as listed, atol = rtol x 1e-3, no `max_step`, analytic Jacobian for "
             "Radau and LSODA; right-hand side in plain Python (`math`). heyoka: `taylor_adaptive` (double "
             "precision) with tol as listed, sech t = 1/cosh t in heyoka's expression system, time variable "
             f"`hy.time`; the curve 'heyoka + max_delta_t' passes `max_delta_t = {HEYOKA_MAX_DT:g}` to "
             "`propagate_until`. Magnus-4: fixed step h (n = 80/h steps, 2 omega evaluations per step, the generated "
             "`omega`), exact rotation per step. mpmath `odefun`: Taylor method at the given dps (tolerance = "
             "its default, one ulp).")
    L.append(f"* FAILED: the solver raised, returned success=False, or returned success with an error above "
             f"{REL_FAIL:g} x its requested tolerance (rtol, heyoka tol, 10^-dps) or above {ABS_FAIL:g}. Failed "
             "runs stay in the tables and are drawn as crosses. For Delta psi the tolerance is taken as at least "
             "the T = 40 truncation |Dpsi(40) - Dpsi(oo)| (dotted line in the diagram).")
    L.append("")
    L.append("## References")
    L.append("")
    L.append("ss power series in x = e^t (at t = -40 and -1, exact for any real p), then a Taylor-series "
             "integrator written in mpmath (Taylor coefficients of tanh, sech from T' = 1 - T^2, S' = -S T at "
             "exact values at each step point; order chosen for (h/(pi/2))^N < 10^-(dps+10)) from -1 through "
             "40 to 60. Error estimate = difference to a second run (series at -2, step 0.4, 10 more digits).")
    L.append("")
    L.append("| case | dps | Taylor steps x order | est. error at t=40 | vs gamma_basis_mp | Dpsi (closed form) | "
             "Dpsi(T=60) integrated - closed | Dpsi(T=40) - Dpsi(oo) | time |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for ref in refs.values():
        i = ref["info"]
        vs = fmt_e(i.get("vs_gamma_basis_mp_at_40")) if "vs_gamma_basis_mp_at_40" in i else "—"
        L.append(f"| p = {ref['p']:g}, d = {ref['d']:g} | {ref['dps']} | {i['taylor_steps']} x {i['taylor_order']} | "
                 f"{fmt_e(i['error_estimate']['t=40'])} | {vs} | {i['dpsi_closed'][:22]} | "
                 f"{fmt_e(i['dpsi_integrated_T60_minus_closed'])} | {fmt_e(i['dpsi_integrated_T40_minus_closed'])} | "
                 f"{i['seconds']:.1f} s |")
    L.append("")
    L.append("The closed form for Delta psi agrees with the independent integration to the size of "
             "e^-60-type truncation at T = 60 (column 'integrated - closed'); the forms arccos(-g1) and the "
             "half-angle form agree with atan2 to "
             f"{fmt_e(max(r['info']['dpsi_forms_disagreement'] for r in refs.values()))} on the reference.")
    for problem, (title, case, quantity) in PROBLEMS.items():
        L.append("")
        L.append(f"## {title}")
        L.append("")
        L.append("| method | setting | error | median time | n | work | status |")
        L.append("|---|---|---:|---:|---:|---|---|")
        for r in sorted_runs(runs, problem):
            status = f"**FAILED**: {r['reason']}" if r["failed"] else "ok"
            extra = ""
            if r.get("compile_s"):
                extra = f" (+ compile {fmt_t(r['compile_s'])})"
            if r["method"] == "closed form (float64)" and problem == "1_closed_form":
                extra = f" (first call {fmt_t(r['time_first_call_s'])})"
            L.append(f"| {r['method']} | {r['setting']} | {fmt_e(r['error'])} | {fmt_t(r['time_median_s'])}{extra} | "
                     f"{r['n_timed']} | {fmt_work(r['work'])} | {status} |")
        if problem == "1_closed_form":
            L.append("")
            L.append("For odd p the ss solution at t = 40 is (1, O(e^-40), O(e^-40)) to 1e-34, so the closed forms "
                     "are exact there up to the representation of the tiny components; the row 'gamma_basis on N "
                     "points' shows the float64 accuracy where the dynamics happen (max over the reference's step "
                     "points, vectorised call).")
        if problem == "2_generic" and window_runs:
            L.append("")
            L.append("The `window [-5, 5]` rows (`--quick` only) integrate from the reference at t = -5 to t = 5 "
                     "(error at t = 5).")
    L.append("")
    L.append("## Cheapest run per accuracy target (not failed, full window)")
    L.append("")
    L.extend(cheapest_table(runs, single_shot=False))
    L.append("")
    L.append("The same for a single integration (one-off costs included: first call + heyoka's cold JIT compile; "
             "the first call of `gamma_basis` computes its coefficients):")
    L.append("")
    L.extend(cheapest_table(runs, single_shot=True))
    L.append("")
    L.append("## Time to reach an accuracy, per method (problem 2, cheapest non-failed run)")
    L.append("")
    L.append("Cell: median time (setting); in brackets the single-integration cost (first call + compile).")
    L.append("")
    L.append("| method | " + " | ".join(f"error <= {t:.0e}" for t in METHOD_TARGETS) + " |")
    L.append("|---|" + "---|" * len(METHOD_TARGETS))
    for method in METHOD_ORDER:
        if not any(r["method"] == method and r["problem"] == "2_generic" for r in runs):
            continue
        cells = []
        for t in METHOD_TARGETS:
            r = cheapest(runs, "2_generic", t, method)
            cells.append(f"{fmt_t(r['time_median_s'])} ({r['setting']}) "
                         f"[{fmt_t(one_off(r))}]" if r else "—")
        L.append(f"| {method} | " + " | ".join(cells) + " |")
    L.append("")
    L.append("## Hazard: a solver started on the limit axis (problem 2)")
    L.append("")
    L.append("gamma(t0) = (-1, 0, 0) exactly at t0 = -40 (differs from the ss solution by ~1e-17, which stays "
             "~1e-17: the flow is a rotation), with no `max_step` against `max_step = 0.5`; the first row per "
             "method is the main sweep's start (reference value, no `max_step`). heyoka: `max_delta_t` in "
             "`propagate_until` plays the part of `max_step`, and rtol means its tol. One run each; cell = "
             "error at t = 40 / nfev (heyoka: steps).")
    L.append("")
    rt = sorted({h["rtol"] for h in hazard}, reverse=True)
    L.append("| method | start | max_step | " + " | ".join(f"rtol {x:.0e}" for x in rt) + " |")
    L.append("|---|---|---|" + "---:|" * len(rt))
    keys = []
    for h in hazard:
        k = (h["method"], h["start"], h["max_step"])
        if k not in keys:
            keys.append(k)
    for k in keys:
        cells = []
        for x in rt:
            h = next(h for h in hazard if (h["method"], h["start"], h["max_step"]) == k and h["rtol"] == x)
            c = f"{fmt_e(h['error'])} / {h['work'].get('nfev', h['work'].get('steps'))}"
            cells.append(f"**FAILED** {c}" if h["failed"] else c)
        L.append(f"| {k[0]} | {k[1]} | {'none' if k[2] is None else k[2]} | " + " | ".join(cells) + " |")
    L.append("")
    L.append("## Sanity checks")
    L.append("")
    for problem, c in checks["magnus_order"].items():
        ratios = ", ".join(f"{x:.1f}" for x in c["ratios_per_halving"])
        sl = f"{c['slope']:.2f}" if c["slope"] is not None else "n/a"
        L.append(f"* Magnus-4, {problem}: observed order (slope of log error vs log h, errors > 1e-12) {sl}; "
                 f"error ratio per halving of h between consecutive step sizes: {ratios} (16 = 4th order).")
    drift = max(v for c in checks["magnus_norm_drift"].values() for v in c.values())
    L.append(f"* Magnus-4 keeps |gamma(40)| = 1 to {drift:.1e} at every step size and problem.")
    for problem, c in checks["dop853_smallest_rtol"].items():
        L.append(f"* DOP853 at rtol {c['rtol']:.0e}, {problem}: error {c['error']:.1e}.")
    L.append("")
    L.append("## Recommendation")
    L.append("")
    L.append(recommendation(runs, hazard, checks, refs))
    L.append("")
    path.write_text("\n".join(L) + "\n")


def write_plot(path, runs, meta, refs=None):
    fig = draw(runs, meta, PROBLEMS, refs)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def jsonable(x):
    if isinstance(x, dict):
        return {str(k): jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, mpmath.mpf):
        return mpmath.nstr(x, 40)
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    if isinstance(x, float) and not math.isfinite(x):
        return str(x)
    return x


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fast smoke run (few settings, one repeat)")
    ap.add_argument("--repeat", type=int, default=5, help="timed runs after a warm-up (default 5)")
    ap.add_argument("--budget", type=float, default=5.0,
                    help="stop the timed runs of one configuration after this many seconds (default 5)")
    ap.add_argument("--jobs", type=int, default=2, help="processes for the (untimed) reference runs (default 2)")
    ap.add_argument("--out", type=Path, default=ROOT / "bench" / "results", help="output directory")
    args = ap.parse_args(argv)
    if args.quick and "--repeat" not in " ".join(sys.argv):
        args.repeat = 1
    start = time.perf_counter()

    def log(msg):
        print(f"[{time.perf_counter() - start:7.1f} s] {msg}", file=sys.stderr, flush=True)

    log(f"machine: {machine_line(machine())}")
    if HEYOKA_ERROR:
        log(f"heyoka not available ({HEYOKA_ERROR}): skipped")
    else:  # compile times independent of earlier runs, and nothing written to ~/.cache/heyoka
        hy.llvm_state.set_diskcache_enabled(False)
    refs, runs, hazard, checks, window_runs = run_study(args, log)
    total = time.perf_counter() - start
    cmd = "python bench/bench_work_precision.py" + (" --quick" if args.quick else "") + \
        (f" --repeat {args.repeat}" if args.repeat != (1 if args.quick else 5) else "") + \
        (f" --budget {args.budget:g}" if args.budget != 5.0 else "")
    meta = {"machine": machine(), "command": cmd, "repeat": args.repeat, "budget": args.budget,
            "quick": args.quick, "total_seconds": total, "heyoka_skipped": HEYOKA_ERROR}
    args.out.mkdir(parents=True, exist_ok=True)
    write_plot(args.out / "work_precision.png", runs, meta, refs)
    write_markdown(args.out / "work_precision.md", meta, refs, runs, hazard, checks, window_runs)
    data = {"meta": meta,
            "settings": {"t0": T0, "t1": T1, "cases": CASES, "problems": PROBLEMS, "atol": "rtol * 1e-3",
                         "fail_rule": {"abs": ABS_FAIL, "times_tolerance": REL_FAIL}},
            "references": {case: {"dps": r["dps"], "p": r["p"], "d": r["d"], "info": r["info"],
                                  "gamma_start_-40": r["start"], "gamma_40": r["at"][40.0],
                                  "gamma_60": r["at"][60.0], "dpsi_closed": r["dpsi_closed"]}
                           for case, r in refs.items()},
            "runs": sorted(runs, key=lambda r: (r["problem"], METHOD_ORDER.index(r["method"]), r["sort_key"],
                                                r["setting"])),
            "hazard": hazard, "checks": checks}
    (args.out / "work_precision.json").write_text(json.dumps(jsonable(data), indent=1, sort_keys=True) + "\n")
    log(f"wrote {args.out / 'work_precision.md'}, .json, .png; total {total:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
