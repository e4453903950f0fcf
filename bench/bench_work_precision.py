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

import json
import math
import statistics
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

import argparse  # noqa: E402

from work_precision_methods import (error_of, heyoka_integrator, judge, magnus_run, measure,  # noqa: E402
                                    odefun_run, scipy_run)
from work_precision_plot import METHOD_ORDER  # noqa: E402
from work_precision_reference import build_references, dpsi_closed_mp, dpsi_closed_np  # noqa: E402
from work_precision_report import jsonable, write_markdown, write_plot  # noqa: E402
from work_precision_setup import (ABS_FAIL, CASES, CLOSED_REF_DPS, HEYOKA_ERROR, HEYOKA_MAX_DT,  # noqa: E402
                                  PROBLEMS, REL_FAIL, T0, T1, gamma_basis, gamma_basis_mp, hy, machine,
                                  machine_line)

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
