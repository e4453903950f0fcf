"""Cost of certifying the first integrals P1, P2, P3 (Theorem 6.2) as p grows.

Three routes, side by side in one run, on the same claim (dF3/dt = 0 along
eq:sysfin + Poisson, P2 a polynomial):

* ``flint``: the build's route, fraction-free in Z[d, w1, w2, g1, g2, g3]
  with python-flint (``derivations.sections.first_integrals.certify_p``);
* ``QQ(d)``: SymPy ``Poly`` over the rational-function field QQ(d)
  (``derivations.sections.first_integrals.sympy_integral`` + ``lie_residual``);
* ``simplify``: SymPy expression trees with ``simplify`` (the straightforward
  route; not a certificate, shown for its cost only), for p <= 11.

Targets (issue 4): all odd p <= 101 in under 10 s in total, p = 201 alone in
under 30 s.  Reports time per p (median of ``--repeat`` runs after a warm-up)
and the growth exponent of the flint route (least-squares slope of
log(time) against log(p) for p >= 21).

Run:  python bench/bench_first_integrals.py            (writes bench/results/first_integrals.md)
"""
from __future__ import annotations

import argparse
import json
import math
import platform
import statistics
import sys
import time
from pathlib import Path

import flint
import sympy as sp

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from bench.machine_info import cpu_name  # noqa: E402
from bench.timing import median_seconds  # noqa: E402
from derivations.core.certificates import CertificateLog  # noqa: E402
from derivations.core.symbols import d, g1, g2, g3, p, w1, w2  # noqa: E402
from derivations.sections import first_integrals as fi  # noqa: E402

FIELD = {w1: d / (p * (d**2 + 1)) * w2**2, w2: -d / p * w1 * w2}


def machine() -> str:
    cpu = cpu_name()
    return (f"{cpu}; {platform.machine()}; Python {platform.python_version()}; python-flint {flint.__version__}; "
            f"SymPy {sp.__version__}")


def flint_route(p_value: int):
    log = CertificateLog()
    _, certs = fi.certify_p(log, p_value, FIELD)
    assert all(c.outcome.value == "pass" for c in certs)


def field_route(p_value: int):
    field = {k: v.subs(p, p_value) for k, v in FIELD.items()}
    P = fi.sympy_integral(p_value, lambda j: fi.hypergeometric_coefficient(j, p_value, d))
    assert fi.lie_residual(P, field).is_zero


def simplify_route(p_value: int):
    F1 = (d**2 + 1) * w1**2 + w2**2
    J = (p_value - 1) // 2
    Q = sum(fi.hypergeometric_coefficient(j, p_value, d) * w2 ** (2 * j) * F1 ** (J - j) for j in range(J + 1))
    L = lambda P: w2 / (d**2 + 1) * sp.diff(P, w1) - w1 * sp.diff(P, w2)  # noqa: E731
    P1 = w1 * Q
    P3 = -d / p_value * L(P1)
    P2 = sp.simplify(w2 / w1 * (P1 - d / p_value * L(P3)))
    F3 = P1 * g1 + P2 * g2 + P3 * g3
    rhs = {w1: FIELD[w1].subs(p, p_value), w2: FIELD[w2].subs(p, p_value),
           g1: -w2 * g3, g2: w1 * g3, g3: w2 * g1 - w1 * g2}
    dF3 = sum(sp.diff(F3, v) * r for v, r in rhs.items())
    assert sp.simplify(dF3) == 0


def slope(points: list[tuple[int, float]]) -> float:
    xs = [math.log(x) for x, _ in points]
    ys = [math.log(y) for _, y in points]
    mx, my = statistics.fmean(xs), statistics.fmean(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pmax", type=int, default=101, help="largest odd p of the flint sweep (default 101)")
    ap.add_argument("--big", type=int, default=201, help="the single large p (default 201)")
    ap.add_argument("--simplify-pmax", type=int, default=11, help="largest p for the simplify route (default 11)")
    ap.add_argument("--field-pmax", type=int, default=21, help="largest p for the QQ(d) route (default 21)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "first_integrals.md")
    args = ap.parse_args(argv)

    rows = {}
    sweep_total = 0.0
    for p_value in range(1, args.pmax + 1, 2):
        seconds = median_seconds(lambda: flint_route(p_value), args.repeat)
        sweep_total += seconds
        rows.setdefault(p_value, {})["flint"] = seconds
        print(f"flint     p = {p_value:4d}: {seconds:.4f} s", file=sys.stderr)
    big = median_seconds(lambda: flint_route(args.big), 1)
    rows.setdefault(args.big, {})["flint"] = big
    print(f"flint     p = {args.big:4d}: {big:.4f} s", file=sys.stderr)
    for p_value in range(1, args.field_pmax + 1, 2):
        rows[p_value]["QQ(d)"] = median_seconds(lambda: field_route(p_value), 1)
        print(f"QQ(d)     p = {p_value:4d}: {rows[p_value]['QQ(d)']:.4f} s", file=sys.stderr)
    for p_value in range(1, args.simplify_pmax + 1, 2):
        start = time.perf_counter()
        simplify_route(p_value)
        rows[p_value]["simplify"] = time.perf_counter() - start
        print(f"simplify  p = {p_value:4d}: {rows[p_value]['simplify']:.4f} s", file=sys.stderr)

    exponent = slope([(q, r["flint"]) for q, r in rows.items() if q >= 21 and "flint" in r])
    lines = [
        "# Certifying the first integrals: cost against p",
        "",
        f"Machine: {machine()}.",
        "",
        f"Command: `python bench/bench_first_integrals.py --pmax {args.pmax} --big {args.big} "
        f"--repeat {args.repeat}`",
        "",
        f"* flint, all odd p <= {args.pmax}: **{sweep_total:.2f} s** in total (target: < 10 s)",
        f"* flint, p = {args.big}: **{big:.2f} s** (target: < 30 s)",
        f"* growth exponent of the flint route (p >= 21): time ~ p^{exponent:.2f}",
        "",
        "Median of the repeats after a warm-up for flint; one run for the SymPy routes.",
        "`simplify` is the straightforward SymPy route (expression trees, `simplify`), shown for its cost;",
        "`QQ(d)` is SymPy's `Poly` over the rational-function field.",
        "",
        "| p | flint (s) | QQ(d) (s) | simplify (s) |",
        "|---:|---:|---:|---:|",
    ]
    for q in sorted(rows):
        r = rows[q]
        cell = lambda key: f"{r[key]:.4f}" if r.get(key) is not None else ""  # noqa: E731
        lines.append(f"| {q} | {cell('flint')} | {cell('QQ(d)')} | {cell('simplify')} |")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text("\n".join(lines) + "\n")
    args.out.with_suffix(".json").write_text(json.dumps(
        {"machine": machine(), "sweep_total_s": sweep_total, "big_p": args.big, "big_s": big,
         "exponent": exponent, "rows": {str(k): v for k, v in sorted(rows.items())}}, indent=1, sort_keys=True))
    print("\n".join(lines[:12]))
    ok = sweep_total < 10 and big < 30
    print("targets met" if ok else "TARGETS MISSED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
