"""The closed-form scattering angle of any body against the integration routes it replaces, in one run.

Measured side by side, on the same bodies, in one process:

1. float64.  ``suslov.general_scattering_angle`` (closed form, NumPy-vectorised) on ``--bodies``
   (default 10^5) random bodies, seeded: I11, I22 uniform in [0.2, 3], I13, I23 uniform in [-1, 1]
   (det I = 1 fixes I33; every such tensor is positive definite), microseconds per body as the median
   of ``--repeat`` vectorised calls divided by the number of bodies; also one scalar call per body.
   Beside it, the simulator's float integration route for a general body (heyoka's Taylor method,
   ``suslov.simulator.taylor.taylor_angle`` at tol 1e-12, as ``suslov.simulator.engine.numeric_angle``
   calls it for ``method = "taylor"``) on the first ``--sample`` bodies (default 20): median over the
   sample of each body's median time (the body built beforehand by ``make_body``; the one-off LLVM
   compilation is reported separately).  Ratios of the medians; the largest |difference| of the two
   routes on the sample, and of each route against the closed-form ball at 200 bits of the same float
   entries (a reference that decides which route is off, if they differ).
2. balls.  ``suslov.general_scattering_angle_ball(..., prec=BITS)`` at ``--digits`` (default 300)
   decimal digits (BITS = ceil(digits log2 10) + 8) on a few exact bodies, seconds (median of
   ``--repeat`` after a warm-up, and the cold first call) and width 2 rad; beside it the validated
   integration ``suslov.validated.scattering_angle_enclosure(..., dps=30)`` (``method="integration"``
   when the keyword exists) on the same bodies: seconds, width, and whether its ball contains the
   closed-form ball's midpoint (and the two balls overlap).

Run: ``python bench/bench_general_angle.py`` (about 1 minute on the 2 shared cores; ``--quick``: 10^4
bodies, sample 10, 3 repeats); writes ``bench/results/general_angle.json`` and ``.md``.  The machine
has 2 shared cores: quote medians and ratios, not single runs.
"""
from __future__ import annotations

import argparse
import inspect
import math
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from flint import arb

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from machine_info import cpu_name  # noqa: E402
from results_io import write_results  # noqa: E402
from timing import median_seconds  # noqa: E402

import suslov as sf  # noqa: E402
from suslov.simulator import taylor  # noqa: E402
from suslov.simulator.body import make_body  # noqa: E402
from suslov.validated import scattering_angle_enclosure  # noqa: E402

NAME = "general_angle"
TAYLOR_TOL = 1e-12          # what engine.numeric_angle passes for method = "taylor"
REFERENCE_BITS = 200        # closed-form ball of the float entries: the reference for the float sample
BALL_BODIES = (             # exact entries (paper's frame, I12 = 0)
    ("5/4", "1", "3/10", "-1/2"),        # the general body of bench_enclosure and the docstrings
    ("5/4", "1", "0", "-1/4"),           # I13 = 0 (p = 2, d = 1/2): Theorem 5.4's case
    ("2", "1/2", "-7/10", "1/5"),
    ("1/2", "2", "1/3", "2/3"),          # I11 < I22 (not the canonical order)
)


def random_bodies(n: int, seed: int) -> tuple:
    rng = np.random.default_rng(seed)
    return (rng.uniform(0.2, 3.0, n), rng.uniform(0.2, 3.0, n), rng.uniform(-1.0, 1.0, n),
            rng.uniform(-1.0, 1.0, n))


def tensor(I11, I22, I13, I23) -> np.ndarray:
    I33 = (1.0 + I11 * I23**2 + I22 * I13**2) / (I11 * I22)     # det I = 1
    return np.array([[I11, 0.0, I13], [0.0, I22, I23], [I13, I23, I33]])


def float_part(n: int, sample: int, repeat: int, seed: int) -> dict:
    I11, I22, I13, I23 = random_bodies(n, seed)
    vector_s = median_seconds(lambda: sf.general_scattering_angle(I11, I22, I13, I23), repeat)
    closed = sf.general_scattering_angle(I11, I22, I13, I23)
    finite = int(np.count_nonzero(np.isfinite(closed)))
    in_range = int(np.count_nonzero((closed >= 0) & (closed <= math.pi)))

    entries = [tuple(float(x[i]) for x in (I11, I22, I13, I23)) for i in range(sample)]
    scalar_s = [median_seconds(lambda e=e: sf.general_scattering_angle(*e), repeat) for e in entries]

    start = time.perf_counter()
    taylor.integrator(1, TAYLOR_TOL)                       # compile both integrators once (cached)
    taylor.integrator(1, taylor._tolerances(TAYLOR_TOL)[1])
    compile_s = time.perf_counter() - start
    rows, heyoka_s, failures = [], [], []
    for i, e in enumerate(entries):
        body = make_body(tensor=tensor(*e))
        try:
            seconds = median_seconds(lambda body=body: taylor.taylor_angle(body, tol=TAYLOR_TOL), repeat)
            angle, estimate, run = taylor.taylor_angle(body, tol=TAYLOR_TOL)
        except (RuntimeError, ValueError) as failure:   # a stopped integration: say so, do not hide it
            failures.append({"index": i, "entries": e, "error": str(failure)})
            continue
        heyoka_s.append(seconds)
        ref = sf.general_scattering_angle_ball(*e, prec=REFERENCE_BITS)
        ref_f = float(ref.mid())
        rows.append({"index": i, "entries": e, "canonical_entries": tuple(map(float, body.entries)),
                     "closed": float(closed[i]), "closed_canonical": float(sf.general_scattering_angle(*body.entries)),
                     "heyoka": angle, "heyoka_error_estimate": estimate, "heyoka_steps": run.nfev,
                     "heyoka_seconds": seconds, "reference": ref_f})
    diff = lambda key, other: max((abs(r[key] - r[other]) for r in rows), default=float("nan"))  # noqa: E731
    us_vector = vector_s / n * 1e6
    us_scalar = statistics.median(scalar_s) * 1e6
    us_heyoka = statistics.median(heyoka_s) * 1e6 if heyoka_s else float("nan")
    return {"bodies": n, "seed": seed, "sample": sample, "repeat": repeat,
            "closed_vector_us_per_body": us_vector, "closed_vector_seconds_total": vector_s,
            "closed_scalar_us_per_call": us_scalar,
            "heyoka_us_per_body": us_heyoka, "heyoka_tol": TAYLOR_TOL, "heyoka_compile_seconds": compile_s,
            "heyoka_us_per_body_min_max": [min(heyoka_s) * 1e6, max(heyoka_s) * 1e6] if heyoka_s else None,
            "ratio_heyoka_over_closed_vector": us_heyoka / us_vector,
            "ratio_heyoka_over_closed_scalar": us_heyoka / us_scalar,
            "finite_angles": finite, "angles_in_0_pi": in_range,
            "max_abs_closed_minus_heyoka": diff("closed", "heyoka"),
            "max_abs_closed_minus_reference": diff("closed", "reference"),
            "max_abs_heyoka_minus_reference": diff("heyoka", "reference"),
            "max_abs_closed_raw_minus_canonical_frame": diff("closed", "closed_canonical"),
            "max_heyoka_error_estimate": max((r["heyoka_error_estimate"] for r in rows), default=float("nan")),
            "heyoka_error_above_its_estimate": sum(abs(r["heyoka"] - r["reference"]) > r["heyoka_error_estimate"]
                                                   for r in rows),
            "heyoka_failures": failures, "sample_rows": rows}


def width_of(ball) -> tuple:
    """(width as a 3-digit string, log10 width): the width can be below float64's range (1e-324)."""
    w = 2 * arb(ball.rad())
    if w == 0:
        return "0", float("-inf")
    return w.str(3, radius=False), float((w.log() / arb(10).log()).mid())


def ball_part(digits: int, enc_digits: int, repeat: int, enc_repeat: int) -> dict:
    bits = math.ceil(digits * math.log2(10)) + 8
    integration_kw = ({"method": "integration"}
                      if "method" in inspect.signature(scattering_angle_enclosure).parameters else {})
    rows = []
    for body in BALL_BODIES:
        start = time.perf_counter()
        ball = sf.general_scattering_angle_ball(*body, prec=bits)
        cold = time.perf_counter() - start
        seconds = median_seconds(lambda body=body: sf.general_scattering_angle_ball(*body, prec=bits), repeat)
        w_str, w_log = width_of(ball)
        enc_s = median_seconds(lambda body=body: scattering_angle_enclosure(*body, dps=enc_digits,
                                                                            **integration_kw), enc_repeat)
        enc = scattering_angle_enclosure(*body, dps=enc_digits, **integration_kw)
        e_str, e_log = width_of(enc.angle)
        mid = arb(ball.mid())
        rows.append({"body": body, "closed_bits": bits, "closed_seconds": seconds, "closed_cold_seconds": cold,
                     "closed_width": w_str, "closed_log10_width": w_log,
                     "closed_mid_30": ball.mid().str(30, radius=False),
                     "integration_digits": enc_digits, "integration_seconds": enc_s,
                     "integration_width": e_str, "integration_log10_width": e_log,
                     "integration_mid_30": enc.angle.mid().str(30, radius=False),
                     "integration_contains_closed_mid": bool(enc.angle.contains(mid)),
                     "balls_overlap": bool(enc.angle.overlaps(ball)),
                     "ratio_integration_over_closed": enc_s / seconds})
    return {"digits": digits, "bits": bits, "repeat": repeat, "integration_repeat": enc_repeat,
            "integration_kwargs": integration_kw, "rows": rows}


def revision() -> str:
    try:
        return subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def uncommitted() -> list:
    """Files of the measured code (suslov/, generated/) that differ from the revision: others edit concurrently."""
    try:
        out = subprocess.run(["git", "status", "--porcelain", "--", "suslov", "generated"], cwd=ROOT,
                             capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return ["unknown"]
    return [line[3:] for line in out.splitlines()]


def markdown(data: dict) -> str:
    f, b = data["float"], data["balls"]
    lines = ["# The closed-form scattering angle of any body against the integration routes", "",
             f"Machine: {data['machine']}. Revision {data['revision']}"
             + (f" with uncommitted changes in {', '.join(data['uncommitted_measured_files'])}"
                if data["uncommitted_measured_files"] else "")
             + f". Command: `{data['command']}` "
             f"({data['wall_seconds']:.0f} s). Medians of {f['repeat']} runs after a warm-up "
             "(2 shared cores: compare ratios). Load average (1 min) before / after: "
             f"{data['load_average_1_5_15']['before'][0]:.2f} / {data['load_average_1_5_15']['after'][0]:.2f}.", "",
             f"## float64: {f['bodies']} random bodies (seed {f['seed']}), I11, I22 in [0.2, 3], I13, I23 in [-1, 1]", "",
             "| route | bodies | us per body (median) | heyoka / this |", "| --- | ---: | ---: | ---: |",
             f"| closed form, one vectorised call | {f['bodies']} | {f['closed_vector_us_per_body']:.3f} | "
             f"{f['ratio_heyoka_over_closed_vector']:.0f} |",
             f"| closed form, one scalar call per body | {f['sample']} | {f['closed_scalar_us_per_call']:.1f} | "
             f"{f['ratio_heyoka_over_closed_scalar']:.1f} |",
             f"| heyoka Taylor tol {f['heyoka_tol']:g} (`taylor_angle`, simulator route) | "
             f"{f['sample'] - len(f['heyoka_failures'])} | {f['heyoka_us_per_body']:.0f} | 1 |", "",
             f"heyoka per body: {f['heyoka_us_per_body_min_max'][0]:.0f} to {f['heyoka_us_per_body_min_max'][1]:.0f} us "
             f"over the sample; its one-off compilation (two integrators): {f['heyoka_compile_seconds']:.2f} s "
             f"(not in the per-body times); heyoka failures: {len(f['heyoka_failures'])}.", "",
             "| on the sample | max abs |", "| --- | ---: |",
             f"| closed form - heyoka | {f['max_abs_closed_minus_heyoka']:.1e} |",
             f"| closed form - closed-form ball at {REFERENCE_BITS} bits (same float entries) | "
             f"{f['max_abs_closed_minus_reference']:.1e} |",
             f"| heyoka - closed-form ball at {REFERENCE_BITS} bits | {f['max_abs_heyoka_minus_reference']:.1e} |",
             f"| heyoka's own error estimate (largest; bodies where the error against the ball exceeds it: "
             f"{f['heyoka_error_above_its_estimate']} of {len(f['sample_rows'])}) | {f['max_heyoka_error_estimate']:.1e} |",
             f"| closed form on the raw entries - on the simulator's canonical-frame entries | "
             f"{f['max_abs_closed_raw_minus_canonical_frame']:.1e} |", "",
             f"All {f['bodies']} closed-form angles finite: {f['finite_angles'] == f['bodies']}; in [0, pi]: "
             f"{f['angles_in_0_pi'] == f['bodies']}.", "",
             f"## Balls: closed form at {b['digits']} digits ({b['bits']} bits) against validated integration "
             f"at {b['rows'][0]['integration_digits']} digits", "",
             "| body (I11, I22, I13, I23) | closed form s (median) | first call s | width | integration s | "
             "width | integration / closed | contains closed mid | overlap |",
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- |"]
    for r in b["rows"]:
        lines.append(f"| {', '.join(r['body'])} | {r['closed_seconds']:.5f} | {r['closed_cold_seconds']:.5f} | "
                     f"{r['closed_width']} | {r['integration_seconds']:.3f} | {r['integration_width']} | "
                     f"{r['ratio_integration_over_closed']:.0f} | {'yes' if r['integration_contains_closed_mid'] else 'NO'} | "
                     f"{'yes' if r['balls_overlap'] else 'NO'} |")
    lines += ["", f"Integration keyword arguments: {b['integration_kwargs'] or 'none (no method= keyword yet)'}; "
              f"integration medians of {b['integration_repeat']} runs.", ""]
    return "\n".join(lines)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bodies", type=int, default=100_000)
    ap.add_argument("--sample", type=int, default=20, help="bodies for the heyoka route (default 20)")
    ap.add_argument("--repeat", type=int, default=9)
    ap.add_argument("--integration-repeat", type=int, default=3)
    ap.add_argument("--digits", type=int, default=300, help="decimal digits of the closed-form balls")
    ap.add_argument("--integration-digits", type=int, default=30)
    ap.add_argument("--seed", type=int, default=20261125)
    ap.add_argument("--quick", action="store_true", help="10^4 bodies, sample 10, 3 repeats (1 for integration)")
    if ap.parse_args(argv).quick:   # new defaults; options given explicitly still win
        ap.set_defaults(bodies=10_000, sample=10, repeat=3, integration_repeat=1)
    args = ap.parse_args(argv)
    load_before = os.getloadavg()
    start = time.perf_counter()
    data = {"machine": f"{cpu_name()}, CPython {platform.python_version()}, NumPy {np.__version__}, 2 cores (shared)",
            "revision": revision(), "uncommitted_measured_files": uncommitted(),
            "command": " ".join(["python bench/bench_general_angle.py", *(sys.argv[1:] if argv is None else argv)]),
            "float": float_part(args.bodies, args.sample, args.repeat, args.seed),
            "balls": ball_part(args.digits, args.integration_digits, args.repeat, args.integration_repeat)}
    data["wall_seconds"] = time.perf_counter() - start
    data["load_average_1_5_15"] = {"before": load_before, "after": os.getloadavg()}
    text = markdown(data)
    write_results(NAME, data, text)
    print(text)


if __name__ == "__main__":
    main()
