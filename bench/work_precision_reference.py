"""Work-precision study, the reference: the ss power series in x = e^t and an mpmath Taylor integrator.

Independent of every method timed (see ``bench/bench_work_precision.py``): exact start values, Taylor
coefficients of tanh and sech by their own recurrences, two runs at different steps and precisions.
"""
from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import matplotlib
import mpmath
import numpy as np

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from work_precision_setup import CASES, T0, T1, gamma_basis_mp  # noqa: E402

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


