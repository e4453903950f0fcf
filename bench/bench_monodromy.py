"""Monodromy of the Poisson equations for any body: the cost of a certified verdict (issue 23).

Two measurements, written to ``bench/results/monodromy.{json,md}``:

1. one general body, every monodromy matrix entry to a ball radius of at most 1e-30 (target <= 2 s);
2. the verdict over a 41 x 41 slice of (I13, I23) in [-0.6, 0.6]^2 at I11 = 2, I22 = 1 (the
   general-body study's slice), on all cores through the project's executor (target <= 10 minutes
   on 2 cores), with the count of verdicts that are not certified away from I13 = 0 and I23 = 0.

    python bench/bench_monodromy.py [--size 41] [--digits 20] [--workers N]
    python bench/bench_monodromy.py --dask-check     # the slice again on a Dask LocalCluster (2 workers):
                                                     # the verdicts must be byte-identical to the committed ones
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from fractions import Fraction
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from machine_info import cpu_name  # noqa: E402
from results_io import write_results  # noqa: E402

from suslov import executor  # noqa: E402
from suslov.validated import monodromy  # noqa: E402


def verdict_chunk(task) -> list:
    """Executor work: the verdict of each body of one chunk (exact decimal strings in, plain data out)."""
    digits, bodies = task
    out = []
    for I13, I23 in bodies:
        if Fraction(I13) == 0 and Fraction(I23) == 0:
            out.append("equilibrium")
            continue
        out.append(monodromy("2", "1", I13, I23, dps=digits, max_dps=4 * digits).verdict)
    return out


def slice_tasks(n: int, digits: int):
    values = [str(Fraction(-6, 10) + Fraction(12, 10) * Fraction(k, n - 1)) for k in range(n)]
    bodies = [(a, b) for a in values for b in values]
    return values, bodies, [(digits, bodies[i:i + n]) for i in range(0, len(bodies), n)]


def dask_check(args) -> int:
    """The committed slice's verdicts recomputed on a Dask LocalCluster: byte-identical JSON or exit 1."""
    import distributed

    committed = json.loads((ROOT / "bench" / "results" / "monodromy.json").read_text())["slice"]
    _, _, chunks = slice_tasks(committed["size"], committed["digits"])
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None) as cluster:
        start = time.perf_counter()
        results, _ = executor.run_chunks(verdict_chunk, chunks, [f"m{i}" for i in range(len(chunks))],
                                         scheduler=cluster.scheduler_address)
        seconds = time.perf_counter() - start
    verdicts = [v for chunk in results for v in chunk]
    same = json.dumps(verdicts) == json.dumps(committed["verdicts"])
    print(f"Dask LocalCluster (2 workers): {seconds:.0f} s; verdicts byte-identical to the committed local run: {same}")
    return 0 if same else 1


def one_body(repeat: int = 5) -> dict:
    times, radius = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        m = monodromy("5/4", "1", "3/10", "-1/2", dps=32)
        times.append(time.perf_counter() - start)
        radius = m.radius
    return {"median_seconds": statistics.median(times), "radius": radius, "verdict": m.verdict}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=41)
    ap.add_argument("--digits", type=int, default=20)
    ap.add_argument("--workers", type=int, default=None)
    ap.add_argument("--dask-check", action="store_true",
                    help="run the slice through a Dask LocalCluster and compare with bench/results/monodromy.json")
    args = ap.parse_args(argv)
    if args.dask_check:
        return dask_check(args)
    single = one_body()
    print(f"one body to radius {single['radius']:.1e}: {single['median_seconds']:.2f} s (median of 5)", flush=True)
    n = args.size
    values, bodies, chunks = slice_tasks(n, args.digits)
    start = time.perf_counter()
    results, _ = executor.run_chunks(verdict_chunk, chunks, [f"m{i}" for i in range(len(chunks))],
                                     workers=args.workers,
                                     progress=lambda line: print(line, file=sys.stderr, flush=True))
    seconds = time.perf_counter() - start
    verdicts = [v for chunk in results for v in chunk]
    counts = {v: verdicts.count(v) for v in sorted(set(verdicts))}
    off_axes = [v for (a, b), v in zip(bodies, verdicts) if Fraction(a) != 0 and Fraction(b) != 0]
    unknown_off = sum(v == "unknown" for v in off_axes)
    data = {"machine": f"{cpu_name()}, {os.cpu_count()} cores", "one_body": single, "slice": {
        "size": n, "digits": args.digits, "seconds": seconds, "counts": counts, "unknown_off_axes": unknown_off,
        "grid": values, "verdicts": verdicts}}
    lines = ["# Monodromy and Galois group: cost of a certified verdict", "",
             f"Machine: {data['machine']}. Reproduce: `python bench/bench_monodromy.py`.", "",
             "| measurement | result | target |", "|---|---|---|",
             f"| one general body (5/4, 1, 3/10, -1/2), every entry to radius {single['radius']:.1e} | "
             f"{single['median_seconds']:.2f} s (median of 5), verdict {single['verdict']} | <= 2 s |",
             f"| {n} x {n} slice of (I13, I23) in [-0.6, 0.6]^2, I11 = 2, I22 = 1, radius 1e-{args.digits} asked "
             "(working digits per body: that plus the guard for the size of omega) | "
             f"{seconds:.0f} s on {executor.default_workers() if args.workers is None else args.workers} workers | "
             "<= 600 s |",
             f"| verdicts | {', '.join(f'{k}: {v}' for k, v in counts.items())} | |",
             f"| not certified away from I13 = 0 and I23 = 0 | {unknown_off} | 0 |", ""]
    write_results("monodromy", data, "\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
