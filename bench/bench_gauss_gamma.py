"""gamma(t) by Gauss's 2F1 closed form against the two integrators it replaces, side by side in one run (issue 44).

The body and grid of Fig. 2 (``scenes/fig2_gamma_ss.toml``: p = 2.5, d = 0.7, t in [-10, 10], 2001 samples, the
boundary condition ss), and the general body (5/4, 1, 3/10, -1/2) on the same grid; ``--fast`` adds p = 30,
d = 0.5 (|u| + |v| = 116).  Per body, the three routes as the simulator calls them:

* ``gauss_2f1``: :func:`suslov.kernel.gauss_gamma_float.solve` (the per-body precomputation in mpmath, the float64
  series at every sample, and the run's checks: ``|gamma|``, the mpmath closed form at 3 samples, the ODE
  residual there), also timed without the checks (``checks=0``);
* DOP853: :func:`suslov.simulator.integrate.solve_poisson` at the scene's rtol 1e-11, atol 1e-13 (with the
  simulator's error estimate, a second run 100 times tighter), from the ss series at lam t = -10;
* heyoka: :func:`suslov.simulator.taylor.solve_poisson_taylor` at tol 1e-11 (with its check run at 1e-14); the
  one-off LLVM compilation is excluded from the medians (a warm-up call) and reported on its own.

Times are medians of ``--repeat`` (default 3) calls after one warm-up.  Accuracy: the largest |difference| of each
route from the mpmath route at 30 digits (:func:`suslov.kernel.gauss_gamma.gamma_gauss_uv`, itself checked against
mpmath's Taylor integration at 45 digits in ``tests/test_gauss_gamma.py``) on 41 evenly spaced samples.  Also the
whole Fig. 2 scene (``suslov.simulate``, no figures) by each route (warm: heyoka compiled, mpmath's caches filled).

Run: ``python bench/bench_gauss_gamma.py`` (about 1 minute on the 2 shared cores); writes
``bench/results/gauss_gamma.json`` and ``.md``.
"""
from __future__ import annotations

import argparse
import os
import platform
import sys
import time
from pathlib import Path

import mpmath
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from machine_info import cpu_name  # noqa: E402
from results_io import write_results  # noqa: E402
from timing import median_seconds  # noqa: E402

import suslov  # noqa: E402
from suslov.kernel.gauss_gamma import gamma_gauss_uv  # noqa: E402
from suslov.kernel.gauss_gamma_float import solve as gauss_solve  # noqa: E402
from suslov.simulator import integrate, taylor  # noqa: E402
from suslov.simulator.body import make_body  # noqa: E402
from suslov.simulator.scene import load_scene  # noqa: E402

NAME = "gauss_gamma"
FIG2 = ROOT / "scenes" / "fig2_gamma_ss.toml"
RTOL, ATOL = 1e-11, 1e-13     # the Fig. 2 scene's numerics
REFERENCE_DPS = 30


def bodies(fast: bool) -> list:
    out = [("Fig. 2: p = 2.5, d = 0.7", make_body(p=2.5, d=0.7)),
           ("general (5/4, 1, 3/10, -1/2)", make_body([[1.25, 0, 0.3], [0, 1, -0.5], [0.3, -0.5, 1.5]]))]
    if fast:
        out.append(("fast: p = 30, d = 0.5", make_body(p=30, d=0.5)))
    return out


def routes(body, t):
    t_start, g0 = integrate.ss_initial(body, t[0])
    return {
        "gauss_2f1": lambda: gauss_solve(body.u, body.v, body.rate * t, "ss").values[:, 0],
        "gauss_2f1 (no checks)": lambda: gauss_solve(body.u, body.v, body.rate * t, "ss", checks=0).values[:, 0],
        "DOP853": lambda: integrate.solve_poisson(body, t, g0, RTOL, ATOL, "DOP853", t_start=t_start).values[:, 0],
        "heyoka": lambda: taylor.solve_poisson_taylor(body, t, g0, tol=RTOL, t_start=t_start).values[:, 0],
    }


def reference(body, t, picks):
    with mpmath.workdps(REFERENCE_DPS):
        exact = gamma_gauss_uv([mpmath.mpf(float(body.rate * t[i])) for i in picks], body.u, body.v, dps=REFERENCE_DPS)
    return np.array([[float(x) for x in g] for g in exact])


def measure(label, body, t, repeat) -> dict:
    picks = np.linspace(0, len(t) - 1, 41).astype(int)
    exact = reference(body, t, picks)
    row = {"body": label, "u": body.u.tolist(), "v": body.v.tolist(), "routes": {}}
    compile_before = dict(taylor.COMPILE_SECONDS)
    for name, run in routes(body, t).items():
        seconds = median_seconds(run, repeat)
        values = run()
        error = float(np.max(np.abs(values[picks] - exact)))
        row["routes"][name] = {"seconds": seconds, "max_abs_error_vs_mp30": error,
                               "max_norm_drift": float(np.max(np.abs(np.linalg.norm(values, axis=-1) - 1)))}
    checks = gauss_solve(body.u, body.v, body.rate * t, "ss").summary()
    row["gauss_checks"] = {k: checks[k] for k in ("norm_drift", "ode_residual", "taylor_centres", "far_series_radius")}
    row["gauss_checks"]["mp_check_max_abs_difference"] = checks["mp_check"]["max_abs_difference"]
    compiled = {f"k={k}, tol={tol:g}": s for (k, tol), s in taylor.COMPILE_SECONDS.items() if (k, tol) not in compile_before}
    row["heyoka_compile_seconds"] = compiled
    return row


def scene_times(repeat) -> dict:
    gauss, integrated, taylor_scene = load_scene(FIG2), load_scene(FIG2), load_scene(FIG2)
    integrated.gamma_route = taylor_scene.gamma_route = "integrate"
    taylor_scene.method = "taylor"
    out = {}
    for name, scene in (("gauss_2f1", gauss), ("integrate (the scene's DOP853)", integrated),
                        ("integrate (heyoka, method = \"taylor\")", taylor_scene)):
        out[name] = median_seconds(lambda s=scene: suslov.simulate(s), repeat)
    return out


def markdown(data) -> str:
    m = data["machine"]
    head = (f"Machine: {m['cpu']}, {m['cores']} cores (shared), Python {m['python']}, {m['platform']}.  "
            f"Command: `{data['command']}`.  Medians of {data['repeat']} calls after a warm-up; errors: largest "
            f"|difference| from the mpmath route at {REFERENCE_DPS} digits on 41 samples.")
    grid = ("Grid: t in [-10, 10], 2001 samples, boundary condition ss; DOP853 and heyoka at the scene's tolerance "
            f"{RTOL:g} (each with the simulator's tighter check run).")
    lines = ["# gamma(t) by Gauss's 2F1 vs integration (Fig. 2 grid)", "", head, "", grid, ""]
    for row in data["bodies"]:
        lines += [f"## {row['body']}", "", "| route | seconds | max error vs mp30 | max abs(norm - 1) |",
                  "|---|---|---|---|"]
        for name, r in row["routes"].items():
            lines.append(f"| {name} | {r['seconds']:.4f} | {r['max_abs_error_vs_mp30']:.2e} | {r['max_norm_drift']:.1e} |")
        g = row["gauss_checks"]
        base = row["routes"]["gauss_2f1"]["seconds"]
        compiled = ", ".join(f"{k}: {s:.2f} s" for k, s in row["heyoka_compile_seconds"].items()) or "cached"
        ratio = (f"DOP853 / gauss_2f1 = {row['routes']['DOP853']['seconds'] / base:.1f}x, heyoka / gauss_2f1 = "
                 f"{row['routes']['heyoka']['seconds'] / base:.3f}x.  Gauss route's own checks: mp (20 digits) at 3 "
                 f"samples {g['mp_check_max_abs_difference']:.1e}, ODE residual {g['ode_residual']:.1e}, "
                 f"{g['taylor_centres']} Taylor centres, far series radius {g['far_series_radius']:.3g}.  heyoka "
                 f"compilation (excluded from its time): {compiled}")
        lines += ["", ratio, ""]
    lines += ["## The whole Fig. 2 scene (`suslov.simulate`, no figures)", "", "| gamma route | seconds |", "|---|---|"]
    lines += [f"| {name} | {s:.3f} |" for name, s in data["scene_seconds"].items()]
    return "\n".join(lines) + "\n"


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--fast", action="store_true", help="add p = 30, d = 0.5 (|u| + |v| = 116)")
    args = parser.parse_args(argv)
    t = load_scene(FIG2).times()
    start = time.perf_counter()
    data = {"machine": {"cpu": cpu_name(), "cores": os.cpu_count(), "python": platform.python_version(),
                        "platform": platform.platform()},
            "command": "python bench/bench_gauss_gamma.py" + (" --fast" if args.fast else "")
                       + (f" --repeat {args.repeat}" if args.repeat != 3 else ""),
            "repeat": args.repeat, "grid": {"t0": float(t[0]), "t1": float(t[-1]), "samples": len(t)},
            "bodies": [measure(label, body, t, args.repeat) for label, body in bodies(args.fast)],
            "scene_seconds": scene_times(args.repeat)}
    data["total_seconds"] = time.perf_counter() - start
    write_results(NAME, data, markdown(data))
    print(markdown(data))


if __name__ == "__main__":
    main()
